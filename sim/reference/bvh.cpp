// sim/reference/bvh.cpp - see bvh.h.
#include "sim/reference/bvh.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/reference/predicates.h"

namespace raycore::reference {
namespace {

constexpr double kEps = DBL_EPSILON / 2;  // unit roundoff
constexpr double gamma(int n) { return n * kEps / (1 - n * kEps); }
constexpr int kBins = 32;
constexpr int kLeafSize = 4;
constexpr int kStackSize = 256;
// Early split clipping: triangles whose box area exceeds this fraction of the scene box's are
// split, at most kMaxSplitDepth times (up to 2^kMaxSplitDepth references).
constexpr double kSplitAreaFraction = 0x1p-12;
constexpr int kMaxSplitDepth = 6;
// A node is pruned only if its entry distance exceeds the best hit by this relative margin, which
// covers the rounding of both the slab test and the triangle test's t (a few ulps each).
constexpr double kPruneSlack = 1.0 + 0x1p-30;

}  // namespace

ShearedRay::ShearedRay(const Ray& r) : org(r.org), dir(r.dir) {
  // Largest direction component -> z; keep the winding by swapping x and y when it is negative.
  const double ax = std::fabs(r.dir.x), ay = std::fabs(r.dir.y), az = std::fabs(r.dir.z);
  kz = (ax > ay) ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
  kx = (kz + 1) % 3;
  ky = (kx + 1) % 3;
  if (r.dir[kz] < 0) std::swap(kx, ky);
  sx = r.dir[kx] / r.dir[kz];
  sy = r.dir[ky] / r.dir[kz];
  sz = 1.0 / r.dir[kz];
}

bool intersect_triangle(const ShearedRay& ray, const Tri& tri, double t_min, double t_max, TriHit* hit) {
  // Vertices relative to the ray origin, then sheared: each vertex's 2D position depends on that
  // vertex and the ray alone.
  const Vec3 a = tri[0] - ray.org, b = tri[1] - ray.org, c = tri[2] - ray.org;
  const double ax = a[ray.kx] - ray.sx * a[ray.kz], ay = a[ray.ky] - ray.sy * a[ray.kz];
  const double bx = b[ray.kx] - ray.sx * b[ray.kz], by = b[ray.ky] - ray.sy * b[ray.kz];
  const double cx = c[ray.kx] - ray.sx * c[ray.kz], cy = c[ray.ky] - ray.sy * c[ray.kz];

  // Edge functions with exact signs (the watertightness): U opposite vertex 0, V vertex 1, W
  // vertex 2.
  const double u = edge_function(cx, by, cy, bx);
  const double v = edge_function(ax, cy, ay, cx);
  const double w = edge_function(bx, ay, by, ax);
  // Those are exact for the projected vertices, which are rounded (a - org once, the shear's
  // quotient, product and difference): a projected x moves by at most 6 eps Sx, Sx = |a_kx| +
  // |sx a_kz| (eps = 2^-53; y likewise), so an edge function x_q y_p - y_q x_p by at most 12 eps
  // (Sx_q Sy_p + Sx_p Sy_q) beside its own rounding (3 eps of the same): 32 eps of it bounds both.
  // Within that bound of zero, the exact ray decides its sign.
  constexpr double eps = 0x1p-53;
  const double sx[3] = {std::fabs(a[ray.kx]) + std::fabs(ray.sx * a[ray.kz]),
                        std::fabs(b[ray.kx]) + std::fabs(ray.sx * b[ray.kz]),
                        std::fabs(c[ray.kx]) + std::fabs(ray.sx * c[ray.kz])};
  const double sy[3] = {std::fabs(a[ray.ky]) + std::fabs(ray.sy * a[ray.kz]),
                        std::fabs(b[ray.ky]) + std::fabs(ray.sy * b[ray.kz]),
                        std::fabs(c[ray.ky]) + std::fabs(ray.sy * c[ray.kz])};
  auto sign = [&](double e, int p, int q) {
    if (std::fabs(e) > 32 * eps * (sx[q] * sy[p] + sx[p] * sy[q])) return e > 0 ? 1 : -1;
    return sheared_edge_sign(ray.org, ray.dir, ray.kx, ray.ky, ray.kz, tri[size_t(p)], tri[size_t(q)]);
  };
  const int su = sign(u, 1, 2), sv = sign(v, 2, 0), sw = sign(w, 0, 1);
  if ((su < 0 || sv < 0 || sw < 0) && (su > 0 || sv > 0 || sw > 0)) return false;
  const double det = u + v + w;
  if (det == 0) return false;  // ray parallel to the plane, or the point on a degenerate edge

  // Scaled distance; the division comes last, only for a candidate that may be kept.
  const double az = ray.sz * a[ray.kz], bz = ray.sz * b[ray.kz], cz = ray.sz * c[ray.kz];
  const double tt = u * az + v * bz + w * cz;
  const double inv_det = 1.0 / det;
  const double t = tt * inv_det;
  if (!(t > t_min && t < t_max)) return false;
  hit->t = t;
  hit->b0 = u * inv_det;
  hit->b1 = v * inv_det;
  hit->b2 = w * inv_det;
  return true;
}

namespace {

using Polygon = std::vector<Vec3>;

// The part of a convex polygon with coordinate[axis] <= pos (keep_below) or >= pos. Intersection
// points get exactly `pos` on the axis; their other coordinates are rounded (a few ulps).
Polygon clip(const Polygon& poly, int axis, double pos, bool keep_below) {
  Polygon out;
  auto inside = [&](const Vec3& p) { return keep_below ? p[axis] <= pos : p[axis] >= pos; };
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec3& a = poly[i];
    const Vec3& b = poly[(i + 1) % poly.size()];
    const bool ia = inside(a), ib = inside(b);
    if (ia) out.push_back(a);
    if (ia != ib && a[axis] != b[axis]) {
      const double f = (pos - a[axis]) / (b[axis] - a[axis]);
      Vec3 x = a + (b - a) * f;
      x[axis] = pos;
      out.push_back(x);
    }
  }
  return out;
}

hls::Box widened(hls::Box b, double margin) {
  b.lo = b.lo - Vec3{margin, margin, margin};
  b.hi = b.hi + Vec3{margin, margin, margin};
  return b;
}

hls::Box intersect(const hls::Box& a, const hls::Box& b) {
  hls::Box r;
  for (int k = 0; k < 3; ++k) {
    r.lo[k] = std::max(a.lo[k], b.lo[k]);
    r.hi[k] = std::min(a.hi[k], b.hi[k]);
  }
  return r;
}

}  // namespace

