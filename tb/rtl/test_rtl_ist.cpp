// tb/rtl/test_rtl_ist.cpp - co-simulation of rtl/units/ist.v (the pipelined Wald test) against
// hls::ist_wald (hls/ist.h), bit for bit: exit code, t, den and the tag, in order.
//
// One test per Verilated variant (format, rounding, STAGES), listed once in rtl/CMakeLists.txt
// (RAYCORE_RTL_IST_VARIANTS). Each test streams, through the unit's valid/ready handshake:
//   1. fullrate: 4096 tests with no stalls (checks one test per cycle and latency == 10*STAGES),
//   2. random: RAYCORE_RTL_IST_N tests (default 5*10^5) with random input gaps and random output
//      back-pressure (bursty rates, new ones every 256 cycles), in 8 runs with different margin
//      registers eps_i / one_eps_i (hls/margins.h; static within a run, the pipeline empty between
//      runs): none, 0.008-ish, 2^-12-ish, random values in [0, 0.05], and random bit patterns.
// Stimulus: triangles from random vertices (hls::make_wald, including near-degenerate and
// degenerate ones) with rays aimed at random barycentric points inside, outside and on the edges,
// and random tmin/tmax around the hit distance (every exit code occurs often; each must reach 2 %
// of the vectors), plus 10 % fully random bit patterns (k = 0..2). A 16-bit sequence number rides
// in the tag. The first mismatches print all inputs, the expected and the received outputs.
#include <gtest/gtest.h>
#include <verilated.h>

#include <array>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>

#include "hls/fp.h"
#include "hls/geom.h"
#include "hls/ist.h"
#include "hls/margins.h"
#include "hls/wald.h"
#include "systemc/config.h"
#include "tb/fp/fp_check.h"
#include "tb/rtl/rtl_cosim.h"
#include "tb/rtl/stimulus.h"

#include "rtl_ist_models.h"

namespace raycore::rtltest {
namespace {

using hls::Rounding;

uint64_t ist_count() { return fptest::env_count("RAYCORE_RTL_IST_N", 500000); }

struct IstRes {
  uint32_t exit = 0, t = 0, den = 0;
  bool operator==(const IstRes& x) const { return exit == x.exit && t == x.t && den == x.den; }
};

template <class F>
std::string show(uint32_t x) {
  return fptest::show<F>(x);
}

template <class F>
std::string describe(const IstIn& x) {
  std::ostringstream s;
  s << "k=" << x.k << " c=[";
  for (int i = 0; i < 9; ++i) s << (i ? " " : "") << show<F>(x.c[i]);
  s << "] o=[" << show<F>(x.o[0]) << " " << show<F>(x.o[1]) << " " << show<F>(x.o[2]) << "] d=["
    << show<F>(x.d[0]) << " " << show<F>(x.d[1]) << " " << show<F>(x.d[2])
    << "] tmin=" << show<F>(x.tmin) << " tmax=" << show<F>(x.tmax);
  return s.str();
}

template <class F>
std::string describe(const IstRes& r) {
  return "exit=" + std::to_string(r.exit) + " t=" + show<F>(r.t) + " den=" + show<F>(r.den);
}

template <class V, class F>
void drive(V& m, const IstIn& x) {
  m.in_k_i = uint8_t(x.k & 3u);
  m.in_c0_i = x.c[0];
  m.in_c1_i = x.c[1];
  m.in_c2_i = x.c[2];
  m.in_c3_i = x.c[3];
  m.in_c4_i = x.c[4];
  m.in_c5_i = x.c[5];
  m.in_c6_i = x.c[6];
  m.in_c7_i = x.c[7];
  m.in_c8_i = x.c[8];
  m.in_o_x_i = x.o[0];
  m.in_o_y_i = x.o[1];
  m.in_o_z_i = x.o[2];
  m.in_d_x_i = x.d[0];
  m.in_d_y_i = x.d[1];
  m.in_d_z_i = x.d[2];
  m.in_tmin_i = x.tmin;
  m.in_tmax_i = x.tmax;
}

template <class V, class F, Rounding R>
class IstCosim {
 public:
  IstCosim(std::string name, int stages, uint64_t seed)
      : name_(std::move(name)), stages_(stages), stim_(seed), rng_(seed ^ 0x9e3779b97f4a7c15ull),
        dut_(seed) {}

