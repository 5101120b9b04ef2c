// hls/wald.h - the triangle record of the memory image, of one of two kinds (IstKind, the image
// header's byte 15; --ist): Wald's projection form for Wald's test, or the plane and the three
// vertices for the watertight test (hls/ist.h). Every constant is computed in double precision from
// the scene's vertices and rounded once to the format (the watertight record's plane from the
// rounded vertices, make_wald).
//
// Wald's constants (the project's convention, NOT Wald's original naming; see docs/image.md):
//   k = dominant axis of n = (B-A) x (C-A), u = (k+1) % 3, v = (k+2) % 3
//   t     = (n_d - o_k - n_u o_u - n_v o_v) / (d_k + n_u d_u + n_v d_v)
//   beta  = b_nu h_u + b_nv h_v + b_d     weight of vertex B  (b_nu multiplies h_u)
//   gamma = c_nu h_u + c_nv h_v + c_d     weight of vertex C
//   alpha = 1 - beta - gamma              weight of vertex A
// with n_u = n_u/n_k, n_v = n_v/n_k, n_d = dot(n, A)/n_k, and (Cramer's rule in the (u, v) plane,
// e1 = B - A, e2 = C - A, n_k = e1_u e2_v - e1_v e2_u):
//   b_nu =  e2_v / n_k   b_nv = -e2_u / n_k   b_d = (e2_u A_v - e2_v A_u) / n_k
//   c_nu = -e1_v / n_k   c_nv =  e1_u / n_k   c_d = (e1_v A_u - e1_u A_v) / n_k
//
// Kinds and layouts (little endian; cb = 3 bytes per constant in FP24, 4 in FP32):
//   wald        nine constants n_u, n_v, n_d, b_nu, b_nv, b_d, c_nu, c_nv, c_d
//   watertight  twelve: the plane n_u, n_v, n_d of the stored triangle (its rounded vertices; what
//               the distance test and the hit unit read: t, the side, the spawn), then the vertices
//               A, B, C as x, y, z each (what the inside test reads); make_wald, watertight_nd
//   the constants at 0, cb, 2 cb, ...; then one byte k (bits 1:0) | flags; the scene index (uint32)
//   at the next multiple of 4; the record padded with zeros to a multiple of 16:
//     FP24 wald 32 bytes (id at 28)   FP24 watertight 48 (id at 40)
//     FP32 wald 48 bytes (id at 40)   FP32 watertight 64 (id at 52)
// Flags: bit 2 = degenerate (zero area in double, or constants beyond the format's range). A
// degenerate Wald record holds n_u=n_v=n_d=0, b_nu=b_nv=0, b_d=-1, c_nu=c_nv=c_d=0: finite, and
// beta = -1 < 0 for every hit point, before and after the VTU transform (b_d' = -1 + 0 + 0); a
// degenerate watertight record is all zeros: three equal vertices, before and after the VTU, whose
// edge functions are all exactly zero, which the test rejects (det = 0).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "hls/fp.h"
#include "hls/geom.h"

