// tb/rtl/test_rtl_trv.cpp - co-simulation of rtl/units/trv.v (the traversal datapath) against
// hls::trv_split / hls::trv_clip_box (hls/trv.h) and systemc/trv.h's child order and interval
// update, bit for bit, in order.
//
// One test per Verilated --cc variant (rtl/units/trv.cmake, RAYCORE_RTL_TRV variants). Each test
// streams through the unit's valid/ready handshake:
//   1. fullrate: 4096 random items with no stalls (one step per cycle, latency == 4*STAGES),
//   2. directed: TrvStim::directed_count() items (every combination of the edge cases: d = +-0 on
//      the axis, the origin on the plane, the plane one ulp off, +-0 planes, the plane at tnear /
//      tfar exactly, -0 interval ends, point intervals, inverted and empty boxes), random stalls,
//   3. random: RAYCORE_RTL_TRV_N items (default 2*10^5; split and clip, 10 % random bit patterns)
//      with random input gaps and bursty random output back-pressure.
// The interval widening register widen_i (hls/margins.h) is static within a run: fullrate and
// directed run with 0 and again with a random N in 1..8, the random items in 8 runs with N = 0, 1,
// 2 and random values 0..8 (the unit's 7 bits: one run with 64).
// A 16-bit sequence number rides in the tag. The first mismatches print the inputs, the expected
// and the received outputs. TRVSUM lines count items per op and per split visit.
#include <gtest/gtest.h>
#include <verilated.h>

#include <array>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>

#include "hls/fp.h"
#include "tb/fp/fp_check.h"
#include "tb/rtl/rtl_cosim.h"
#include "tb/rtl/trv_stim.h"

#include "rtl_trv_models.h"

namespace raycore::rtltest {
namespace {

using hls::Rounding;

uint64_t trv_count() { return fptest::env_count("RAYCORE_RTL_TRV_N", 200000); }

template <class V>
void drive(V& m, const TrvIn& x) {
  m.in_op_i = uint8_t(x.op & 1u);
  m.in_axis_i = uint8_t(x.axis & 3u);
  m.in_split_i = x.split;
  m.in_node_i = x.node;
  m.in_child_i = x.child;
  m.in_o_x_i = x.o[0];
  m.in_o_y_i = x.o[1];
  m.in_o_z_i = x.o[2];
  m.in_d_x_i = x.d[0];
  m.in_d_y_i = x.d[1];
  m.in_d_z_i = x.d[2];
  m.in_inv_x_i = x.inv[0];
  m.in_inv_y_i = x.inv[1];
  m.in_inv_z_i = x.inv[2];
  m.in_tnear_i = x.tnear;
  m.in_tfar_i = x.tfar;
  m.in_lo_x_i = x.lo[0];
  m.in_lo_y_i = x.lo[1];
  m.in_lo_z_i = x.lo[2];
  m.in_hi_x_i = x.hi[0];
  m.in_hi_y_i = x.hi[1];
  m.in_hi_z_i = x.hi[2];
}

template <class V>
TrvOut read(const V& m) {
  TrvOut r;
  r.op = m.out_op_o;
  r.hit = m.out_hit_o;
  r.visit = m.out_visit_o;
  r.below = m.out_below_o;
  r.tsplit = m.out_tsplit_o;
  r.tnear = m.out_tnear_o;
  r.tfar = m.out_tfar_o;
  r.node = m.out_node_o;
  r.far_node = m.out_far_node_o;
  r.far_tfar = m.out_far_tfar_o;
  return r;
}

enum class Set { fullrate, directed, random };

template <class V, class F, Rounding R>
class TrvCosim {
  using A = hls::Arith<F, R>;

 public:
  TrvCosim(std::string name, int stages, uint64_t seed)
      : name_(std::move(name)), stages_(stages), stim_(seed), rng_(seed ^ 0x9e3779b97f4a7c15ull),
        dut_(seed) {}

