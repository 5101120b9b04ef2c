// hls/image.h - the memory image the hardware reads: one little-endian byte array holding a 64-byte
// header, the kd-tree's nodes, the leaf lists and the Wald triangles (docs/image.md has the
// address map). Built by build_image from double-precision triangles; saved, loaded and validated.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "hls/fp.h"
#include "hls/geom.h"
#include "hls/kdtree.h"
#include "hls/wald.h"

namespace raycore::hls {

// ---- nodes --------------------------------------------------------------------------------------
//
// 8 bytes (uint64, little endian), depth-first, left child = next node:
//   bits [31:0]  split position (format bits) of an inner node, or a leaf's triangle count
//   bits [55:32] right-child node index (inner) or first leaf-list entry index (leaf), 24 bits
//   bits [57:56] axis 0/1/2 = x/y/z, 3 = leaf; bits [63:58] zero
constexpr uint32_t node_leaf_axis = 3;
constexpr uint32_t node_index_mask = (1u << 24) - 1u;

struct Node {
  uint32_t split_or_count = 0;
  uint32_t index = 0;
  uint32_t axis = 0;
  constexpr bool leaf() const { return axis == node_leaf_axis; }
};

constexpr uint64_t encode_node(const Node& n) {
  return uint64_t(n.split_or_count) | (uint64_t(n.index & node_index_mask) << 32) |
         (uint64_t(n.axis & 3u) << 56);
}
constexpr Node decode_node(uint64_t w) {
  Node n;
  n.split_or_count = uint32_t(w);
  n.index = uint32_t(w >> 32) & node_index_mask;
  n.axis = uint32_t(w >> 56) & 3u;
  return n;
}
constexpr bool node_is_leaf(uint64_t w) { return ((w >> 56) & 3u) == node_leaf_axis; }

// ---- formats ------------------------------------------------------------------------------------

enum class FormatId : uint8_t { fp24, fp32 };

const char* format_name(FormatId f);                    // "fp24" / "fp32"
FormatId format_from_string(const std::string& s);      // throws std::invalid_argument
const char* rounding_name(Rounding r);                  // "rtz" / "rne" / "raycore"
Rounding rounding_from_string(const std::string& s);    // throws std::invalid_argument

template <class F>
constexpr FormatId format_id() {
  static_assert(std::is_same<F, FP24>::value || std::is_same<F, FP32>::value, "fp24 or fp32");
  return std::is_same<F, FP24>::value ? FormatId::fp24 : FormatId::fp32;
}

// Throws std::invalid_argument for a pair that does not exist: rounding `raycore` is RayCore's
// FP24 arithmetic (hls/fp.h), so fp32 + raycore is refused.
void check_format_rounding(FormatId f, Rounding r);

// Calls fn(F{}, std::integral_constant<Rounding, R>{}) with the format and policy as types:
//   visit_format(fmt, rnd, [&](auto f, auto r) {
//     using F = decltype(f); constexpr Rounding R = decltype(r)::value; ... });
// The pairs: fp24 x {rtz, rne, raycore}, fp32 x {rtz, rne}; fp32 + raycore throws
// (check_format_rounding).
template <class Fn>
decltype(auto) visit_format(FormatId f, Rounding r, Fn&& fn) {
  using rtz = std::integral_constant<Rounding, Rounding::rtz>;
  using rne = std::integral_constant<Rounding, Rounding::rne>;
  using raycore = std::integral_constant<Rounding, Rounding::raycore>;
  check_format_rounding(f, r);
  if (f == FormatId::fp24) {
    if (r == Rounding::rtz) return fn(FP24{}, rtz{});
    if (r == Rounding::raycore) return fn(FP24{}, raycore{});
    return fn(FP24{}, rne{});
  }
  if (r == Rounding::rtz) return fn(FP32{}, rtz{});
  return fn(FP32{}, rne{});
}

// ---- the image ----------------------------------------------------------------------------------

constexpr char image_magic[8] = {'R', 'C', 'I', 'M', 'A', 'G', 'E', '1'};
constexpr uint16_t image_version = 1;
constexpr size_t image_header_bytes = 64;
constexpr size_t image_align = 64;
constexpr uint8_t image_flag_vtu = 1u << 0;  // the image was translated by the VTU (transform_image)

// Header, 64 bytes at address 0 (offsets in bytes, all little endian):
//    0  magic "RCIMAGE1"        8  version (u16)      10 exp_bits (u8)     11 man_bits (u8)
//   12  rounding (u8: 0 rtz, 1 rne, 2 raycore (fp24 only); the policy the constants and splits
//       were rounded with, and so the arithmetic the image is traced with)
//   13  triangle record bytes (u8: hls/wald.h's tri_record_bytes: wald 32 fp24, 48 fp32; watertight
//       48 fp24, 64 fp32)   14 flags (u8, image_flag_*)   15 triangle record kind (u8: IstKind, 0
//       wald, 1 watertight; --ist)
//   16  node count (u32)      20  list count (u32)      24  triangle count (u32)
//   28  node offset (u32)     32  list offset (u32)     36  triangle offset (u32)
//   40  scene box lo x, y, z  52  scene box hi x, y, z  (u32 format bits each, rounded outward)
struct ImageHeader {
  char magic[8] = {};
  uint16_t version = 0;
  uint8_t exp_bits = 0, man_bits = 0;
  uint8_t rounding = 0;
  uint8_t tri_bytes = 0;
  uint8_t flags = 0;
  uint8_t ist = 0;  // IstKind
  uint32_t node_count = 0, list_count = 0, tri_count = 0;
  uint32_t node_offset = 0, list_offset = 0, tri_offset = 0;
  uint32_t box_lo[3] = {}, box_hi[3] = {};

