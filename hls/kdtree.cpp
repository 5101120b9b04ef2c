// hls/kdtree.cpp - SAH kd-tree builder with perfect splits; see kdtree.h and docs/image.md.
#include "hls/kdtree.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace raycore::hls {
namespace {

constexpr uint64_t index_limit = uint64_t(1) << 24;  // 24-bit node and list indices

// A triangle's reference in a node: its index, its box clipped to the node's cell, and the box of
// the triangle the hardware tests (its stored vertices) clipped to the cell; a box is empty where
// its triangle misses the cell (sb always, when the records hold no vertices).
struct Ref {
  uint32_t tri;
  Box b, sb;
};

Box tri_box(const Tri& t) {
  Box b;
  for (const Vec3& v : t) b.extend(v);
  return b;
}

Box intersect(const Box& a, const Box& c) {
  Box r;
  for (int i = 0; i < 3; ++i) {
    r.lo[i] = std::max(a.lo[i], c.lo[i]);
    r.hi[i] = std::min(a.hi[i], c.hi[i]);
  }
  return r;
}

// Sutherland-Hodgman against one plane: keep x[axis] >= bound (keep_above) or <= bound.
int clip_plane(const Vec3* in, int n, Vec3* out, int axis, double bound, bool keep_above) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3& p = in[i];
    const Vec3& q = in[(i + 1) % n];
    const bool pin = keep_above ? p[axis] >= bound : p[axis] <= bound;
    const bool qin = keep_above ? q[axis] >= bound : q[axis] <= bound;
    if (pin) out[m++] = p;
    if (pin != qin) {
      const double t = (bound - p[axis]) / (q[axis] - p[axis]);
      Vec3 r = p + (q - p) * t;
      r[axis] = bound;
      out[m++] = r;
    }
  }
  return m;
}

double area(const Box& b) { return b.empty() ? 0.0 : b.area(); }

struct Builder {
  const std::vector<Tri>& tris;
  const std::vector<Tri>* stored;  // null: the records hold no vertices (the tree is over tris)
  const Quantizer& q;
  const BuildOptions& opt;
  int max_depth;
  double root_area;
  KdTree tree;
  TreeStats st;

  void leaf(const std::vector<Ref>& refs, const Box& cell, int depth) {
    KdNode n;
    n.leaf = true;
    n.count = uint32_t(refs.size());
    n.first = refs.empty() ? 0u : uint32_t(tree.list.size());
    for (const Ref& r : refs) tree.list.push_back(r.tri);
    if (tree.list.size() > index_limit)
      throw std::runtime_error("kd-tree: more than 2^24 leaf-list entries (the node's 24-bit index)");
    tree.nodes.push_back(n);
    ++st.leaves;
    if (refs.empty()) ++st.empty_leaves;
    st.max_leaf = std::max<uint64_t>(st.max_leaf, refs.size());
    st.max_depth = std::max(st.max_depth, depth);
    st.sah_cost += opt.cost_intersect * double(refs.size()) * prob(cell);
  }

  double prob(const Box& cell) const { return root_area > 0 ? area(cell) / root_area : 1.0; }

  struct Split {
    double cost;
    int axis = -1;
    uint32_t bits = 0;
    double pos = 0;
  };

