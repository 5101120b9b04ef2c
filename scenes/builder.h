// scenes/builder.h - building blocks of the procedural scenes (internal to scenes/).
//
// Everything here is deterministic on any IEEE-754 machine: integer RNG (splitmix64), our own
// sine/cosine (only + and *), no library distributions, no FMA contraction (the library is built
// with -ffp-contract=off). The generated files are checked byte for byte against the shipped ones.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "scenes/options.h"
#include "scenes/scene.h"

namespace raycore::scenes::gen {

// splitmix64 (Steele, Lea, Flood 2014): a 64-bit integer generator; doubles from its top 53 bits.
struct Rng {
  uint64_t state;
  explicit Rng(uint64_t seed) : state(seed) {}
  uint64_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }           // [0, 1)
  double range(double lo, double hi) { return lo + (hi - lo) * uniform(); }  // [lo, hi)
  int below(int n) { return int(next() % uint64_t(n)); }                    // [0, n)
};

constexpr double kPi = 3.14159265358979323846;

// sin and cos of a (radians), |a| < 1e6: Cody-Waite reduction by pi/2, Taylor polynomials.
inline void sincos(double a, double& s, double& c) {
  const double pio2_hi = 1.5707963267948966, pio2_lo = 6.123233995736766e-17;
  const double k = std::floor(a * (2.0 / kPi) + 0.5);
  const double r = (a - k * pio2_hi) - k * pio2_lo;
  const double r2 = r * r;
  const double sr =
      r * (1 + r2 * (-1.0 / 6 + r2 * (1.0 / 120 + r2 * (-1.0 / 5040 + r2 * (1.0 / 362880 + r2 * (-1.0 / 39916800 +
           r2 * (1.0 / 6227020800.0 + r2 * (-1.0 / 1307674368000.0 + r2 * (1.0 / 355687428096000.0)))))))));
  const double cr =
      1 + r2 * (-0.5 + r2 * (1.0 / 24 + r2 * (-1.0 / 720 + r2 * (1.0 / 40320 + r2 * (-1.0 / 3628800 +
          r2 * (1.0 / 479001600.0 + r2 * (-1.0 / 87178291200.0 + r2 * (1.0 / 20922789888000.0))))))));
  switch (int64_t(k) & 3) {
    case 0: s = sr, c = cr; break;
    case 1: s = cr, c = -sr; break;
    case 2: s = -sr, c = -cr; break;
    default: s = -cr, c = sr; break;
  }
}

// A camera at `eye` looking at `target`, +Y up, full vertical field of view in degrees, 800 x 480.
inline Camera look_at_camera(Vec3 eye, Vec3 target, double fov_deg) {
  return look_at(eye, target, fov_deg * (kPi / 180), 800.0 / 480.0);
}

// A placement: rotate about +Y by `yaw` (radians), then translate by `origin`.
struct Frame {
  Vec3 origin;
  double cy = 1, sy = 0;
  Frame() = default;
  explicit Frame(Vec3 o, double yaw = 0) : origin(o) { sincos(yaw, sy, cy); }
  Vec3 operator()(Vec3 p) const { return {origin.x + cy * p.x + sy * p.z, origin.y + p.y, origin.z - sy * p.x + cy * p.z}; }
};

// Collects named parts (MeshRanges) of triangles. Front faces are counter-clockwise; the closed
// primitives (box, cylinder, sphere) face outwards.
class Builder {
 public:
  explicit Builder(std::string name) { s_.name = std::move(name); s_.source = "generated"; }

  void part(const std::string& name) {
    close_part();
    s_.meshes.push_back(MeshRange{name, "", s_.tris.size(), 0});
  }

