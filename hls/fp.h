// hls/fp.h - the one definition of the hardware's floating-point numbers.
//
// A format is a template on (exponent bits, mantissa bits); FP24 = Format<7, 16> (RayCore's,
// bias 63) and FP32 = Format<8, 23>. Numbers travel as bit patterns in a uint32_t (sign in bit
// E+M, exponent field above the mantissa field), exactly the wires of the hardware.
//
// Semantics, for every operation: the exact result, rounded once to M+1 significant bits with the
// rounding policy (rtz: toward zero; rne: to nearest, ties to even) at unbounded exponent range,
// then
//   - flushed to a signed zero if its exponent is below the smallest normal (no denormals), and
//   - saturated to the largest magnitude with its sign if above the largest (no Inf/NaN).
// Inputs whose exponent field is 0 are zeros, whatever their mantissa field holds (flush on input).
// The top exponent field is an ordinary binade (there is no Inf/NaN encoding). An exact zero sum
// is +0 unless every addend is -0 (IEEE 754's rule for rtz and rne).
//
// The third policy, `raycore`, is RayCore's own arithmetic as far as it is published (designed
// here from those facts; FP24 only: formats with M > 16 are refused at compile time by rcp, and
// at run time by hls::visit_format). It is NOT correctly rounded:
//   - conversions, mul and sqrt: exactly rtz (the exact result truncated once), bit for bit;
//   - add/sub (one guard bit, no sticky): order by magnitude |a| >= |b|; b's significand is
//     aligned to a's exponent and truncated (toward zero, in magnitude) to a multiple of
//     2^(ea-M-1), one guard bit below a's last place; the magnitudes are added or subtracted
//     exactly and the result truncated to M+1 bits (then flush/saturate). An effective addition
//     equals rtz bit for bit. An effective subtraction |a| - trunc(|b|) is >= the exact
//     |a| - |b| by less than 2^(ea-M-1), so its result is rtz's or the next magnitude above it:
//     the exact value lies on either side, |result - exact| < 1 ulp of the exact value, and an
//     exactly representable difference is exact;
//   - add3 (two guard bits, no sticky): order by magnitude |a| >= |b| >= |c| (a nonzero); b and c
//     are aligned to a's exponent and each truncated (in magnitude) to a multiple of
//     2^(ea-M-2); the signed sum is exact and truncated to M+1 bits. No special cases: an exact
//     pair cancellation a = -b leaves c truncated to that grid. |result - exact| <
//     2^(ea-M-1) + ulp(result) (half an ulp of a for the two dropped tails, plus the final
//     truncation); when every operand's bits fit the grid (exponents >= ea - 2) the sum is rtz's
//     bit for bit; with three equal signs the result is rtz's or one ulp below it;
//   - rcp: a 32-entry table of quadratic segment coefficients indexed by the top 5 mantissa
//     bits, two small multiplies, every step truncated (rcp_raycore below); exhaustively over all
//     FP24 mantissas its error is at most 1.19 ulp of the exact reciprocal (measured against MPFR
//     in tb/fp, RaycoreRcp.Exhaustive: max 1.183 ulp, from -1.183 to +0.735 in magnitude);
//   - div(a, b) = mul(a, rcp(b)): relative error < 2.19 * 2^-M (rcp's plus the truncation; tb/fp
//     measures 2.10 on its vectors); b = 0 saturates as div does; rcp(b) flushes for |b| > 2^62
//     in FP24, and so does the quotient.
// A sound unit roundoff for error bounds is u = 2^(1-M) (hls/hit.h: unit_roundoff): every raycore
// operation the datapaths use errs by less than u times the magnitudes an rtz analysis charges
// (which uses u = 2^-M): add, mul, conversions, sqrt < 2^-M |exact|, rcp <= 1.19 * 2^-M |exact|,
// add3 < 1.5 * 2^-M (|a| + |b| + |c|). (div, used by no datapath, errs up to 2.19 * 2^-M.)
//
// Written in the synthesizable style: fixed-width integer arithmetic on bit patterns, no host
// floating point inside the operations, no allocation. The same functions are the datapath of the
// golden tracer and of the SystemC models; the RTL in rtl/ produces the same bits.
#pragma once

#include <cstdint>
#include <cstring>
#include <type_traits>

