// tb/hls/test_margins.cpp - the watertightness margins (hls/margins.h) of hls::ist_wald,
// hls::trv_split and hls::trv_clip_box, on random and directed vectors in every format/rounding:
//   - no margins (margins_none, widen 0) give today's results bit for bit: the test and the two
//     traversal steps are compared against literal copies of the code before the margins;
//   - a margin only adds hits of a given triangle test: hit with eps = 0 implies hit with eps > 0,
//     t and den never change, and a test that fails with a margin fails in the same phase without;
//   - a widening only widens: a split that visits both children still does, one that visits one
//     child visits it or both; a clip that hits still hits, with the same narrowed interval;
//   - hls::add_ulps on directed values, and make_margins' registers and refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>

#include "hls/fp.h"
#include "hls/ist.h"
#include "hls/margins.h"
#include "hls/trv.h"
#include "tb/rtl/stimulus.h"
#include "tb/rtl/trv_stim.h"

namespace raycore::hls {
namespace {

// ---- today's datapaths, copied literally from before the margins ------------------------------

template <class A>
IstOut ist_today(uint32_t k, const uint32_t c[9], const uint32_t o[3], const uint32_t d[3],
                 uint32_t tmin, uint32_t tmax) {
  const int u = axis_u(k), v = axis_v(k);
  const uint32_t den = A::add3(d[k], A::mul(c[kNU], d[u]), A::mul(c[kNV], d[v]));
  const uint32_t num =
      A::sub(A::sub(c[kND], o[k]), A::add(A::mul(c[kNU], o[u]), A::mul(c[kNV], o[v])));
  const uint32_t t = A::mul(num, A::rcp(den));
  if (!(A::lt(tmin, t) && A::lt(t, tmax))) return {IstExit::distance, t, den, t_key<typename A::Fmt>(t)};
  const uint32_t hu = A::add(o[u], A::mul(t, d[u]));
  const uint32_t hv = A::add(o[v], A::mul(t, d[v]));
  const uint32_t beta = A::add3(A::mul(c[kBNU], hu), A::mul(c[kBNV], hv), c[kBD]);
  if (A::sign(beta) && !A::is_zero(beta)) return {IstExit::beta, t, den, t_key<typename A::Fmt>(t)};
  const uint32_t gamma = A::add3(A::mul(c[kCNU], hu), A::mul(c[kCNV], hv), c[kCD]);
  if (A::sign(gamma) && !A::is_zero(gamma)) return {IstExit::gamma, t, den, t_key<typename A::Fmt>(t)};
  if (A::lt(A::one, A::add(beta, gamma))) return {IstExit::sum, t, den, t_key<typename A::Fmt>(t)};
  return {IstExit::hit, t, den, t_key<typename A::Fmt>(t)};
}

template <class A>
bool clip_today(const uint32_t lo[3], const uint32_t hi[3], const Ray& r, uint32_t& tnear,
                uint32_t& tfar) {
  uint32_t t0 = r.tmin, t1 = r.tmax;
  for (int a = 0; a < 3; ++a) {
    uint32_t tl = A::mul(A::sub(lo[a], r.o[a]), r.inv[a]);
    uint32_t th = A::mul(A::sub(hi[a], r.o[a]), r.inv[a]);
    if (A::lt(th, tl)) {
      const uint32_t x = tl;
      tl = th;
      th = x;
    }
    t0 = A::max(t0, tl);
    t1 = A::min(t1, th);
  }
  tnear = t0;
  tfar = t1;
  return A::le(t0, t1);
}

template <class A>
SplitStep split_today(uint32_t split, uint32_t axis, const Ray& r, uint32_t tnear, uint32_t tfar) {
  const uint32_t ts = A::mul(A::sub(split, r.o[axis]), r.inv[axis]);
  const bool below = A::lt(r.o[axis], split) ||
                     (A::eq(r.o[axis], split) && (A::sign(r.d[axis]) || A::is_zero(r.d[axis])));
  Visit v;
  if (A::lt(tfar, ts) || !A::lt(A::zero, ts))
    v = Visit::first;
  else if (A::lt(ts, tnear))
    v = Visit::second;
  else
    v = Visit::both;
  return {v, below, ts};
}

// ---- helpers ----------------------------------------------------------------------------------

constexpr int kIstVectors = 200000;
constexpr int kTrvVectors = 200000;

Ray ray_of(const rtltest::TrvIn& x) {
  Ray r;
  for (int i = 0; i < 3; ++i) {
    r.o[i] = x.o[i];
    r.d[i] = x.d[i];
    r.inv[i] = x.inv[i];
  }
  r.tmin = x.tnear;
  r.tmax = x.tfar;
  return r;
}

// A random margin: 0, about 0.008, about 2^-12, or uniform in [0, 0.05].
template <class A>
Margins random_margins(std::mt19937_64& rng) {
  double eps = 0;
  switch (rng() % 4) {
    case 0: eps = 0; break;
    case 1: eps = 0.008 * (1 + 0.1 * (double(rng() % 1000) / 1000 - 0.5)); break;
    case 2: eps = std::ldexp(1.0, -12) * (1 + double(rng() % 1000) / 1000); break;
    default: eps = 0.05 * double(rng() % 100000) / 100000; break;
  }
  return make_margins<A>(eps, int32_t(rng() % 9));
}

// ---- ist --------------------------------------------------------------------------------------

template <class F, Rounding R>
void ist_zero_is_today(uint64_t seed) {
  using A = Arith<F, R>;
  rtltest::Stimulus<F, R> stim(seed);
  for (int i = 0; i < kIstVectors; ++i) {
    const rtltest::IstIn x = stim.next();
    const IstOut a = ist_today<A>(x.k, x.c, x.o, x.d, x.tmin, x.tmax);
    const IstOut b = ist_wald<A>(x.k, x.c, x.o, x.d, x.tmin, x.tmax, margins_none<A>());
    const IstOut c = ist_wald<A>(x.k, x.c, x.o, x.d, x.tmin, x.tmax, make_margins<A>(0.0, 0));
    ASSERT_EQ(a.exit, b.exit) << i;
    ASSERT_EQ(a.t, b.t) << i;
    ASSERT_EQ(a.den, b.den) << i;
    ASSERT_EQ(b.exit, c.exit) << i;
  }
}

TEST(Margins, IstZeroIsTodayFp24Rtz) { ist_zero_is_today<FP24, Rounding::rtz>(1); }
TEST(Margins, IstZeroIsTodayFp24Rne) { ist_zero_is_today<FP24, Rounding::rne>(2); }
TEST(Margins, IstZeroIsTodayFp32Rtz) { ist_zero_is_today<FP32, Rounding::rtz>(3); }
TEST(Margins, IstZeroIsTodayFp32Rne) { ist_zero_is_today<FP32, Rounding::rne>(4); }

// A margin can only add hits: hit without implies hit with; t and den are the same; a failure with
// the margin is the same failure without it.
template <class F, Rounding R>
void ist_more_hits_only(uint64_t seed) {
  using A = Arith<F, R>;
  rtltest::Stimulus<F, R> stim(seed);
  std::mt19937_64 rng(seed * 7 + 1);
  uint64_t added = 0, base_hits = 0;
  for (int i = 0; i < kIstVectors; ++i) {
    const rtltest::IstIn x = stim.next();
    const Margins m = random_margins<A>(rng);
    const IstOut a = ist_wald<A>(x.k, x.c, x.o, x.d, x.tmin, x.tmax, margins_none<A>());
    const IstOut b = ist_wald<A>(x.k, x.c, x.o, x.d, x.tmin, x.tmax, m);
    ASSERT_EQ(a.t, b.t) << i;
    ASSERT_EQ(a.den, b.den) << i;
    if (a.exit == IstExit::hit) {
      ++base_hits;
      ASSERT_EQ(b.exit, IstExit::hit) << i << ": a margin lost a hit (eps " << A::to_double(m.eps) << ")";
    } else if (b.exit == IstExit::hit) {
      ++added;
    } else if (b.exit != a.exit) {
      // A later phase may fail instead of an earlier one the margin now passes.
      ASSERT_GT(int(b.exit), int(a.exit)) << i;
    }
    if (b.exit != IstExit::hit && b.exit != IstExit::distance) {
      ASSERT_NE(a.exit, IstExit::hit) << i;
    }
  }
  EXPECT_GT(base_hits, uint64_t(kIstVectors / 20));
  EXPECT_GT(added, uint64_t(kIstVectors / 1000)) << "the margins never added a hit";
  std::printf("MARGINS ist %s hits=%llu added_by_margins=%llu\n", R == Rounding::rtz ? "rtz" : "rne",
              (unsigned long long)base_hits, (unsigned long long)added);
}

TEST(Margins, IstMoreHitsOnlyFp24Rtz) { ist_more_hits_only<FP24, Rounding::rtz>(11); }
TEST(Margins, IstMoreHitsOnlyFp24Rne) { ist_more_hits_only<FP24, Rounding::rne>(12); }
TEST(Margins, IstMoreHitsOnlyFp32Rne) { ist_more_hits_only<FP32, Rounding::rne>(13); }

// A hit on the edge: beta slightly negative fails without a margin and passes with 0.008.
TEST(Margins, IstEdgeDirected) {
  using A = Arith<FP24, Rounding::rtz>;
  // Triangle in the plane z = 0 (k = 2, u = x, v = y): beta = x, gamma = y (n_u = n_v = 0,
  // n_d = 0; b_nu = 1, c_nv = 1), ray straight down from z = 1.
  uint32_t c[9] = {0, 0, 0, A::one, 0, 0, 0, A::one, 0};
  const uint32_t d[3] = {0, 0, A::neg(A::one)};
  const Margins m = make_margins<A>(0.008, 0);
  struct Case {
    double x, y;
    IstExit none, with;
  };
  for (const Case& k : {Case{0.25, 0.25, IstExit::hit, IstExit::hit},
                        Case{-0.004, 0.25, IstExit::beta, IstExit::hit},
                        Case{0.25, -0.004, IstExit::gamma, IstExit::hit},
                        Case{-0.02, 0.25, IstExit::beta, IstExit::beta},
                        Case{0.504, 0.5, IstExit::sum, IstExit::hit},
                        Case{0.52, 0.5, IstExit::sum, IstExit::sum},
                        Case{0.0, 0.0, IstExit::hit, IstExit::hit}}) {
    const uint32_t o[3] = {A::from_double(k.x), A::from_double(k.y), A::one};
    EXPECT_EQ(ist_wald<A>(2, c, o, d, 0, A::from_double(4), margins_none<A>()).exit, k.none)
        << k.x << " " << k.y;
    EXPECT_EQ(ist_wald<A>(2, c, o, d, 0, A::from_double(4), m).exit, k.with) << k.x << " " << k.y;
  }
  // -0 is a hit without a margin (negative zero passes), as before.
  const uint32_t o0[3] = {A::neg(0), A::from_double(0.5), A::one};
  EXPECT_EQ(ist_wald<A>(2, c, o0, d, 0, A::from_double(4), margins_none<A>()).exit, IstExit::hit);
}

// ---- trv --------------------------------------------------------------------------------------

template <class F, Rounding R>
void trv_zero_is_today_and_widens(uint64_t seed) {
  using A = Arith<F, R>;
  rtltest::TrvStim<F, R> stim(seed);
  std::mt19937_64 rng(seed + 99);
  uint64_t widened_split = 0, widened_clip = 0;
  const uint64_t nd = rtltest::TrvStim<F, R>::directed_count();
  for (uint64_t i = 0; i < nd + kTrvVectors; ++i) {
    const rtltest::TrvIn x = i < nd ? stim.directed(i) : stim.random();
    const uint32_t axis = x.axis == 3 ? 0u : x.axis;
    const Ray r = ray_of(x);
    const int32_t n = int32_t(1 + rng() % 8);
    // Split.
    const SplitStep s0 = split_today<A>(x.split, axis, r, x.tnear, x.tfar);
    const SplitStep s1 = trv_split<A>(x.split, axis, r, x.tnear, x.tfar, 0);
    const SplitStep sw = trv_split<A>(x.split, axis, r, x.tnear, x.tfar, n);
    ASSERT_EQ(s0.visit, s1.visit) << i;
    ASSERT_EQ(s0.below_first, s1.below_first) << i;
    ASSERT_EQ(s0.tsplit, s1.tsplit) << i;
    ASSERT_EQ(sw.tsplit, s0.tsplit) << i;
    ASSERT_EQ(sw.below_first, s0.below_first) << i;
    if (s0.visit == Visit::both) {
      ASSERT_EQ(sw.visit, Visit::both) << i;
    }
    if (sw.visit != s0.visit) {
      ASSERT_EQ(sw.visit, Visit::both) << i << ": widening must add the other child, not swap";
      ++widened_split;
    }
    // Clip.
    uint32_t a0 = 0, a1 = 0, b0 = 0, b1 = 0, c0 = 0, c1 = 0;
    const bool h0 = clip_today<A>(x.lo, x.hi, r, a0, a1);
    const bool h1 = trv_clip_box<A>(x.lo, x.hi, r, b0, b1, 0);
    const bool hw = trv_clip_box<A>(x.lo, x.hi, r, c0, c1, n);
    ASSERT_EQ(h0, h1) << i;
    ASSERT_EQ(a0, b0) << i;
    ASSERT_EQ(a1, b1) << i;
    ASSERT_EQ(c0, a0) << i << ": the narrowed interval is not widened";
    ASSERT_EQ(c1, a1) << i;
    if (h0) {
      ASSERT_TRUE(hw) << i;
    }
    if (hw && !h0) ++widened_clip;
  }
  EXPECT_GT(widened_split, 0u);
  EXPECT_GT(widened_clip, 0u);
}

TEST(Margins, TrvZeroIsTodayAndWidensFp24Rtz) { trv_zero_is_today_and_widens<FP24, Rounding::rtz>(21); }
TEST(Margins, TrvZeroIsTodayAndWidensFp24Rne) { trv_zero_is_today_and_widens<FP24, Rounding::rne>(22); }
TEST(Margins, TrvZeroIsTodayAndWidensFp32Rne) { trv_zero_is_today_and_widens<FP32, Rounding::rne>(23); }

// ---- add_ulps and the registers ---------------------------------------------------------------

TEST(Margins, AddUlps) {
  using F = FP24;
  using A = Arith<F, Rounding::rtz>;
  const uint32_t one = F::one, mone = A::neg(F::one);
  EXPECT_EQ(add_ulps<F>(one, 1), next_up<F>(one));
  EXPECT_EQ(add_ulps<F>(one, -1), next_down<F>(one));  // crosses the binade
  EXPECT_EQ(add_ulps<F>(mone, 1), next_up<F>(mone));
  EXPECT_EQ(add_ulps<F>(mone, -2), next_down<F>(next_down<F>(mone)));
  EXPECT_EQ(add_ulps<F>(F::max_mag, 3), F::max_mag);                    // saturates
  EXPECT_EQ(add_ulps<F>(F::sign_mask | F::max_mag, -3), F::sign_mask | F::max_mag);
  EXPECT_EQ(add_ulps<F>(F::min_mag, -1), 0u);                          // below normal: +0
  EXPECT_EQ(add_ulps<F>(F::sign_mask | F::min_mag, 1), 0u);            // never crosses zero
  EXPECT_EQ(add_ulps<F>(0u, 5), 0u);                                   // zero stays zero
  EXPECT_EQ(add_ulps<F>(F::sign_mask, -5), 0u);
  EXPECT_EQ(add_ulps<F>(one, 0), one);
}

TEST(Margins, MakeMargins) {
  using A = Arith<FP24, Rounding::rtz>;
  const Margins z = make_margins<A>(0.0, 0);
  EXPECT_EQ(z.eps, 0u);
  EXPECT_EQ(z.one_eps, A::one);
  EXPECT_EQ(z.widen_ulps, 0);
  const Margins m = make_margins<A>(0.008, 2);
  EXPECT_EQ(m.eps, A::from_double(0.008));
  EXPECT_EQ(m.one_eps, A::add(A::one, m.eps));
  EXPECT_NEAR(A::to_double(m.one_eps), 1.008, 1e-4);
  EXPECT_EQ(m.widen_ulps, 2);
  // Below the format's resolution at 1: eps counts for beta and gamma, one_eps stays 1 (rtz).
  EXPECT_EQ(make_margins<A>(std::ldexp(1.0, -20), 0).one_eps, A::one);
  EXPECT_THROW(make_margins<A>(-0.001, 0), std::invalid_argument);
  EXPECT_THROW(make_margins<A>(std::nan(""), 0), std::invalid_argument);
  EXPECT_THROW(make_margins<A>(INFINITY, 0), std::invalid_argument);
  EXPECT_THROW(make_margins<A>(0.0, -1), std::invalid_argument);
  EXPECT_THROW(make_margins<A>(0.0, 65), std::invalid_argument);
  EXPECT_NO_THROW(make_margins<A>(0.0, 64));
}

}  // namespace
}  // namespace raycore::hls
