// systemc/pins/rtl.h - the Verilated (--sc) models this binary can bind in place of a unit's
// SystemC twin (raycore simulate --rtl vtu; ist, hit and rgu are bound whole, not at their
// datapath's pins: systemc/{ist,hit,rgu}_rtl.h). Built from rtl/ when RAYCORE_RTL is ON
// (systemc/pins/rtl.cpp, models listed in rtl/CMakeLists.txt "raycore_rtl_frame"); without it
// (the sanitizer build) every call says so (rtl_none.cpp).
#pragma once

#include <systemc>

#include <memory>
#include <string>

#include "hls/fp.h"
#include "hls/image.h"
#include "systemc/pins/vtu.h"

namespace raycore::sc::pins {

// nullptr when no model of that format, rounding and STAGES is built; what_is lists the built ones.
std::unique_ptr<VtuPort> make_rtl_vtu(hls::FormatId f, hls::Rounding r, unsigned stages,
                                      const char* name, sc_core::sc_signal<bool>& clk,
                                      sc_core::sc_signal<bool>& rst_n);
// "vtu fp24 rtz STAGES=2, ..." or "none (built with RAYCORE_RTL=OFF)".
std::string rtl_models_built();

}  // namespace raycore::sc::pins