namespace raycore::hls {

enum class Rounding : uint8_t { rtz, rne, raycore };

template <int E, int M>
struct Format {
  static_assert(E >= 2 && E <= 11, "exponent width must fit an IEEE double's range");
  static_assert(M >= 2 && 1 + E + M <= 32, "a number must fit in 32 bits");
  static constexpr int exp_bits = E;
  static constexpr int man_bits = M;
  static constexpr int width = 1 + E + M;
  static constexpr int bias = (1 << (E - 1)) - 1;
  static constexpr int exp_field_max = (1 << E) - 1;  // an ordinary binade: no Inf/NaN
  static constexpr int emin = 1 - bias;               // unbiased exponent of the smallest normal
  static constexpr int emax = exp_field_max - bias;   // unbiased exponent of the largest binade
  static constexpr uint32_t sign_mask = 1u << (E + M);
  static constexpr uint32_t exp_mask = uint32_t(exp_field_max) << M;
  static constexpr uint32_t man_mask = (1u << M) - 1u;
  static constexpr uint32_t mask = sign_mask | exp_mask | man_mask;
  static constexpr uint32_t max_mag = exp_mask | man_mask;  // largest magnitude
  static constexpr uint32_t min_mag = 1u << M;              // smallest normal magnitude
  static constexpr uint32_t one = uint32_t(bias) << M;      // 1.0
};

using FP24 = Format<7, 16>;
using FP32 = Format<8, 23>;

namespace detail {

__extension__ typedef unsigned __int128 u128;
__extension__ typedef __int128 i128;

constexpr int msb(uint64_t v) { return 63 - __builtin_clzll(v); }
constexpr int msb(u128 v) {
  const uint64_t hi = uint64_t(v >> 64);
  return hi ? 64 + msb(hi) : msb(uint64_t(v));
}

// The significand of a nonzero number with its hidden one (M+1 bits) and its unbiased exponent:
// value = sig * 2^(exp - M).
template <class F>
struct Unpacked {
  bool sign;
  int exp;
  uint32_t sig;
};

template <class F>
constexpr Unpacked<F> unpack(uint32_t a) {
  return {(a & F::sign_mask) != 0, int((a >> F::man_bits) & uint32_t(F::exp_field_max)) - F::bias,
          (a & F::man_mask) | (1u << F::man_bits)};
}

}  // namespace detail

template <class F>
constexpr bool is_zero(uint32_t a) {
  return (a & F::exp_mask) == 0;
}
template <class F>
constexpr bool sign_of(uint32_t a) {
  return (a & F::sign_mask) != 0;
}
template <class F>
constexpr uint32_t signed_zero(bool sign) {
  return sign ? F::sign_mask : 0u;
}

// The shared rounding step (raycore truncates here, as rtz). The exact value is (-1)^sign * (mag + s) * 2^lsb_exp, where s = 0 if
// !sticky and 0 < s < 1 otherwise. Precondition: mag != 0, and if sticky then mag has at least
// M+2 significant bits (so the dropped part holds a guard bit above the sticky one).
template <class F, Rounding R, class U>
constexpr uint32_t round_pack(bool sign, int lsb_exp, U mag, bool sticky) {
  constexpr int M = F::man_bits;
  const int p = detail::msb(mag);
  int e = lsb_exp + p;
  const int sh = p - M;
  uint64_t kept = 0;
  if (sh > 0) {
    kept = uint64_t(mag >> sh);
    if constexpr (R == Rounding::rne) {
      const U rem = mag & ((U(1) << sh) - 1);
      const U half = U(1) << (sh - 1);
      if (rem > half || (rem == half && (sticky || (kept & 1u)))) {
        ++kept;
        if (kept >> (M + 1)) {
          kept >>= 1;
          ++e;
        }
      }
    }
  } else {
    kept = uint64_t(mag) << (-sh);
  }
  const int biased = e + F::bias;
  if (biased < 1) return signed_zero<F>(sign);  // flush: no denormals
  if (biased > F::exp_field_max) return signed_zero<F>(sign) | F::max_mag;  // saturate
  return signed_zero<F>(sign) | (uint32_t(biased) << M) | (uint32_t(kept) & F::man_mask);
}

// ---- sign operations --------------------------------------------------------------------------

template <class F>
constexpr uint32_t neg(uint32_t a) {
  return a ^ F::sign_mask;
}
template <class F>
constexpr uint32_t abs(uint32_t a) {
  return a & ~F::sign_mask;
}

// ---- comparison ---------------------------------------------------------------------------------

// A key that orders numbers like their values (+0 and -0 and unflushed zeros all map to 0).
template <class F>
constexpr int64_t order_key(uint32_t a) {
  if (is_zero<F>(a)) return 0;
  const int64_t m = int64_t(a & F::max_mag);
  return sign_of<F>(a) ? -m : m;
}
template <class F>
constexpr bool lt(uint32_t a, uint32_t b) {
  return order_key<F>(a) < order_key<F>(b);
}
template <class F>
constexpr bool le(uint32_t a, uint32_t b) {
  return order_key<F>(a) <= order_key<F>(b);
}
template <class F>
constexpr bool eq(uint32_t a, uint32_t b) {
  return order_key<F>(a) == order_key<F>(b);
}
// Three-way compare: -1, 0, +1.
template <class F>
constexpr int cmp(uint32_t a, uint32_t b) {
  const int64_t ka = order_key<F>(a), kb = order_key<F>(b);
  return (ka > kb) - (ka < kb);
}
// min/max return one of their operands; on equal values, the first.
template <class F>
constexpr uint32_t min(uint32_t a, uint32_t b) {
  return lt<F>(b, a) ? b : a;
}
template <class F>
constexpr uint32_t max(uint32_t a, uint32_t b) {
  return lt<F>(a, b) ? b : a;
}

// ---- arithmetic ---------------------------------------------------------------------------------

// Two-input adder: align the smaller operand to the larger with three extra bits (the smaller is
// jammed into a sticky bit below them), add or subtract, round once.
template <class F, Rounding R>
constexpr uint32_t add(uint32_t a, uint32_t b) {
  constexpr int M = F::man_bits;
  constexpr int G = 3;  // guard bits: with a jammed operand the result is rounded at >= 2^(ea-M-2)
  const bool za = is_zero<F>(a), zb = is_zero<F>(b);
  if (za || zb) {
    if (za && zb) return signed_zero<F>(sign_of<F>(a) && sign_of<F>(b));
    return za ? b : a;
  }
  if ((a & F::max_mag) < (b & F::max_mag)) {
    const uint32_t t = a;
    a = b;
    b = t;
  }
  const auto ua = detail::unpack<F>(a), ub = detail::unpack<F>(b);
  const int d = ua.exp - ub.exp;
  if constexpr (R == Rounding::raycore) {
    // One guard bit, no sticky: b truncated to a multiple of 2^(ea-M-1) (see the header).
    constexpr int G1 = 1;
    const uint64_t ra = uint64_t(ua.sig) << G1;
    const uint64_t rb =
        d <= G1 ? uint64_t(ub.sig) << (G1 - d) : (d <= M + 1 + G1 ? uint64_t(ub.sig) >> (d - G1) : 0);
    const uint64_t rmag = ua.sign == ub.sign ? ra + rb : ra - rb;  // |a| >= |b| >= trunc |b|
    if (rmag == 0) return 0;
    return round_pack<F, R>(ua.sign, ua.exp - M - G1, rmag, false);
  }
  const uint64_t ma = uint64_t(ua.sig) << G;
  uint64_t mb = 0;
  if (d <= G) {
    mb = uint64_t(ub.sig) << (G - d);
  } else if (d <= M + 1 + G) {
    const int s = d - G;
    mb = (uint64_t(ub.sig) >> s) | ((ub.sig & ((1u << s) - 1u)) != 0);
  } else {
    mb = 1;  // entirely below the window: a sticky bit only
  }
  const uint64_t mag = ua.sign == ub.sign ? ma + mb : ma - mb;  // |a| >= |b|, so no borrow
  if (mag == 0) return 0;  // exact cancellation: +0
  return round_pack<F, R>(ua.sign, ua.exp - M - G, mag, false);
}

template <class F, Rounding R>
constexpr uint32_t sub(uint32_t a, uint32_t b) {
  return add<F, R>(a, neg<F>(b));
}

// Three-input adder (RayCore's datapath has them): a + b + c exactly, rounded once.
//
// Sort by magnitude (|a| >= |b| >= |c|) and place a's leading bit at position W = 3M+6 of a signed
// accumulator whose lsb is u = 2^(ea - W). Why this is exact after rounding:
//  - An exact pair cancellation (x + -x) returns the third operand: no window needed.
//  - If b's lsb is >= 2u it is exact in the window, and a + b is a multiple of 2u. If c does not
//    fit, it is jammed (its lost bits ORed into bit 0), which keeps it in the same open interval
//    (2ku, 2(k+1)u) as its true value. The jam happens only if |c| < 2^(ea-2M-6); then either
//    ea - eb >= 2 and |sum| > 2^(ea-2), or a + b is a nonzero multiple of 2^(ea-M-1) and
//    |sum| > 2^(ea-M-2). Either way every rounding boundary near the sum is a multiple of
//    2^(ea-2M-3), so of 2u, and the jammed sum rounds like the exact one.
//  - Otherwise |b|, |c| < 2^(ea-2M-5), well below a quarter ulp of a: the rounding depends only on
//    a and the sign of b + c (which is b's, since |b| > |c| or they are equal with equal signs), so
//    b + c is replaced by one signed lsb.
namespace detail {
// raycore's three-input adder (two guard bits, no sticky; see the header): the window's lsb is
// 2^(ea-M-2), b and c are truncated to it in magnitude, the signed sum is exact, then truncated.
template <class F>
constexpr uint32_t add3_raycore(uint32_t a, uint32_t b, uint32_t c) {
  constexpr int M = F::man_bits;
  constexpr int G = 2;
  if (is_zero<F>(a) && is_zero<F>(b) && is_zero<F>(c))
    return signed_zero<F>(sign_of<F>(a) && sign_of<F>(b) && sign_of<F>(c));
  // The largest magnitude first (zeros have exponent field 0: below every nonzero).
  if ((a & F::max_mag) < (b & F::max_mag)) {
    const uint32_t t = a;
    a = b;
    b = t;
  }
  if ((a & F::max_mag) < (c & F::max_mag)) {
    const uint32_t t = a;
    a = c;
    c = t;
  }
  const auto ua = unpack<F>(a);
  auto aligned = [&](uint32_t x) -> int64_t {
    if (is_zero<F>(x)) return 0;
    const auto ux = unpack<F>(x);
    const int d = ua.exp - ux.exp;
    const int64_t m = d <= G ? int64_t(ux.sig) << (G - d)
                             : (d <= M + 1 + G ? int64_t(ux.sig >> (d - G)) : 0);
    return ux.sign ? -m : m;
  };
  const int64_t ma = int64_t(ua.sig) << G;
  const int64_t sum = (ua.sign ? -ma : ma) + aligned(b) + aligned(c);
  if (sum == 0) return 0;  // exact zero: +0
  const bool sign = sum < 0;
  return round_pack<F, Rounding::raycore>(sign, ua.exp - M - G, uint64_t(sign ? -sum : sum), false);
}
}  // namespace detail

template <class F, Rounding R>
constexpr uint32_t add3(uint32_t a, uint32_t b, uint32_t c) {
  if constexpr (R == Rounding::raycore) return detail::add3_raycore<F>(a, b, c);
  constexpr int M = F::man_bits;
  constexpr int W = 3 * M + 6;
  using S = typename std::conditional<W + 4 <= 63, int64_t, detail::i128>::type;
  using U = typename std::conditional<W + 4 <= 63, uint64_t, detail::u128>::type;

  const bool za = is_zero<F>(a), zb = is_zero<F>(b), zc = is_zero<F>(c);
  if (za + zb + zc >= 2) {
    if (za && zb && zc) return signed_zero<F>(sign_of<F>(a) && sign_of<F>(b) && sign_of<F>(c));
    return !za ? a : (!zb ? b : c);
  }
  if (za) return add<F, R>(b, c);
  if (zb) return add<F, R>(a, c);
  if (zc) return add<F, R>(a, b);

  // Sort by magnitude, descending.
  auto swap_if_less = [](uint32_t& x, uint32_t& y) {
    if ((x & F::max_mag) < (y & F::max_mag)) {
      const uint32_t t = x;
      x = y;
      y = t;
    }
  };
  swap_if_less(a, b);
  swap_if_less(b, c);
  swap_if_less(a, b);

  // Exact pair cancellations.
  if (a == neg<F>(b)) return c;
  if (b == neg<F>(c)) return a;
  if (a == neg<F>(c)) return b;

  const auto ua = detail::unpack<F>(a), ub = detail::unpack<F>(b), uc = detail::unpack<F>(c);
  const S ma = S(U(ua.sig) << (W - M));
  S mb = 0, mc = 0;
  const int db = ua.exp - ub.exp;
  if (W - M - db >= 1) {
    mb = S(U(ub.sig) << (W - M - db));
    const int sc = W - M - (ua.exp - uc.exp);  // left shift of c's significand
    if (sc >= 0) {
      mc = S(U(uc.sig) << sc);
    } else if (-sc <= M + 1) {
      const int s = -sc;
      mc = S((uc.sig >> s) | ((uc.sig & ((1u << s) - 1u)) != 0));
    } else {
      mc = 1;
    }
    if (uc.sign) mc = -mc;
  } else {
    mb = 1;  // b + c, both tiny: one lsb with b's sign
    mc = 0;
  }
  const S sum = (ua.sign ? -ma : ma) + (ub.sign ? -mb : mb) + mc;
  if (sum == 0) return 0;  // exact zero: +0
  const bool sign = sum < 0;
  return round_pack<F, R>(sign, ua.exp - W, U(sign ? -sum : sum), false);
}

template <class F, Rounding R>
constexpr uint32_t mul(uint32_t a, uint32_t b) {
  constexpr int M = F::man_bits;
  const bool sign = sign_of<F>(a) != sign_of<F>(b);
  if (is_zero<F>(a) || is_zero<F>(b)) return signed_zero<F>(sign);
  const auto ua = detail::unpack<F>(a), ub = detail::unpack<F>(b);
  const uint64_t prod = uint64_t(ua.sig) * uint64_t(ub.sig);  // exact, 2M+2 bits
  return round_pack<F, R>(sign, ua.exp + ub.exp - 2 * M, prod, false);
}

// Sum of two addends and two products with one rounding: a + b + x1*y1 + x2*y2 (the VTU's plane
// and edge offsets, hls/vtu.h). A wide intermediate, the same way as add3's window:
//  - every term exact: a number's M+1-bit significand, a product's exact 2M+2-bit one;
//  - T = the top of the largest nonzero term, by exponents only (a number x < 2^(ex+1), a product
//    x*y < 2^(ex+ey+2));
//  - each term aligned to a signed accumulator whose lsb is 2^(T-S), S = 3M+7 (a product whose top
//    is T keeps M+5 bits below its own lsb), the bits a term has below that lsb jammed (ORed into
//    bit 0); the four signed terms added exactly (|sum| < 2^(S+2));
//  - rounded once (round_pack).
// So result = round(exact + d) with |d| < 4 * 2^(T-S) = 2^(T-3M-5): the exact sum rounded once
// whenever no term lies below the window (and, as add, for two terms whatever their exponents: a
// jammed second addend is below 2^(T-2M-6) while the sum is above 2^(T-2), the round-to-odd
// argument); with several terms below it, an error of at most 2^(T-3M-5) before the rounding, at
// most 2^-(3M+3) of the largest term (which is at least 2^(T-2)). The rounding policy's own step
// is round_pack's (raycore truncates, as rtz). Zero terms (a zero number, or a zero factor) add nothing; every term zero gives -0 if
// every one is -0 (a product's sign is the xor of its factors'), else +0; an exact zero sum is +0.
template <class F, Rounding R>
constexpr uint32_t sop(uint32_t a, uint32_t b, uint32_t x1, uint32_t y1, uint32_t x2, uint32_t y2) {
  constexpr int M = F::man_bits;
  constexpr int S = 3 * M + 7;
  using SI = typename std::conditional<S + 3 <= 63, int64_t, detail::i128>::type;
  using U = typename std::conditional<S + 3 <= 63, uint64_t, detail::u128>::type;
  struct Term {
    bool zero, sign;
    int lsb, top;  // value = sig * 2^lsb < 2^top
    uint64_t sig;
  };
  auto plain = [](uint32_t v) -> Term {
    if (is_zero<F>(v)) return {true, sign_of<F>(v), 0, 0, 0};
    const auto u = detail::unpack<F>(v);
    return {false, u.sign, u.exp - M, u.exp + 1, u.sig};
  };
  auto product = [](uint32_t x, uint32_t y) -> Term {
    const bool sign = sign_of<F>(x) != sign_of<F>(y);
    if (is_zero<F>(x) || is_zero<F>(y)) return {true, sign, 0, 0, 0};
    const auto ux = detail::unpack<F>(x), uy = detail::unpack<F>(y);
    return {false, sign, ux.exp + uy.exp - 2 * M, ux.exp + uy.exp + 2, uint64_t(ux.sig) * uy.sig};
  };
  const Term t[4] = {plain(a), plain(b), product(x1, y1), product(x2, y2)};
  bool any = false, all_neg = true;
  int top = 0;
  for (const Term& x : t) {
    all_neg = all_neg && x.sign;
    if (x.zero) continue;
    top = any ? (x.top > top ? x.top : top) : x.top;
    any = true;
  }
  if (!any) return signed_zero<F>(all_neg);
  const int lsb = top - S;
  SI sum = 0;
  for (const Term& x : t) {
    if (x.zero) continue;
    const int sh = x.lsb - lsb;  // <= S - (M+1) for a number, S - (2M+2) for a product
    U mag;
    if (sh >= 0) {
      mag = U(x.sig) << sh;
    } else if (-sh < 64) {
      const int s = -sh;
      mag = U((x.sig >> s) | ((x.sig & ((uint64_t(1) << s) - 1u)) != 0));
    } else {
      mag = 1;  // entirely below the window: the jammed bit
    }
    sum += x.sign ? -SI(mag) : SI(mag);
  }
  if (sum == 0) return 0;  // exact zero: +0
  const bool sign = sum < 0;
  return round_pack<F, R>(sign, lsb, U(sign ? -sum : sum), false);
}

// Division: the quotient of the significands to M+3 bits plus a sticky remainder bit, rounded
// once. x / 0 saturates with the sign of the quotient; 0 / 0 is +0 (there is no NaN).
namespace detail {
// raycore's reciprocal: 1/m for the significand m = 1 + f (f = the mantissa field, widened to 16
// bits) from a 32-entry table indexed by f's top 5 bits i; with d = f's low 11 bits
// (delta = d 2^-16 = m - (1 + i/32)), 1/m ~ c0 - delta (c1 - c2 delta):
//   t1 = (c2 d) >> 7          c2 delta        in units of 2^-16   (8 x 11-bit multiply)
//   p  = c1 - t1              c1 - c2 delta   in units of 2^-16
//   t2 = (p d) >> 13          delta p         in units of 2^-19   (17 x 11-bit multiply)
//   y  = c0 - t2              ~ 1/m           in units of 2^-19, then truncated to M+1 bits
// Every shift truncates. c0 = 1/m_i's quadratic fit in 2^-19 (c0[0] = 2^19 exactly, so rcp(1) =
// 1), c1 in 2^-16, c2 in 2^-7: the fit through the three Chebyshev nodes of the segment
// [1 + i/32, 1 + (i+1)/32), each coefficient rounded to nearest. Worst error over all 2^16
// mantissas: 1.183 ulp of the result (tb/fp, RaycoreRcp.Exhaustive).
struct RcpSegment {
  uint32_t c0, c1, c2;
};
inline constexpr RcpSegment kRaycoreRcpTable[32] = {
    {524288, 65502, 122}, {508400, 61594, 112}, {493447, 58026, 102}, {479349, 54759, 94},
    {466033, 51760, 86},  {453438, 49001, 80},  {441505, 46457, 74},  {430185, 44106, 68},
    {419430, 41929, 63},  {409200, 39909, 59},  {399457, 38032, 55},  {390168, 36284, 51},
    {381300, 34654, 48},  {372827, 33131, 45},  {364722, 31707, 42},  {356962, 30372, 39},
    {349525, 29120, 37},  {342392, 27944, 35},  {335544, 26838, 33},  {328965, 25796, 31},
    {322639, 24813, 29},  {316551, 23886, 27},  {310689, 23010, 26},  {305040, 22181, 25},
    {299593, 21396, 23},  {294337, 20652, 22},  {289262, 19946, 21},  {284360, 19276, 20},
    {279620, 18639, 19},  {275036, 18033, 18},  {270600, 17456, 17},  {266305, 16906, 16}};
constexpr int kRaycoreRcpFrac = 19;  // y's lsb is 2^-19

template <class F>
constexpr uint32_t rcp_raycore(uint32_t a) {
  constexpr int M = F::man_bits;
  static_assert(M <= 16, "rounding `raycore` is defined for FP24 (its reciprocal table has 16 "
                         "mantissa bits)");
  const bool sign = sign_of<F>(a);
  if (is_zero<F>(a)) return signed_zero<F>(sign) | F::max_mag;  // 1/0 saturates, as div
  const auto ua = unpack<F>(a);
  const uint32_t f = (a & F::man_mask) << (16 - M);
  const RcpSegment s = kRaycoreRcpTable[f >> 11];
  const uint32_t d = f & 0x7FFu;
  const uint32_t t1 = (s.c2 * d) >> 7;
  const uint32_t p = s.c1 - t1;
  const uint32_t t2 = (p * d) >> 13;
  const uint32_t y = s.c0 - t2;  // 1/m in units of 2^-19, in (2^18, 2^19]
  return round_pack<F, Rounding::raycore>(sign, -ua.exp - kRaycoreRcpFrac, uint64_t(y), false);
}
}  // namespace detail

template <class F, Rounding R>
constexpr uint32_t div(uint32_t a, uint32_t b) {
  constexpr int M = F::man_bits;
  constexpr int K = M + 3;  // quotient has M+3 or M+4 bits: guard bits for the sticky
  const bool sign = sign_of<F>(a) != sign_of<F>(b);
  if (is_zero<F>(b)) return is_zero<F>(a) ? 0u : (signed_zero<F>(sign) | F::max_mag);
  if (is_zero<F>(a)) return signed_zero<F>(sign);
  if constexpr (R == Rounding::raycore) return mul<F, R>(a, detail::rcp_raycore<F>(b));
  const auto ua = detail::unpack<F>(a), ub = detail::unpack<F>(b);
  const uint64_t num = uint64_t(ua.sig) << K;
  const uint64_t q = num / ub.sig, r = num % ub.sig;
  return round_pack<F, R>(sign, ua.exp - ub.exp - K, q, r != 0);
}

// rcp: div(1, a) for rtz and rne; raycore's table reciprocal (detail::rcp_raycore) for raycore.
template <class F, Rounding R>
constexpr uint32_t rcp(uint32_t a) {
  if constexpr (R == Rounding::raycore) return detail::rcp_raycore<F>(a);
  else return div<F, R>(F::one, a);
}

// Square root: the exact root of the significand (digit by digit, M+3 or more bits) plus a sticky
// remainder bit, rounded once (raycore: truncated, i.e. rtz's result). sqrt of a negative number is +0 (there is no NaN); sqrt(-0) = -0.
template <class F, Rounding R>
constexpr uint32_t sqrt(uint32_t a) {
  constexpr int M = F::man_bits;
  if (is_zero<F>(a)) return a & F::sign_mask;
  if (sign_of<F>(a)) return 0u;
  const auto ua = detail::unpack<F>(a);
  // x = sig << s with (exp - M - s) even and 2M+5 or 2M+6 bits, so the root has M+3 bits.
  int s = M + 5;
  if (((ua.exp - M - s) & 1) != 0) ++s;
  const uint64_t x = uint64_t(ua.sig) << s;
  uint64_t rem = x, root = 0;
  uint64_t bit = uint64_t(1) << ((detail::msb(x) & ~1));
  while (bit != 0) {
    if (rem >= root + bit) {
      rem -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return round_pack<F, R>(false, (ua.exp - M - s) / 2, root, rem != 0);
}

// To a signed integer, rounding toward zero; saturates at +-(2^31 - 1).
template <class F>
constexpr int32_t to_int_rtz(uint32_t a) {
  if (is_zero<F>(a)) return 0;
  const auto u = detail::unpack<F>(a);
  if (u.exp < 0) return 0;
  if (u.exp >= 31) return sign_of<F>(a) ? -2147483647 : 2147483647;
  const int sh = u.exp - F::man_bits;
  const uint64_t m = sh >= 0 ? uint64_t(u.sig) << sh : uint64_t(u.sig) >> (-sh);
  const int32_t v = m > 2147483647u ? 2147483647 : int32_t(m);
  return sign_of<F>(a) ? -v : v;
}

// ---- conversions --------------------------------------------------------------------------------

// From an IEEE binary64 given by its bits. Subnormal doubles flush to zero; Inf and NaN saturate
// with their sign bit (callers that must reject NaN check before converting).
template <class F, Rounding R>
constexpr uint32_t from_double_bits(uint64_t d) {
  const bool sign = (d >> 63) != 0;
  const int ef = int((d >> 52) & 0x7FF);
  if (ef == 0) return signed_zero<F>(sign);
  if (ef == 0x7FF) return signed_zero<F>(sign) | F::max_mag;
  const uint64_t sig = (d & ((uint64_t(1) << 52) - 1)) | (uint64_t(1) << 52);
  return round_pack<F, R>(sign, ef - 1023 - 52, sig, false);
}
template <class F, Rounding R>
inline uint32_t from_double(double x) {
  uint64_t d;
  std::memcpy(&d, &x, sizeof d);
  return from_double_bits<F, R>(d);
}
template <class F, Rounding R>
constexpr uint32_t from_float_bits(uint32_t f) {
  const bool sign = (f >> 31) != 0;
  const int ef = int((f >> 23) & 0xFF);
  if (ef == 0) return signed_zero<F>(sign);
  if (ef == 0xFF) return signed_zero<F>(sign) | F::max_mag;
  const uint64_t sig = (f & 0x7FFFFFu) | 0x800000u;
  return round_pack<F, R>(sign, ef - 127 - 23, sig, false);
}
template <class F, Rounding R>
inline uint32_t from_float(float x) {
  uint32_t f;
  std::memcpy(&f, &x, sizeof f);
  return from_float_bits<F, R>(f);
}

// A number of format F as one of the wider format G, exactly: the exponent rebiased, the mantissa
// shifted left (a zero exponent field stays a zero; the watertight test's shear, hls/ist.h).
template <class F, class G>
constexpr uint32_t widen(uint32_t x) {
  static_assert(G::exp_bits >= F::exp_bits && G::man_bits >= F::man_bits, "widen: G must be wider");
  const uint32_t sign = (x & F::sign_mask) ? G::sign_mask : 0u;
  const uint32_t e = (x & F::exp_mask) >> F::man_bits;
  if (e == 0) return sign;
  return sign | ((e - uint32_t(F::bias) + uint32_t(G::bias)) << G::man_bits) |
         ((x & F::man_mask) << (G::man_bits - F::man_bits));
}

// A number of format G as one of format F with the policy R: exact when F holds it, else rounded
// once, flushed or saturated as every operation (the watertight test's t from the shear format
// to the closest-hit key, hls/ist.h: the same mantissa, so only the exponent's range can act).
template <class G, class F, Rounding R>
constexpr uint32_t narrow(uint32_t x) {
  if (is_zero<G>(x)) return signed_zero<F>(sign_of<G>(x));
  const auto u = detail::unpack<G>(x);
  return round_pack<F, R>(u.sign, u.exp - G::man_bits, uint64_t(u.sig), false);
}

// To binary64: exact for every format here (E <= 11, M <= 31).
template <class F>
constexpr uint64_t to_double_bits(uint32_t a) {
  const uint64_t sign = uint64_t(sign_of<F>(a)) << 63;
  if (is_zero<F>(a)) return sign;
  const auto u = detail::unpack<F>(a);
  return sign | (uint64_t(u.exp + 1023) << 52) | (uint64_t(a & F::man_mask) << (52 - F::man_bits));
}
template <class F>
inline double to_double(uint32_t a) {
  const uint64_t d = to_double_bits<F>(a);
  double x;
  std::memcpy(&x, &d, sizeof x);
  return x;
}
// To binary32 under the policy (exact for FP24). Beyond binary32's range: saturate to +-FLT_MAX
// (binary32's top exponent field is Inf/NaN, ours is an ordinary binade); below: flush to zero.
template <class F, Rounding R>
constexpr uint32_t to_float_bits(uint32_t a) {
  if (is_zero<F>(a)) return sign_of<F>(a) ? 0x80000000u : 0u;
  const auto u = detail::unpack<F>(a);
  const uint32_t r = round_pack<FP32, R>(u.sign, u.exp - F::man_bits, uint64_t(u.sig), false);
  if ((r & FP32::exp_mask) == FP32::exp_mask) return (r & FP32::sign_mask) | 0x7F7FFFFFu;
  return r;
}
template <class F, Rounding R>
inline float to_float(uint32_t a) {
  const uint32_t b = to_float_bits<F, R>(a);
  float x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}

// ---- neighbours and ulp -------------------------------------------------------------------------

// The next representable number above a (the largest magnitude stays put: it is saturated).
template <class F>
constexpr uint32_t next_up(uint32_t a) {
  if (is_zero<F>(a)) return F::min_mag;
  const uint32_t m = a & F::max_mag;
  if (!sign_of<F>(a)) return m == F::max_mag ? a : a + 1u;
  return m == F::min_mag ? F::sign_mask : a - 1u;  // -min -> -0 (IEEE nextUp)
}
template <class F>
constexpr uint32_t next_down(uint32_t a) {
  return neg<F>(next_up<F>(neg<F>(a)));
}
// Exponent of one unit in the last place of a: ulp(a) = 2^ulp_exp(a). For zero, the exponent of
// the smallest normal (the step from zero to the next number).
template <class F>
constexpr int ulp_exp(uint32_t a) {
  if (is_zero<F>(a)) return F::emin;
  return detail::unpack<F>(a).exp - F::man_bits;
}
// ulp(a) as a number of the format; flushes to zero when it is below the smallest normal.
template <class F>
constexpr uint32_t ulp(uint32_t a) {
  if (is_zero<F>(a)) return F::min_mag;
  const int biased = ulp_exp<F>(a) + F::bias;
  return biased < 1 ? 0u : uint32_t(biased) << F::man_bits;
}

// Move p by `ulps` units in the last place of p, on the bit pattern: the magnitude bits plus or
// minus |ulps| as an integer (toward larger magnitude if ulps and p agree in sign, so a positive
// ulps moves the value up), crossing binades; a result below the smallest normal is +0 (it never
// crosses zero), one above the largest magnitude saturates. A zero stays zero (for |ulps| below
// 2^M). Hardware: one M+E-bit adder and two clamps (hit's skip_back, trv's interval widening).
template <class F>
constexpr uint32_t add_ulps(uint32_t p, int32_t ulps) {
  const bool neg = sign_of<F>(p);
  const int64_t n = ulps < 0 ? -int64_t(ulps) : int64_t(ulps);
  const int64_t m = int64_t(p & F::max_mag) + ((ulps < 0) != neg ? -n : n);
  if (m < int64_t(F::min_mag)) return 0u;
  if (m > int64_t(F::max_mag)) return signed_zero<F>(neg) | F::max_mag;
  return signed_zero<F>(neg) | uint32_t(m);
}

// ---- a typed view for call sites that prefer it -------------------------------------------------

// Arith<F, R> bundles the operations for one format and rounding policy, so a datapath can be
// written once as a template on it: `using A = Arith<FP24, Rounding::rtz>; A::mul(x, y)`.
// Arith<FP24, Rounding::raycore> is RayCore's arithmetic (see the top of this file).
template <class F, Rounding R>
struct Arith {
  using Fmt = F;
  static constexpr Rounding rounding = R;
  static constexpr uint32_t zero = 0, one = F::one;
  static constexpr uint32_t add(uint32_t a, uint32_t b) { return hls::add<F, R>(a, b); }
  static constexpr uint32_t sub(uint32_t a, uint32_t b) { return hls::sub<F, R>(a, b); }
  static constexpr uint32_t add3(uint32_t a, uint32_t b, uint32_t c) {
    return hls::add3<F, R>(a, b, c);
  }
  static constexpr uint32_t mul(uint32_t a, uint32_t b) { return hls::mul<F, R>(a, b); }
  static constexpr uint32_t sop(uint32_t a, uint32_t b, uint32_t x1, uint32_t y1, uint32_t x2,
                                uint32_t y2) {
    return hls::sop<F, R>(a, b, x1, y1, x2, y2);
  }
  static constexpr uint32_t div(uint32_t a, uint32_t b) { return hls::div<F, R>(a, b); }
  static constexpr uint32_t rcp(uint32_t a) { return hls::rcp<F, R>(a); }
  static constexpr uint32_t sqrt(uint32_t a) { return hls::sqrt<F, R>(a); }
  static constexpr uint32_t neg(uint32_t a) { return hls::neg<F>(a); }
  static constexpr uint32_t abs(uint32_t a) { return hls::abs<F>(a); }
  static constexpr bool lt(uint32_t a, uint32_t b) { return hls::lt<F>(a, b); }
  static constexpr bool le(uint32_t a, uint32_t b) { return hls::le<F>(a, b); }
  static constexpr bool eq(uint32_t a, uint32_t b) { return hls::eq<F>(a, b); }
  static constexpr uint32_t min(uint32_t a, uint32_t b) { return hls::min<F>(a, b); }
  static constexpr uint32_t max(uint32_t a, uint32_t b) { return hls::max<F>(a, b); }
  static constexpr bool is_zero(uint32_t a) { return hls::is_zero<F>(a); }
  static constexpr bool sign(uint32_t a) { return hls::sign_of<F>(a); }
  static uint32_t from_double(double x) { return hls::from_double<F, R>(x); }
  static double to_double(uint32_t a) { return hls::to_double<F>(a); }
  static float to_float(uint32_t a) { return hls::to_float<F, R>(a); }
  static constexpr uint32_t next_up(uint32_t a) { return hls::next_up<F>(a); }
  static constexpr uint32_t next_down(uint32_t a) { return hls::next_down<F>(a); }
};

}  // namespace raycore::hls
