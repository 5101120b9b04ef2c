// sim/reference/reference.h - the double-precision reference tracer: the same camera rays as
// every other tracer (scenes::primary_direction, origin = camera position), traced in double
// precision on the scene's double-precision triangles (not the memory image), with a watertight
// ray/triangle test and a robust shadow test. The error metrics (metrics.h) compare other frames
// with its frames.
//
// Per pixel:
// 1. Primary ray: the closest hit with t > 0 (bvh.h: watertight, conservative traversal, ties at
//    equal t to the lowest scene index). t is the distance (the direction is normalised).
// 2. Hit point: P = b0 v0 + b1 v1 + b2 v2 from the barycentrics, with pbrt's componentwise error
//    bound e = gamma(7) (|b0 v0| + |b1 v1| + |b2 v2|) (the true ray/triangle intersection lies
//    within P +- e).
// 3. Light side ("light in front"): with the triangle's plane through v0, v1, v2, a shadow ray is
//    spawned only if the light and the ray origin (the camera) lie strictly on the same side, both
//    decided exactly (orient3d). Otherwise (light behind the surface, or the light or the camera
//    exactly in its plane) the pixel is shadowed and no shadow ray is spawned: shadow_ray = false,
//    lit = false, shadow_tri = -1. The golden tracer uses the same rule in its number format.
// 4. Shadow ray: the segment P + t (L - P), t in (t_lo, 1), closest occluder reported. Skipped,
//    because the exact segment from the true hit point cannot cross them for t > 0 when the light
//    is strictly in front: the hit triangle itself (by index) and every triangle whose three
//    vertices are exactly coplanar with it (orient3d == 0). Ignored: occluders crossed at
//    t <= t_lo = max(2 |e|, 2 dot(|n|, e) / |cos|) / |L - P| (times 1 + 2^-20; n the unit
//    normal, cos between n and L - P), i.e. within twice the hit point's error radius of P or
//    within twice its error slab around the plane (pbrt's offset dot(|n|, e)), where the
//    computed segment cannot tell which side of them the true point is on. This is the
//    reference's only approximation (about 1e-15 of the coordinates' magnitude; more only for
//    light grazing the surface, by 1 / |cos|).
//    lit = no occluder; shadow_tri = the nearest occluder (ties to the lowest index), else -1.
// 5. shade (cosmetic, not used by the metrics): 0 for a miss; 40 + 215 |cos| (rounded) when lit,
//    40 when shadowed, cos = angle between the geometric normal and L - P.
// Frames are bit-identical for any thread count (rows are independent; no shared state).
#pragma once

#include <cstdint>
#include <vector>

#include "scenes/scene.h"
#include "sim/frame.h"
#include "sim/reference/bvh.h"

namespace raycore::reference {

// The outcome of the shadow-ray stage for one primary hit.
struct ShadowResult {
  bool shadow_ray = false;  // light strictly in front (same side as the ray origin)
  bool lit = false;
  int32_t shadow_tri = -1;  // nearest occluder, -1 none
  double t_lo = 0;          // the ignored interval (0, t_lo] of the segment
};

class Reference {
 public:
  // Builds the BVH over scene.tris (copied; the scene need not outlive this). Throws std::runtime_error naming the scene if it has
  // no light or a coordinate is not finite.
  explicit Reference(const scenes::Scene& scene);

  // The closest hit of a ray with t in (t_min, t_max), tri = -1 for a miss; `filter` skips
  // candidates (bvh.h).
  TriHit closest(const Ray& ray, double t_min = 0, double t_max = HUGE_VAL,
                 const HitFilter* filter = nullptr) const {
    return bvh_.closest(ray, t_min, t_max, filter);
  }

  // Hit point of a hit (barycentric form) and its componentwise error bound.
  Vec3 hit_point(const TriHit& h, Vec3* error = nullptr) const;

  // The shadow stage for a hit `h` of a ray from `origin` (the light-side rule, then the segment).
  ShadowResult shadow(const Vec3& origin, const TriHit& h) const;

  // One pixel: primary ray (origin = camera), hit, shadow, shade. `shadows` = false traces the
  // primary ray only (shadow_ray = lit = false).
  sim::PixelResult trace(const Ray& primary, bool shadows = true) const;

  // A whole frame with the scene's camera, w x h pixels, on `threads` threads (0: all cores).
  sim::Frame render(int width, int height, int threads = 1, bool shadows = true) const;

  const Bvh& bvh() const { return bvh_; }
  const scenes::Camera& camera() const { return camera_; }
  const scenes::Light& light() const { return light_; }

 private:
  scenes::Camera camera_;
  scenes::Light light_;
  Bvh bvh_;
};

// Convenience: Reference(scene).render(width, height, threads).
sim::Frame render(const scenes::Scene& scene, int width, int height, int threads = 1);

// Runs fn(y) for y in [0, rows) on `threads` threads (rows interleaved; 0 = all cores). Used by
// the reference and the Embree check; results written per row are independent of the count.
template <class Fn>
void parallel_rows(int rows, int threads, Fn fn);

}  // namespace raycore::reference

#include <algorithm>
#include <exception>
#include <thread>

template <class Fn>
void raycore::reference::parallel_rows(int rows, int threads, Fn fn) {
  if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::max(1, std::min(threads, rows));
  if (threads == 1) {
    for (int y = 0; y < rows; ++y) fn(y);
    return;
  }
  std::vector<std::thread> pool;
  std::vector<std::exception_ptr> error(static_cast<size_t>(threads));
  for (int k = 0; k < threads; ++k)
    pool.emplace_back([&, k] {
      try {
        for (int y = k; y < rows; y += threads) fn(y);
      } catch (...) {
        error[size_t(k)] = std::current_exception();
      }
    });
  for (auto& t : pool) t.join();
  for (auto& e : error)
    if (e) std::rethrow_exception(e);
}
