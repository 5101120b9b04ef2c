// hls/fp.h arithmetic (add, sub, mul, div, add3) against the MPFR oracle, FP24 and FP32, rtz and
// rne: all pairs (triples for add3) of a directed set, then RAYCORE_FP_RANDOM seeded random
// vectors per op, mode and format. Division by zero is hls/fp.h's own definition and is checked
// apart from MPFR. FP32 in rne is also checked against the host's IEEE float, bit for bit, for
// normal inputs and normal results.
#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <string>

#include "hls/fp.h"
#include "tb/fp/fp_check.h"
#include "tb/fp/fp_ref.h"

namespace raycore::fptest {
namespace {

template <class F, Rounding R>
uint32_t dut(Op op, uint32_t a, uint32_t b, uint32_t c) {
  switch (op) {
    case Op::add: return hls::add<F, R>(a, b);
    case Op::sub: return hls::sub<F, R>(a, b);
    case Op::mul: return hls::mul<F, R>(a, b);
    case Op::div: return hls::div<F, R>(a, b);
    case Op::add3: return hls::add3<F, R>(a, b, c);
  }
  return 0;
}

template <class F>
uint32_t expect(Oracle<F>& o, Op op, Rounding R, uint32_t a, uint32_t b, uint32_t c) {
  switch (op) {
    case Op::add: return o.add(a, b, R);
    case Op::sub: return o.sub(a, b, R);
    case Op::mul: return o.mul(a, b, R);
    case Op::div: return o.div(a, b, R);
    case Op::add3: return o.add3(a, b, c, R);
  }
  return 0;
}

template <class F>
std::string operands(Op op, uint32_t a, uint32_t b, uint32_t c) {
  std::string s = "a=" + show<F>(a) + " b=" + show<F>(b);
  if (op == Op::add3) s += " c=" + show<F>(c);
  return s;
}

// Checks one vector; division by a zero goes to the definitional tally.
template <class F, Rounding R>
bool check_one(Oracle<F>& o, Op op, uint32_t a, uint32_t b, uint32_t c, Tally& t, Tally& tz) {
  const auto desc = [&] { return operands<F>(op, a, b, c); };
  const Shown<F> got{dut<F, R>(op, a, b, c)};
  if (op == Op::div && Spec<F>::zero(b))
    return tz.check(got, Shown<F>{Oracle<F>::div_special(a, b)}, desc);
  return t.check(got, Shown<F>{expect<F>(o, op, R, a, b, c)}, desc);
}

struct Case {
  int fmt;  // 24 or 32
  Op op;
  Rounding r;
};
void PrintTo(const Case& c, std::ostream* os) {
  *os << "FP" << c.fmt << " " << op_name(c.op) << " " << mode_name(c.r);
}
std::string case_name(const testing::TestParamInfo<Case>& i) {
  return std::string("FP") + std::to_string(i.param.fmt) + "_" + op_name(i.param.op) + "_" +
         mode_name(i.param.r);
}
std::vector<Case> all_cases() {
  std::vector<Case> v;
  for (int fmt : {24, 32})
    for (Op op : {Op::add, Op::sub, Op::mul, Op::div, Op::add3})
      for (Rounding r : {Rounding::rtz, Rounding::rne}) v.push_back({fmt, op, r});
  return v;
}

// ---- directed ----------------------------------------------------------------------------------

template <class F, Rounding R>
void run_directed(Op op) {
  Oracle<F> o;
  Tally t(fmt_name<F>(), op_name(op), mode_name(R), "directed");
  Tally tz(fmt_name<F>(), "div_by_zero", mode_name(R), "directed");
  if (op == Op::add3) {
    const auto v = directed_set<F>(true);
    for (uint32_t a : v)
      for (uint32_t b : v)
        for (uint32_t c : v)
          if (!check_one<F, R>(o, op, a, b, c, t, tz)) goto done;
  } else {
    const auto v = directed_set<F>(false);
    for (uint32_t a : v)
      for (uint32_t b : v)
        if (!check_one<F, R>(o, op, a, b, 0, t, tz)) goto done;
  }
done:
  t.finish();
  if (op == Op::div) tz.finish();
  else tz.discard();
}

template <class F, Rounding R>
void run_random(Op op) {
  const uint64_t n = random_count();
  const std::string name = std::string(fmt_name<F>()) + op_name(op) + mode_name(R);
  const uint64_t seed = seed_for(name);
  Oracle<F> o;
  Gen<F> g(seed);
  Tally t(fmt_name<F>(), op_name(op), mode_name(R), "random");
  Tally tz(fmt_name<F>(), "div_by_zero", mode_name(R), "random");
  t.note("seed=" + std::to_string(seed));
  for (uint64_t i = 0; i < n; ++i) {
    uint32_t a = 0, b = 0, c = 0;
    if (op == Op::add3) g.triple(a, b, c);
    else g.pair(op, a, b);
    if (!check_one<F, R>(o, op, a, b, c, t, tz)) break;
  }
  t.finish();
  if (op == Op::div) tz.finish();
  else tz.discard();
}

template <template <class, Rounding> class Run>
void dispatch(const Case& c) {
  if (c.fmt == 24) {
    if (c.r == Rounding::rtz) Run<hls::FP24, Rounding::rtz>::go(c.op);
    else Run<hls::FP24, Rounding::rne>::go(c.op);
  } else {
    if (c.r == Rounding::rtz) Run<hls::FP32, Rounding::rtz>::go(c.op);
    else Run<hls::FP32, Rounding::rne>::go(c.op);
  }
}
template <class F, Rounding R>
struct Directed {
  static void go(Op op) { run_directed<F, R>(op); }
};
template <class F, Rounding R>
struct Random {
  static void go(Op op) { run_random<F, R>(op); }
};

class ArithDirected : public testing::TestWithParam<Case> {};
TEST_P(ArithDirected, MatchesMpfr) { dispatch<Directed>(GetParam()); }
INSTANTIATE_TEST_SUITE_P(Fp, ArithDirected, testing::ValuesIn(all_cases()), case_name);

class ArithRandom : public testing::TestWithParam<Case> {};
TEST_P(ArithRandom, MatchesMpfr) { dispatch<Random>(GetParam()); }
INSTANTIATE_TEST_SUITE_P(Fp, ArithRandom, testing::ValuesIn(all_cases()), case_name);

// ---- small formats, exhaustively ---------------------------------------------------------------

// The same templates on formats small enough to enumerate: every pair of E5M4 (10 bits) for the
// binary ops, every triple of E5M2 (8 bits) for add3. Their exponent ranges (30 binades) exceed
// every alignment distance the adders distinguish (up to 3M+7), so every alignment, jam and
// cancellation case of these widths is enumerated: an adder window that is too narrow fails here
// even if the directed and random FP24 vectors miss it.
template <class F, Rounding R>
void run_all_pairs(Op op) {
  Oracle<F> o;
  Tally t(fmt_name<F>(), op_name(op), mode_name(R), "all-pairs");
  Tally tz(fmt_name<F>(), "div_by_zero", mode_name(R), "all-pairs");
  for (uint32_t a = 0; a <= Spec<F>::all; ++a)
    for (uint32_t b = 0; b <= Spec<F>::all; ++b)
      if (!check_one<F, R>(o, op, a, b, 0, t, tz)) goto done;
done:
  t.finish();
  if (op == Op::div) tz.finish();
  else tz.discard();
}
template <class F, Rounding R>
void run_all_triples() {
  Oracle<F> o;
  Tally t(fmt_name<F>(), "add3", mode_name(R), "all-triples");
  Tally tz(fmt_name<F>(), "div_by_zero", mode_name(R), "all-triples");
  for (uint32_t a = 0; a <= Spec<F>::all; ++a)
    for (uint32_t b = 0; b <= Spec<F>::all; ++b)
      for (uint32_t c = 0; c <= Spec<F>::all; ++c)
        if (!check_one<F, R>(o, Op::add3, a, b, c, t, tz)) goto done;
done:
  t.finish();
  tz.discard();
}
using E5M4 = hls::Format<5, 4>;
using E5M2 = hls::Format<5, 2>;
TEST(SmallFormatExhaustive, E5M4_binary_ops) {
  for (Op op : {Op::add, Op::sub, Op::mul, Op::div}) {
    run_all_pairs<E5M4, Rounding::rtz>(op);
    run_all_pairs<E5M4, Rounding::rne>(op);
  }
}
TEST(SmallFormatExhaustive, E5M2_add3_rtz) { run_all_triples<E5M2, Rounding::rtz>(); }
TEST(SmallFormatExhaustive, E5M2_add3_rne) { run_all_triples<E5M2, Rounding::rne>(); }

// ---- division by zero (hls/fp.h's definition, not MPFR's) -------------------------------------

template <class F, Rounding R>
void run_div_zero() {
  using S = Spec<F>;
  Tally t(fmt_name<F>(), "div_by_zero", mode_name(R), "all-zero-divisors");
  const std::vector<uint32_t> zeros = {0u, S::sign_bit, 1u, S::sign_bit | S::man_all, S::man_all};
  for (uint32_t b : zeros) {
    for (uint32_t a : directed_set<F>(false)) {
      const uint32_t want = S::zero(a) ? 0u : S::sat(S::sign(a) != S::sign(b));
      t.check(Shown<F>{hls::div<F, R>(a, b)}, Shown<F>{want},
              [&] { return "a=" + show<F>(a) + " b=" + show<F>(b); });
    }
  }
  // The definition spelled out: 0/0 = +0 for every sign; x/0 = the largest magnitude.
  t.check(Shown<F>{hls::div<F, R>(S::sign_bit, S::sign_bit)}, Shown<F>{0u}, [] { return "-0/-0"; });
  t.check(Shown<F>{hls::div<F, R>(S::sign_bit, 0u)}, Shown<F>{0u}, [] { return "-0/+0"; });
  t.check(Shown<F>{hls::div<F, R>(S::make(false, 0, 0), S::sign_bit)}, Shown<F>{S::sat(true)},
          [] { return "1/-0"; });
  t.check(Shown<F>{hls::rcp<F, R>(0u)}, Shown<F>{S::sat(false)}, [] { return "rcp(+0)"; });
  t.finish();
}
TEST(DivByZero, FP24_rtz) { run_div_zero<hls::FP24, Rounding::rtz>(); }
TEST(DivByZero, FP24_rne) { run_div_zero<hls::FP24, Rounding::rne>(); }
TEST(DivByZero, FP32_rtz) { run_div_zero<hls::FP32, Rounding::rtz>(); }
TEST(DivByZero, FP32_rne) { run_div_zero<hls::FP32, Rounding::rne>(); }

// rcp is div(1, x): every FP24 pattern once.
template <Rounding R>
void run_rcp_exhaustive() {
  using F = hls::FP24;
  Oracle<F> o;
  Tally t(fmt_name<F>(), "rcp", mode_name(R), "exhaustive");
  const uint32_t stride = exhaustive_stride();
  for (uint32_t a = 0; a <= Spec<F>::all; a += stride) {
    const uint32_t want = Spec<F>::zero(a) ? Oracle<F>::div_special(F::one, a)
                                           : o.div(Spec<F>::make(false, 0, 0), a, R);
    if (!t.check(Shown<F>{hls::rcp<F, R>(a)}, Shown<F>{want}, [&] { return "a=" + show<F>(a); }))
      break;
  }
  t.finish();
}
TEST(RcpExhaustive, FP24_rtz) { run_rcp_exhaustive<Rounding::rtz>(); }
TEST(RcpExhaustive, FP24_rne) { run_rcp_exhaustive<Rounding::rne>(); }

// sqrt: every FP24 pattern in both modes, random FP32 patterns (and their neighbourhood of 1.0).
template <class F, Rounding R>
void run_sqrt() {
  Oracle<F> o;
  const bool exhaustive = std::is_same<F, hls::FP24>::value;
  Tally t(fmt_name<F>(), "sqrt", mode_name(R), exhaustive ? "exhaustive" : "random");
  auto one = [&](uint32_t a) {
    return t.check(Shown<F>{hls::sqrt<F, R>(a)}, Shown<F>{o.sqrt(a, R)},
                   [&] { return "a=" + show<F>(a); });
  };
  if (exhaustive) {
    const uint32_t stride = exhaustive_stride();
    for (uint32_t a = 0; a <= Spec<F>::all; a += stride)
      if (!one(a)) break;
  } else {
    uint64_t x = seed_for("sqrt");
    for (uint64_t i = 0; i < random_count(); ++i) {
      x = x * 6364136223846793005ull + 1442695040888963407ull;
      if (!one(uint32_t(x >> 32) & Spec<F>::all)) break;
    }
  }
  t.finish();
}
TEST(SqrtExhaustive, FP24_rtz) { run_sqrt<hls::FP24, Rounding::rtz>(); }
TEST(SqrtExhaustive, FP24_rne) { run_sqrt<hls::FP24, Rounding::rne>(); }
TEST(SqrtRandom, FP32_rtz) { run_sqrt<hls::FP32, Rounding::rtz>(); }
TEST(SqrtRandom, FP32_rne) { run_sqrt<hls::FP32, Rounding::rne>(); }

// to_int_rtz: every FP24 pattern against truncation of the exact value (saturating at 2^31 - 1).
TEST(ToIntExhaustive, FP24) {
  using F = hls::FP24;
  Tally t(fmt_name<F>(), "to_int_rtz", "rtz", "exhaustive");
  const uint32_t stride = exhaustive_stride();
  for (uint32_t a = 0; a <= Spec<F>::all; a += stride) {
    const double v = std::trunc(hls::to_double<F>(a));
    const double c = std::fmin(std::fmax(v, -2147483647.0), 2147483647.0);
    if (!t.check(int(hls::to_int_rtz<F>(a)), int(c), [&] { return "a=" + show<F>(a); }))
      break;
  }
  t.finish();
}

// ---- the oracle's own assumptions ---------------------------------------------------------------

// mpfr_sum's sign of an exact zero must be IEEE's (+0 unless all addends are -0) for RNDZ/RNDN.
TEST(Oracle, MpfrSumZeroSignIsIeee) {
  using F = hls::FP24;
  using S = Spec<F>;
  Oracle<F> o;
  const uint32_t one = S::make(false, 0, 0), m_one = S::make(true, 0, 0);
  const uint32_t pz = 0, nz = S::sign_bit;
  for (Rounding r : {Rounding::rtz, Rounding::rne}) {
    EXPECT_EQ(o.add3(nz, nz, nz, r), nz);
    EXPECT_EQ(o.add3(pz, nz, nz, r), pz);
    EXPECT_EQ(o.add3(nz, pz, nz, r), pz);
    EXPECT_EQ(o.add3(one, m_one, nz, r), pz);
    EXPECT_EQ(o.add3(nz, one, m_one, r), pz);
    EXPECT_EQ(o.add3(one, one, S::make(true, 1, 0), r), pz);
    EXPECT_EQ(o.add(nz, nz, r), nz);
    EXPECT_EQ(o.add(one, m_one, r), pz);
    EXPECT_EQ(o.sub(nz, pz, r), nz);
    EXPECT_EQ(o.mul(nz, one, r), nz);
  }
}

// The header's constants equal the ones derived from (E, M), and FP24 is RayCore's.
TEST(Oracle, FormatConstants) {
  using S24 = Spec<hls::FP24>;
  using S32 = Spec<hls::FP32>;
  EXPECT_EQ(hls::FP24::bias, 63);
  EXPECT_EQ(hls::FP24::one, 0x3F0000u);
  EXPECT_EQ(hls::FP24::max_mag, 0x7FFFFFu);
  EXPECT_EQ(hls::FP24::emin, S24::emin);
  EXPECT_EQ(hls::FP24::emax, S24::emax);
  EXPECT_EQ(hls::FP24::sign_mask, S24::sign_bit);
  EXPECT_NEAR(ref_value<hls::FP24>(0x7FFFFF), 3.69e19, 0.01e19);
  EXPECT_EQ(ref_value<hls::FP24>(0x010000), std::ldexp(1.0, -62));
  EXPECT_EQ(hls::FP32::bias, 127);
  EXPECT_EQ(hls::FP32::emin, S32::emin);
  EXPECT_EQ(hls::FP32::emax, S32::emax);
  EXPECT_EQ(hls::FP32::one, 0x3F800000u);
}

// Known hard cases, pinned (each is also inside the generated sets).
TEST(Regressions, Pinned) {
  using F = hls::FP24;
  using S = Spec<F>;
  // rtz: 1 - 2^-30 truncates to the largest number below 1.
  EXPECT_EQ((hls::add<F, Rounding::rtz>(S::make(false, 0, 0), S::make(true, -30, 0))),
            S::make(false, -1, S::man_all));
  // rne: 1 + 2^-17 (half an ulp, even) stays 1; 1 + 2^-17 + 2^-33 rounds up.
  EXPECT_EQ((hls::add<F, Rounding::rne>(S::make(false, 0, 0), S::make(false, -17, 0))),
            S::make(false, 0, 0));
  EXPECT_EQ((hls::add<F, Rounding::rne>(S::make(false, 0, 0), S::make(false, -17, 1))),
            S::make(false, 0, 1));
  // The flush threshold: 0x1.f848p0 2^emin * 0x1.03ebp0 2^-1 = 2^emin (1 - 15848 2^-33), less
  // than a quarter ulp below the smallest normal: rne rounds it up to 2^emin, rtz truncates it
  // into the binade below, which flushes.
  EXPECT_EQ((hls::mul<F, Rounding::rne>(S::make(false, S::emin, 0xf848), S::make(false, -1, 0x3eb))),
            S::make(false, S::emin, 0));
  EXPECT_EQ((hls::mul<F, Rounding::rtz>(S::make(false, S::emin, 0xf848), S::make(false, -1, 0x3eb))),
            0u);
  EXPECT_EQ((hls::add3<F, Rounding::rne>(S::make(false, 0, 0), S::make(true, 0, 0),
                                         S::make(true, S::emin, 0))),
            S::make(true, S::emin, 0));
}

// ---- FP32 against the host's float --------------------------------------------------------------

float as_float(uint32_t b) {
  float f;
  std::memcpy(&f, &b, sizeof f);
  return f;
}
uint32_t float_bits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}
bool normal_input(uint32_t a) {
  const uint32_t ef = (a >> 23) & 0xFFu;
  return ef != 0 && ef != 0xFF;
}
// A host result we compare: finite and normal above FLT_MIN (a result that rounds up to FLT_MIN
// from below is tiny before rounding: IEEE rounds it at the subnormal grid, we flush), or an exact
// zero of an addition (sums of normal floats that cancel exactly).
bool comparable(float h, Op op) {
  if (h == 0.0f) return op == Op::add || op == Op::sub || op == Op::add3;
  return std::isnormal(h) && std::fabs(h) > FLT_MIN;
}

class HostFloat : public testing::TestWithParam<Op> {};
TEST_P(HostFloat, Fp32RneMatchesIeeeFloat) {
  using F = hls::FP32;
  constexpr Rounding R = Rounding::rne;
  const Op op = GetParam();
  Oracle<F> o;  // add3 only: exact sum, then round-to-odd double, then the host's (float) cast
  Tally t("FP32", op_name(op), "rne", "host-float");
  t.note("(inputs normal, host result normal)");
  volatile float sink = 0;  // keeps the host's float arithmetic at run time
  auto host = [&](uint32_t a, uint32_t b, uint32_t c) -> float {
    const float x = as_float(a), y = as_float(b);
    switch (op) {
      case Op::add: return sink = x + y;
      case Op::sub: return sink = x - y;
      case Op::mul: return sink = x * y;
      case Op::div: return sink = x / y;
      case Op::add3: return sink = float(o.sum3_round_to_odd_double(a, b, c));
    }
    return 0;
  };
  auto one = [&](uint32_t a, uint32_t b, uint32_t c) {
    if (!normal_input(a) || !normal_input(b) || (op == Op::add3 && !normal_input(c))) return true;
    const float h = host(a, b, c);
    if (!comparable(h, op)) {
      t.skip();
      return true;
    }
    return t.check(Shown<F>{dut<F, R>(op, a, b, c)}, Shown<F>{float_bits(h)},
                   [&] { return operands<F>(op, a, b, c); });
  };
  if (op == Op::add3) {
    const auto v = directed_set<F>(true);
    for (uint32_t a : v)
      for (uint32_t b : v)
        for (uint32_t c : v)
          if (!one(a, b, c)) goto random;
  } else {
    const auto v = directed_set<F>(false);
    for (uint32_t a : v)
      for (uint32_t b : v)
        if (!one(a, b, 0)) goto random;
  }
random : {
  const uint64_t n = random_count();
  Gen<F> g(seed_for(std::string("host") + op_name(op)));
  for (uint64_t i = 0; i < n && !t.stopped(); ++i) {
    uint32_t a = 0, b = 0, c = 0;
    if (op == Op::add3) g.triple(a, b, c);
    else g.pair(op, a, b);
    if (!one(a, b, c)) break;
  }
}
  t.finish();
}
INSTANTIATE_TEST_SUITE_P(Fp, HostFloat, testing::Values(Op::add, Op::sub, Op::mul, Op::div, Op::add3),
                         [](const testing::TestParamInfo<Op>& i) { return std::string(op_name(i.param)); });

}  // namespace
}  // namespace raycore::fptest