  Split find_split(const std::vector<Ref>& refs, const Box& cell) {
    const size_t n = refs.size();
    const double a0 = area(cell);
    Split best;
    best.cost = opt.split_ratio * opt.cost_intersect * double(n);  // a split must beat the leaf
    if (!(a0 > 0)) return best;
    // A reference goes left when its scene box's lo <= s or its stored box's lo < s (build), so
    // its left bound is the smaller of the two, compared non-strictly (los) or, when the stored
    // one is smaller, strictly (slos); the same for the right (his: hi < s does not go right;
    // shis: hi <= s does not). Without stored triangles slos and shis stay empty.
    std::vector<double> los, his, slos, shis;
    los.reserve(n);
    his.reserve(n);
    struct Cand {
      double s;
      uint32_t bits;
    };
    std::vector<Cand> cands;
    cands.reserve(4 * n);
    for (int a = 0; a < 3; ++a) {
      if (!(cell.lo[a] < cell.hi[a])) continue;
      los.clear();
      his.clear();
      slos.clear();
      shis.clear();
      for (const Ref& r : refs) {
        const bool sc = !r.b.empty(), sd = !r.sb.empty();
        if (sd && (!sc || r.sb.lo[a] < r.b.lo[a])) slos.push_back(r.sb.lo[a]);
        else los.push_back(sc ? r.b.lo[a] : r.sb.lo[a]);
        if (sd && (!sc || r.sb.hi[a] > r.b.hi[a])) shis.push_back(r.sb.hi[a]);
        else his.push_back(sc ? r.b.hi[a] : r.sb.hi[a]);
      }
      std::sort(los.begin(), los.end());
      std::sort(his.begin(), his.end());
      std::sort(slos.begin(), slos.end());
      std::sort(shis.begin(), shis.end());
      // Candidates: the representable planes on both sides of every bound (the rounded bound and,
      // if rounding moved it, its neighbour across the bound), so that the cost can choose the
      // plane that separates a triangle cleanly whatever the rounding policy.
      cands.clear();
      auto add = [&](double b) {
        const uint32_t r = q.round(b);
        const double v = q.value(r);
        cands.push_back({v, r});
        if (v < b) {
          const uint32_t u = q.next_up(r);
          cands.push_back({q.value(u), u});
        } else if (v > b) {
          const uint32_t d = q.next_down(r);
          cands.push_back({q.value(d), d});
        }
      };
      for (double b : los) add(b);
      for (double b : his) add(b);
      for (double b : slos) add(b);
      for (double b : shis) add(b);
      if (stored)  // the stored boxes' own bounds, where the scene's bound was kept
        for (const Ref& r : refs)
          if (!r.sb.empty() && !r.b.empty()) {
            if (r.sb.lo[a] >= r.b.lo[a]) add(r.sb.lo[a]);
            if (r.sb.hi[a] <= r.b.hi[a]) add(r.sb.hi[a]);
          }
      std::sort(cands.begin(), cands.end(), [](const Cand& x, const Cand& y) { return x.s < y.s; });
      const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;
      const double d1 = cell.hi[b1] - cell.lo[b1], d2 = cell.hi[b2] - cell.lo[b2];
      size_t nl = 0, nb = 0, snl = 0, snb = 0;  // #los <= s, #his < s, #slos < s, #shis <= s
      double prev = -HUGE_VAL;
      for (const Cand& c : cands) {
        const uint32_t bits = c.bits;
        const double s = c.s;
        if (!(s > prev)) continue;  // duplicate plane
        prev = s;
        if (!(s > cell.lo[a])) continue;
        if (!(s < cell.hi[a])) break;
        while (nl < los.size() && los[nl] <= s) ++nl;
        while (nb < his.size() && his[nb] < s) ++nb;
        while (snl < slos.size() && slos[snl] < s) ++snl;
        while (snb < shis.size() && shis[snb] <= s) ++snb;
        const size_t nL = nl + snl, nR = n - nb - snb;
        const double wl = s - cell.lo[a], wr = cell.hi[a] - s;
        const double al = 2 * (d1 * d2 + wl * (d1 + d2)), ar = 2 * (d1 * d2 + wr * (d1 + d2));
        const double lambda = (nL == 0 || nR == 0) ? 1.0 - opt.empty_bonus : 1.0;
        const double cost = opt.cost_traversal +
                            opt.cost_intersect * lambda * (al * double(nL) + ar * double(nR)) / a0;
        if (cost < best.cost) {
          best.cost = cost;
          best.axis = a;
          best.bits = bits;
          best.pos = s;
        }
      }
    }
    return best;
  }

