// hls/image.cpp - the memory image: building, saving, loading and validating; see image.h.
#include "hls/image.h"

#include "hls/vtu.h"

#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace raycore::hls {

const char* format_name(FormatId f) { return f == FormatId::fp24 ? "fp24" : "fp32"; }
FormatId format_from_string(const std::string& s) {
  if (s == "fp24") return FormatId::fp24;
  if (s == "fp32") return FormatId::fp32;
  throw std::invalid_argument("unknown number format '" + s + "' (fp24 or fp32)");
}
const char* rounding_name(Rounding r) {
  switch (r) {
    case Rounding::rtz: return "rtz";
    case Rounding::rne: return "rne";
    case Rounding::raycore: return "raycore";
  }
  return "?";
}
const char* ist_kind_name(IstKind k) { return k == IstKind::wald ? "wald" : "watertight"; }
IstKind ist_kind_from_string(const std::string& s) {
  if (s == "wald") return IstKind::wald;
  if (s == "watertight") return IstKind::watertight;
  throw std::invalid_argument("unknown intersection test '" + s + "' (wald or watertight)");
}
Rounding rounding_from_string(const std::string& s) {
  if (s == "rtz") return Rounding::rtz;
  if (s == "rne") return Rounding::rne;
  if (s == "raycore") return Rounding::raycore;
  throw std::invalid_argument("unknown rounding '" + s + "' (rtz, rne or raycore)");
}
void check_format_rounding(FormatId f, Rounding r) {
  if (f == FormatId::fp32 && r == Rounding::raycore)
    throw std::invalid_argument(
        "rounding 'raycore' is RayCore's FP24 arithmetic: it needs --format fp24 (fp32 takes rtz "
        "or rne)");
}

// ---- header and layout --------------------------------------------------------------------------

namespace {
void put32(uint8_t* p, uint32_t v) { detail::put_le(p, v, 4); }
uint32_t get32(const uint8_t* p) { return uint32_t(detail::get_le(p, 4)); }
uint64_t align_up(uint64_t x) { return (x + image_align - 1) & ~uint64_t(image_align - 1); }
}  // namespace

ImageHeader ImageHeader::read(const uint8_t* p) {
  ImageHeader h;
  std::memcpy(h.magic, p, 8);
  h.version = uint16_t(detail::get_le(p + 8, 2));
  h.exp_bits = p[10];
  h.man_bits = p[11];
  h.rounding = p[12];
  h.tri_bytes = p[13];
  h.flags = p[14];
  h.ist = p[15];
  h.node_count = get32(p + 16);
  h.list_count = get32(p + 20);
  h.tri_count = get32(p + 24);
  h.node_offset = get32(p + 28);
  h.list_offset = get32(p + 32);
  h.tri_offset = get32(p + 36);
  for (int i = 0; i < 3; ++i) {
    h.box_lo[i] = get32(p + 40 + 4 * i);
    h.box_hi[i] = get32(p + 52 + 4 * i);
  }
  return h;
}

void ImageHeader::write(uint8_t* p) const {
  std::memset(p, 0, image_header_bytes);
  std::memcpy(p, magic, 8);
  detail::put_le(p + 8, version, 2);
  p[10] = exp_bits;
  p[11] = man_bits;
  p[12] = rounding;
  p[13] = tri_bytes;
  p[14] = flags;
  p[15] = ist;
  put32(p + 16, node_count);
  put32(p + 20, list_count);
  put32(p + 24, tri_count);
  put32(p + 28, node_offset);
  put32(p + 32, list_offset);
  put32(p + 36, tri_offset);
  for (int i = 0; i < 3; ++i) {
    put32(p + 40 + 4 * i, box_lo[i]);
    put32(p + 52 + 4 * i, box_hi[i]);
  }
}

