// systemc/pins/rtl_none.cpp - a build without Verilated models (RAYCORE_RTL=OFF): see rtl.h.
#include "systemc/pins/rtl.h"

namespace raycore::sc::pins {

std::unique_ptr<VtuPort> make_rtl_vtu(hls::FormatId, hls::Rounding, unsigned, const char*,
                                      sc_core::sc_signal<bool>&, sc_core::sc_signal<bool>&) {
  return nullptr;
}
std::string rtl_models_built() { return "none (built with RAYCORE_RTL=OFF)"; }

}  // namespace raycore::sc::pins
