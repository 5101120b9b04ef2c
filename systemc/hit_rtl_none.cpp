// systemc/hit_rtl_none.cpp - a build without Verilated models (RAYCORE_RTL=OFF): see hit_rtl.h.
#include "systemc/hit_rtl.h"

namespace raycore::sc {

std::unique_ptr<HitRtl> make_rtl_hit_unit(hls::FormatId, hls::Rounding, unsigned, RtuChannels&,
                                          const SimConfig&) {
  return nullptr;
}
std::string rtl_hit_unit_built() { return "none (built with RAYCORE_RTL=OFF)"; }

}  // namespace raycore::sc