ImageLayout image_layout(uint64_t nodes, uint64_t lists, uint64_t tris, uint64_t tri_bytes) {
  const uint64_t node_off = image_header_bytes;
  const uint64_t list_off = align_up(node_off + nodes * 8);
  const uint64_t tri_off = align_up(list_off + lists * 4);
  const uint64_t size = tri_off + tris * tri_bytes;
  if (size > UINT32_MAX) throw std::runtime_error("memory image larger than 4 GiB");
  return {uint32_t(node_off), uint32_t(list_off), uint32_t(tri_off), size};
}

void Image::box(uint32_t lo[3], uint32_t hi[3]) const {
  for (int i = 0; i < 3; ++i) {
    lo[i] = u32(40 + 4 * size_t(i));
    hi[i] = u32(52 + 4 * size_t(i));
  }
}

// ---- save / load / check ------------------------------------------------------------------------

void Image::save(const std::string& path) const {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw std::runtime_error("cannot write memory image '" + path + "'");
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  f.close();
  if (!f) throw std::runtime_error("error writing memory image '" + path + "'");
}

Image Image::load(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("memory image '" + path + "': cannot open");
  Image img;
  img.bytes.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  if (f.bad()) throw std::runtime_error("memory image '" + path + "': read error");
  img.check("memory image '" + path + "'");
  return img;
}

namespace {

[[noreturn]] void fail(const std::string& what, const std::string& msg) {
  throw std::runtime_error(what + ": " + msg);
}
std::string num(uint64_t v) { return std::to_string(v); }

template <class F>
void check_records(const Image& img, const std::string& what) {
  const ImageHeader h = img.header();
  const IstKind kind = img.ist_kind();
  const size_t rb = tri_record_bytes<F>(kind), kfo = tri_kflags_offset<F>(kind), ido = tri_id_offset<F>(kind);
  for (uint32_t i = 0; i < h.tri_count; ++i) {
    const uint8_t* r = img.tri(i);
    const uint32_t kf = r[kfo];
    if ((kf & 3u) == 3u) fail(what, "triangle " + num(i) + ": projection axis k = 3");
    if ((kf & ~3u & ~tri_flags_known) != 0)
      fail(what, "triangle " + num(i) + ": unknown flag bits " + num(kf & ~3u & ~tri_flags_known));
    for (size_t b = kfo + 1; b < rb; ++b) {
      if (b >= ido && b < ido + 4) continue;
      if (r[b] != 0) fail(what, "triangle " + num(i) + ": nonzero padding byte " + num(b));
    }
    if (F::width < 8 * int(tri_const_bytes<F>()))
      for (int c = 0; c < tri_const_count(kind); ++c) {
        const uint64_t v = detail::get_le(r + size_t(c) * tri_const_bytes<F>(), tri_const_bytes<F>());
        if (v & ~uint64_t(F::mask)) fail(what, "triangle " + num(i) + ": constant " + num(c) + " has bits beyond the format");
      }
  }
}

}  // namespace

