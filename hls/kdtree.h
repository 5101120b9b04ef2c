// hls/kdtree.h - the SAH kd-tree builder behind the memory image (see docs/image.md).
//
// Split candidates are the bounds of each triangle clipped to the node's cell ("perfect splits",
// Havran; Wald & Havran 2006). Each candidate is rounded to the image's number format with the
// image's rounding policy BEFORE the triangles are classified, because the hardware compares
// against the rounded plane. A triangle goes left if its clipped box's lo <= split and right if its
// hi >= split: a triangle touching the plane (or lying in it) goes to both sides. With vertex
// records, also to a side its stored triangle crosses into (build_kdtree's stored). A node becomes a
// leaf when it holds <= leaf_size triangles, when no split beats the leaf's cost, or at max_depth.
// The sweep sorts the bounds per node and axis (O(N log^2 N) overall); the build is single-threaded
// and deterministic: the same input gives the same tree, bit for bit.
//
// Cost model (pbrt's form, Wald & Havran's constants):
//   split cost = cost_traversal + cost_intersect * lambda * (P_L n_L + P_R n_R)
//   leaf cost  = cost_intersect * n
// with P_X = area(cell_X) / area(cell) and lambda = 1 - empty_bonus when one side is empty.
#pragma once

#include <cstdint>
#include <vector>

#include "hls/geom.h"
#include "hls/wald.h"

namespace raycore::hls {

// The deepest tree an image may hold (the builder never exceeds it; load() rejects deeper trees):
// a traversal stack of this many entries can never overflow.
constexpr int max_tree_depth = 64;

struct BuildOptions {
  int leaf_size = 8;             // a node with this many triangles or fewer is a leaf (RayCore's 8)
  double cost_traversal = 1.0;   // one traversal step (one 8-byte node, one plane distance)
  double cost_intersect = 1.5;   // one triangle test (4 + 32 bytes, 21 operations, early exits)
  double empty_bonus = 0.2;      // Wald & Havran's lambda = 0.8 for splits with an empty side
  int max_depth = 0;             // <= 0: automatic, round(8 + 1.3 log2 N) (pbrt); capped at 64
  double split_ratio = 1.0;      // split only when its cost is below split_ratio x the leaf's cost
                                 //   (RayCore's driver: 0.8, with costs 1.7072 / 3.4623)
  IstKind ist = IstKind::wald;   // the triangle records' kind (hls/wald.h; --ist); not the tree's
};

// RayCore's driver builder (reference.md): node cost 1.7072, triangle cost 3.4623, leaves of at
// most 8 triangles, a split only when it beats 0.8 x the leaf cost; the empty bonus and depth limit
// stay ours (not published).
inline BuildOptions raycore_build_options() {
  BuildOptions o;
  o.cost_traversal = 1.7072;
  o.cost_intersect = 3.4623;
  o.split_ratio = 0.8;
  return o;
}

struct TreeStats {
  uint64_t nodes = 0, inner = 0, leaves = 0, empty_leaves = 0;
  int max_depth = 0;  // of the deepest leaf (root = 0)
  uint64_t refs = 0;  // leaf-list entries
  uint64_t tris = 0;  // triangles in the scene (records in the image)
  uint64_t tree_tris = 0;  // non-degenerate triangles (the ones in the tree)
  double refs_per_tri = 0;  // refs / tree_tris
  uint64_t max_leaf = 0;    // largest leaf (triangles)
  double mean_leaf = 0;     // mean triangles per non-empty leaf
  double sah_cost = 0;      // expected cost of a random ray through the root cell, cost model above
  double build_seconds = 0;
  uint64_t degenerate = 0;           // triangles flagged degenerate (not in the tree)
  uint64_t saturated_constants = 0;  // constants that rounded to the largest magnitude
  uint64_t flushed_constants = 0;    // nonzero constants that flushed to zero
};

// The abstract tree, before encoding: nodes depth-first (left child = next node), the leaf lists
// concatenated, and the root cell.
struct KdNode {
  bool leaf = false;
  int axis = 0;            // inner node: 0/1/2
  uint32_t split_bits = 0;  // inner node: the split in the format
  double split = 0;        // its value
  uint32_t right = 0;      // inner node: index of the right child
  uint32_t first = 0, count = 0;  // leaf: its entries in the list
};

struct KdTree {
  std::vector<KdNode> nodes;
  std::vector<uint32_t> list;
  Box cell;  // the root cell: the scene box rounded outward to the format
};

// The format's rounding, as the builder needs it: bits of a double rounded with the image's policy,
// and the (exact) value of bits.
struct Quantizer {
  uint32_t (*round)(double);
  double (*value)(uint32_t);
  uint32_t (*next_up)(uint32_t);
  uint32_t (*next_down)(uint32_t);
};

// Builds the tree over the triangles with skip[i] == 0 (skip may be empty: all triangles).
// root_lo/root_hi receive the root cell's bounds as format bits. Fills the tree fields of stats
// (not the constant counts, not build_seconds).
//
// stored (may be null): the triangles the hardware tests, when the records hold vertices (the
// watertight kind: each vertex rounded to the format, hls/wald.h stored_vertices), index for index
// with tris. The candidates and costs stay the scene's; a stored triangle that crosses a split
// plane (lo < split < hi, clipped to the cell) the scene's does not reach is listed on that side
// too, so every leaf whose cell a stored triangle enters lists it (far from the origin the rounding
// moves a vertex by units: the scene's triangle alone left it out of cells it enters).
KdTree build_kdtree(const std::vector<Tri>& tris, const std::vector<uint8_t>& skip,
                    const Quantizer& q, const BuildOptions& opt, uint32_t root_lo[3],
                    uint32_t root_hi[3], TreeStats* stats,
                    const std::vector<Tri>* stored = nullptr);

// The box of triangle t clipped to cell (conservative: it contains the exact box of t intersected
// with cell, widened by a relative 2^-36 against rounding in the clipper, and never exceeds t's
// box or the cell). Empty if t's box does not meet the cell.
Box clip_box(const Tri& t, const Box& cell);

// The automatic depth limit for n triangles: round(8 + 1.3 log2 n), capped at max_tree_depth.
int auto_max_depth(uint64_t n);

}  // namespace raycore::hls
