// hls/margins.h - watertightness margins of the ist and trv datapaths (issue 15, section 3): two
// per-frame registers of the ist and one of the trv, set on the host. RayCore's own emulator
// accepts beta, gamma >= -0.008 and widens traversal intervals by a few ulps; here both are options
// independent of the shadow-ray spawn strategy, and Margins{} of margins_none() changes nothing
// bit for bit.
//
//   ist (hls::ist_wald): a hit needs beta >= -eps, gamma >= -eps and beta + gamma <= one_eps, with
//     eps >= 0 a number of the format and one_eps = 1 + eps rounded once (the format's add). A
//     coordinate x fails iff sign(x) && |eps| < |x| (a sign bit and an integer compare of the
//     magnitude bits, a zero exponent field meaning zero; eps's sign bit is ignored); the sum fails
//     iff one_eps < beta + gamma. eps = 0, one_eps = 1 are today's rules (x fails iff negative and
//     nonzero; the sum iff 1 < beta + gamma), and a larger eps only turns failures into hits.
//   trv (hls::trv_split, hls::trv_clip_box): widen_ulps N >= 0 widens the interval each comparison
//     sees by N ulps on each side, on the bit pattern (hls::add_ulps: tnear N ulps down, tfar N
//     ulps up); the interval values the unit keeps and pushes are not widened. N = 0 is today's.
//     add_ulps never crosses zero: a widened interval end stops at +0.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "hls/fp.h"

namespace raycore::hls {

struct Margins {
  uint32_t eps = 0;      // ist: barycentric margin (a non-negative number of the format)
  uint32_t one_eps = 0;  // ist: 1 + eps rounded once (the format's 1.0 when eps = 0)
  int32_t widen_ulps = 0;  // trv: interval widening in ulps (0..kMaxWidenUlps)
};

// The largest widening the trv's register takes (7 bits in rtl/units/trv.v).
constexpr int32_t kMaxWidenUlps = 64;

// No margins: today's ist and trv bit for bit.
template <class A>
constexpr Margins margins_none() {
  return Margins{0u, A::one, 0};
}

// The registers from the host's values: eps (a double >= 0, rounded once to the format) and N.
template <class A>
inline Margins make_margins(double eps, int32_t widen_ulps) {
  if (!(eps >= 0) || !std::isfinite(eps)) throw std::invalid_argument("barycentric margin must be a finite number >= 0");
  if (widen_ulps < 0 || widen_ulps > kMaxWidenUlps)
    throw std::invalid_argument("trv widening must be 0..64 ulps");
  Margins m;
  m.eps = A::from_double(eps);
  m.one_eps = A::add(A::one, m.eps);
  m.widen_ulps = widen_ulps;
  return m;
}

}  // namespace raycore::hls