// Early split clipping (Ernst & Greiner 2007): a triangle whose box is large is referenced by
// several smaller boxes that together cover it, so that large triangles (Sponza's floors and
// walls) do not inflate every node above them. The pieces are the triangle clipped at box
// midplanes; since the clipped coordinates are rounded, every piece's box is its polygon's bounds
// widened by a margin (2^-40 of the largest coordinate, far above the few ulps of error) and
// clipped to its half-box widened by the same margin: together they cover the exact triangle.
void Bvh::add_references(int32_t tri, double split_area, std::vector<hls::Box>& boxes) {
  struct Piece {
    Polygon poly;
    hls::Box box;
    int depth;
  };
  const Tri& t = tris_[size_t(tri)];
  hls::Box tb;
  for (const Vec3& p : t) tb.extend(p);
  std::vector<Piece> work{{Polygon{t[0], t[1], t[2]}, tb, 0}};
  while (!work.empty()) {
    Piece pc = std::move(work.back());
    work.pop_back();
    const Vec3 ext = pc.box.hi - pc.box.lo;
    if (pc.depth >= kMaxSplitDepth || pc.box.area() <= split_area) {
      boxes.push_back(pc.box);
      ref_tri_.push_back(tri);
      continue;
    }
    const int axis = ext.x >= ext.y ? (ext.x >= ext.z ? 0 : 2) : (ext.y >= ext.z ? 1 : 2);
    const double pos = 0.5 * (pc.box.lo[axis] + pc.box.hi[axis]);
    double mag = 0;
    for (int k = 0; k < 3; ++k) mag = std::max({mag, std::fabs(pc.box.lo[k]), std::fabs(pc.box.hi[k])});
    const double margin = mag * 0x1p-40 + 0x1p-1000;
    for (int side = 0; side < 2; ++side) {
      Polygon q = clip(pc.poly, axis, pos, side == 0);
      if (q.empty()) continue;
      hls::Box qb, half = pc.box;
      for (const Vec3& p : q) qb.extend(p);
      (side == 0 ? half.hi : half.lo)[axis] = pos;
      const hls::Box b = intersect(widened(qb, margin), widened(half, margin));
      if (b.empty()) continue;
      work.push_back({std::move(q), b, pc.depth + 1});
    }
  }
}

