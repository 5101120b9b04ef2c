// sim/reference/metrics.h - the error metrics of design.md ("Error metrics", fixed definitions):
// a test frame (golden tracer, cycle model, ...) against the reference frame of the same scene,
// camera, light and size.
//
// Definitions, per pixel (lit means shadow_ray && lit; a pixel without a shadow ray is shadowed):
// - self_intersections: test pixels with a shadow ray whose nearest hit is the triangle the ray
//   started on (shadow_tri == tri >= 0), whatever the reference says; self_intersection_pct =
//   100 * self_intersections / pixels. (The test's own t_min applies: it is in its shadow_tri.)
//   Of these, self_intersections_front: the light is in front (front), i.e. the ones that can
//   change the image (with --shadow-spawn all, rays toward a light behind the surface are spawned
//   too; they self-intersect as often but the pixel is shadowed anyway).
// - primary_errors = primary_hit_vs_miss + primary_miss_vs_hit + primary_distance:
//     primary_hit_vs_miss: the test hits, the reference misses;
//     primary_miss_vs_hit: the test misses, the reference hits;
//     primary_distance:    both hit and |t_test - t_ref| > 1% of t_ref.
//   Both hitting within 1% is not an error whatever the triangle ids (edge ties, coplanar
//   overlaps); those with different ids are counted, for information, in primary_other_tri.
// - shadow_errors = false_shadow + light_leak, over the pixels where the visible surface agrees
//   (both hit and the pixel is not a primary error; counted in shadow_compared). Pixels with a
//   primary error are not compared for shadows: their shadow rays start from different surfaces,
//   and they are already counted once, as primary errors.
//     false_shadow: test shadowed, reference lit (acne). Of these, for information:
//       false_shadow_self  - the test's shadow ray hit its own triangle (self-intersection);
//       false_shadow_no_ray - the test's light-side decision says behind (front false; with
//       --shadow-spawn front it spawned no shadow ray).
//     light_leak: test lit, reference shadowed.
// Percentages (..._pct) are of `pixels`.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "hls/geom.h"
#include "sim/frame.h"

namespace raycore::reference {

struct ErrorMetrics {
  uint64_t pixels = 0;
  uint64_t primary_rays = 0;  // test frame: one per pixel
  uint64_t shadow_rays = 0;   // test frame: pixels with shadow_ray
  uint64_t self_intersections = 0;
  double self_intersection_pct = 0;
  uint64_t self_intersections_front = 0;  // of those, light in front (the image-changing ones)
  uint64_t shadow_compared = 0;
  uint64_t shadow_errors = 0;
  uint64_t false_shadow = 0;
  uint64_t false_shadow_self = 0;
  uint64_t false_shadow_no_ray = 0;
  uint64_t light_leak = 0;
  double shadow_error_pct = 0;
  uint64_t primary_errors = 0;
  uint64_t primary_miss_vs_hit = 0;
  uint64_t primary_hit_vs_miss = 0;
  uint64_t primary_distance = 0;
  uint64_t primary_other_tri = 0;
  double primary_error_pct = 0;
};

// The relative distance tolerance of primary_distance (1%).
constexpr double kPrimaryDistanceTolerance = 0.01;

// One pixel's verdict under the definitions above (compute_errors counts these): the primary kinds
// first; a shadow kind only where the visible surface agrees.
enum class PixelError : uint8_t { none, primary_hit_vs_miss, primary_miss_vs_hit, primary_distance, false_shadow, light_leak };
PixelError classify_pixel(const sim::PixelResult& test, const sim::PixelResult& ref);
constexpr bool is_primary_error(PixelError e) {
  return e == PixelError::primary_hit_vs_miss || e == PixelError::primary_miss_vs_hit || e == PixelError::primary_distance;
}
constexpr bool is_shadow_error(PixelError e) { return e == PixelError::false_shadow || e == PixelError::light_leak; }

// Throws std::invalid_argument if the frames differ in size or a triangle index is outside
// `tris` (the scene's triangles, which both frames index).
ErrorMetrics compute_errors(const sim::Frame& test, const sim::Frame& ref, const std::vector<hls::Tri>& tris);

// Stable keys: pixels, primary_rays, shadow_rays, self_intersections, self_intersection_pct,
// self_intersections_front,
// shadow_errors, false_shadow, light_leak, primary_errors, primary_miss_vs_hit,
// primary_hit_vs_miss, primary_distance, and the informative shadow_compared, false_shadow_self,
// false_shadow_no_ray, shadow_error_pct, primary_other_tri, primary_error_pct.
nlohmann::json to_json(const ErrorMetrics& m);

}  // namespace raycore::reference
