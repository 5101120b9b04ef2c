// Small procedural meshes and scenes for the reference's tests (deterministic, double precision).
#pragma once

#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "scenes/scene.h"

namespace raycore::reference::testing {

using hls::Tri;
using hls::Vec3;

// The cube [-h, h]^3 (h a power of two keeps every coordinate exact), each face split along a
// diagonal: 12 triangles sharing edges and corners exactly.
inline std::vector<Tri> cube(double h = 1.0) {
  std::vector<Tri> out;
  for (int axis = 0; axis < 3; ++axis)
    for (int s = -1; s <= 1; s += 2) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      Vec3 c[4];
      const double uv[4][2] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
      for (int i = 0; i < 4; ++i) {
        c[i][axis] = s * h;
        c[i][u] = uv[i][0];
        c[i][v] = uv[i][1];
      }
      out.push_back({c[0], c[1], c[2]});
      out.push_back({c[0], c[2], c[3]});
    }
  return out;
}

// An icosphere of radius r about `centre`: the icosahedron subdivided `levels` times, vertices
// shared by index (so shared edges have identical coordinates in both triangles).
inline std::vector<Tri> icosphere(int levels, double r = 1.0, Vec3 centre = {}) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v) p = hls::normalize(p);
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(hls::normalize(v[size_t(key.first)] + v[size_t(key.second)]));
      return mid[key] = int(v.size() - 1);
    };
    std::vector<std::array<int, 3>> g;
    for (const auto& q : f) {
      const int a = midpoint(q[0], q[1]), b = midpoint(q[1], q[2]), c = midpoint(q[2], q[0]);
      g.push_back({q[0], a, c});
      g.push_back({q[1], b, a});
      g.push_back({q[2], c, b});
      g.push_back({a, b, c});
    }
    f = g;
  }
  std::vector<Tri> out;
  for (const auto& q : f)
    out.push_back({v[size_t(q[0])] * r + centre, v[size_t(q[1])] * r + centre, v[size_t(q[2])] * r + centre});
  return out;
}

// An axis-aligned quad (two triangles, diagonal from corner 0 to corner 2) in the plane
// coordinate[axis] = level, spanning [lo_u, hi_u] x [lo_v, hi_v] in the other two axes.
inline std::vector<Tri> quad(int axis, double level, double lo_u, double hi_u, double lo_v, double hi_v) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  Vec3 c[4];
  const double uv[4][2] = {{lo_u, lo_v}, {hi_u, lo_v}, {hi_u, hi_v}, {lo_u, hi_v}};
  for (int i = 0; i < 4; ++i) {
    c[i][axis] = level;
    c[i][u] = uv[i][0];
    c[i][v] = uv[i][1];
  }
  return {{c[0], c[1], c[2]}, {c[0], c[2], c[3]}};
}

inline void append(std::vector<Tri>& a, const std::vector<Tri>& b) { a.insert(a.end(), b.begin(), b.end()); }

// A camera at `eye` looking at `target`, +Y up.
inline scenes::Camera look_at(Vec3 eye, Vec3 target, double yfov_deg = 50.0) {
  scenes::Camera c;
  c.present = true;
  c.position = eye;
  c.forward = hls::normalize(target - eye);
  c.right = hls::normalize(hls::cross(c.forward, Vec3{0, 1, 0}));
  c.up = hls::cross(c.right, c.forward);
  c.yfov = yfov_deg * M_PI / 180.0;
  return c;
}

inline scenes::Scene make_scene(std::vector<Tri> tris, scenes::Camera cam, Vec3 light) {
  scenes::Scene s;
  s.name = "test";
  s.source = "generated";
  s.tris = std::move(tris);
  s.camera = cam;
  s.light.present = true;
  s.light.position = light;
  return s;
}

// A small test world: a floor, a box (cube), an icosphere and a hovering plate, lit from above.
inline scenes::Scene test_world() {
  std::vector<Tri> t = quad(1, 0.0, -20, 20, -20, 20);
  for (Tri& tri : cube(1.0))
    t.push_back({tri[0] + Vec3{-3, 1, 0}, tri[1] + Vec3{-3, 1, 0}, tri[2] + Vec3{-3, 1, 0}});
  append(t, icosphere(3, 1.5, {2, 1.5, -1}));
  append(t, quad(1, 4.0, -1, 1, 2, 4));
  return make_scene(t, look_at({0, 6, 12}, {0, 1, 0}), {3, 12, 6});
}

}  // namespace raycore::reference::testing