Bvh::Bvh(const std::vector<Tri>& tris) : tris_(tris) {
  if (tris_.size() > size_t(INT32_MAX / 64)) throw std::runtime_error("reference: too many triangles");
  hls::Box scene;
  for (size_t i = 0; i < tris_.size(); ++i) {
    for (const Vec3& p : tris_[i]) {
      if (!hls::is_finite(p))
        throw std::runtime_error("reference: triangle " + std::to_string(i) +
                                 " has a coordinate that is not finite");
      scene.extend(p);
    }
  }
  const double split_area = scene.area() * kSplitAreaFraction;
  std::vector<hls::Box> box;
  for (size_t i = 0; i < tris_.size(); ++i) {
    const Tri& t = tris_[i];
    if (is_degenerate(t[0], t[1], t[2])) {
      ++stats_.degenerate;
      continue;
    }
    add_references(int32_t(i), split_area, box);
  }
  stats_.references = ref_tri_.size();
  if (ref_tri_.empty()) return;
  std::vector<Vec3> centroid(box.size());
  for (size_t r = 0; r < box.size(); ++r) centroid[r] = (box[r].lo + box[r].hi) * 0.5;
  order_.resize(ref_tri_.size());
  for (size_t r = 0; r < order_.size(); ++r) order_[r] = int32_t(r);
  build(centroid, box);
  for (int32_t& e : order_) e = ref_tri_[size_t(e)];  // leaf entries: scene indices
  ref_tri_.clear();
  ref_tri_.shrink_to_fit();
}

// Top-down binned SAH build with an explicit work list (no recursion), depth first: a node's two
// children are adjacent in nodes_.
void Bvh::build(const std::vector<Vec3>& centroid, const std::vector<hls::Box>& box) {
  struct Work {
    int32_t node, begin, end;
    uint64_t depth;
  };
  nodes_.reserve(2 * order_.size() / kLeafSize + 2);
  nodes_.emplace_back();
  std::vector<Work> work{{0, 0, int32_t(order_.size()), 1}};
  while (!work.empty()) {
    const Work wk = work.back();
    work.pop_back();
    stats_.depth = std::max(stats_.depth, wk.depth);
    hls::Box bounds, cbounds;
    for (int32_t i = wk.begin; i < wk.end; ++i) {
      bounds.extend(box[size_t(order_[size_t(i)])]);  // order_ holds reference indices here
      cbounds.extend(centroid[size_t(order_[size_t(i)])]);
    }
    Node& n = nodes_[size_t(wk.node)];
    n.lo = bounds.lo;
    n.hi = bounds.hi;
    const int32_t count = wk.end - wk.begin;
    auto make_leaf = [&] {
      Node& leaf = nodes_[size_t(wk.node)];
      leaf.first = wk.begin;
      leaf.count = count;
      ++stats_.leaves;
    };
    if (count <= kLeafSize) {
      make_leaf();
      continue;
    }
    // Best binned SAH split over the three axes.
    double best_cost = HUGE_VAL;
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const double lo = cbounds.lo[axis], extent = cbounds.hi[axis] - lo;
      if (!(extent > 0)) continue;
      hls::Box bin_box[kBins];
      int64_t bin_count[kBins] = {};
      const double scale = kBins / extent;
      auto bin_of = [&](int32_t tri) {
        const int b = int((centroid[size_t(tri)][axis] - lo) * scale);
        return std::clamp(b, 0, kBins - 1);
      };
      for (int32_t i = wk.begin; i < wk.end; ++i) {
        const int b = bin_of(order_[size_t(i)]);
        ++bin_count[b];
        bin_box[b].extend(box[size_t(order_[size_t(i)])]);
      }
      double right_area[kBins];
      int64_t right_count[kBins];
      hls::Box acc;
      int64_t cnt = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.extend(bin_box[b]);
        cnt += bin_count[b];
        right_area[b] = acc.area();
        right_count[b] = cnt;
      }
      acc = hls::Box();
      cnt = 0;
      for (int b = 1; b < kBins; ++b) {  // split between bin b-1 and bin b
        acc.extend(bin_box[b - 1]);
        cnt += bin_count[b - 1];
        if (cnt == 0 || right_count[b] == 0) continue;
        const double cost = acc.area() * double(cnt) + right_area[b] * double(right_count[b]);
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_bin = b;
        }
      }
    }
    int32_t mid = 0;
    int axis = 0;
    if (best_axis >= 0) {
      axis = best_axis;
      const double lo = cbounds.lo[axis], scale = kBins / (cbounds.hi[axis] - lo);
      auto* first = order_.data() + wk.begin;
      auto* pivot = std::stable_partition(first, order_.data() + wk.end, [&](int32_t tri) {
        return std::clamp(int((centroid[size_t(tri)][axis] - lo) * scale), 0, kBins - 1) < best_bin;
      });
      mid = int32_t(pivot - order_.data());
    } else {
      // All centroids coincide: split the list in halves (keeps leaves small).
      mid = wk.begin + count / 2;
    }
    const int32_t left = int32_t(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    Node& inner = nodes_[size_t(wk.node)];  // re-fetch: emplace_back may have reallocated
    inner.first = left;
    inner.count = 0;
    inner.axis = axis;
    work.push_back({left + 1, mid, wk.end, wk.depth + 1});
    work.push_back({left, wk.begin, mid, wk.depth + 1});
  }
  stats_.nodes = nodes_.size();
}

