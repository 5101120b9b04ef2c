// systemc/trv_rtl_none.cpp - a build without Verilated models (RAYCORE_RTL=OFF): see trv_rtl.h.
#include "systemc/trv_rtl.h"

namespace raycore::sc {

std::unique_ptr<TrvRtl> make_rtl_trv(hls::FormatId, hls::Rounding, FrameCtx&, RtuChannels&,
                                     const SimConfig&) {
  return nullptr;
}
std::string rtl_trv_built() { return "none (built with RAYCORE_RTL=OFF)"; }

}  // namespace raycore::sc
