// tb/hls/test_util.h - random scenes and an independent triangle/box overlap test for the hls tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "hls/geom.h"

namespace raycore::hls::test {

using Rng = std::mt19937_64;

inline double uni(Rng& r, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(r);
}

// A random triangle: vertices within `size` of a centre; reasonably shaped unless the rng says not.
inline Tri random_tri(Rng& r, const Vec3& centre, double size) {
  Tri t;
  for (Vec3& v : t)
    v = {centre.x + uni(r, -size, size), centre.y + uni(r, -size, size),
         centre.z + uni(r, -size, size)};
  return t;
}

// A random scene that stresses the builder: mixed sizes (tiny to scene-spanning), vertices on an
// integer grid (so triangles touch split planes exactly), axis-aligned planar triangles, duplicates,
// and coordinates that are not representable in FP24.
inline std::vector<Tri> random_scene(uint64_t seed, int n, double extent = 100.0) {
  Rng r(seed);
  std::vector<Tri> tris;
  while (int(tris.size()) < n) {
    const int kind = int(r() % 6);
    const Vec3 c{uni(r, -extent, extent), uni(r, -extent, extent), uni(r, -extent, extent)};
    switch (kind) {
      case 0:  // small, arbitrary
        tris.push_back(random_tri(r, c, extent * 0.02));
        break;
      case 1:  // large
        tris.push_back(random_tri(r, c, extent * 0.5));
        break;
      case 2: {  // on an integer grid
        Tri t = random_tri(r, c, extent * 0.1);
        for (Vec3& v : t) v = {std::round(v.x), std::round(v.y), std::round(v.z)};
        tris.push_back(t);
        break;
      }
      case 3: {  // axis-aligned planar (all three vertices share one coordinate), grid-aligned
        Tri t = random_tri(r, c, extent * 0.1);
        const int a = int(r() % 3);
        const double p = std::round(c[a]);
        for (Vec3& v : t) {
          v[a] = p;
          for (int i = 0; i < 3; ++i) v[i] = std::round(v[i] * 4) / 4;
        }
        tris.push_back(t);
        break;
      }
      case 4:  // a duplicate of an earlier triangle
        if (!tris.empty()) tris.push_back(tris[r() % tris.size()]);
        break;
      default: {  // a sliver
        Tri t = random_tri(r, c, extent * 0.2);
        t[2] = t[0] + (t[1] - t[0]) * uni(r, 0, 1) + Vec3{uni(r, -1e-3, 1e-3), 0, 0};
        tris.push_back(t);
        break;
      }
    }
  }
  return tris;
}

// Akenine-Moeller's separating-axis test: does triangle t meet the closed box b? (touching counts)
inline bool tri_box_overlap(const Tri& t, const Box& b) {
  if (b.empty()) return false;
  const Vec3 c = (b.lo + b.hi) * 0.5, h = (b.hi - b.lo) * 0.5;
  const Vec3 v[3] = {t[0] - c, t[1] - c, t[2] - c};
  for (int a = 0; a < 3; ++a) {
    const double mn = std::min({v[0][a], v[1][a], v[2][a]});
    const double mx = std::max({v[0][a], v[1][a], v[2][a]});
    if (mn > h[a] || mx < -h[a]) return false;
  }
  const Vec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  auto separated = [&](const Vec3& ax) {
    const double p0 = dot(v[0], ax), p1 = dot(v[1], ax), p2 = dot(v[2], ax);
    const double r = h.x * std::fabs(ax.x) + h.y * std::fabs(ax.y) + h.z * std::fabs(ax.z);
    return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
  };
  const Vec3 n = cross(e[0], e[1]);
  if (separated(n)) return false;
  const Vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const Vec3& ei : e)
    for (const Vec3& aj : axes) {
      const Vec3 ax = cross(ei, aj);
      if (dot(ax, ax) == 0) continue;
      if (separated(ax)) return false;
    }
  return true;
}

inline bool point_in_closed_box(const Vec3& p, const Box& b) {
  for (int a = 0; a < 3; ++a)
    if (!(b.lo[a] <= p[a] && p[a] <= b.hi[a])) return false;
  return true;
}

// A synthetic stand-in for a furnished interior of about n triangles: a tessellated floor and
// walls, boxes of varied size (furniture), and tessellated spheres; deterministic.
inline std::vector<Tri> synthetic_scene(int n, uint64_t seed = 1) {
  Rng r(seed);
  std::vector<Tri> tris;
  auto quad = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    tris.push_back({a, b, c});
    tris.push_back({a, c, d});
  };
  // Floor and two walls as grids: 3 x 2 x 50 x 50 = 15,000 triangles.
  const int g = 50;
  const double s = 2000.0 / g, h = 600.0 / g;
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j) {
      const double x = -1000 + i * s, z = -1000 + j * s, y = -300 + j * h;
      quad({x, -300, z}, {x + s, -300, z}, {x + s, -300, z + s}, {x, -300, z + s});
      quad({x, y, -1000}, {x + s, y, -1000}, {x + s, y + h, -1000}, {x, y + h, -1000});
      quad({-1000, y, x}, {-1000, y, x + s}, {-1000, y + h, x + s}, {-1000, y + h, x});
    }
  // Boxes: 12 triangles each.
  auto box = [&](Vec3 lo, Vec3 hi) {
    const Vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                       {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    quad(p[0], p[1], p[2], p[3]);
    quad(p[5], p[4], p[7], p[6]);
    quad(p[4], p[0], p[3], p[7]);
    quad(p[1], p[5], p[6], p[2]);
    quad(p[3], p[2], p[6], p[7]);
    quad(p[4], p[5], p[1], p[0]);
  };
  for (int i = 0; i < 800; ++i) {
    const Vec3 lo{uni(r, -950, 900), uni(r, -300, 200), uni(r, -950, 900)};
    const Vec3 sz{uni(r, 2, 80), uni(r, 2, 100), uni(r, 2, 80)};
    box(lo, lo + sz);
  }
  // Spheres (latitude-longitude) until n triangles.
  while (int(tris.size()) < n) {
    const Vec3 c{uni(r, -900, 900), uni(r, -200, 250), uni(r, -900, 900)};
    const double rad = uni(r, 5, 60);
    const int nu = 32, nv = 16;
    auto pt = [&](int i, int j) {
      const double th = M_PI * j / nv, ph = 2 * M_PI * i / nu;
      return c + Vec3{std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)} * rad;
    };
    for (int i = 0; i < nu && int(tris.size()) < n; ++i)
      for (int j = 0; j < nv && int(tris.size()) < n; ++j) {
        if (j > 0) tris.push_back({pt(i, j), pt(i + 1, j), pt(i + 1, j + 1)});
        if (j < nv - 1 && int(tris.size()) < n) tris.push_back({pt(i, j), pt(i + 1, j + 1), pt(i, j + 1)});
      }
  }
  return tris;
}

}  // namespace raycore::hls::test
