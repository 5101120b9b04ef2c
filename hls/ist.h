// hls/ist.h - the intersection unit's datapath, one of two tests (the image's record kind, --ist):
// Wald's projected ray/triangle test with three early-exit phases (distance, first barycentric,
// second barycentric and their sum), or the watertight test (ist_watertight, below).
//
// Per test: 11 multiplies, 6 two-input adds, 3 three-input adds, 1 reciprocal (RayCore's count).
// The triangle is the nine constants of the memory image, in the project's convention:
//   t     = (n_d - o_k - (n_u o_u + n_v o_v)) / (d_k + n_u d_u + n_v d_v)
//   beta  = b_nu h_u + b_nv h_v + b_d      (weight of vertex B)
//   gamma = c_nu h_u + c_nv h_v + c_d      (weight of vertex C)
// with h = o + t d the hit point and (k, u, v) the projection axes.
#pragma once

#include <cstdint>
#include <type_traits>

#include "hls/fp.h"
#include "hls/margins.h"
#include "hls/ray.h"
#include "hls/wald.h"

namespace raycore::hls {

enum WaldConst : int { kNU = 0, kNV, kND, kBNU, kBNV, kBD, kCNU, kCNV, kCD };

// Which phase ended the test (the hardware frees the slot there; timing stays the pipeline's).
enum class IstExit : uint8_t { hit = 0, distance = 1, beta = 2, gamma = 3, sum = 4 };

struct IstOut {
  IstExit exit;
  uint32_t t;    // in the format F (valid from phase 1 on: Wald's; every exit: the watertight test's)
  uint32_t den;  // n . d (unnormalised normal with n_k = 1): its sign says which side the ray hits
  uint32_t tk;   // t as the closest-hit key (KeyFormat<F>, below): what the interval compares see
};

// The watertight test's shear format: the format with 23 mantissa bits and 8 exponent bits (FP32's)
// when the image's format is narrower (FP24), else the format itself. Every FP24 number is exactly
// an FP32 number (widen), so the sheared coordinates and edge functions are computed from the same
// exact products, rounded to 24 bits instead of 17: a ray has to pass 2^7 times closer to an
// outline edge for the rounding of px, py to decide its side. raycore's sop is the exact sum
// truncated once, as rtz's (hls/fp.h), so the shear runs rtz for it (its add3 too: det is only
// tested for zero).
template <class F>
using ShearFormat = typename std::conditional<(F::man_bits < 23), Format<8, 23>, F>::type;
constexpr Rounding shear_rounding(Rounding r) { return r == Rounding::raycore ? Rounding::rtz : r; }

// The closest-hit key: a hit's t in the format with F's exponent and the shear format's mantissa
// (FP24: 7 / 23; FP32: FP32 itself). The watertight test's t is computed in the shear format G
// and narrowed to the key exactly (the same mantissa; only an exponent outside F's range flushes
// or saturates); Wald's t is its F value widened (t_key: the mantissa shifted left, the
// extension bits zero), so a Wald frame's compares are its F compares. Every "which hit is
// closer" and "is the hit beyond this cell" compare of the tracer, the model and the RTL is on
// keys (the ray's tmax, the leaf and best records, the traversal's tfar / tnear widened); the hit
// unit's t is the key truncated to F (key_t: the top bits, whatever the image's rounding: no
// logic). On the bit patterns: a key is an F pattern with KeyFormat::man_bits - F::man_bits more
// mantissa bits below (the RTL's {t, ext}).
template <class F>
using KeyFormat = Format<F::exp_bits, ShearFormat<F>::man_bits>;
template <class F>
constexpr uint32_t t_key(uint32_t t) {
  return widen<F, KeyFormat<F>>(t);
}
template <class F>
constexpr uint32_t key_t(uint32_t k) {
  return k >> (KeyFormat<F>::man_bits - F::man_bits);
}
template <class F>
constexpr bool key_lt(uint32_t a, uint32_t b) {
  return lt<KeyFormat<F>>(a, b);
}

// Phase 1 of Wald's test: t on the record's plane n_u, n_v, n_d (c[0..2]), den = n . d; exit
// distance unless tmin < t < tmax (else exit hit: phase 1 passed).
template <class A>
inline IstOut ist_distance(uint32_t k, const uint32_t* c, const uint32_t o[3], const uint32_t d[3], uint32_t tmin,
                           uint32_t tmax) {
  const int u = axis_u(k), v = axis_v(k);
  const uint32_t den = A::add3(d[k], A::mul(c[kNU], d[u]), A::mul(c[kNV], d[v]));
  const uint32_t num =
      A::sub(A::sub(c[kND], o[k]), A::add(A::mul(c[kNU], o[u]), A::mul(c[kNV], o[v])));
  const uint32_t t = A::mul(num, A::rcp(den));
  return {A::lt(tmin, t) && A::lt(t, tmax) ? IstExit::hit : IstExit::distance, t, den,
          t_key<typename A::Fmt>(t)};
}

// A hit needs tmin < t < tmax; beta >= -eps, gamma >= -eps, beta + gamma <= one_eps (hls/margins.h:
// a coordinate x fails iff sign(x) && |eps| < |x|, the sum iff one_eps < beta + gamma; with
// margins_none(), eps = 0 and one_eps = 1: beta >= 0, gamma >= 0, beta + gamma <= 1).
template <class A>
inline IstOut ist_wald(uint32_t k, const uint32_t c[9], const uint32_t o[3], const uint32_t d[3],
                       uint32_t tmin, uint32_t tmax, const Margins& m) {
  const int u = axis_u(k), v = axis_v(k);
  const IstOut p1 = ist_distance<A>(k, c, o, d, tmin, tmax);
  if (p1.exit != IstExit::hit) return p1;
  const uint32_t t = p1.t, den = p1.den;
  // Phase 2: first barycentric coordinate at the hit point's projection.
  const uint32_t hu = A::add(o[u], A::mul(t, d[u]));
  const uint32_t hv = A::add(o[v], A::mul(t, d[v]));
  const uint32_t beta = A::add3(A::mul(c[kBNU], hu), A::mul(c[kBNV], hv), c[kBD]);
  const uint32_t eps = A::abs(m.eps);
  if (A::sign(beta) && A::lt(eps, A::abs(beta))) return {IstExit::beta, t, den, p1.tk};
  // Phase 3: second coordinate and the sum.
  const uint32_t gamma = A::add3(A::mul(c[kCNU], hu), A::mul(c[kCNV], hv), c[kCD]);
  if (A::sign(gamma) && A::lt(eps, A::abs(gamma))) return {IstExit::gamma, t, den, p1.tk};
  if (A::lt(m.one_eps, A::add(beta, gamma))) return {IstExit::sum, t, den, p1.tk};
  return {IstExit::hit, t, den, p1.tk};
}

// Without margins (today's test).
template <class A>
inline IstOut ist_wald(uint32_t k, const uint32_t c[9], const uint32_t o[3], const uint32_t d[3],
                       uint32_t tmin, uint32_t tmax) {
  return ist_wald<A>(k, c, o, d, tmin, tmax, margins_none<A>());
}

// The watertight test (Woop, Benthin and Wald 2013) on a watertight record: c = the plane n_u,
// n_v, n_d (the stored triangle's: through its vertex A, hls/wald.h watertight_nd; den comes from
// it) and the vertices A, B, C at c[3..11]. The ray is sheared to +z: kz = the axis of the largest
// |d| (ties to the lower axis), kx = kz + 1, ky = kz + 2 (mod 3); the sheared coordinates are
// scaled by d_kz instead of divided by it (no per-ray reciprocal; the edge functions scale by
// d_kz^2 > 0, so their signs are the paper's, and t's numerator and denominator both by d_kz^2):
//   den = sop(d_k, -0, n_u, d_u, n_v, d_v) in F (n . d on the record's plane: the hit unit's side)
//   in the shear format G (ShearFormat: FP32's 8/23 for FP24; the inputs widened exactly):
//   the ray's origin   ox = sop(-0, -0, d_kz, o_kx, -d_kx, o_kz)   oy likewise with ky
//   a vertex P         px = sop(-ox, -0, d_kz, P_kx, -d_kx, P_kz)  = d_kz (P - o)_kx - d_kx (P - o)_kz,
//                      py likewise (one rounding, and the ray's ox); pz = P_kz - o_kz (sub)
//   an edge            E(P, Q) = sop(-0, -0, qx, py, -qy, px) = qx py - qy px, rounded once
//   U = E(B, C), V = E(C, A), W = E(A, B); outside (exit beta) when some are < 0 and some > 0;
//   det = add3(U, V, W) = 0: no hit (exit sum: edge-on, or a degenerate record's equal vertices);
//   t = div(sop(mul(W, pz_C), -0, U, pz_A, V, pz_B), mul(det, d_kz))   (Woop's T / det with the
//     sheared z = pz / d_kz: its 1 / d_kz moves to the divisor), narrowed to the key exactly;
//   exit distance unless tmin < t < tmax, compared as keys (tmax is one: the ray's, or the best
//   hit's). The result's t (F) is the key truncated (key_t), its tk the key.
// Why it is watertight: a vertex's (px, py) depends on the vertex and the ray only, so two
// triangles sharing an edge see the same two points, and E(Q, P) has exactly the negated terms of
// E(P, Q), rounded once by a sign-symmetric rounding (rtz, rne, raycore's truncation): its exact
// negation. A ray through the shared edge is inside one of the two triangles or on the edge of
// both (E = 0, inside for both); no ray passes between them, nor through a shared vertex. The sop
// rounds an edge function once from exact products, so its sign is the exact sign for the sheared
// points. Why t from the vertices, in G (since 2026-12-07; before: Wald's plane distance in F):
// the closest of two hits is decided at 23 bits on a t computed from the same sheared vertices the
// inside test used, so two surfaces an F ulp of t apart are ordered, and a ray that is inside
// meets the plane it was tested against (docs/results.md, "The next lever, built"). Per test: 1 sop
// in F, 2 + 6 + 3 + 1 sops, 3 subs, 2 muls, 1 add3 and 1 division in G.
template <class A>
inline IstOut ist_watertight(uint32_t k, const uint32_t c[12], const uint32_t o[3], const uint32_t d[3],
                             uint32_t tmin, uint32_t tmax_k) {
  using F = typename A::Fmt;
  using G = ShearFormat<F>;
  using AW = Arith<G, shear_rounding(A::rounding)>;
  constexpr uint32_t absent = F::sign_mask, wabsent = G::sign_mask;
  auto wide = [](uint32_t x) { return widen<F, G>(x); };
  const int u = axis_u(k), v = axis_v(k);
  const uint32_t den = A::sop(d[k], absent, c[kNU], d[u], c[kNV], d[v]);
  int kz = 0;
  if (A::lt(A::abs(d[0]), A::abs(d[1]))) kz = 1;
  if (A::lt(A::abs(d[kz]), A::abs(d[2]))) kz = 2;
  const int kx = kz == 2 ? 0 : kz + 1, ky = kz == 0 ? 2 : kz - 1;
  const uint32_t dz = wide(d[kz]), ndx = wide(A::neg(d[kx])), ndy = wide(A::neg(d[ky]));
  const uint32_t ox = AW::sop(wabsent, wabsent, dz, wide(o[kx]), ndx, wide(o[kz]));
  const uint32_t oy = AW::sop(wabsent, wabsent, dz, wide(o[ky]), ndy, wide(o[kz]));
  uint32_t px[3], py[3], pz[3];
  for (int j = 0; j < 3; ++j) {
    const uint32_t* p = c + 3 + 3 * j;
    px[j] = AW::sop(AW::neg(ox), wabsent, dz, wide(p[kx]), ndx, wide(p[kz]));
    py[j] = AW::sop(AW::neg(oy), wabsent, dz, wide(p[ky]), ndy, wide(p[kz]));
    pz[j] = AW::sub(wide(p[kz]), wide(o[kz]));
  }
  auto edge = [&](int p, int q) { return AW::sop(wabsent, wabsent, px[q], py[p], AW::neg(py[q]), px[p]); };
  const uint32_t U = edge(1, 2), V = edge(2, 0), W = edge(0, 1);
  const uint32_t det = AW::add3(U, V, W);
  const uint32_t T = AW::sop(AW::mul(W, pz[2]), wabsent, U, pz[0], V, pz[1]);
  const uint32_t tk = narrow<G, KeyFormat<F>, Rounding::rtz>(AW::div(T, AW::mul(det, dz)));
  IstOut r{IstExit::hit, key_t<F>(tk), den, tk};
  auto negative = [](uint32_t x) { return AW::sign(x) && !AW::is_zero(x); };
  auto positive = [](uint32_t x) { return !AW::sign(x) && !AW::is_zero(x); };
  if ((negative(U) || negative(V) || negative(W)) && (positive(U) || positive(V) || positive(W)))
    r.exit = IstExit::beta;
  else if (AW::is_zero(det))  // a triangle seen edge-on (or the degenerate record) has no inside
    r.exit = IstExit::sum;
  else if (!(key_lt<F>(t_key<F>(tmin), tk) && key_lt<F>(tk, tmax_k)))
    r.exit = IstExit::distance;
  return r;
}

// The image's test for a record of either kind (margins: Wald's only; the watertight test has
// none), the interval's end tmax_k a key (the ray's tmax, or its best hit's; Wald's test compares
// its F value, the key truncated: a Wald frame's keys are widened F values, so exactly).
template <class A>
inline IstOut ist_test_key(const WaldTri<typename A::Fmt>& w, const uint32_t o[3], const uint32_t d[3],
                           uint32_t tmin, uint32_t tmax_k, const Margins& m) {
  using F = typename A::Fmt;
  if (w.kind == IstKind::watertight) return ist_watertight<A>(w.k, w.c, o, d, tmin, tmax_k);
  return ist_wald<A>(w.k, w.c, o, d, tmin, key_t<F>(tmax_k), m);
}
// With tmax in F (a ray's own interval).
template <class A>
inline IstOut ist_test(const WaldTri<typename A::Fmt>& w, const uint32_t o[3], const uint32_t d[3], uint32_t tmin,
                       uint32_t tmax, const Margins& m) {
  return ist_test_key<A>(w, o, d, tmin, t_key<typename A::Fmt>(tmax), m);
}
template <class A>
inline IstOut ist_test(const WaldTri<typename A::Fmt>& w, const uint32_t o[3], const uint32_t d[3], uint32_t tmin,
                       uint32_t tmax) {
  return ist_test<A>(w, o, d, tmin, tmax, margins_none<A>());
}

}  // namespace raycore::hls
