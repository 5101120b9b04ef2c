// sim/golden/golden.h - the golden tracer: the untimed reference for the hardware, bit for bit.
//
// It reads only the memory image plus camera and light, and computes only through the hls/ unit
// datapaths (rgu, trv, ist, hit, vtu), so the cycle model (systemc/) must produce the same frame.
#pragma once

#include <cstdint>
#include <string>

#include "hls/fp.h"
#include "hls/hit.h"
#include "hls/image.h"
#include "hls/margins.h"
#include "hls/trace.h"
#include "scenes/scene.h"
#include "sim/frame.h"

namespace raycore::sim {

// Work done, for comparison with the cycle model and for the report.
struct TraceStats {
  uint64_t primary_rays = 0, shadow_rays = 0;
  uint64_t inner_steps = 0;  // inner-node traversal steps
  uint64_t leaf_visits = 0;
  uint64_t tri_tests = 0;
  uint64_t primary_hits = 0;
  double seconds = 0;
};

// The frame configuration and the registers derived from it live in hls/trace.h (below the cycle
// model too); their names here.
using hls::default_spawn_ulps;
using hls::frame_margins;
using hls::resolved_spawn;
using hls::spawn_uses_ulps;
using hls::TraceConfig;

Frame trace_golden(const hls::Image& image, const scenes::Camera& cam, const scenes::Light& light,
                   const TraceConfig& cfg, TraceStats* stats = nullptr);

std::string to_string(hls::Spawn s);
hls::Spawn spawn_from_string(const std::string& s);  // throws std::invalid_argument
std::string spawn_choices();  // "none, skip-origin, ..." (every --spawn value)

}  // namespace raycore::sim
