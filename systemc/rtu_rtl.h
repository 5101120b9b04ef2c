// systemc/rtu_rtl.h - raycore simulate --rtl rtu: the whole RTU in RTL. Every RTU of the frame is
// one Verilated rtl/units/rtu.v (rgu_unit, trv_unit, ist_unit, hit_unit, the three ascaches, the
// slots' pixel and skip id, the fill path with vtu.v), stepped from C++ every cycle; their caches'
// line requests and data beats go through the Verilated bus interface (membus_if.v, the Membus
// class's RTL view: the memory's timing and bytes stay C++, as the testbench's). No C++ glue
// between the units is left: what the host does is what the chip top (rtl/units/chip.v) leaves
// outside, the frame registers, the line address (region base + line x line bytes) and the
// frame buffer's pixel write (systemc/hit.h write_pixel, from rtu.v's px_* outputs).
//
// Built for the cycle model's default parameters (rtl/units/rtu.cmake): the options that change
// the RTU's structure (rays in flight, ist units, caches, list line, pipeline depths) must be the
// built ones or are refused with the list; the others (latencies of the caches and the trv, the
// spawn strategy, --trv-pipes / --ist-units up to the built, the memory) are registers.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hls/hit.h"
#include "hls/image.h"
#include "systemc/config.h"
#include "systemc/membus.h"
#include "systemc/pins/hit.h"
#include "systemc/slot.h"

namespace raycore::sc {

struct RtuRtlRun {
  Cycle cycles = 0;            // last retire + 1, as the cycle model counts
  Cycle clocked = 0;           // cycles the models were clocked
  std::vector<RtuStats> rtus;  // from rtu.v's counters
  MembusStats bus;
};

// The frame buffer's pixel write of a ray leaving a hit unit (systemc/hit.h write_pixel<A>).
using PixelWrite = std::function<bool(uint32_t pixel, bool shadow, const Best& b,
                                      const hls::ShadowSetup& ss, double& cos_light)>;

// Runs the frame set up in fc (its frame buffer, counters and registers, as simulate() forms them)
// on the RTUs in RTL; vtu_cam is the VTU's camera in the format (hls::Vtu::c), hit the hit unit's
// registers (systemc/hit.h hit_config). Throws ConfigError for what is not built and
// std::runtime_error on a stack overflow or a hang.
RtuRtlRun run_rtl_rtus(hls::FormatId f, hls::Rounding r, FrameCtx& fc, const SimConfig& cfg,
                       const std::vector<uint8_t>& image, const uint32_t vtu_cam[3],
                       const pins::HitConfig& hit, const PixelWrite& write);
std::string rtl_rtu_built();

}  // namespace raycore::sc