void Image::check(const std::string& what) const {
  if (bytes.size() < image_header_bytes)
    fail(what, "truncated: " + num(bytes.size()) + " bytes, the header alone needs 64");
  const ImageHeader h = header();
  if (std::memcmp(h.magic, image_magic, 8) != 0) fail(what, "not a memory image (bad magic)");
  if (h.version != image_version)
    fail(what, "version " + num(h.version) + " (this build reads version " + num(image_version) + ")");
  FormatId fmt;
  if (h.exp_bits == FP24::exp_bits && h.man_bits == FP24::man_bits) fmt = FormatId::fp24;
  else if (h.exp_bits == FP32::exp_bits && h.man_bits == FP32::man_bits) fmt = FormatId::fp32;
  else fail(what, "unsupported number format " + num(h.exp_bits) + "/" + num(h.man_bits) + " (exponent/mantissa bits)");
  if (h.rounding > 2) fail(what, "unknown rounding code " + num(h.rounding));
  if (h.rounding == 2 && fmt != FormatId::fp24) fail(what, "rounding raycore (code 2) is fp24 only");
  if (h.ist > uint8_t(IstKind::watertight)) fail(what, "unknown triangle record kind " + num(h.ist));
  const IstKind kind = IstKind(h.ist);
  const uint64_t rb = fmt == FormatId::fp24 ? tri_record_bytes<FP24>(kind) : tri_record_bytes<FP32>(kind);
  if (h.tri_bytes != rb)
    fail(what, "triangle record size " + num(h.tri_bytes) + " (" + format_name(fmt) + " " + ist_kind_name(kind) +
                   " records need " + num(rb) + ")");
  if ((h.flags & ~image_flag_vtu) != 0) fail(what, "unknown header flags");
  if (h.node_count == 0) fail(what, "no nodes (the root is node 0)");
  if (h.node_count > node_index_mask + 1u || h.list_count > node_index_mask + 1u)
    fail(what, "node or list count beyond the 24-bit index");
  const ImageLayout L = image_layout(h.node_count, h.list_count, h.tri_count, rb);
  if (h.node_offset != L.node_offset || h.list_offset != L.list_offset || h.tri_offset != L.tri_offset)
    fail(what, "array offsets " + num(h.node_offset) + "/" + num(h.list_offset) + "/" + num(h.tri_offset) +
                   " are not the layout's " + num(L.node_offset) + "/" + num(L.list_offset) + "/" + num(L.tri_offset));
  if (bytes.size() != L.size)
    fail(what, (bytes.size() < L.size ? "truncated: " : "trailing bytes: ") + num(bytes.size()) +
                   " bytes, the header's counts need " + num(L.size));
  const uint32_t fmask = fmt == FormatId::fp24 ? FP24::mask : FP32::mask;
  for (int i = 0; i < 3; ++i)
    if ((h.box_lo[i] | h.box_hi[i]) & ~fmask) fail(what, "scene box has bits beyond the format");

  // Nodes: one tree, reachable from the root, children after their parent.
  std::vector<int> depth(h.node_count, -1);
  depth[0] = 0;
  for (uint32_t i = 0; i < h.node_count; ++i) {
    const uint64_t w = node(i);
    const std::string at = "node " + num(i);
    if (depth[size_t(i)] < 0) fail(what, at + " is not reachable from the root");
    if (w >> 58) fail(what, at + ": reserved bits 63:58 set");
    const Node n = decode_node(w);
    if (n.leaf()) {
      if (uint64_t(n.index) + n.split_or_count > h.list_count)
        fail(what, at + ": leaf list [" + num(n.index) + ", +" + num(n.split_or_count) +
                       ") beyond the list's " + num(h.list_count) + " entries");
      continue;
    }
    if (n.split_or_count & ~fmask) fail(what, at + ": split has bits beyond the format");
    if (depth[size_t(i)] + 1 > max_tree_depth)
      fail(what, at + ": tree deeper than " + num(max_tree_depth));
    if (i + 1 >= h.node_count) fail(what, at + ": inner node without a left child");
    if (n.index <= i + 1 || n.index >= h.node_count)
      fail(what, at + ": right child " + num(n.index) + " out of range (" + num(i + 2) + ".." +
                     num(h.node_count - 1) + ")");
    for (uint32_t c : {i + 1, n.index}) {
      if (depth[c] >= 0) fail(what, "node " + num(c) + " has two parents");
      depth[c] = depth[size_t(i)] + 1;
    }
  }
  for (uint32_t i = 0; i < h.list_count; ++i)
    if (list(i) >= h.tri_count)
      fail(what, "list entry " + num(i) + ": triangle " + num(list(i)) + " out of range (" +
                     num(h.tri_count) + " triangles)");
  if (fmt == FormatId::fp24) check_records<FP24>(*this, what);
  else check_records<FP32>(*this, what);
}

// ---- build ----------------------------------------------------------------------------------------

