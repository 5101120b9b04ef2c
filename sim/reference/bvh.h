// sim/reference/bvh.h - the double-precision reference's own acceleration structure and its
// watertight ray/triangle test.
//
// - Triangles: the scene's double-precision vertices, untouched.
// - Ray/triangle: Woop, Benthin, Wald 2013 ("Watertight ray/triangle intersection", JCGT 2(1)),
//   in double: shear the ray to +z, project each vertex once (a per-vertex function, so a shared
//   edge projects identically for both triangles), and take the signs of the 2D edge functions
//   EXACTLY (edge_function: a filtered evaluation with Kahan's fused-multiply-add difference of
//   products as the fallback; this replaces and strengthens the paper's "recompute in higher
//   precision when an edge function is 0"). A ray through a shared edge or vertex of a closed mesh
//   therefore hits at least one of the triangles around it. Where an edge function lies within the
//   error bound of the projected vertices' own rounding (the ray passes that close to the edge),
//   its sign is the exact ray's (sheared_edge_sign, MPFR; since 2026-12-07): a ray exactly on an
//   edge is on it (inside), whatever the double shear says; a shared edge's two triangles take the
//   same path (the bound is symmetric), so the test stays watertight. Triangles with exactly
//   collinear vertices (zero area) are never hit.
// - BVH: binned SAH (32 bins, leaves of at most 4 references) over references: a large triangle
//   is split into several references with smaller boxes (early split clipping, conservative
//   boxes: see add_references), so a triangle may sit in several leaves. Traversal is conservative (Ize 2013, "Robust BVH ray traversal", JCGT 2(2)): the
//   slab exit distance is widened by 2 gamma(3) relative (pbrt's form), and a node is pruned
//   only when its entry distance exceeds the best hit so far by a relative 2^-30.
// - Closest hit: the smallest t in (t_min, t_max), ties at exactly equal t broken by the lowest
//   scene index, so the answer does not depend on the tree or on traversal order.
#pragma once

#include <cstdint>
#include <vector>

#include "hls/geom.h"

namespace raycore::reference {

using hls::Tri;
using hls::Vec3;

struct Ray {
  Vec3 org;
  Vec3 dir;  // any non-zero length; t is measured in units of |dir|
};

// A hit: t along the ray, barycentric weights (b0 of vertex 0, b1 of vertex 1, b2 of vertex 2;
// they sum to 1 up to rounding), and the scene index of the triangle.
struct TriHit {
  int32_t tri = -1;
  double t = 0;
  double b0 = 0, b1 = 0, b2 = 0;
};

// The ray, sheared and permuted once for the watertight test.
struct ShearedRay {
  Vec3 org, dir;
  int kx = 0, ky = 1, kz = 2;
  double sx = 0, sy = 0, sz = 1;
  explicit ShearedRay(const Ray& r);
};

// Watertight test of one triangle: true when the ray hits it at t in (t_min, t_max); fills
// `hit` (t and barycentrics; hit->tri is left alone).
bool intersect_triangle(const ShearedRay& ray, const Tri& tri, double t_min, double t_max, TriHit* hit);

// Decides whether a candidate hit is ignored (used by the shadow test to skip the surface the
// ray starts on). Called only for triangles the ray hits within the interval.
struct HitFilter {
  virtual ~HitFilter() = default;
  virtual bool skip(int32_t tri) const = 0;
};

struct BvhStats {
  uint64_t nodes = 0, leaves = 0, depth = 0, degenerate = 0;
  uint64_t references = 0;  // leaf entries (a large triangle is split into several)
};

class Bvh {
 public:
  // Copies the triangles. Throws std::runtime_error naming the triangle if a coordinate is not
  // finite.
  explicit Bvh(const std::vector<Tri>& tris);

  // The closest hit with t in (t_min, t_max), or tri = -1.
  TriHit closest(const Ray& ray, double t_min, double t_max, const HitFilter* filter = nullptr) const;

  const Tri& triangle(int32_t scene_index) const { return tris_[size_t(scene_index)]; }
  size_t size() const { return tris_.size(); }
  const BvhStats& stats() const { return stats_; }

 private:
  struct Node {
    Vec3 lo, hi;
    int32_t first = 0;  // leaf: first entry in order_; inner: index of the left child (right = +1)
    int32_t count = 0;  // leaf: number of triangles (> 0); inner: 0
    int32_t axis = 0;   // inner: split axis (visit order)
  };
  void add_references(int32_t tri, double split_area, std::vector<hls::Box>& boxes);
  void build(const std::vector<Vec3>& centroid, const std::vector<hls::Box>& box);

  std::vector<Tri> tris_;           // scene order
  std::vector<int32_t> order_;      // leaf entries -> scene index
  std::vector<int32_t> ref_tri_;    // during the build: reference -> scene index
  std::vector<Node> nodes_;
  BvhStats stats_;
};

}  // namespace raycore::reference
