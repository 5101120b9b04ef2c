// hls/fp.h conversions against MPFR: every one of the 2^24 FP24 patterns (split into shards so
// ctest can run them in parallel), and a random sample of FP32 patterns.
//
// Per pattern x (sign s, binade e, mantissa m; the exponent-field-0 patterns stand for the binade
// just below the smallest normal, so the flush threshold is crossed from every point of it):
//   - to_double(x) is exactly x's value (MPFR's), with the sign of a zero;
//   - from_double(to_double(x)) == canonical x, rtz and rne;
//   - to_float(x) is exactly x's value (FP24) or its rounding (FP32), rtz and rne;
//   - from_double and from_float of lo (exponent-field-0 patterns only), of the midpoint between x
//     and the next pattern away from zero, and of the doubles (floats) just below and above that
//     midpoint, rtz and rne, against mpfr_set_d (mpfr_set_flt) at precision M+1 + the format rules.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>

#include "hls/fp.h"
#include "tb/fp/fp_check.h"
#include "tb/fp/fp_ref.h"

namespace raycore::fptest {
namespace {

template <class F>
struct ConvTallies {
  explicit ConvTallies(const std::string& set)
      : to_double(fmt_name<F>(), "to_double", "-", set),
        round_trip_rtz(fmt_name<F>(), "from_double(to_double)", "rtz", set),
        round_trip_rne(fmt_name<F>(), "from_double(to_double)", "rne", set),
        to_float_rtz(fmt_name<F>(), "to_float", "rtz", set),
        to_float_rne(fmt_name<F>(), "to_float", "rne", set),
        from_double_rtz(fmt_name<F>(), "from_double", "rtz", set),
        from_double_rne(fmt_name<F>(), "from_double", "rne", set),
        from_float_rtz(fmt_name<F>(), "from_float", "rtz", set),
        from_float_rne(fmt_name<F>(), "from_float", "rne", set) {}
  Tally to_double, round_trip_rtz, round_trip_rne, to_float_rtz, to_float_rne, from_double_rtz,
      from_double_rne, from_float_rtz, from_float_rne;
  bool stopped() const {
    return to_double.stopped() || round_trip_rtz.stopped() || round_trip_rne.stopped() ||
           to_float_rtz.stopped() || to_float_rne.stopped() || from_double_rtz.stopped() ||
           from_double_rne.stopped() || from_float_rtz.stopped() || from_float_rne.stopped();
  }
  void finish(bool with_float_points) {
    to_double.finish();
    round_trip_rtz.finish();
    round_trip_rne.finish();
    to_float_rtz.finish();
    to_float_rne.finish();
    from_double_rtz.finish();
    from_double_rne.finish();
    if (with_float_points) {
      from_float_rtz.finish();
      from_float_rne.finish();
    } else {
      from_float_rtz.discard();
      from_float_rne.discard();
    }
  }
};

float float_of(uint32_t b) {
  float f;
  std::memcpy(&f, &b, sizeof f);
  return f;
}
uint32_t bits_of(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}

// All checks for one pattern. float_points: the midpoints are exact in binary32 (M+2 <= 24).
template <class F>
void check_pattern(Oracle<F>& o, ConvTallies<F>& t, uint32_t x, bool float_points) {
  using S = Spec<F>;
  const auto desc = [&] { return "x=" + show<F>(x); };
  const double dv = hls::to_double<F>(x);
  t.to_double.check(o.equals(x, dv), true,
                    [&] { return desc() + " to_double=" + show_double(dv); });
  const uint32_t canon = S::canonical(x);
  t.round_trip_rtz.check(Shown<F>{hls::from_double<F, Rounding::rtz>(dv)}, Shown<F>{canon}, desc);
  t.round_trip_rne.check(Shown<F>{hls::from_double<F, Rounding::rne>(dv)}, Shown<F>{canon}, desc);
  t.to_float_rtz.check(bits_of(hls::to_float<F, Rounding::rtz>(x)),
                       bits_of(o.to_float(x, Rounding::rtz)), desc);
  t.to_float_rne.check(bits_of(hls::to_float<F, Rounding::rne>(x)),
                       bits_of(o.to_float(x, Rounding::rne)), desc);

  // The binade of x (exponent field 0: the one below the smallest normal), its lo and midpoint.
  const int e = S::zero(x) ? S::emin - 1 : S::exp_field(x) - S::bias;
  const double sgn = S::sign(x) ? -1.0 : 1.0;
  const double lo = sgn * std::ldexp(double(S::man(x) | (1u << S::M)), e - S::M);
  const double mid = lo + sgn * std::ldexp(1.0, e - S::M - 1);
  const double inf = std::numeric_limits<double>::infinity();
  const double dpts[4] = {mid, std::nextafter(mid, -inf), std::nextafter(mid, inf), lo};
  const int npts = S::zero(x) ? 4 : 3;
  for (int i = 0; i < npts; ++i) {
    const double d = dpts[i];
    const auto dd = [&] { return desc() + " d=" + show_double(d); };
    t.from_double_rtz.check(Shown<F>{hls::from_double<F, Rounding::rtz>(d)},
                            Shown<F>{o.from_double(d, Rounding::rtz)}, dd);
    t.from_double_rne.check(Shown<F>{hls::from_double<F, Rounding::rne>(d)},
                            Shown<F>{o.from_double(d, Rounding::rne)}, dd);
  }
  if (!float_points) return;
  const float fmid = float(mid), flo = float(lo);
  if (double(fmid) != mid || double(flo) != lo) {
    t.from_float_rtz.check(false, true, [&] { return desc() + " midpoint not exact in float"; });
    return;
  }
  const float finf = std::numeric_limits<float>::infinity();
  const float fpts[4] = {fmid, std::nextafterf(fmid, -finf), std::nextafterf(fmid, finf), flo};
  for (int i = 0; i < npts; ++i) {
    const float f = fpts[i];
    const auto df = [&] { return desc() + " f=" + show_float(f); };
    t.from_float_rtz.check(Shown<F>{hls::from_float<F, Rounding::rtz>(f)},
                           Shown<F>{o.from_float(f, Rounding::rtz)}, df);
    t.from_float_rne.check(Shown<F>{hls::from_float<F, Rounding::rne>(f)},
                           Shown<F>{o.from_float(f, Rounding::rne)}, df);
  }
}

constexpr int kShards = 16;

class Fp24Exhaustive : public testing::TestWithParam<int> {};
TEST_P(Fp24Exhaustive, Conversions) {
  using F = hls::FP24;
  const int shard = GetParam();
  const uint32_t per = (1u << 24) / kShards;
  const uint32_t stride = exhaustive_stride();
  Oracle<F> o;
  ConvTallies<F> t("exhaustive[" + std::to_string(shard) + "/" + std::to_string(kShards) + "]");
  if (stride != 1) t.to_double.note("stride=" + std::to_string(stride));
  for (uint32_t x = uint32_t(shard) * per; x < uint32_t(shard + 1) * per && !t.stopped(); x += stride)
    check_pattern<F>(o, t, x, true);
  t.finish(true);
}
INSTANTIATE_TEST_SUITE_P(Fp, Fp24Exhaustive, testing::Range(0, kShards));

// hls::widen (the watertight test's shear inputs): every FP24 pattern as FP32 is the exact
// conversion through binary64 (both exact: FP32 holds every FP24 number), zeros with their sign.
TEST(Widen, Fp24ToFp32EveryPattern) {
  uint32_t bad = 0, first = 0;
  for (uint32_t x = 0; x < (1u << 24); ++x) {
    const uint32_t w = hls::widen<hls::FP24, hls::FP32>(x);
    const uint32_t r = hls::from_double_bits<hls::FP32, Rounding::rtz>(hls::to_double_bits<hls::FP24>(x));
    if (w != r && bad++ == 0) first = x;
  }
  EXPECT_EQ(bad, 0u) << "first at " << std::hex << first;
}

// FP32: random patterns (uniform bits and structured ones), the same checks without float points.
TEST(Fp32Conversions, RandomPatterns) {
  using F = hls::FP32;
  Oracle<F> o;
  Gen<F> g(seed_for("fp32conv"));
  ConvTallies<F> t("random");
  const uint64_t n = random_count();
  for (uint64_t i = 0; i < n && !t.stopped(); ++i) check_pattern<F>(o, t, i & 1 ? g.uniform() : g.any(), false);
  for (uint32_t x : directed_set<F>(false)) check_pattern<F>(o, t, x, false);
  t.finish(false);
}

// from_float for FP32 on random binary32 bit patterns (subnormals, Inf and NaN included), and
// from_float / from_double for FP24 on random floats and doubles around and beyond its range.
TEST(FromHost, RandomBitsAndRanges) {
  Oracle<hls::FP32> o32;
  Oracle<hls::FP24> o24;
  Gen<hls::FP32> g(seed_for("fromhost"));
  Tally f32z("FP32", "from_float", "rtz", "random-bits"), f32n("FP32", "from_float", "rne", "random-bits");
  Tally f24z("FP24", "from_float", "rtz", "random-bits"), f24n("FP24", "from_float", "rne", "random-bits");
  Tally d24z("FP24", "from_double", "rtz", "random-range"), d24n("FP24", "from_double", "rne", "random-range");
  Tally d32z("FP32", "from_double", "rtz", "random-range"), d32n("FP32", "from_double", "rne", "random-range");
  const uint64_t n = random_count();
  for (uint64_t i = 0; i < n; ++i) {
    const uint32_t b = uint32_t(g.bits());
    const float f = float_of(b);
    const auto df = [&] { return "f=" + show_float(f); };
    f32z.check(hls::from_float<hls::FP32, Rounding::rtz>(f), o32.from_float(f, Rounding::rtz), df);
    f32n.check(hls::from_float<hls::FP32, Rounding::rne>(f), o32.from_float(f, Rounding::rne), df);
    f24z.check(hls::from_float<hls::FP24, Rounding::rtz>(f), o24.from_float(f, Rounding::rtz), df);
    f24n.check(hls::from_float<hls::FP24, Rounding::rne>(f), o24.from_float(f, Rounding::rne), df);
    // A double with a random 53-bit significand and an exponent a little beyond either format.
    const double d = std::ldexp(double(g.bits() >> 11) * 0x1p-52 + 0.0, g.range(-160, 160)) *
                     (g.coin() ? -1.0 : 1.0);
    const auto dd = [&] { return "d=" + show_double(d); };
    d24z.check(hls::from_double<hls::FP24, Rounding::rtz>(d), o24.from_double(d, Rounding::rtz), dd);
    d24n.check(hls::from_double<hls::FP24, Rounding::rne>(d), o24.from_double(d, Rounding::rne), dd);
    d32z.check(hls::from_double<hls::FP32, Rounding::rtz>(d), o32.from_double(d, Rounding::rtz), dd);
    d32n.check(hls::from_double<hls::FP32, Rounding::rne>(d), o32.from_double(d, Rounding::rne), dd);
    if (f32z.stopped() || f32n.stopped() || f24z.stopped() || f24n.stopped() || d24z.stopped() ||
        d24n.stopped() || d32z.stopped() || d32n.stopped())
      break;
  }
  for (Tally* t : {&f32z, &f32n, &f24z, &f24n, &d24z, &d24n, &d32z, &d32n}) t->finish();
}

// Host special values: Inf and NaN saturate with their sign; subnormals and tiny values flush to
// a zero with their sign; huge finite values saturate.
template <class F, Rounding R>
void run_host_specials() {
  using S = Spec<F>;
  Tally t(fmt_name<F>(), "from_double/from_float", mode_name(R), "specials");
  const double dinf = std::numeric_limits<double>::infinity();
  const double dnan = std::numeric_limits<double>::quiet_NaN();
  const struct {
    double d;
    uint32_t want;
  } dcases[] = {
      {dinf, S::sat(false)},          {-dinf, S::sat(true)},
      {dnan, S::sat(false)},          {-dnan, S::sat(true)},
      {DBL_MAX, S::sat(false)},       {-DBL_MAX, S::sat(true)},
      {DBL_TRUE_MIN, 0u},             {-DBL_TRUE_MIN, S::sign_bit},
      {DBL_MIN, 0u},                  {-DBL_MIN, S::sign_bit},
      {0.0, 0u},                      {-0.0, S::sign_bit},
      {std::ldexp(1.0, S::emax + 1), S::sat(false)},
      {std::ldexp(1.0, S::emin), S::make(false, S::emin, 0)},
  };
  for (const auto& c : dcases)
    t.check(Shown<F>{hls::from_double<F, R>(c.d)}, Shown<F>{c.want},
            [&] { return "d=" + show_double(c.d); });
  const float finf = std::numeric_limits<float>::infinity();
  const struct {
    float f;
    uint32_t want;
  } fcases[] = {
      {finf, S::sat(false)},     {-finf, S::sat(true)},          {std::nanf(""), S::sat(false)},
      {-std::nanf(""), S::sat(true)}, {FLT_TRUE_MIN, 0u},         {-FLT_TRUE_MIN, S::sign_bit},
      {0.0f, 0u},                {-0.0f, S::sign_bit},
  };
  for (const auto& c : fcases)
    t.check(Shown<F>{hls::from_float<F, R>(c.f)}, Shown<F>{c.want},
            [&] { return "f=" + show_float(c.f); });
  t.finish();
}
TEST(HostSpecials, FP24_rtz) { run_host_specials<hls::FP24, Rounding::rtz>(); }
TEST(HostSpecials, FP24_rne) { run_host_specials<hls::FP24, Rounding::rne>(); }
TEST(HostSpecials, FP32_rtz) { run_host_specials<hls::FP32, Rounding::rtz>(); }
TEST(HostSpecials, FP32_rne) { run_host_specials<hls::FP32, Rounding::rne>(); }

// FP32's top binade (exponent field 255, an ordinary binade here) saturates to +-FLT_MAX in
// to_float; FP32 normal patterns convert to themselves.
TEST(HostSpecials, Fp32ToFloatTopBinade) {
  using F = hls::FP32;
  EXPECT_EQ(bits_of(hls::to_float<F, Rounding::rne>(0x7F800000u)), 0x7F7FFFFFu);
  EXPECT_EQ(bits_of(hls::to_float<F, Rounding::rtz>(0xFFFFFFFFu)), 0xFF7FFFFFu);
  EXPECT_EQ(bits_of(hls::to_float<F, Rounding::rne>(0x3F800001u)), 0x3F800001u);
}

}  // namespace
}  // namespace raycore::fptest
