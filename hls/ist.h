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
  uint32_t t;    // valid from phase 1 on
  uint32_t den;  // n . d (unnormalised normal with n_k = 1): its sign says which side the ray hits
};

// Phase 1 of both tests (Wald's and the watertight one): t on the record's plane n_u, n_v, n_d
// (c[0..2]), den = n . d; exit distance unless tmin < t < tmax (else exit hit: phase 1 passed).
template <class A>
inline IstOut ist_distance(uint32_t k, const uint32_t* c, const uint32_t o[3], const uint32_t d[3], uint32_t tmin,
                           uint32_t tmax) {
  const int u = axis_u(k), v = axis_v(k);
  const uint32_t den = A::add3(d[k], A::mul(c[kNU], d[u]), A::mul(c[kNV], d[v]));
  const uint32_t num =
      A::sub(A::sub(c[kND], o[k]), A::add(A::mul(c[kNU], o[u]), A::mul(c[kNV], o[v])));
  const uint32_t t = A::mul(num, A::rcp(den));
  return {A::lt(tmin, t) && A::lt(t, tmax) ? IstExit::hit : IstExit::distance, t, den};
}

// Phase 1 of the watertight test: the same plane and interval test with num = n_d - o_k - n_u o_u -
// n_v o_v and den = d_k + n_u d_u + n_v d_v each one sop (the exact products summed, rounded once;
// -0 an absent term) and t = div(num, den) rounded once (raycore's div: num x its table reciprocal,
// as Wald's): about 1.5 ulps of t at most, where Wald's ten roundings reach tens of ulps as num
// cancels (a ray from far away: docs/results.md, "What is left in the zero configuration").
template <class A>
inline IstOut ist_distance_sop(uint32_t k, const uint32_t* c, const uint32_t o[3], const uint32_t d[3],
                               uint32_t tmin, uint32_t tmax) {
  const int u = axis_u(k), v = axis_v(k);
  constexpr uint32_t absent = A::Fmt::sign_mask;
  const uint32_t den = A::sop(d[k], absent, c[kNU], d[u], c[kNV], d[v]);
  const uint32_t num = A::sop(c[kND], A::neg(o[k]), A::neg(c[kNU]), o[u], A::neg(c[kNV]), o[v]);
  const uint32_t t = A::div(num, den);
  return {A::lt(tmin, t) && A::lt(t, tmax) ? IstExit::hit : IstExit::distance, t, den};
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
  if (A::sign(beta) && A::lt(eps, A::abs(beta))) return {IstExit::beta, t, den};
  // Phase 3: second coordinate and the sum.
  const uint32_t gamma = A::add3(A::mul(c[kCNU], hu), A::mul(c[kCNV], hv), c[kCD]);
  if (A::sign(gamma) && A::lt(eps, A::abs(gamma))) return {IstExit::gamma, t, den};
  if (A::lt(m.one_eps, A::add(beta, gamma))) return {IstExit::sum, t, den};
  return {IstExit::hit, t, den};
}

// Without margins (today's test).
template <class A>
inline IstOut ist_wald(uint32_t k, const uint32_t c[9], const uint32_t o[3], const uint32_t d[3],
                       uint32_t tmin, uint32_t tmax) {
  return ist_wald<A>(k, c, o, d, tmin, tmax, margins_none<A>());
}

// The watertight test (Woop, Benthin and Wald 2013's inside test) on a watertight record: c = the
// plane n_u, n_v, n_d (the stored triangle's: through its vertex A, hls/wald.h watertight_nd) and
// the vertices A, B, C at c[3..11]. The distance is Wald's phase 1, the same operations, on the
// record's plane (so the hit unit and every spawn rule see points made as Wald's test makes them:
// on an axis-aligned plane, where n_u = n_v = 0, a shadow ray's own t is exactly 0 as with Wald's
// record); the inside test is the paper's, on the vertices. The ray is sheared to +z: kz = the
// axis of the largest |d| (ties to the lower axis), kx = kz + 1, ky = kz + 2 (mod 3); the sheared
// coordinates are scaled by d_kz instead of divided by it (no per-ray reciprocal; the edge
// functions scale by d_kz^2 > 0, so their signs are the paper's):
//   phase 1 (exit distance)  ist_distance_sop: num and den each one sop, t = div(num, den) (until
//                            2026-12-07 Wald's ist_distance: den = add3(d_k, n_u d_u, n_v d_v), t = num rcp(den))
//   in the shear format G (ShearFormat: FP32's 8/23 for FP24; the inputs widened exactly):
//   the ray's origin   ox = sop(-0, -0, d_kz, o_kx, -d_kx, o_kz)   oy likewise with ky
//   a vertex P         px = sop(-ox, -0, d_kz, P_kx, -d_kx, P_kz)  = d_kz (P - o)_kx - d_kx (P - o)_kz,
//                      py likewise                                 one rounding (and the ray's ox)
//   an edge            E(P, Q) = sop(-0, -0, qx, py, -qy, px) = qx py - qy px, rounded once
//   U = E(B, C), V = E(C, A), W = E(A, B); outside (exit beta) when some are < 0 and some > 0;
//   det = add3(U, V, W) = 0: no hit (exit sum: edge-on, or a degenerate record's equal vertices).
// Why it is watertight: a vertex's (px, py) depends on the vertex and the ray only, so two
// triangles sharing an edge see the same two points, and E(Q, P) has exactly the negated terms of
// E(P, Q), rounded once by a sign-symmetric rounding (rtz, rne, raycore's truncation): its exact
// negation. A ray through the shared edge is inside one of the two triangles or on the edge of
// both (E = 0, inside for both); no ray passes between them, nor through a shared vertex. The sop
// rounds an edge function once from exact products, so its sign is the exact sign for the sheared
// points. Per test: phase 1's 2 sops and a division in the format, 2 + 6 + 3 sops (22 exact
// products) and 1 add3 in the shear format G (below).

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

