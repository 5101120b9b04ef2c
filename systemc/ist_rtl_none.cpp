// systemc/ist_rtl_none.cpp - a build without Verilated models (RAYCORE_RTL=OFF): see ist_rtl.h.
#include "systemc/ist_rtl.h"

namespace raycore::sc {

std::unique_ptr<IstRtl> make_rtl_ist_unit(hls::FormatId, hls::Rounding, unsigned, hls::IstKind, FrameCtx&,
                                          RtuChannels&, const SimConfig&) {
  return nullptr;
}
std::string rtl_ist_unit_built() { return "none (built with RAYCORE_RTL=OFF)"; }

}  // namespace raycore::sc