namespace {

template <class F, Rounding R>
Image build_t(const std::vector<Tri>& tris, const BuildOptions& opt, TreeStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  if (tris.size() > UINT32_MAX) throw std::runtime_error("memory image: more than 2^32 triangles");
  std::vector<WaldTri<F>> recs(tris.size());
  std::vector<uint8_t> skip(tris.size(), 0);
  TreeStats st;
  for (size_t i = 0; i < tris.size(); ++i) {
    WaldInfo info;
    recs[i] = make_wald<F, R>(tris[i], uint32_t(i), opt.ist, &info);
    skip[i] = info.degenerate;
    st.degenerate += info.degenerate;
    st.saturated_constants += uint64_t(info.saturated);
    st.flushed_constants += uint64_t(info.flushed);
  }
  const Quantizer q{&from_double<F, R>, &to_double<F>, &next_up<F>, &next_down<F>};
  ImageHeader h;
  // Watertight records hold the rounded vertices: the tree lists each triangle wherever the stored
  // one reaches (kdtree.h).
  std::vector<Tri> stored;
  if (opt.ist == IstKind::watertight) {
    stored.reserve(tris.size());
    for (const Tri& t : tris) stored.push_back(stored_vertices<F, R>(t));
  }
  const KdTree tree = build_kdtree(tris, skip, q, opt, h.box_lo, h.box_hi, &st,
                                   opt.ist == IstKind::watertight ? &stored : nullptr);

  std::memcpy(h.magic, image_magic, 8);
  h.version = image_version;
  h.exp_bits = uint8_t(F::exp_bits);
  h.man_bits = uint8_t(F::man_bits);
  h.rounding = R == Rounding::raycore ? 2 : (R == Rounding::rne ? 1 : 0);
  h.tri_bytes = uint8_t(tri_record_bytes<F>(opt.ist));
  h.ist = uint8_t(opt.ist);
  h.node_count = uint32_t(tree.nodes.size());
  h.list_count = uint32_t(tree.list.size());
  h.tri_count = uint32_t(tris.size());
  const ImageLayout L = image_layout(h.node_count, h.list_count, h.tri_count, h.tri_bytes);
  h.node_offset = L.node_offset;
  h.list_offset = L.list_offset;
  h.tri_offset = L.tri_offset;

  Image img;
  img.bytes.assign(size_t(L.size), 0);
  uint8_t* p = img.bytes.data();
  h.write(p);
  for (size_t i = 0; i < tree.nodes.size(); ++i) {
    const KdNode& k = tree.nodes[i];
    Node n;
    if (k.leaf) {
      n = {k.count, k.first, node_leaf_axis};
    } else {
      n = {k.split_bits, k.right, uint32_t(k.axis)};
    }
    detail::put_le(p + L.node_offset + 8 * i, encode_node(n), 8);
  }
  for (size_t i = 0; i < tree.list.size(); ++i) put32(p + L.list_offset + 4 * i, tree.list[i]);
  for (size_t i = 0; i < recs.size(); ++i) encode_tri<F>(recs[i], p + L.tri_offset + h.tri_bytes * i);

  st.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (stats) *stats = st;
  return img;
}

}  // namespace

Image build_image(const std::vector<Tri>& tris, FormatId format, Rounding rounding,
                  const BuildOptions& opt, TreeStats* stats) {
  return visit_format(format, rounding, [&](auto f, auto r) {
    return build_t<decltype(f), decltype(r)::value>(tris, opt, stats);
  });
}

// ---- analysis -------------------------------------------------------------------------------------

