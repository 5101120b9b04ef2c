// systemc/ascache_rtl_none.cpp - a build without Verilated models (RAYCORE_RTL=OFF): see
// ascache_rtl.h.
#include "systemc/ascache_rtl.h"

namespace raycore::sc {

std::unique_ptr<AscacheRtl> make_rtl_ascache(uint32_t, uint32_t, uint32_t, uint32_t) {
  return nullptr;
}
std::string rtl_ascache_built() { return "none (built with RAYCORE_RTL=OFF)"; }

}  // namespace raycore::sc
