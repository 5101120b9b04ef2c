// sim/reference/reference.cpp - see reference.h.
#include "sim/reference/reference.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/reference/predicates.h"

namespace raycore::reference {
namespace {

constexpr double kEps = DBL_EPSILON / 2;
constexpr double gamma(int n) { return n * kEps / (1 - n * kEps); }

Vec3 abs(const Vec3& v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }

// Skips, for a shadow ray, the triangle it starts on and every triangle exactly coplanar with it.
class OriginSurface : public HitFilter {
 public:
  OriginSurface(const Bvh& bvh, int32_t origin) : bvh_(bvh), origin_(origin), plane_(bvh.triangle(origin)) {}
  bool skip(int32_t tri) const override {
    if (tri == origin_) return true;
    const Tri& t = bvh_.triangle(tri);
    for (const Vec3& p : t)
      if (orient3d(plane_[0], plane_[1], plane_[2], p) != 0) return false;
    return true;
  }

 private:
  const Bvh& bvh_;
  int32_t origin_;
  const Tri& plane_;
};

}  // namespace

Reference::Reference(const scenes::Scene& scene)
    : camera_(scene.camera), light_(scene.light), bvh_(scene.tris) {
  if (!scene.light.present)
    throw std::runtime_error("reference: scene '" + scene.name + "' has no point light");
  if (!hls::is_finite(scene.light.position) || !hls::is_finite(scene.camera.position))
    throw std::runtime_error("reference: scene '" + scene.name +
                             "' has a camera or light position that is not finite");
}

Vec3 Reference::hit_point(const TriHit& h, Vec3* error) const {
  const Tri& t = bvh_.triangle(h.tri);
  const Vec3 p0 = h.b0 * t[0], p1 = h.b1 * t[1], p2 = h.b2 * t[2];
  if (error) *error = gamma(7) * (abs(p0) + abs(p1) + abs(p2));
  return p0 + p1 + p2;
}

ShadowResult Reference::shadow(const Vec3& origin, const TriHit& h) const {
  ShadowResult r;
  const Tri& t = bvh_.triangle(h.tri);
  const int side_light = orient3d(t[0], t[1], t[2], light_.position);
  const int side_origin = orient3d(t[0], t[1], t[2], origin);
  if (side_light == 0 || side_light != side_origin) return r;  // light behind or in the plane
  r.shadow_ray = true;
  Vec3 err;
  const Vec3 p = hit_point(h, &err);
  const Vec3 w = light_.position - p;
  const double len = hls::length(w);
  // Ignored: the part of the segment within twice the hit point's error radius of P, and within
  // twice its error slab around the triangle's plane (which matters at grazing light).
  const Vec3 n = hls::normalize(hls::cross(t[1] - t[0], t[2] - t[0]));
  const double slab = hls::dot(abs(n), err);
  const double rise = std::fabs(hls::dot(n, w));  // distance from the plane gained per unit t
  const double t_ball = len > 0 ? 2.0 * hls::length(err) / len : HUGE_VAL;
  const double t_slab = rise > 0 ? 2.0 * slab / rise : HUGE_VAL;
  r.t_lo = std::max(t_ball, t_slab) * (1.0 + 0x1p-20);
  if (r.t_lo >= 1.0) {
    r.lit = true;
    return r;
  }
  const OriginSurface filter(bvh_, h.tri);
  const TriHit occ = bvh_.closest(Ray{p, w}, r.t_lo, 1.0, &filter);
  r.lit = occ.tri < 0;
  r.shadow_tri = occ.tri;
  return r;
}

sim::PixelResult Reference::trace(const Ray& primary, bool shadows) const {
  sim::PixelResult px;
  const TriHit h = bvh_.closest(primary, 0.0, HUGE_VAL);
  if (h.tri < 0) return px;
  px.tri = h.tri;
  px.t = h.t;
  px.hit = hit_point(h);
  if (!shadows) return px;
  const ShadowResult s = shadow(primary.org, h);
  px.front = s.shadow_ray;  // the reference spawns exactly when the light is strictly in front
  px.shadow_ray = s.shadow_ray;
  px.lit = s.lit;
  px.shadow_tri = s.shadow_tri;
  double shade = 40;
  if (s.lit) {
    const Tri& t = bvh_.triangle(h.tri);
    const Vec3 n = hls::cross(t[1] - t[0], t[2] - t[0]);
    const Vec3 w = light_.position - px.hit;
    const double denom = hls::length(n) * hls::length(w);
    const double c = denom > 0 ? std::fabs(hls::dot(n, w)) / denom : 0.0;
    shade += 215.0 * std::min(1.0, c);
  }
  px.shade = uint8_t(std::lround(shade));
  return px;
}

sim::Frame Reference::render(int width, int height, int threads, bool shadows) const {
  if (width <= 0 || height <= 0)
    throw std::runtime_error("reference: image size " + std::to_string(width) + " x " +
                             std::to_string(height) + " is not positive");
  sim::Frame f;
  f.width = width;
  f.height = height;
  f.px.resize(size_t(width) * size_t(height));
  parallel_rows(height, threads, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const Ray ray{camera_.position, scenes::primary_direction(camera_, x, y, width, height)};
      f.px[size_t(y) * size_t(width) + size_t(x)] = trace(ray, shadows);
    }
  });
  return f;
}

sim::Frame render(const scenes::Scene& scene, int width, int height, int threads) {
  return Reference(scene).render(width, height, threads);
}

}  // namespace raycore::reference