  // Streams `count` tests with the margin registers mg; returns the number checked. full: no gaps,
  // no back-pressure.
  uint64_t run(const char* set, uint64_t count, bool full, const hls::Margins& mg) {
    using A = hls::Arith<F, R>;
    struct Item {
      IstIn x;
      IstRes expected;
    };
    const StreamSpec spec{name_, count, full, uint64_t(sc::kIstLevels) * stages_, "10*STAGES",
                          2000u + 64u * uint64_t(stages_), 1};
    std::array<uint64_t, 5> by_exit{};
    uint64_t mismatches = 0;
    V& m = *dut_;
    m.eps_i = mg.eps;  // per-frame registers: static while the run streams
    m.one_eps_i = mg.one_eps;
    const StreamStats st = stream(
        dut_, spec, [&] { return stim_.raw(); }, rng_,
        [&](uint64_t) {
          Item it;
          it.x = stim_.next();
          const hls::IstOut e = hls::ist_wald<A>(it.x.k, it.x.c, it.x.o, it.x.d, it.x.tmin, it.x.tmax, mg);
          it.expected = IstRes{uint32_t(e.exit), e.t, e.den};
          drive<V, F>(m, it.x);
          return it;
        },
        [&] {  // junk inputs
          IstIn junk;
          junk.k = uint32_t(rng_() & 3u);
          for (uint32_t& c : junk.c) c = uint32_t(rng_()) & F::mask;
          junk.tmax = uint32_t(rng_()) & F::mask;
          drive<V, F>(m, junk);
        },
        [&](const Item& it, uint16_t seq, uint64_t cycle) {
          const IstRes got{uint32_t(m.out_exit_o), uint32_t(m.out_t_o), uint32_t(m.out_den_o)};
          if (it.expected.exit < 5) ++by_exit[it.expected.exit];
          if (!(got == it.expected)) {
            ++mismatches;
            ADD_FAILURE() << mismatch(name_ + " " + set, seq, cycle, describe<F>(it.x),
                                      describe<F>(it.expected), describe<F>(got));
          }
        },
        [&] { return mismatches >= 5; });
    std::printf("ISTSUM %s %s eps=%g vectors=%" PRIu64 " mismatches=%" PRIu64 " hit=%" PRIu64
                " distance=%" PRIu64 " beta=%" PRIu64 " gamma=%" PRIu64 " sum=%" PRIu64
                " cycles=%" PRIu64 " latency=%" PRIu64 "..%" PRIu64 "\n",
                name_.c_str(), set, A::to_double(mg.eps), st.checked, mismatches, by_exit[0], by_exit[1], by_exit[2],
                by_exit[3], by_exit[4], st.cycles, st.min_lat, st.max_lat);
    EXPECT_GT(st.checked, 0u) << name_ << " " << set << ": no vectors checked";
    EXPECT_EQ(st.checked, count) << name_ << " " << set << ": not every test came back";
    last_by_exit_ = by_exit;
    return st.checked;
  }

  const std::array<uint64_t, 5>& by_exit() const { return last_by_exit_; }

 private:
  std::string name_;
  int stages_;
  Stimulus<F, R> stim_;
  std::mt19937_64 rng_;
  Dut<V> dut_;
  std::array<uint64_t, 5> last_by_exit_{};
};

template <class V, class F, Rounding R>
void run_variant(const std::string& name, int stages) {
  using A = hls::Arith<F, R>;
  IstCosim<V, F, R> sim(name, stages, fptest::seed_for("rtl.ist." + name));
  sim.run("fullrate", 4096, true, hls::margins_none<A>());
  sim.run("fullrate-margin", 4096, true, hls::make_margins<A>(0.008, 0));
  // The random tests in 8 runs, each with its own margin registers.
  std::mt19937_64 rng(fptest::seed_for("rtl.ist.margins." + name));
  const uint64_t n = ist_count();
  uint64_t checked = 0;
  std::array<uint64_t, 5> by_exit{};
  for (int k = 0; k < 8; ++k) {
    double eps = 0;
    if (k == 1) eps = 0.008;
    if (k == 2) eps = std::ldexp(1.0, -12);
    if (k == 3) eps = 0.008 * (0.9 + 0.2 * double(rng() % 1000) / 1000);
    if (k >= 4) eps = 0.05 * double(rng() % 100000) / 100000;
    const uint64_t part = n / 8 + (k == 7 ? n % 8 : 0);
    hls::Margins mg = hls::make_margins<A>(eps, 0);
    if (k == 7) mg = hls::Margins{uint32_t(rng()) & F::mask, uint32_t(rng()) & F::mask, 0};  // any bits
    checked += sim.run("random", part, false, mg);
    for (int e = 0; e < 5; ++e) by_exit[size_t(e)] += sim.by_exit()[size_t(e)];
  }
  ASSERT_EQ(checked, n);
  static const char* kNames[] = {"hit", "distance", "beta", "gamma", "sum"};
  for (int e = 0; e < 5; ++e)
    EXPECT_GE(by_exit[size_t(e)], n / 50)
        << name << ": exit code " << e << " (" << kNames[e] << ") exercised too rarely";
}

#define RAYCORE_RTL_IST_VARIANT(prefix, module, fmt, mode, stages)                   \
  TEST(RtlIst, prefix) {                                                      \
    run_variant<prefix, hls::fmt, Rounding::mode>(#fmt "_" #mode "_s" #stages, \
                                                  stages);                    \
  }
#include "rtl_ist_variants.h"
#undef RAYCORE_RTL_IST_VARIANT

}  // namespace
}  // namespace raycore::rtltest
