// hls/ist.h - the intersection unit's datapath: Wald's projected ray/triangle test with three
// early-exit phases (distance, first barycentric, second barycentric and their sum).
//
// Per test: 11 multiplies, 6 two-input adds, 3 three-input adds, 1 reciprocal (RayCore's count).
// The triangle is the nine constants of the memory image, in the project's convention:
//   t     = (n_d - o_k - (n_u o_u + n_v o_v)) / (d_k + n_u d_u + n_v d_v)
//   beta  = b_nu h_u + b_nv h_v + b_d      (weight of vertex B)
//   gamma = c_nu h_u + c_nv h_v + c_d      (weight of vertex C)
// with h = o + t d the hit point and (k, u, v) the projection axes.
#pragma once

#include <cstdint>

#include "hls/fp.h"
#include "hls/margins.h"
#include "hls/ray.h"

namespace raycore::hls {

enum WaldConst : int { kNU = 0, kNV, kND, kBNU, kBNV, kBD, kCNU, kCNV, kCD };

// Which phase ended the test (the hardware frees the slot there; timing stays the pipeline's).
enum class IstExit : uint8_t { hit = 0, distance = 1, beta = 2, gamma = 3, sum = 4 };

struct IstOut {
  IstExit exit;
  uint32_t t;    // valid from phase 1 on
  uint32_t den;  // n . d (unnormalised normal with n_k = 1): its sign says which side the ray hits
};

// A hit needs tmin < t < tmax; beta >= -eps, gamma >= -eps, beta + gamma <= one_eps (hls/margins.h:
// a coordinate x fails iff sign(x) && |eps| < |x|, the sum iff one_eps < beta + gamma; with
// margins_none(), eps = 0 and one_eps = 1: beta >= 0, gamma >= 0, beta + gamma <= 1).
template <class A>
inline IstOut ist_wald(uint32_t k, const uint32_t c[9], const uint32_t o[3], const uint32_t d[3],
                       uint32_t tmin, uint32_t tmax, const Margins& m) {
  const int u = axis_u(k), v = axis_v(k);
  // Phase 1: distance.
  const uint32_t den = A::add3(d[k], A::mul(c[kNU], d[u]), A::mul(c[kNV], d[v]));
  const uint32_t num =
      A::sub(A::sub(c[kND], o[k]), A::add(A::mul(c[kNU], o[u]), A::mul(c[kNV], o[v])));
  const uint32_t t = A::mul(num, A::rcp(den));
  if (!(A::lt(tmin, t) && A::lt(t, tmax))) return {IstExit::distance, t, den};
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

}  // namespace raycore::hls
