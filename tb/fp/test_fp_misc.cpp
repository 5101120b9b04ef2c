// hls/fp.h sign operations, comparisons, min/max, neighbours and ulp against independent
// definitions: values compared by MPFR (mpfr_cmp), neighbours by mpfr_nextabove/nextbelow at
// precision M+1 followed by the format's rules, ulp as (next above |a|) - |a| computed in MPFR.
// Unary ops: every FP24 pattern, and random FP32 patterns. Binary ops: all pairs of the directed
// set plus random pairs.
#include <gtest/gtest.h>

#include "hls/fp.h"
#include "tb/fp/fp_check.h"
#include "tb/fp/fp_ref.h"

namespace raycore::fptest {
namespace {

template <class F>
struct UnaryTallies {
  explicit UnaryTallies(const std::string& set)
      : neg(fmt_name<F>(), "neg", "-", set),
        abs(fmt_name<F>(), "abs", "-", set),
        next_up(fmt_name<F>(), "next_up", "-", set),
        next_down(fmt_name<F>(), "next_down", "-", set),
        ulp_exp(fmt_name<F>(), "ulp_exp", "-", set),
        ulp(fmt_name<F>(), "ulp", "-", set) {}
  Tally neg, abs, next_up, next_down, ulp_exp, ulp;
  bool stopped() const {
    return neg.stopped() || abs.stopped() || next_up.stopped() || next_down.stopped() ||
           ulp_exp.stopped() || ulp.stopped();
  }
  void finish() {
    for (Tally* t : {&neg, &abs, &next_up, &next_down, &ulp_exp, &ulp}) t->finish();
  }
};

// A neighbour equal up to the sign of a zero (that sign has its own test below).
template <class F>
uint32_t zero_sign_agnostic(uint32_t got, uint32_t want) {
  return (Spec<F>::zero(got) && Spec<F>::zero(want)) ? want : got;
}

template <class F>
void check_unary(Oracle<F>& o, UnaryTallies<F>& t, uint32_t a) {
  using S = Spec<F>;
  const auto d = [&] { return "a=" + show<F>(a); };
  // neg and abs: only the sign bit changes (so a zero's sign too).
  const uint32_t n = hls::neg<F>(a), b = hls::abs<F>(a);
  t.neg.check(Shown<F>{n}, Shown<F>{(a ^ S::sign_bit)}, d);
  t.abs.check(Shown<F>{b}, Shown<F>{(a & ~S::sign_bit)}, d);
  t.next_up.check(Shown<F>{zero_sign_agnostic<F>(hls::next_up<F>(a), o.next_up(a))},
                  Shown<F>{o.next_up(a)}, d);
  t.next_down.check(Shown<F>{zero_sign_agnostic<F>(hls::next_down<F>(a), o.next_down(a))},
                    Shown<F>{o.next_down(a)}, d);
  t.ulp_exp.check(hls::ulp_exp<F>(a), o.ulp_exp(a), d);
  t.ulp.check(Shown<F>{hls::ulp<F>(a)}, Shown<F>{o.ulp(a)}, d);
}

constexpr int kShards = 4;
class Fp24UnaryExhaustive : public testing::TestWithParam<int> {};
TEST_P(Fp24UnaryExhaustive, MatchesMpfr) {
  using F = hls::FP24;
  const int shard = GetParam();
  const uint32_t per = (1u << 24) / kShards, stride = exhaustive_stride();
  Oracle<F> o;
  UnaryTallies<F> t("exhaustive[" + std::to_string(shard) + "/" + std::to_string(kShards) + "]");
  for (uint32_t a = uint32_t(shard) * per; a < uint32_t(shard + 1) * per && !t.stopped(); a += stride)
    check_unary<F>(o, t, a);
  t.finish();
}
INSTANTIATE_TEST_SUITE_P(Fp, Fp24UnaryExhaustive, testing::Range(0, kShards));

TEST(Fp32Unary, RandomAndDirected) {
  using F = hls::FP32;
  Oracle<F> o;
  Gen<F> g(seed_for("fp32unary"));
  UnaryTallies<F> t("random+directed");
  for (uint32_t a : directed_set<F>(false)) check_unary<F>(o, t, a);
  const uint64_t n = random_count();
  for (uint64_t i = 0; i < n && !t.stopped(); ++i) check_unary<F>(o, t, i & 1 ? g.uniform() : g.any());
  t.finish();
}

// IEEE 754's nextUp(-smallest) is -0 (and nextDown(+smallest) is +0); with the header's rule
// "flushed to a signed zero" the exact neighbour -(2^emin - ulp) keeps its sign too.
template <class F>
void run_next_zero_sign() {
  using S = Spec<F>;
  Oracle<F> o;
  Tally t(fmt_name<F>(), "next_up/down_zero_sign", "-", "directed");
  const uint32_t pmin = S::make(false, S::emin, 0), nmin = S::make(true, S::emin, 0);
  t.check(Shown<F>{hls::next_up<F>(nmin)}, Shown<F>{o.next_up(nmin)},
          [&] { return "next_up(a), a=" + show<F>(nmin); });
  t.check(Shown<F>{hls::next_down<F>(pmin)}, Shown<F>{o.next_down(pmin)},
          [&] { return "next_down(a), a=" + show<F>(pmin); });
  t.finish();
}
TEST(NextZeroSign, FP24) { run_next_zero_sign<hls::FP24>(); }
TEST(NextZeroSign, FP32) { run_next_zero_sign<hls::FP32>(); }

// Comparisons and min/max on pairs.
template <class F>
void run_compare() {
  Oracle<F> o;
  Gen<F> g(seed_for(std::string("cmp") + fmt_name<F>()));
  Tally tlt(fmt_name<F>(), "lt", "-", "directed+random"), tle(fmt_name<F>(), "le", "-", "directed+random");
  Tally teq(fmt_name<F>(), "eq", "-", "directed+random"), tc(fmt_name<F>(), "cmp", "-", "directed+random");
  Tally tmin(fmt_name<F>(), "min", "-", "directed+random"), tmax(fmt_name<F>(), "max", "-", "directed+random");
  auto one = [&](uint32_t a, uint32_t b) {
    const auto d = [&] { return "a=" + show<F>(a) + " b=" + show<F>(b); };
    const int c = o.cmp(a, b);
    tlt.check(hls::lt<F>(a, b), c < 0, d);
    tle.check(hls::le<F>(a, b), c <= 0, d);
    teq.check(hls::eq<F>(a, b), c == 0, d);
    tc.check(hls::cmp<F>(a, b), c, d);
    // min/max return an operand; on equal values the first.
    tmin.check(Shown<F>{hls::min<F>(a, b)}, Shown<F>{c > 0 ? b : a}, d);
    tmax.check(Shown<F>{hls::max<F>(a, b)}, Shown<F>{c < 0 ? b : a}, d);
    return !(tlt.stopped() || tle.stopped() || teq.stopped() || tc.stopped() || tmin.stopped() ||
             tmax.stopped());
  };
  const auto v = directed_set<F>(false);
  for (uint32_t a : v)
    for (uint32_t b : v)
      if (!one(a, b)) goto done;
  for (uint64_t i = 0, n = random_count(); i < n; ++i) {
    const uint32_t a = g.any();
    const uint32_t b = i % 3 == 0 ? g.uniform() : (i % 3 == 1 ? g.close_to(a) : g.step(a, g.range(-2, 2)));
    if (!one(a, b)) break;
  }
done:
  for (Tally* t : {&tlt, &tle, &teq, &tc, &tmin, &tmax}) t->finish();
}
TEST(Compare, FP24) { run_compare<hls::FP24>(); }
TEST(Compare, FP32) { run_compare<hls::FP32>(); }

}  // namespace
}  // namespace raycore::fptest