  static ImageHeader read(const uint8_t* p);  // p: 64 bytes
  void write(uint8_t* p) const;
};

// Where each array starts for the given counts (64-byte aligned, in this order) and the total size.
struct ImageLayout {
  uint32_t node_offset, list_offset, tri_offset;
  uint64_t size;
};
ImageLayout image_layout(uint64_t nodes, uint64_t lists, uint64_t tris, uint64_t tri_bytes);

class Image {
 public:
  std::vector<uint8_t> bytes;

  ImageHeader header() const { return ImageHeader::read(bytes.data()); }
  // Unchecked accessors (load() and check() validate every index once):
  uint64_t node(uint32_t i) const { return get64(u32(28) + size_t(i) * 8); }
  uint32_t list(uint32_t i) const { return u32(u32(32) + size_t(i) * 4); }
  const uint8_t* tri(uint32_t i) const { return bytes.data() + u32(36) + size_t(i) * bytes[13]; }
  uint32_t node_count() const { return u32(16); }
  uint32_t list_count() const { return u32(20); }
  uint32_t tri_count() const { return u32(24); }
  FormatId format() const { return bytes[10] == 7 ? FormatId::fp24 : FormatId::fp32; }
  Rounding rounding() const {
    return bytes[12] == 2 ? Rounding::raycore : (bytes[12] ? Rounding::rne : Rounding::rtz);
  }
  bool vtu_applied() const { return (bytes[14] & image_flag_vtu) != 0; }
  IstKind ist_kind() const { return IstKind(bytes[15]); }
  size_t tri_bytes() const { return bytes[13]; }
  void box(uint32_t lo[3], uint32_t hi[3]) const;
  template <class F>
  WaldTri<F> wald(uint32_t i) const {
    return decode_tri<F>(tri(i), ist_kind());
  }

  void save(const std::string& path) const;     // throws std::runtime_error naming the file
  static Image load(const std::string& path);   // reads and check()s; errors name the file
  // Validates everything a consumer relies on: size >= 64, magic, version, a known format and
  // policy, record size, canonical offsets and exact size, every node (axis, reserved bits, split
  // within the format, right child after its left subtree, leaf list range), the node array being
  // one tree reachable from node 0 no deeper than max_tree_depth, every list entry < triangle
  // count, every record's k, flags and padding. Throws std::runtime_error("<what>: ...").
  void check(const std::string& what) const;

 private:
  uint32_t u32(size_t at) const {
    return uint32_t(bytes[at]) | uint32_t(bytes[at + 1]) << 8 | uint32_t(bytes[at + 2]) << 16 |
           uint32_t(bytes[at + 3]) << 24;
  }
  uint64_t get64(size_t at) const { return uint64_t(u32(at)) | uint64_t(u32(at + 4)) << 32; }
};

// Builds the tree and the image. Triangle record i is scene triangle i (scene order); degenerate
// triangles get a degenerate record and are left out of the tree. Deterministic. Throws
// std::runtime_error if the tree outgrows the 24-bit indices.
Image build_image(const std::vector<Tri>& tris, FormatId format, Rounding rounding,
                  const BuildOptions& opt = {}, TreeStats* stats = nullptr);

// --store anchored: the point a scene is stored relative to (the centre of its bounding box, in
// double; 0 for no triangles), and the triangles relative to a point (exact subtraction in double
// where it is exact; the image rounds the result once, as it rounds world coordinates).
Vec3 store_anchor(const std::vector<Tri>& tris);
std::vector<Tri> relative_to(const std::vector<Tri>& tris, const Vec3& anchor);

// Statistics of an image's tree, computed from the image alone (SAH cost with opt's costs; the
// constant counts: degenerate records and saturated constants; build_seconds = 0).
TreeStats analyze_image(const Image& img, const BuildOptions& opt = {});

// Every leaf with its cell (format values as doubles) and depth, in depth-first order.
struct LeafInfo {
  uint32_t node;
  Box cell;
  int depth;
  uint32_t first, count;
};
std::vector<LeafInfo> image_leaves(const Image& img);

}  // namespace raycore::hls
