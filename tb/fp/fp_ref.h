// tb/fp/fp_ref.h - the independent reference for hls/fp.h: the format's facts re-derived from
// (E, M) alone, and an MPFR oracle.
//
// The oracle computes every operation exactly and rounds once with MPFR at precision M+1 and
// MPFR's default (huge) exponent range (MPFR_RNDZ for rtz, MPFR_RNDN for rne), then applies the
// format's rules itself: a result whose exponent is below emin becomes a zero with the result's
// sign, one above emax saturates to the largest magnitude with its sign. Inputs whose exponent
// field is 0 are loaded as zeros with their sign. Nothing here calls hls/fp.h: patterns are
// decoded and encoded from the field widths, so a wrong constant in the header shows up too.
#pragma once

#include <gmp.h>
#include <mpfr.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "hls/fp.h"

namespace raycore::fptest {

using hls::Rounding;

inline const char* mode_name(Rounding r) {
  return r == Rounding::rtz ? "rtz" : (r == Rounding::rne ? "rne" : "raycore");
}
// raycore is not correctly rounded: the oracle rounds toward zero for it (its conversions and mul
// are rtz exactly); tb/fp/test_fp_raycore.cpp checks its other operations against bounds.
inline mpfr_rnd_t mpfr_mode(Rounding r) { return r == Rounding::rne ? MPFR_RNDN : MPFR_RNDZ; }

// The format's facts from its field widths only (the header's constants are checked against
// these in a test).
template <class F>
struct Spec {
  static constexpr int E = F::exp_bits;
  static constexpr int M = F::man_bits;
  static constexpr int P = M + 1;  // significant bits
  static constexpr int bias = (1 << (E - 1)) - 1;
  static constexpr int emin = 1 - bias;
  static constexpr int emax = (1 << E) - 1 - bias;
  static constexpr uint32_t sign_bit = uint32_t(1) << (E + M);
  static constexpr uint32_t man_all = (uint32_t(1) << M) - 1u;
  static constexpr uint32_t max_mag = (((uint32_t(1) << E) - 1u) << M) | man_all;
  static constexpr uint32_t all = sign_bit | max_mag;
  static constexpr int exp_field(uint32_t a) { return int((a >> M) & ((1u << E) - 1u)); }
  static constexpr bool sign(uint32_t a) { return (a & sign_bit) != 0; }
  static constexpr uint32_t man(uint32_t a) { return a & man_all; }
  static constexpr bool zero(uint32_t a) { return exp_field(a) == 0; }
  // A zero canonicalised to its sign bit; other patterns unchanged.
  static constexpr uint32_t canonical(uint32_t a) { return zero(a) ? (a & sign_bit) : a; }
  // Pattern from fields; e is the unbiased exponent and must be in [emin, emax].
  static constexpr uint32_t make(bool s, int e, uint32_t m) {
    return (s ? sign_bit : 0u) | (uint32_t(e + bias) << M) | (m & man_all);
  }
  static constexpr uint32_t sat(bool s) { return (s ? sign_bit : 0u) | max_mag; }
  static constexpr uint32_t signed_zero(bool s) { return s ? sign_bit : 0u; }
};

template <class F>
std::string fmt_name() {
  if constexpr (F::exp_bits == 7 && F::man_bits == 16) return "FP24";
  else if constexpr (F::exp_bits == 8 && F::man_bits == 23) return "FP32";
  else return "E" + std::to_string(F::exp_bits) + "M" + std::to_string(F::man_bits);
}

// The value of a pattern as a double (exact for E <= 11, M <= 52), decoded from the fields.
template <class F>
double ref_value(uint32_t a) {
  using S = Spec<F>;
  if (S::zero(a)) return S::sign(a) ? -0.0 : 0.0;
  const double mag =
      std::ldexp(double(S::man(a) | (uint32_t(1) << S::M)), S::exp_field(a) - S::bias - S::M);
  return S::sign(a) ? -mag : mag;
}

// "0x3f0000 (1)" for messages.
template <class F>
std::string show(uint32_t a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "0x%0*x (%.9g)", (F::width + 3) / 4, a, ref_value<F>(a));
  return buf;
}
inline std::string show_double(double d) {
  uint64_t b;
  std::memcpy(&b, &d, sizeof b);
  char buf[80];
  std::snprintf(buf, sizeof buf, "%a (%.17g, bits 0x%016llx)", d, d, (unsigned long long)b);
  return buf;
}
inline std::string show_float(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  char buf[80];
  std::snprintf(buf, sizeof buf, "%a (%.9g, bits 0x%08x)", double(f), double(f), b);
  return buf;
}

// The MPFR oracle for one format. Not thread-safe (one per test).
template <class F>
class Oracle {
 public:
  using S = Spec<F>;
  static_assert(GMP_NUMB_BITS == 64, "64-bit limbs assumed");