  // Whether a triangle with this box goes to the side below (or above) the plane s on axis a: the
  // scene's triangle when it reaches or touches that side, the stored one when it crosses into it
  // (its part on the plane is in the closed cell of the side the scene's triangle goes to). An
  // empty box (the triangle misses the cell) goes nowhere.
  static bool goes(const Box& box, int a, double s, bool below, bool scene) {
    if (scene) return below ? box.lo[a] <= s : box.hi[a] >= s;
    return below ? box.lo[a] < s : box.hi[a] > s;
  }

  // A triangle's box in the closed child cell c (the side below the plane s on axis a, or above
  // it): box itself when it lies on that side, else the triangle clipped to c; empty when it does
  // not reach c.
  static Box part(const Tri& t, const Box& box, const Box& c, int a, double s, bool below) {
    if (!goes(box, a, s, below, true)) return Box{};
    if (below ? box.hi[a] <= s : box.lo[a] >= s) return box;
    const Box nb = intersect(clip_box(t, c), box);
    return nb.empty() ? intersect(box, c) : nb;
  }

  // The reference in a child: both triangles clipped to it, touching included (a stored triangle
  // on the plane stays in the child the scene's triangle took the reference to).
  Ref child(const Ref& r, const Box& c, int a, double s, bool below) const {
    Ref n{r.tri, part(tris[r.tri], r.b, c, a, s, below), {}};
    if (stored) n.sb = part((*stored)[r.tri], r.sb, c, a, s, below);
    return n;
  }

  void build(std::vector<Ref> refs, const Box& cell, int depth) {
    if (refs.size() <= size_t(std::max(opt.leaf_size, 0)) || depth >= max_depth) {
      leaf(refs, cell, depth);
      return;
    }
    const Split sp = find_split(refs, cell);
    if (sp.axis < 0) {
      leaf(refs, cell, depth);
      return;
    }
    const int a = sp.axis;
    Box cl = cell, cr = cell;
    cl.hi[a] = sp.pos;
    cr.lo[a] = sp.pos;
    std::vector<Ref> left, right;
    for (const Ref& r : refs) {
      const double s = sp.pos;
      // (A stored triangle whose scene triangle misses the cell, lying in the plane: left.)
      const bool flat = r.b.empty() && r.sb.lo[a] == s && r.sb.hi[a] == s;
      if (goes(r.b, a, s, true, true) || (stored && goes(r.sb, a, s, true, false)) || flat)
        left.push_back(child(r, cl, a, s, true));
      if (goes(r.b, a, s, false, true) || (stored && goes(r.sb, a, s, false, false)))
        right.push_back(child(r, cr, a, s, false));
    }
    std::vector<Ref>().swap(refs);
    const size_t me = tree.nodes.size();
    KdNode node;
    node.axis = a;
    node.split_bits = sp.bits;
    node.split = sp.pos;
    tree.nodes.push_back(node);
    ++st.inner;
    st.sah_cost += opt.cost_traversal * prob(cell);
    build(std::move(left), cl, depth + 1);
    if (tree.nodes.size() >= index_limit)
      throw std::runtime_error("kd-tree: more than 2^24 nodes (the node's 24-bit right-child index)");
    tree.nodes[me].right = uint32_t(tree.nodes.size());
    build(std::move(right), cr, depth + 1);
  }
};

}  // namespace

int auto_max_depth(uint64_t n) {
  const double d = std::round(8.0 + 1.3 * std::log2(double(std::max<uint64_t>(n, 1))));
  return std::min(int(d), max_tree_depth);
}

