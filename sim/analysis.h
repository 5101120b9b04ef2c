// sim/analysis.h - measurements that explain error metrics: where a hardware frame's hit points
// lie relative to the planes of their own triangles (in exact arithmetic), and why its shadow rays
// self-intersect.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

#include "hls/image.h"
#include "scenes/scene.h"
#include "sim/frame.h"
#include "sim/golden/golden.h"

namespace raycore::sim {

struct HitSideStats {
  uint64_t shadow_rays = 0;
  uint64_t behind = 0;    // hit point strictly on the far side of its plane, seen from the light
  uint64_t on_plane = 0;  // exactly on it
  uint64_t self_intersections = 0;
  uint64_t self_behind = 0;  // ... of which the hit point was behind (t > 0 in exact arithmetic)
  double median_plane_distance_ulps = 0;  // |f(h)| / ulp(max |h_i|), f the stored plane function
};

// For a frame made by trace_golden(image, cam, light, cfg): the plane function f(p) = p_k +
// n_u p_u + n_v p_v - n_d of the triangle each shadow ray starts on, with the constants the
// datapath used (VTU-translated when cfg.vtu), evaluated at the hit point in extended precision.
HitSideStats hit_side_stats(const Frame& f, const hls::Image& image, const scenes::Camera& cam,
                            const scenes::Light& light, const TraceConfig& cfg);

nlohmann::json to_json(const HitSideStats& s);

}  // namespace raycore::sim