  Oracle() {
    for (auto& x : in_) mpfr_init2(x, S::P);
    mpfr_init2(r_, S::P);
    mpfr_init2(wide_, 4 * 64 + 64);  // exact sums of three FP32 values need < 300 bits
  }
  ~Oracle() {
    for (auto& x : in_) mpfr_clear(x);
    mpfr_clear(r_);
    mpfr_clear(wide_);
  }
  Oracle(const Oracle&) = delete;
  Oracle& operator=(const Oracle&) = delete;

  // Loads a pattern exactly; exponent field 0 gives a zero with the pattern's sign.
  static void load(mpfr_ptr x, uint32_t a) {
    if (S::zero(a)) {
      mpfr_set_zero(x, S::sign(a) ? -1 : 1);
      return;
    }
    const unsigned long sig = S::man(a) | (1ul << S::M);
    const int t = mpfr_set_ui_2exp(x, sig, S::exp_field(a) - S::bias - S::M, MPFR_RNDN);
    if (t != 0) throw std::logic_error("oracle: inexact load");
    if (S::sign(a)) mpfr_neg(x, x, MPFR_RNDN);
  }

  // A value already rounded to at most P significant bits (any exponent) -> pattern, applying
  // the format's flush and saturation rules.
  static uint32_t encode(mpfr_srcptr r) {
    if (mpfr_nan_p(r) || mpfr_inf_p(r)) throw std::logic_error("oracle: NaN/Inf result");
    const bool s = mpfr_signbit(r) != 0;
    if (mpfr_zero_p(r)) return S::signed_zero(s);
    long e = 0;
    const double d = mpfr_get_d_2exp(&e, r, MPFR_RNDN);  // 0.5 <= |d| < 1, exact (P <= 53)
    const long ex = e - 1;                               // r = 1.f * 2^ex
    if (ex < S::emin) return S::signed_zero(s);
    if (ex > S::emax) return S::sat(s);
    const double sig = std::ldexp(std::fabs(d), S::P);  // integer in [2^M, 2^(M+1))
    const auto isig = uint64_t(sig);
    if (double(isig) != sig || (isig >> S::M) != 1u)
      throw std::logic_error("oracle: value has more than P bits");
    return S::make(s, int(ex), uint32_t(isig));
  }