  void tri(Vec3 a, Vec3 b, Vec3 c) {
    if (s_.meshes.empty()) part("mesh");
    s_.tris.push_back({a, b, c});
  }
  void quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    tri(a, b, c);
    tri(a, c, d);
  }
  // The quad, wound so that its front faces along `n`.
  void quad_facing(Vec3 a, Vec3 b, Vec3 c, Vec3 d, Vec3 n) {
    if (hls::dot(hls::cross(b - a, c - a), n) < 0) quad(a, d, c, b);
    else quad(a, b, c, d);
  }

  // Axis-aligned (in the frame) box [lo, hi], 12 triangles.
  void box(const Frame& f, Vec3 lo, Vec3 hi) {
    auto p = [&](int i, int j, int k) { return f({i ? hi.x : lo.x, j ? hi.y : lo.y, k ? hi.z : lo.z}); };
    quad(p(0, 0, 0), p(0, 0, 1), p(0, 1, 1), p(0, 1, 0));  // -x
    quad(p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1));  // +x
    quad(p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1));  // -y
    quad(p(0, 1, 0), p(0, 1, 1), p(1, 1, 1), p(1, 1, 0));  // +y
    quad(p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0));  // -z
    quad(p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1));  // +z
  }
  void box(Vec3 lo, Vec3 hi) { box(Frame(), lo, hi); }

  // Closed cylinder (or frustum when r1 != r0) along +Y from `base`, `seg` sides: 4 * seg triangles.
  void cylinder(const Frame& f, Vec3 base, double r0, double h, int seg, double r1 = -1) {
    if (r1 < 0) r1 = r0;
    const Vec3 cb = f(base), ct = f(base + Vec3{0, h, 0});
    auto ring = [&](int i, double r, double y) {
      double s, c;
      sincos(2 * kPi * (i % seg) / seg, s, c);
      return f(base + Vec3{r * c, y, r * s});
    };
    for (int i = 0; i < seg; ++i) {
      const Vec3 b0 = ring(i, r0, 0), b1 = ring(i + 1, r0, 0), t0 = ring(i, r1, h), t1 = ring(i + 1, r1, h);
      quad(b0, t0, t1, b1);
      tri(ct, t1, t0);
      tri(cb, b0, b1);
    }
  }

  // Closed UV sphere, `stacks` rings x `slices` segments: 2 * slices * (stacks - 1) triangles. The
  // optional `radius` gives the radius per unit direction (a bumpy blob).
  void sphere(const Frame& f, Vec3 c, double r, int stacks, int slices,
              const std::function<double(Vec3)>& radius = nullptr) {
    auto pt = [&](int i, int j) {
      double sp, cp, st, ct;
      sincos(kPi * i / stacks, sp, cp);
      sincos(2 * kPi * (j % slices) / slices, st, ct);
      const Vec3 d{sp * ct, cp, sp * st};
      const double rr = radius ? radius(d) : r;
      return f(c + d * rr);
    };
    const Vec3 top = pt(0, 0), bottom = pt(stacks, 0), centre = f(c);
    for (int j = 0; j < slices; ++j) {
      outward(top, pt(1, j), pt(1, j + 1), centre);
      outward(bottom, pt(stacks - 1, j + 1), pt(stacks - 1, j), centre);
      for (int i = 1; i < stacks - 1; ++i) {
        const Vec3 a = pt(i, j), b = pt(i + 1, j), cc = pt(i + 1, j + 1), d = pt(i, j + 1);
        outward(a, b, cc, centre);
        outward(a, cc, d, centre);
      }
    }
  }

  // A planar grid of nu x nv quads from `o` spanned by `u` and `v` (2 nu nv triangles), front along u x v.
  void grid(Vec3 o, Vec3 u, Vec3 v, int nu, int nv) {
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) {
        const Vec3 a = o + u * (double(i) / nu) + v * (double(j) / nv);
        const Vec3 b = o + u * (double(i + 1) / nu) + v * (double(j) / nv);
        const Vec3 c = o + u * (double(i + 1) / nu) + v * (double(j + 1) / nv);
        const Vec3 d = o + u * (double(i) / nu) + v * (double(j + 1) / nv);
        quad(a, b, c, d);
      }
  }

  Scene& scene() { return s_; }
  Scene finish() {
    close_part();
    return std::move(s_);
  }

 private:
  void outward(Vec3 a, Vec3 b, Vec3 c, Vec3 centre) {
    const Vec3 m = (a + b + c) * (1.0 / 3);
    if (hls::dot(hls::cross(b - a, c - a), m - centre) < 0) tri(a, c, b);
    else tri(a, b, c);
  }
  void close_part() {
    if (!s_.meshes.empty()) s_.meshes.back().count = s_.tris.size() - s_.meshes.back().first;
  }
  Scene s_;
};

}  // namespace raycore::scenes::gen