template <class A>
inline IstOut ist_watertight(uint32_t k, const uint32_t c[12], const uint32_t o[3], const uint32_t d[3],
                             uint32_t tmin, uint32_t tmax) {
  using F = typename A::Fmt;
  const IstOut p1 = ist_distance_sop<A>(k, c, o, d, tmin, tmax);  // on the record's plane
  if (p1.exit != IstExit::hit) return p1;
  const uint32_t t = p1.t, den = p1.den;
  // Phase 2: the edge functions on the sheared vertices, in the shear format G (FP24's inputs
  // widened exactly to FP32's 8/23: the sheared coordinates rounded to 24 bits instead of 17).
  using G = ShearFormat<F>;
  using AW = Arith<G, shear_rounding(A::rounding)>;
  constexpr uint32_t wabsent = G::sign_mask;
  auto wide = [](uint32_t x) { return widen<F, G>(x); };
  int kz = 0;
  if (A::lt(A::abs(d[0]), A::abs(d[1]))) kz = 1;
  if (A::lt(A::abs(d[kz]), A::abs(d[2]))) kz = 2;
  const int kx = kz == 2 ? 0 : kz + 1, ky = kz == 0 ? 2 : kz - 1;
  const uint32_t dz = wide(d[kz]), ndx = wide(A::neg(d[kx])), ndy = wide(A::neg(d[ky]));
  const uint32_t ox = AW::sop(wabsent, wabsent, dz, wide(o[kx]), ndx, wide(o[kz]));
  const uint32_t oy = AW::sop(wabsent, wabsent, dz, wide(o[ky]), ndy, wide(o[kz]));
  uint32_t px[3], py[3];
  for (int j = 0; j < 3; ++j) {
    const uint32_t* p = c + 3 + 3 * j;
    px[j] = AW::sop(AW::neg(ox), wabsent, dz, wide(p[kx]), ndx, wide(p[kz]));
    py[j] = AW::sop(AW::neg(oy), wabsent, dz, wide(p[ky]), ndy, wide(p[kz]));
  }
  auto edge = [&](int p, int q) { return AW::sop(wabsent, wabsent, px[q], py[p], AW::neg(py[q]), px[p]); };
  const uint32_t U = edge(1, 2), V = edge(2, 0), W = edge(0, 1);
  auto negative = [](uint32_t x) { return AW::sign(x) && !AW::is_zero(x); };
  auto positive = [](uint32_t x) { return !AW::sign(x) && !AW::is_zero(x); };
  if ((negative(U) || negative(V) || negative(W)) && (positive(U) || positive(V) || positive(W)))
    return {IstExit::beta, t, den};
  // Phase 3: a triangle seen edge-on (or the degenerate record) has no inside.
  if (AW::is_zero(AW::add3(U, V, W))) return {IstExit::sum, t, den};
  return {IstExit::hit, t, den};
}

// The image's test for a record of either kind (margins: Wald's only; the watertight test has none).
template <class A>
inline IstOut ist_test(const WaldTri<typename A::Fmt>& w, const uint32_t o[3], const uint32_t d[3], uint32_t tmin,
                       uint32_t tmax, const Margins& m) {
  if (w.kind == IstKind::watertight) return ist_watertight<A>(w.k, w.c, o, d, tmin, tmax);
  return ist_wald<A>(w.k, w.c, o, d, tmin, tmax, m);
}
template <class A>
inline IstOut ist_test(const WaldTri<typename A::Fmt>& w, const uint32_t o[3], const uint32_t d[3], uint32_t tmin,
                       uint32_t tmax) {
  return ist_test<A>(w, o, d, tmin, tmax, margins_none<A>());
}

}  // namespace raycore::hls
