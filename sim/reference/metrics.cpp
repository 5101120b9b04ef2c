// sim/reference/metrics.cpp - see metrics.h.
#include "sim/reference/metrics.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace raycore::reference {
namespace {

void check_index(int32_t tri, size_t n, const char* frame, const char* field, size_t pixel) {
  if (tri < -1 || (tri >= 0 && size_t(tri) >= n))
    throw std::invalid_argument(std::string("compute_errors: ") + frame + " frame, pixel " +
                                std::to_string(pixel) + ": " + field + " = " + std::to_string(tri) +
                                " is not a triangle of the scene (" + std::to_string(n) + ")");
}

bool lit(const sim::PixelResult& p) { return p.shadow_ray && p.lit; }

double pct(uint64_t n, uint64_t of) { return of ? 100.0 * double(n) / double(of) : 0.0; }

}  // namespace

PixelError classify_pixel(const sim::PixelResult& a, const sim::PixelResult& r) {
  // Primary: the visible surface.
  if (a.tri >= 0 && r.tri < 0) return PixelError::primary_hit_vs_miss;
  if (a.tri < 0 && r.tri >= 0) return PixelError::primary_miss_vs_hit;
  if (a.tri < 0) return PixelError::none;  // both miss
  if (!(std::fabs(a.t - r.t) <= kPrimaryDistanceTolerance * r.t)) return PixelError::primary_distance;
  // Shadow: same visible surface.
  const bool la = lit(a), lr = lit(r);
  if (!la && lr) return PixelError::false_shadow;
  if (la && !lr) return PixelError::light_leak;
  return PixelError::none;
}

ErrorMetrics compute_errors(const sim::Frame& test, const sim::Frame& ref, const std::vector<hls::Tri>& tris) {
  if (test.width != ref.width || test.height != ref.height)
    throw std::invalid_argument("compute_errors: frame sizes differ: test " + std::to_string(test.width) +
                                " x " + std::to_string(test.height) + ", reference " +
                                std::to_string(ref.width) + " x " + std::to_string(ref.height));
  const size_t n = size_t(test.width) * size_t(test.height);
  if (test.px.size() != n || ref.px.size() != n)
    throw std::invalid_argument("compute_errors: a frame's pixel count does not match its size");
  ErrorMetrics m;
  m.pixels = n;
  m.primary_rays = n;
  for (size_t i = 0; i < n; ++i) {
    const sim::PixelResult& a = test.px[i];
    const sim::PixelResult& r = ref.px[i];
    check_index(a.tri, tris.size(), "test", "tri", i);
    check_index(a.shadow_tri, tris.size(), "test", "shadow_tri", i);
    check_index(r.tri, tris.size(), "reference", "tri", i);
    check_index(r.shadow_tri, tris.size(), "reference", "shadow_tri", i);

    const bool self = a.shadow_ray && a.tri >= 0 && a.shadow_tri == a.tri;
    if (a.shadow_ray) ++m.shadow_rays;
    if (self) ++m.self_intersections;
    if (self && a.front) ++m.self_intersections_front;

    switch (classify_pixel(a, r)) {
      case PixelError::primary_hit_vs_miss: ++m.primary_hit_vs_miss; continue;
      case PixelError::primary_miss_vs_hit: ++m.primary_miss_vs_hit; continue;
      case PixelError::primary_distance: ++m.primary_distance; continue;
      case PixelError::false_shadow:
        ++m.false_shadow;
        if (self) ++m.false_shadow_self;
        if (!a.front) ++m.false_shadow_no_ray;
        break;
      case PixelError::light_leak: ++m.light_leak; break;
      case PixelError::none: break;
    }
    if (a.tri < 0) continue;  // both miss
    // Same visible surface: its shadow was compared.
    ++m.shadow_compared;
    if (a.tri != r.tri) ++m.primary_other_tri;
  }
  m.primary_errors = m.primary_hit_vs_miss + m.primary_miss_vs_hit + m.primary_distance;
  m.shadow_errors = m.false_shadow + m.light_leak;
  m.self_intersection_pct = pct(m.self_intersections, m.pixels);
  m.shadow_error_pct = pct(m.shadow_errors, m.pixels);
  m.primary_error_pct = pct(m.primary_errors, m.pixels);
  return m;
}

nlohmann::json to_json(const ErrorMetrics& m) {
  return nlohmann::json{
      {"pixels", m.pixels},
      {"primary_rays", m.primary_rays},
      {"shadow_rays", m.shadow_rays},
      {"self_intersections", m.self_intersections},
      {"self_intersection_pct", m.self_intersection_pct},
      {"self_intersections_front", m.self_intersections_front},
      {"shadow_compared", m.shadow_compared},
      {"shadow_errors", m.shadow_errors},
      {"shadow_error_pct", m.shadow_error_pct},
      {"false_shadow", m.false_shadow},
      {"false_shadow_self", m.false_shadow_self},
      {"false_shadow_no_ray", m.false_shadow_no_ray},
      {"light_leak", m.light_leak},
      {"primary_errors", m.primary_errors},
      {"primary_error_pct", m.primary_error_pct},
      {"primary_miss_vs_hit", m.primary_miss_vs_hit},
      {"primary_hit_vs_miss", m.primary_hit_vs_miss},
      {"primary_distance", m.primary_distance},
      {"primary_other_tri", m.primary_other_tri},
  };
}

}  // namespace raycore::reference
