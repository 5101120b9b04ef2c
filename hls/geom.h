// hls/geom.h - double-precision geometry shared by the scene loader, the kd-tree builder and the
// double-precision reference. (The hardware's numbers are in hls/fp.h; this is the host side.)
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace raycore::hls {

struct Vec3 {
  double x = 0, y = 0, z = 0;
  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};
constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
constexpr Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator*(double s, Vec3 a) { return a * s; }
constexpr double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) { return a * (1.0 / length(a)); }
inline bool is_finite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

struct Box {
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL};
  Vec3 hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(Vec3 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  void extend(const Box& b) {
    extend(b.lo);
    extend(b.hi);
  }
  double area() const {
    if (empty()) return 0;
    const Vec3 d = hi - lo;
    return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
  }
};

using Tri = std::array<Vec3, 3>;

}  // namespace raycore::hls
