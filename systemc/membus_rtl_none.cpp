// systemc/membus_rtl_none.cpp - a build without Verilated models (RAYCORE_RTL=OFF): see
// membus_rtl.h.
#include "systemc/membus_rtl.h"

namespace raycore::sc {

std::unique_ptr<MembusRtl> make_rtl_membus(unsigned, unsigned, unsigned, const L2Config&) {
  return nullptr;
}
std::string rtl_membus_built() { return "none (built with RAYCORE_RTL=OFF)"; }

}  // namespace raycore::sc