namespace {

Box root_cell(const Image& img) {
  uint32_t lo[3], hi[3];
  img.box(lo, hi);
  const bool fp24 = img.format() == FormatId::fp24;
  Box b;
  for (int i = 0; i < 3; ++i) {
    b.lo[i] = fp24 ? to_double<FP24>(lo[i]) : to_double<FP32>(lo[i]);
    b.hi[i] = fp24 ? to_double<FP24>(hi[i]) : to_double<FP32>(hi[i]);
  }
  return b;
}

// Depth-first walk: fn(node index, decoded node, cell, depth) for every node.
template <class Fn>
void walk(const Image& img, Fn&& fn) {
  const bool fp24 = img.format() == FormatId::fp24;
  struct Item {
    uint32_t node;
    Box cell;
    int depth;
  };
  std::vector<Item> stack{{0, root_cell(img), 0}};
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    const Node n = decode_node(img.node(it.node));
    fn(it.node, n, it.cell, it.depth);
    if (n.leaf()) continue;
    Box l = it.cell, r = it.cell;
    l.hi[n.axis] = r.lo[n.axis] =
        fp24 ? to_double<FP24>(n.split_or_count) : to_double<FP32>(n.split_or_count);
    stack.push_back({n.index, r, it.depth + 1});
    stack.push_back({it.node + 1, l, it.depth + 1});
  }
}

double cell_area(const Box& c) { return c.empty() ? 0.0 : c.area(); }

}  // namespace

std::vector<LeafInfo> image_leaves(const Image& img) {
  std::vector<LeafInfo> out;
  walk(img, [&](uint32_t i, const Node& n, const Box& cell, int depth) {
    if (n.leaf()) out.push_back({i, cell, depth, n.index, n.split_or_count});
  });
  return out;
}

TreeStats analyze_image(const Image& img, const BuildOptions& opt) {
  TreeStats s;
  const ImageHeader h = img.header();
  s.nodes = h.node_count;
  s.tris = h.tri_count;
  s.refs = h.list_count;
  const double ra = cell_area(root_cell(img));
  walk(img, [&](uint32_t, const Node& n, const Box& cell, int depth) {
    const double p = ra > 0 ? cell_area(cell) / ra : 1.0;
    if (!n.leaf()) {
      ++s.inner;
      s.sah_cost += opt.cost_traversal * p;
      return;
    }
    ++s.leaves;
    s.max_depth = std::max(s.max_depth, depth);
    if (n.split_or_count == 0) ++s.empty_leaves;
    s.max_leaf = std::max<uint64_t>(s.max_leaf, n.split_or_count);
    s.sah_cost += opt.cost_intersect * double(n.split_or_count) * p;
  });
  const uint64_t full = s.leaves - s.empty_leaves;
  s.mean_leaf = full ? double(s.refs) / double(full) : 0.0;
  visit_format(img.format(), img.rounding(), [&](auto f, auto) {
    using F = decltype(f);
    for (uint32_t i = 0; i < h.tri_count; ++i) {
      const WaldTri<F> w = img.wald<F>(i);
      if (w.degenerate()) {
        ++s.degenerate;
        continue;
      }
      for (uint32_t c : w.c)
        if ((c & F::max_mag) == F::max_mag) ++s.saturated_constants;
    }
  });
  s.tree_tris = s.tris - s.degenerate;
  s.refs_per_tri = s.tree_tris ? double(s.refs) / double(s.tree_tris) : 0.0;
  return s;
}

Image transform_image(const Image& img, const Vec3& camera) {
  return visit_format(img.format(), img.rounding(), [&](auto f, auto r) {
    return transform_image(img, Vtu<decltype(f), decltype(r)::value>::from_camera(camera));
  });
}

Vec3 store_anchor(const std::vector<Tri>& tris) {
  if (tris.empty()) return {};
  Box b;
  for (const Tri& t : tris)
    for (const Vec3& v : t) b.extend(v);
  return (b.lo + b.hi) * 0.5;
}

std::vector<Tri> relative_to(const std::vector<Tri>& tris, const Vec3& anchor) {
  std::vector<Tri> out = tris;
  for (Tri& t : out)
    for (Vec3& v : t) v = v - anchor;
  return out;
}

}  // namespace raycore::hls