  uint32_t add(uint32_t a, uint32_t b, Rounding R) {
    load(in_[0], a);
    load(in_[1], b);
    mpfr_add(r_, in_[0], in_[1], mpfr_mode(R));
    return encode(r_);
  }
  uint32_t sub(uint32_t a, uint32_t b, Rounding R) {
    load(in_[0], a);
    load(in_[1], b);
    mpfr_sub(r_, in_[0], in_[1], mpfr_mode(R));
    return encode(r_);
  }
  uint32_t mul(uint32_t a, uint32_t b, Rounding R) {
    load(in_[0], a);
    load(in_[1], b);
    mpfr_mul(r_, in_[0], in_[1], mpfr_mode(R));
    return encode(r_);
  }
  // Division by a zero is hls/fp.h's own definition (no Inf/NaN), not MPFR's: see div_special.
  uint32_t div(uint32_t a, uint32_t b, Rounding R) {
    if (S::zero(b)) throw std::logic_error("oracle: div by zero goes to div_special");
    load(in_[0], a);
    load(in_[1], b);
    mpfr_div(r_, in_[0], in_[1], mpfr_mode(R));
    return encode(r_);
  }
  // x / 0 saturates with the sign of the quotient; 0 / 0 is +0.
  static uint32_t div_special(uint32_t a, uint32_t b) {
    if (S::zero(a)) return 0u;
    return S::sat(S::sign(a) != S::sign(b));
  }
  // mpfr_sum rounds the exact sum once. Its exact-zero rule (checked in a test): the sign of the
  // zero is that of the addends if all are zeros of one sign, otherwise +0 (for RNDZ and RNDN).
  uint32_t add3(uint32_t a, uint32_t b, uint32_t c, Rounding R) {
    load(in_[0], a);
    load(in_[1], b);
    load(in_[2], c);
    mpfr_ptr tab[3] = {in_[0], in_[1], in_[2]};
    mpfr_sum(r_, tab, 3, mpfr_mode(R));
    return encode(r_);
  }
  // sqrt: hls/fp.h's definition for negative operands (+0; sqrt(-0) = -0), MPFR otherwise.
  uint32_t sqrt(uint32_t a, Rounding R) {
    if (S::zero(a)) return S::signed_zero(S::sign(a));
    if (S::sign(a)) return 0u;
    load(in_[0], a);
    mpfr_sqrt(r_, in_[0], mpfr_mode(R));
    return encode(r_);
  }
  uint32_t from_double(double d, Rounding R) {
    if (std::isnan(d) || std::isinf(d)) return S::sat(std::signbit(d));
    mpfr_set_d(r_, d, mpfr_mode(R));
    return encode(r_);
  }
  uint32_t from_float(float f, Rounding R) {
    if (std::isnan(f) || std::isinf(f)) return S::sat(std::signbit(f));
    mpfr_set_flt(r_, f, mpfr_mode(R));
    return encode(r_);
  }
  // Is the double exactly the pattern's value (zeros: with the same sign)?
  bool equals(uint32_t a, double d) {
    load(in_[0], a);
    if (std::isnan(d)) return false;
    if (mpfr_cmp_d(in_[0], d) != 0) return false;
    return (mpfr_signbit(in_[0]) != 0) == std::signbit(d);
  }
  // The pattern as a binary32 under the mode: exact rounding of the value, beyond FLT_MAX
  // saturated to +-FLT_MAX (binary32's top exponent field is Inf/NaN), below FLT_MIN flushed.
  float to_float(uint32_t a, Rounding R) {
    load(in_[0], a);
    mpfr_set(wide_, in_[0], MPFR_RNDN);
    const bool s = mpfr_signbit(wide_) != 0;
    if (mpfr_zero_p(wide_)) return s ? -0.0f : 0.0f;
    mpfr_t t;
    mpfr_init2(t, 24);
    mpfr_set(t, wide_, mpfr_mode(R));
    float out;
    if (mpfr_get_exp(t) > 128) {  // |t| >= 2^128
      out = s ? -3.40282347e38f : 3.40282347e38f;
    } else if (mpfr_get_exp(t) < -125) {  // |t| < 2^-126
      out = s ? -0.0f : 0.0f;
    } else {
      out = mpfr_get_flt(t, MPFR_RNDN);  // exact: t has 24 bits and is in range
    }
    mpfr_clear(t);
    return out;
  }
  // Three-way comparison of the values (all zeros equal).
  int cmp(uint32_t a, uint32_t b) {
    load(in_[0], a);
    load(in_[1], b);
    const int c = mpfr_cmp(in_[0], in_[1]);
    return (c > 0) - (c < 0);
  }
  // The neighbour above a in the set of representable values (IEEE 754 nextUp over this format;
  // the largest magnitude stays put). From below the smallest negative normal this is -0, as
  // nextUp(-minSubnormal) = -0 in IEEE 754 and the flush rule keeps the sign.
  uint32_t next_up(uint32_t a) {
    if (S::zero(a)) return S::make(false, S::emin, 0);
    if (a == S::max_mag) return a;
    load(r_, a);
    mpfr_nextabove(r_);  // at precision P, unbounded exponent
    return encode(r_);
  }
  uint32_t next_down(uint32_t a) {
    if (S::zero(a)) return S::make(true, S::emin, 0);
    if (a == (S::sign_bit | S::max_mag)) return a;
    load(r_, a);
    mpfr_nextbelow(r_);
    return encode(r_);
  }
  // ulp(a) = (next number above |a| at unbounded exponent) - |a|, as its exponent; zero: the step
  // from zero to the smallest normal.
  int ulp_exp(uint32_t a) {
    if (S::zero(a)) return S::emin;
    load(r_, a);
    mpfr_abs(r_, r_, MPFR_RNDN);
    mpfr_set(wide_, r_, MPFR_RNDN);
    mpfr_nextabove(r_);
    mpfr_sub(wide_, r_, wide_, MPFR_RNDN);  // exact: a power of two
    return int(mpfr_get_exp(wide_) - 1);
  }
  // ulp(a) as a pattern, flushed to +0 below the smallest normal.
  uint32_t ulp(uint32_t a) {
    const int e = ulp_exp(a);
    mpfr_set_ui_2exp(r_, 1, e, MPFR_RNDN);
    return encode(r_);
  }

  // FP32 helper: the exact sum of three values rounded to binary64 with round-to-odd (RNDZ, then
  // the lsb set if inexact). Casting that double to float with the host's rne gives the correctly
  // rounded binary32 sum (53 >= 24 + 2 bits; Boldo and Melquiond 2008), so the final rounding is
  // the host's own, not MPFR's.
  double sum3_round_to_odd_double(uint32_t a, uint32_t b, uint32_t c) {
    load(in_[0], a);
    load(in_[1], b);
    load(in_[2], c);
    mpfr_ptr tab[3] = {in_[0], in_[1], in_[2]};
    if (mpfr_sum(wide_, tab, 3, MPFR_RNDN) != 0) throw std::logic_error("oracle: inexact wide sum");
    mpfr_t d;
    mpfr_init2(d, 53);
    const int t = mpfr_set(d, wide_, MPFR_RNDZ);
    double out = mpfr_get_d(d, MPFR_RNDN);  // exact: in binary64's normal range for FP32 sums
    mpfr_clear(d);
    if (t != 0) {
      uint64_t bits;
      std::memcpy(&bits, &out, sizeof bits);
      bits |= 1u;
      std::memcpy(&out, &bits, sizeof bits);
    }
    return out;
  }

 private:
  mpfr_t in_[3];
  mpfr_t r_;
  mpfr_t wide_;
};

}  // namespace raycore::fptest