TriHit Bvh::closest(const Ray& ray, double t_min, double t_max, const HitFilter* filter) const {
  TriHit best;
  best.t = t_max;
  if (nodes_.empty()) return best;
  const ShearedRay sheared(ray);
  double inv[3];
  bool zero[3];
  for (int k = 0; k < 3; ++k) {
    zero[k] = ray.dir[k] == 0;
    inv[k] = zero[k] ? 0.0 : 1.0 / ray.dir[k];
  }
  const double widen = 1.0 + 2.0 * gamma(3);  // Ize / pbrt: conservative slab exit
  auto box_entry = [&](const Node& n, double limit, double* entry) {
    double t0 = 0, t1 = limit;
    for (int k = 0; k < 3; ++k) {
      if (zero[k]) {
        if (ray.org[k] < n.lo[k] || ray.org[k] > n.hi[k]) return false;
        continue;
      }
      double tn = (n.lo[k] - ray.org[k]) * inv[k];
      double tf = (n.hi[k] - ray.org[k]) * inv[k];
      if (tn > tf) std::swap(tn, tf);
      tf *= widen;
      t0 = tn > t0 ? tn : t0;
      t1 = tf < t1 ? tf : t1;
      if (t0 > t1) return false;
    }
    *entry = t0;
    return true;
  };

  int32_t stack[kStackSize];
  double stack_entry[kStackSize];
  int sp = 0;
  int32_t current = 0;
  double entry = 0;
  if (!box_entry(nodes_[0], t_max * kPruneSlack, &entry)) return best;
  for (;;) {
    const Node& n = nodes_[size_t(current)];
    if (n.count > 0) {
      for (int32_t i = n.first; i < n.first + n.count; ++i) {
        const int32_t id = order_[size_t(i)];
        TriHit h;
        // Candidates at exactly the best t are kept too (ties go to the lowest index).
        const double hi = best.tri >= 0 ? std::nextafter(best.t, HUGE_VAL) : t_max;
        if (!intersect_triangle(sheared, tris_[size_t(id)], t_min, hi, &h)) continue;
        if (best.tri >= 0 && !(h.t < best.t || id < best.tri)) continue;
        if (filter && filter->skip(id)) continue;
        h.tri = id;
        best = h;
      }
    } else {
      const int32_t near_child = ray.dir[n.axis] >= 0 ? n.first : n.first + 1;
      const int32_t far_child = ray.dir[n.axis] >= 0 ? n.first + 1 : n.first;
      const double limit = best.t * kPruneSlack;
      double e_near = 0, e_far = 0;
      const bool hit_near = box_entry(nodes_[size_t(near_child)], limit, &e_near);
      const bool hit_far = box_entry(nodes_[size_t(far_child)], limit, &e_far);
      if (hit_near && hit_far) {
        if (sp >= kStackSize) throw std::logic_error("reference: BVH traversal stack overflow");
        stack_entry[sp] = e_far;
        stack[sp++] = far_child;
        current = near_child;
        continue;
      }
      if (hit_near || hit_far) {
        current = hit_near ? near_child : far_child;
        continue;
      }
    }
    // Pop the next node that can still hold a closer hit.
    for (;;) {
      if (sp == 0) return best;
      --sp;
      if (stack_entry[sp] <= best.t * kPruneSlack) break;
    }
    current = stack[sp];
  }
  return best;
}

}  // namespace raycore::reference
