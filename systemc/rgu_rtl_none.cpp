// systemc/rgu_rtl_none.cpp - a build without Verilated models (RAYCORE_RTL=OFF): see rgu_rtl.h.
#include "systemc/rgu_rtl.h"

namespace raycore::sc {

std::unique_ptr<RguRtl> make_rtl_rgu_unit(hls::FormatId, hls::Rounding, unsigned, unsigned,
                                          const SimConfig&) {
  return nullptr;
}
std::string rtl_rgu_unit_built() { return "none (built with RAYCORE_RTL=OFF)"; }

}  // namespace raycore::sc
