// systemc/pins/rtl.cpp - the Verilated --sc models of rtl/ bound into the cycle model (see rtl.h).
#include "systemc/pins/rtl.h"

#include <type_traits>

#include "rtl_frame_models.h"
#include "systemc/vl_bits.h"

namespace raycore::sc::pins {
namespace {

bool matches(const char* fmt, const char* mode, unsigned stages, hls::FormatId f, hls::Rounding r,
             unsigned s) {
  return vl::variant_is(fmt, mode, f, r) && stages == s;
}

// The port of each module in rtl_frame_variants.h.
using PortOf_vtu = VtuPort;
// ist.v's and rgu.v's --sc models are their lockstep tests' (the frame binds ist_unit.v, rgu_unit.v).
using PortOf_ist = void;
using PortOf_rgu = void;

// The built model of the unit whose port is Port (only its module's lines instantiate one; the
// others' ports do not match), bound to a new Port; nullptr if none has that configuration.
template <class Port>
std::unique_ptr<Port> make_rtl(hls::FormatId f, hls::Rounding r, unsigned s, const char* name,
                               sc_core::sc_signal<bool>& clk, sc_core::sc_signal<bool>& rst_n) {
#define RAYCORE_RTL_FRAME_VARIANT(prefix, module, fmt, mode, stages)                 \
  if constexpr (std::is_same_v<Port, PortOf_##module>) {                             \
    if (matches(#fmt, #mode, stages, f, r, s))                                       \
      return std::make_unique<BoundPort<Port, prefix>>(name, "Verilated " #prefix, clk, \
                                                       rst_n);                       \
  }
#include "rtl_frame_variants.h"
#undef RAYCORE_RTL_FRAME_VARIANT
  return nullptr;
}

}  // namespace

std::unique_ptr<VtuPort> make_rtl_vtu(hls::FormatId f, hls::Rounding r, unsigned s, const char* name,
                                      sc_core::sc_signal<bool>& clk, sc_core::sc_signal<bool>& rst_n) {
  return make_rtl<VtuPort>(f, r, s, name, clk, rst_n);
}


std::string rtl_models_built() {
  std::string s;
#define RAYCORE_RTL_FRAME_VARIANT(prefix, module, fmt, mode, stages) \
  if (std::string(#module) == "vtu")                                 \
    s += std::string(s.empty() ? "" : ", ") + #module " " #fmt " " #mode " STAGES=" #stages;
#include "rtl_frame_variants.h"
#undef RAYCORE_RTL_FRAME_VARIANT
  return s;
}

}  // namespace raycore::sc::pins
