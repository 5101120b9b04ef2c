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

// A triangle's reference in a node: its index and its box clipped to the node's cell.
struct Ref {
  uint32_t tri;
  Box b;
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
    std::vector<double> los(n), his(n);
    struct Cand {
      double s;
      uint32_t bits;
    };
    std::vector<Cand> cands;
    cands.reserve(4 * n);
    for (int a = 0; a < 3; ++a) {
      if (!(cell.lo[a] < cell.hi[a])) continue;
      for (size_t i = 0; i < n; ++i) {
        los[i] = refs[i].b.lo[a];
        his[i] = refs[i].b.hi[a];
      }
      std::sort(los.begin(), los.end());
      std::sort(his.begin(), his.end());
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
      for (size_t i = 0; i < n; ++i) {
        add(los[i]);
        add(his[i]);
      }
      std::sort(cands.begin(), cands.end(), [](const Cand& x, const Cand& y) { return x.s < y.s; });
      const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;
      const double d1 = cell.hi[b1] - cell.lo[b1], d2 = cell.hi[b2] - cell.lo[b2];
      size_t nl = 0, nb = 0;  // #lo <= s, #hi < s (true bounds)
      double prev = -HUGE_VAL;
      for (const Cand& c : cands) {
        const uint32_t bits = c.bits;
        const double s = c.s;
        if (!(s > prev)) continue;  // duplicate plane
        prev = s;
        if (!(s > cell.lo[a])) continue;
        if (!(s < cell.hi[a])) break;
        while (nl < n && los[nl] <= s) ++nl;
        while (nb < n && his[nb] < s) ++nb;
        const size_t nL = nl, nR = n - nb;
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
      if (r.b.lo[a] <= sp.pos) {
        if (r.b.hi[a] <= sp.pos) {
          left.push_back(r);
        } else {
          const Box nb = intersect(clip_box(tris[r.tri], cl), r.b);
          left.push_back({r.tri, nb.empty() ? intersect(r.b, cl) : nb});
        }
      }
      if (r.b.hi[a] >= sp.pos) {
        if (r.b.lo[a] >= sp.pos) {
          right.push_back(r);
        } else {
          const Box nb = intersect(clip_box(tris[r.tri], cr), r.b);
          right.push_back({r.tri, nb.empty() ? intersect(r.b, cr) : nb});
        }
      }
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
                    uint32_t root_hi[3], TreeStats* stats) {
  std::vector<Ref> refs;
  Box scene;
  for (size_t i = 0; i < tris.size(); ++i) {
    if (!skip.empty() && skip[i]) continue;
    const Box b = tri_box(tris[i]);
    refs.push_back({uint32_t(i), b});
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
  for (Ref& r : refs) r.b = intersect(r.b, cell);

  Builder b{tris, q, opt, opt.max_depth > 0 ? std::min(opt.max_depth, max_tree_depth)
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
