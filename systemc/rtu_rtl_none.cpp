// systemc/rtu_rtl_none.cpp - a build without Verilated models (RAYCORE_RTL=OFF): see rtu_rtl.h.
#include "systemc/rtu_rtl.h"

namespace raycore::sc {

RtuRtlRun run_rtl_rtus(hls::FormatId, hls::Rounding, FrameCtx&, const SimConfig&,
                       const std::vector<uint8_t>&, const uint32_t[3], const pins::HitConfig&,
                       const PixelWrite&) {
  throw ConfigError("--rtl rtu: no Verilated rtu in this build (RAYCORE_RTL=OFF)");
}
std::string rtl_rtu_built() { return "none (built with RAYCORE_RTL=OFF)"; }

}  // namespace raycore::sc