  // Streams `count` items of the set with the widening register N; returns the number checked.
  uint64_t run(Set set, uint64_t count, uint32_t widen) {
    const char* set_name = set == Set::fullrate ? "fullrate" : set == Set::directed ? "directed"
                                                                                      : "random";
    struct Item {
      TrvIn x;
      TrvOut expected;
    };
    const StreamSpec spec{name_, count, set == Set::fullrate, 4u * uint64_t(stages_), "4*STAGES",
                          2000u + 64u * uint64_t(stages_), 1};
    std::array<uint64_t, 6> by_kind{};  // split first/second/both, clip miss/hit, other
    uint64_t mismatches = 0;
    V& m = *dut_;
    m.widen_i = uint8_t(widen);  // a per-frame register: static while the run streams
    const StreamStats st = stream(
        dut_, spec, rng_, rng_,
        [&](uint64_t k) {
          Item it;
          it.x = set == Set::directed ? stim_.directed(k) : stim_.random();
          it.expected = trv_expect<A>(it.x, widen);
          drive(m, it.x);
          return it;
        },
        [&] { drive(m, stim_.random()); },  // junk inputs
        [&](const Item& it, uint16_t seq, uint64_t cycle) {
          const TrvOut got = read(m);
          const TrvOut& e = it.expected;
          ++by_kind[e.op == 0 ? (e.visit < 3 ? e.visit : 5) : 3 + e.hit];
          if (!same(got, e)) {
            ++mismatches;
            ADD_FAILURE() << mismatch(name_ + " " + set_name, seq, cycle, describe<F>(it.x),
                                      describe<F>(e), describe<F>(got));
          }
        },
        [&] { return mismatches >= 5; });
    std::printf("TRVSUM %s %s widen=%u vectors=%" PRIu64 " mismatches=%" PRIu64 " split_first=%" PRIu64
                " split_second=%" PRIu64 " split_both=%" PRIu64 " clip_miss=%" PRIu64
                " clip_hit=%" PRIu64 " cycles=%" PRIu64 " latency=%" PRIu64 "..%" PRIu64 "\n",
                name_.c_str(), set_name, widen, st.checked, mismatches, by_kind[0], by_kind[1], by_kind[2],
                by_kind[3], by_kind[4], st.cycles, st.min_lat, st.max_lat);
    EXPECT_EQ(mismatches, 0u);
    EXPECT_EQ(st.checked, count) << name_ << " " << set_name << ": not every item came back";
    last_ = by_kind;
    return st.checked;
  }
  const std::array<uint64_t, 6>& by_kind() const { return last_; }

 private:
  std::string name_;
  int stages_;
  TrvStim<F, R> stim_;
  std::mt19937_64 rng_;
  Dut<V> dut_;
  std::array<uint64_t, 6> last_{};
};

template <class V, class F, Rounding R>
void run_variant(const std::string& name, int stages) {
  TrvCosim<V, F, R> sim(name, stages, fptest::seed_for("rtl.trv." + name));
  std::mt19937_64 rng(fptest::seed_for("rtl.trv.widen." + name));
  const uint32_t nw = uint32_t(1 + rng() % 8);
  sim.run(Set::fullrate, 4096, 0);
  sim.run(Set::fullrate, 4096, nw);
  const uint64_t nd = TrvStim<F, R>::directed_count();
  ASSERT_EQ(sim.run(Set::directed, nd, 0), nd);
  ASSERT_EQ(sim.run(Set::directed, nd, nw), nd);
  const uint64_t n = trv_count();
  uint64_t checked = 0;
  std::array<uint64_t, 6> by_kind{};
  for (uint32_t k = 0; k < 8; ++k) {
    const uint32_t w = k < 3 ? k : k == 7 ? 64u : uint32_t(rng() % 9);
    checked += sim.run(Set::random, n / 8 + (k == 7 ? n % 8 : 0), w);
    for (size_t j = 0; j < by_kind.size(); ++j) by_kind[j] += sim.by_kind()[j];
  }
  ASSERT_EQ(checked, n);
  // Every outcome must be exercised: each split visit and both clip results.
  static const char* kNames[] = {"split first", "split second", "split both", "clip miss",
                                 "clip hit"};
  for (int k = 0; k < 5; ++k)
    EXPECT_GE(by_kind[size_t(k)], n / 50) << name << ": " << kNames[k] << " too rare";
}

#define RAYCORE_RTL_TRV_VARIANT(prefix, module, fmt, mode, stages)                  \
  TEST(RtlTrv, prefix) {                                                              \
    run_variant<prefix, hls::fmt, Rounding::mode>(#fmt "_" #mode "_s" #stages, stages); \
  }
#include "rtl_trv_variants.h"
#undef RAYCORE_RTL_TRV_VARIANT

}  // namespace
}  // namespace raycore::rtltest