namespace raycore::hls {

constexpr uint32_t tri_flag_degenerate = 1u << 2;  // in byte 27 (FP24) / 36 (FP32), above k
constexpr uint32_t tri_flags_known = tri_flag_degenerate;

// The triangle record's kind, and so the intersection test (hls/ist.h): --ist wald|watertight.
enum class IstKind : uint8_t { wald = 0, watertight = 1 };
const char* ist_kind_name(IstKind k);                // "wald" / "watertight"
IstKind ist_kind_from_string(const std::string& s);  // throws std::invalid_argument

// Constants per record: 9 (wald), 12 (watertight).
constexpr int tri_const_count(IstKind kind) { return kind == IstKind::wald ? 9 : 12; }

template <class F>
struct WaldTri {
  enum { NU = 0, NV, ND, BNU, BNV, BD, CNU, CNV, CD };  // wald; watertight: NU, NV, ND, then VA..
  enum { VA = 3, VB = 6, VC = 9 };                      // watertight: vertex j's x at VA + 3 j
  IstKind kind = IstKind::wald;
  uint32_t k = 0;       // projection axis 0/1/2
  uint32_t flags = 0;   // tri_flag_* bits (bit positions as in the record byte; bits 1:0 are k's)
  uint32_t c[12] = {};  // the constants, format bit patterns, in the order above (9 or 12 used)
  uint32_t id = 0;      // the triangle's index in the scene
  bool degenerate() const { return (flags & tri_flag_degenerate) != 0; }
  int count() const { return tri_const_count(kind); }
};

template <class F>
constexpr bool operator==(const WaldTri<F>& a, const WaldTri<F>& b) {
  for (int i = 0; i < 12; ++i)
    if (a.c[i] != b.c[i]) return false;
  return a.kind == b.kind && a.k == b.k && a.flags == b.flags && a.id == b.id;
}

// Bytes per constant, and the offsets inside a record of a kind.
template <class F>
constexpr size_t tri_const_bytes() {
  return F::width <= 24 ? 3 : 4;
}
template <class F>
constexpr size_t tri_kflags_offset(IstKind kind) {
  return size_t(tri_const_count(kind)) * tri_const_bytes<F>();
}
template <class F>
constexpr size_t tri_id_offset(IstKind kind) {
  return (tri_kflags_offset<F>(kind) + 1 + 3) & ~size_t(3);
}
template <class F>
constexpr size_t tri_record_bytes(IstKind kind) {
  return (tri_id_offset<F>(kind) + 4 + 15) & ~size_t(15);
}
static_assert(tri_record_bytes<FP24>(IstKind::wald) == 32 && tri_id_offset<FP24>(IstKind::wald) == 28, "FP24 layout");
static_assert(tri_record_bytes<FP32>(IstKind::wald) == 48 && tri_id_offset<FP32>(IstKind::wald) == 40, "FP32 layout");
static_assert(tri_record_bytes<FP24>(IstKind::watertight) == 48 && tri_id_offset<FP24>(IstKind::watertight) == 40,
              "FP24 watertight layout");
static_assert(tri_record_bytes<FP32>(IstKind::watertight) == 64 && tri_id_offset<FP32>(IstKind::watertight) == 52,
              "FP32 watertight layout");

namespace detail {
inline void put_le(uint8_t* p, uint64_t v, size_t n) {
  for (size_t i = 0; i < n; ++i) p[i] = uint8_t(v >> (8 * i));
}
inline uint64_t get_le(const uint8_t* p, size_t n) {
  uint64_t v = 0;
  for (size_t i = 0; i < n; ++i) v |= uint64_t(p[i]) << (8 * i);
  return v;
}
}  // namespace detail

// Writes the whole record (tri_record_bytes<F>(t.kind) bytes, padding zeroed).
template <class F>
void encode_tri(const WaldTri<F>& t, uint8_t* out) {
  constexpr size_t cb = tri_const_bytes<F>();
  for (size_t i = 0; i < tri_record_bytes<F>(t.kind); ++i) out[i] = 0;
  for (size_t i = 0; i < size_t(t.count()); ++i) detail::put_le(out + i * cb, t.c[i] & F::mask, cb);
  out[tri_kflags_offset<F>(t.kind)] = uint8_t((t.k & 3u) | (t.flags & ~3u));
  detail::put_le(out + tri_id_offset<F>(t.kind), t.id, 4);
}

// A record of the given kind (the image's: Image::ist_kind()).
template <class F>
WaldTri<F> decode_tri(const uint8_t* in, IstKind kind) {
  constexpr size_t cb = tri_const_bytes<F>();
  WaldTri<F> t;
  t.kind = kind;
  for (size_t i = 0; i < size_t(t.count()); ++i) t.c[i] = uint32_t(detail::get_le(in + i * cb, cb)) & F::mask;
  const uint32_t kf = in[tri_kflags_offset<F>(kind)];
  t.k = kf & 3u;
  t.flags = kf & ~3u;
  t.id = uint32_t(detail::get_le(in + tri_id_offset<F>(kind), 4));
  return t;
}

// The nine constants in double precision before rounding (the reference for tests and tools).
struct WaldDouble {
  uint32_t k = 0;
  bool degenerate = false;  // zero area (n_k == 0) or a non-finite constant
  double c[9] = {};
};

inline WaldDouble wald_double(const Tri& t) {
  WaldDouble w;
  const Vec3 a = t[0];
  const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
  const Vec3 n = cross(e1, e2);
  int k = 0;
  if (std::fabs(n.y) > std::fabs(n[k])) k = 1;
  if (std::fabs(n.z) > std::fabs(n[k])) k = 2;
  const int u = (k + 1) % 3, v = (k + 2) % 3;
  w.k = uint32_t(k);
  const double nk = n[k];
  if (!(nk != 0) || !std::isfinite(nk)) {
    w.degenerate = true;
    return w;
  }
  w.c[0] = n[u] / nk;
  w.c[1] = n[v] / nk;
  w.c[2] = dot(n, a) / nk;
  w.c[3] = e2[v] / nk;
  w.c[4] = -e2[u] / nk;
  w.c[5] = (e2[u] * a[v] - e2[v] * a[u]) / nk;
  w.c[6] = -e1[v] / nk;
  w.c[7] = e1[u] / nk;
  w.c[8] = (e1[v] * a[u] - e1[u] * a[v]) / nk;
  for (double x : w.c)
    if (!std::isfinite(x)) w.degenerate = true;
  return w;
}

// Per-triangle rounding facts, for the build statistics.
struct WaldInfo {
  bool degenerate = false;
  int saturated = 0;  // constants that rounded to the format's largest magnitude
  int flushed = 0;    // nonzero constants that flushed to zero (below the smallest normal)
};

// The degenerate record: never hits (wald: beta = -1; watertight: three equal vertices, det = 0),
// finite, unchanged in meaning by the VTU.
template <class F>
WaldTri<F> degenerate_wald(uint32_t k, uint32_t id, IstKind kind = IstKind::wald) {
  WaldTri<F> w;
  w.kind = kind;
  w.k = k;
  w.flags = tri_flag_degenerate;
  if (kind == IstKind::wald) w.c[WaldTri<F>::BD] = neg<F>(F::one);
  w.id = id;
  return w;
}

// The plane offset of a watertight record: the plane through its stored vertex A with its stored
// normal, n_d = A_k + n_u A_u + n_v A_v as one sop (exact products, one rounding). The builder's on
// the world's (or the anchor's) vertices and the VTU's on the shifted ones (hls/vtu.h), so the plane
// the distance test and the hit unit read is the stored triangle's wherever it is translated.
template <class F, Rounding R>
uint32_t watertight_nd(const WaldTri<F>& w) {
  using W = WaldTri<F>;
  const int k = int(w.k), u = k == 2 ? 0 : k + 1, v = k == 0 ? 2 : k - 1;
  return sop<F, R>(w.c[W::VA + k], F::sign_mask, w.c[W::NU], w.c[W::VA + u], w.c[W::NV], w.c[W::VA + v]);
}

// The record of triangle t with scene index id, of the given kind, rounded with policy R. Wald's:
// the constants computed in double (wald_double) and rounded once. Watertight: the vertices rounded
// once, then the plane of the stored (rounded) triangle: n_u, n_v from wald_double of the rounded
// vertices, rounded once, and n_d = watertight_nd (so the record is one triangle, the one the
// inside test sees). A constant or vertex coordinate whose magnitude exceeds the format's largest
// number makes the triangle degenerate (it could only saturate to a meaningless value), as does a
// triangle of zero area (in double; for watertight, after its vertices are rounded); a constant that
// rounds up to the largest magnitude (rne, within half an ulp of it) keeps that value and is
// counted as saturated. A shared vertex rounds to the same bits in every triangle that has it:
// watertight records keep the scene's mesh closed, which the watertight test then keeps closed for
// every ray.
// The triangle a watertight record holds: each vertex coordinate rounded to the format (the
// triangle the test and the kd-tree builder's classification see).
template <class F, Rounding R>
Tri stored_vertices(const Tri& t) {
  Tri s;
  for (size_t j = 0; j < 3; ++j)
    for (int a = 0; a < 3; ++a) s[j][a] = to_double<F>(from_double<F, R>(t[j][a]));
  return s;
}

template <class F, Rounding R>
WaldTri<F> make_wald(const Tri& t, uint32_t id, IstKind kind = IstKind::wald, WaldInfo* info = nullptr) {
  const double maxv = to_double<F>(F::max_mag);
  const bool watertight = kind == IstKind::watertight;
  bool degenerate = false;
  Tri stored = t;  // watertight: the rounded vertices
  if (watertight) {
    for (size_t j = 0; j < 3; ++j)
      for (int a = 0; a < 3; ++a)
        if (!(std::fabs(t[j][a]) <= maxv)) degenerate = true;
    stored = stored_vertices<F, R>(t);
  }
  const WaldDouble d = wald_double(degenerate ? t : stored);
  double x[12] = {};
  const int n = tri_const_count(kind);
  for (int i = 0; i < 3; ++i) x[i] = d.c[i];
  for (int i = 3; i < n; ++i) x[i] = watertight ? t[size_t(i / 3 - 1)][i % 3] : d.c[i];
  degenerate = degenerate || d.degenerate;
  for (int i = 0; i < n; ++i)
    if (!(std::fabs(x[i]) <= maxv)) degenerate = true;
  WaldInfo local;
  WaldTri<F> w;
  if (degenerate) {
    w = degenerate_wald<F>(d.k, id, kind);
    local.degenerate = true;
  } else {
    w.kind = kind;
    w.k = d.k;
    w.id = id;
    for (int i = 0; i < n; ++i) {
      w.c[i] = from_double<F, R>(x[i]);
      if ((w.c[i] & F::max_mag) == F::max_mag) ++local.saturated;
      if (is_zero<F>(w.c[i]) && x[i] != 0) ++local.flushed;
    }
    if (watertight) {
      w.c[WaldTri<F>::ND] = watertight_nd<F, R>(w);
      if ((w.c[WaldTri<F>::ND] & F::max_mag) == F::max_mag) ++local.saturated;
    }
  }
  if (info) *info = local;
  return w;
}

}  // namespace raycore::hls
