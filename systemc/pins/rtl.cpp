// systemc/pins/rtl.cpp - the Verilated --sc models of rtl/ bound into the cycle model (see rtl.h).
#include "systemc/pins/rtl.h"

#include <cstring>

#include "rtl_frame_models.h"

namespace raycore::sc::pins {
namespace {
bool matches(const char* fmt, const char* mode, unsigned stages, hls::FormatId f, hls::Rounding r,
             unsigned s) {
  const hls::FormatId mf = std::strcmp(fmt, "FP24") == 0 ? hls::FormatId::fp24 : hls::FormatId::fp32;
  const hls::Rounding mr = std::strcmp(mode, "rne") == 0 ? hls::Rounding::rne : hls::Rounding::rtz;
  return mf == f && mr == r && stages == s;
}
}  // namespace

std::unique_ptr<VtuPort> make_rtl_vtu(hls::FormatId f, hls::Rounding r, unsigned s, const char* name,
                                      sc_core::sc_signal<bool>& clk, sc_core::sc_signal<bool>& rst_n) {
// Only the lines of the unit's module instantiate a port (the others' ports do not match).
#define RAYCORE_CASE_vtu(prefix, fmt, mode, stages) \
  if (matches(#fmt, #mode, stages, f, r, s))        \
    return std::make_unique<VtuPortT<prefix>>(name, "Verilated " #prefix, clk, rst_n);
#define RAYCORE_CASE_ist(prefix, fmt, mode, stages)
#define RAYCORE_RTL_FRAME_VARIANT(prefix, module, fmt, mode, stages) \
  RAYCORE_CASE_##module(prefix, fmt, mode, stages)
#include "rtl_frame_variants.h"
#undef RAYCORE_RTL_FRAME_VARIANT
#undef RAYCORE_CASE_vtu
#undef RAYCORE_CASE_ist
  return nullptr;
}

std::unique_ptr<IstPort> make_rtl_ist(hls::FormatId f, hls::Rounding r, unsigned s, const char* name,
                                      sc_core::sc_signal<bool>& clk, sc_core::sc_signal<bool>& rst_n) {
#define RAYCORE_CASE_ist(prefix, fmt, mode, stages) \
  if (matches(#fmt, #mode, stages, f, r, s))        \
    return std::make_unique<IstPortT<prefix>>(name, "Verilated " #prefix, clk, rst_n);
#define RAYCORE_CASE_vtu(prefix, fmt, mode, stages)
#define RAYCORE_RTL_FRAME_VARIANT(prefix, module, fmt, mode, stages) \
  RAYCORE_CASE_##module(prefix, fmt, mode, stages)
#include "rtl_frame_variants.h"
#undef RAYCORE_RTL_FRAME_VARIANT
#undef RAYCORE_CASE_vtu
#undef RAYCORE_CASE_ist
  return nullptr;
}

std::string rtl_models_built() {
  std::string s;
#define RAYCORE_RTL_FRAME_VARIANT(prefix, module, fmt, mode, stages) \
  s += std::string(s.empty() ? "" : ", ") + #module " " #fmt " " #mode " STAGES=" #stages;
#include "rtl_frame_variants.h"
#undef RAYCORE_RTL_FRAME_VARIANT
  return s;
}

}  // namespace raycore::sc::pins