Box clip_box(const Tri& t, const Box& cell) {
  const Box tb = intersect(tri_box(t), cell);
  if (tb.empty()) return tb;
  Vec3 buf[2][16];
  for (int i = 0; i < 3; ++i) buf[0][i] = t[i];
  int n = 3, cur = 0;
  for (int a = 0; a < 3 && n > 0; ++a) {
    n = clip_plane(buf[cur], n, buf[1 - cur], a, cell.lo[a], true);
    cur = 1 - cur;
    if (n == 0) break;
    n = clip_plane(buf[cur], n, buf[1 - cur], a, cell.hi[a], false);
    cur = 1 - cur;
  }
  if (n == 0) return Box{};  // empty: the caller decides (the builder falls back to its parent box)
  Box b;
  for (int i = 0; i < n; ++i) b.extend(buf[cur][i]);
  // Widen against the clipper's rounding: every computed vertex is within a few units of 2^-53
  // times the triangle's largest coordinate of an exact one; 2^-36 leaves a wide margin.
  double scale = 0;
  for (const Vec3& v : t)
    for (int i = 0; i < 3; ++i) scale = std::max(scale, std::fabs(v[i]));
  const double eps = std::ldexp(scale, -36);
  for (int i = 0; i < 3; ++i) {
    b.lo[i] -= eps;
    b.hi[i] += eps;
  }
  return intersect(b, tb);
}

KdTree build_kdtree(const std::vector<Tri>& tris, const std::vector<uint8_t>& skip,
                    const Quantizer& q, const BuildOptions& opt, uint32_t root_lo[3],
                    uint32_t root_hi[3], TreeStats* stats, const std::vector<Tri>* stored) {
  if (stored && stored->size() != tris.size())
    throw std::invalid_argument("kd-tree: the stored triangles do not match the scene's");
  std::vector<Ref> refs;
  Box scene;
  for (size_t i = 0; i < tris.size(); ++i) {
    if (!skip.empty() && skip[i]) continue;
    const Box b = tri_box(tris[i]);
    refs.push_back({uint32_t(i), b, stored ? tri_box((*stored)[i]) : Box{}});
    scene.extend(b);
  }
  if (tris.size() > UINT32_MAX) throw std::runtime_error("kd-tree: more than 2^32 triangles");
  if (scene.empty()) scene = Box{{0, 0, 0}, {0, 0, 0}};
  // The root cell: the scene box rounded outward to the format.
  Box cell;
  for (int a = 0; a < 3; ++a) {
    uint32_t lo = q.round(scene.lo[a]), hi = q.round(scene.hi[a]);
    if (q.value(lo) > scene.lo[a]) lo = q.next_down(lo);
    if (q.value(hi) < scene.hi[a]) hi = q.next_up(hi);
    root_lo[a] = lo;
    root_hi[a] = hi;
    cell.lo[a] = q.value(lo);
    cell.hi[a] = q.value(hi);
  }
  // Triangles beyond the format's range are clipped to the (saturated) root cell.
  // (A stored vertex is the scene's rounded with the format's monotone rounding, so the outward
  // rounded box holds it too.)
  for (Ref& r : refs) {
    r.b = intersect(r.b, cell);
    if (stored) r.sb = intersect(r.sb, cell);
  }

  Builder b{tris, stored, q, opt, opt.max_depth > 0 ? std::min(opt.max_depth, max_tree_depth)
                                            : auto_max_depth(refs.size()),
            area(cell), {}, {}};
  b.tree.cell = cell;
  b.st.tree_tris = refs.size();
  b.build(std::move(refs), cell, 0);

  if (stats) {
    TreeStats& s = *stats;
    s.nodes = b.tree.nodes.size();
    s.inner = b.st.inner;
    s.leaves = b.st.leaves;
    s.empty_leaves = b.st.empty_leaves;
    s.max_depth = b.st.max_depth;
    s.refs = b.tree.list.size();
    s.tris = tris.size();
    s.tree_tris = b.st.tree_tris;
    s.refs_per_tri = s.tree_tris ? double(s.refs) / double(s.tree_tris) : 0.0;
    s.max_leaf = b.st.max_leaf;
    const uint64_t full = s.leaves - s.empty_leaves;
    s.mean_leaf = full ? double(s.refs) / double(full) : 0.0;
    s.sah_cost = b.st.sah_cost;
  }
  return std::move(b.tree);
}

}  // namespace raycore::hls
