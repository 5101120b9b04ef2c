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
#include "scenes/scene.h"
#include "sim/frame.h"

namespace raycore::sim {

struct TraceConfig {
  hls::FormatId format = hls::FormatId::fp24;
  hls::Rounding rounding = hls::Rounding::rtz;
  bool vtu = false;
  // --store: the point the memory image is stored relative to (world: 0; anchored: the scene's box
  // centre, chosen on the host in double by sim::prepare). See hls::FrameSetup.
  bool anchored = false;
  hls::Vec3 anchor;
  hls::SpawnParams spawn;     // strategy and (ulp_offset) its ulps
  double tmin = 1.0 / 4096;   // 2^-12, RayCore's
  // Watertightness margins (hls/margins.h; --bary-margin, --trv-widen): the ist accepts beta,
  // gamma >= -bary_margin and beta + gamma <= 1 + bary_margin; the trv widens its intervals by
  // trv_widen ulps. 0 and 0: none (today's frames bit for bit).
  double bary_margin = 0;
  int32_t trv_widen = 0;
  int width = 800, height = 480;
  int threads = 0;            // 0: all hardware threads
};

// Work done, for comparison with the cycle model and for the report.
struct TraceStats {
  uint64_t primary_rays = 0, shadow_rays = 0;
  uint64_t inner_steps = 0;  // inner-node traversal steps
  uint64_t leaf_visits = 0;
  uint64_t tri_tests = 0;
  uint64_t primary_hits = 0;
  double seconds = 0;
};

// Default ulps for ulp_offset when SpawnParams::ulps is 0: Waechter & Binder's 256 FP32 ulps,
// scaled to the format's precision (2 ulps for FP24).
int32_t default_spawn_ulps(hls::FormatId f);

// The default ulps of a strategy when SpawnParams::ulps is 0: default_spawn_ulps(f) for
// ulp_offset and skip_offset, 4 for skip_slab (a slab of 4 ulps of the hit point in any format),
// 1 for skip_back (the back-off), 0 for the others (unused).
int32_t default_spawn_ulps(hls::FormatId f, hls::Spawn s);

// Whether a strategy reads SpawnParams::ulps (ulp_offset, skip_offset, skip_slab, skip_back).
bool spawn_uses_ulps(hls::Spawn s);

// The ist / trv margin registers of cfg for the arithmetic A (hls::make_margins; throws
// std::invalid_argument on a negative or non-finite margin or a widening outside 0..64).
template <class A>
hls::Margins frame_margins(const TraceConfig& cfg) {
  return hls::make_margins<A>(cfg.bary_margin, cfg.trv_widen);
}

// cfg.spawn with the default ulps filled in (the spawn parameters every model uses).
hls::SpawnParams resolved_spawn(const TraceConfig& cfg);

Frame trace_golden(const hls::Image& image, const scenes::Camera& cam, const scenes::Light& light,
                   const TraceConfig& cfg, TraceStats* stats = nullptr);

// Grey level of a pixel: ambient + Lambert for a lit surface; shared with the cycle model.
uint8_t shade_pixel(bool hit, bool lit, double cos_light);

std::string to_string(hls::Spawn s);
hls::Spawn spawn_from_string(const std::string& s);  // throws std::invalid_argument
std::string spawn_choices();  // "none, skip-origin, ..." (every --spawn value)

}  // namespace raycore::sim
