// tb/rtl/test_rtl_ist_watertight.cpp - co-simulation of rtl/units/ist_watertight.v (the pipelined
// watertight test) against hls::ist_watertight (hls/ist.h), bit for bit: exit code, t, its key, den
// and the tag, in order.
//
// One test per Verilated variant (format, rounding, STAGES), listed once in rtl/CMakeLists.txt
// (RAYCORE_RTL_IST_WATERTIGHT_VARIANTS). Each streams, through the valid/ready handshake:
//   1. fullrate: 4096 tests with no stalls (one test per cycle, latency == 18*STAGES),
//   2. random: RAYCORE_RTL_IST_N / 4 tests (default 125,000) with random input gaps and output
//      back-pressure.
// Stimulus: tb/rtl/stimulus.h's, with watertight records (hls::make_wald(.., IstKind::watertight):
// the plane and the vertices of random, near-degenerate and degenerate triangles, rays aimed at
// points inside, outside, on edges and vertices, tmin/tmax around the hit) and 10 % random bit
// patterns; tmax as a key (the stimulus's F tmax widened, half of them with random extension bits
// below: a best hit's key); the hit, distance, edge (beta) and det (sum) exits must each reach 1 % of
// the vectors.
#include <gtest/gtest.h>
#include <verilated.h>

#include <array>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>

#include "hls/fp.h"
#include "hls/ist.h"
#include "hls/wald.h"
#include "systemc/vl_bits.h"
#include "tb/fp/fp_check.h"
#include "tb/rtl/rtl_cosim.h"
#include "tb/rtl/stimulus.h"

#include "rtl_ist_watertight_models.h"

namespace raycore::rtltest {
namespace {

using hls::Rounding;

constexpr uint64_t kLevels = 18;  // latency = 18 * STAGES (systemc/config.h kIstWatertightLevels)

struct Res {
  uint32_t exit = 0, t = 0, den = 0, tk = 0;
  bool operator==(const Res& x) const { return exit == x.exit && t == x.t && den == x.den && tk == x.tk; }
};

template <class F>
std::string describe(const IstIn& x) {
  std::ostringstream s;
  s << "k=" << x.k << " c=[";
  for (int i = 0; i < 12; ++i) s << (i ? " " : "") << fptest::show<F>(x.c[i]);
  s << "] o=[" << fptest::show<F>(x.o[0]) << " " << fptest::show<F>(x.o[1]) << " " << fptest::show<F>(x.o[2])
    << "] d=[" << fptest::show<F>(x.d[0]) << " " << fptest::show<F>(x.d[1]) << " " << fptest::show<F>(x.d[2])
    << "] tmin=" << fptest::show<F>(x.tmin) << " tmax key=" << fptest::show<hls::KeyFormat<F>>(x.tmax);
  return s.str();
}
template <class F>
std::string describe(const Res& r) {
  return "exit=" + std::to_string(r.exit) + " t=" + fptest::show<F>(r.t) + " key=" + fptest::show<hls::KeyFormat<F>>(r.tk) +
         " den=" + fptest::show<F>(r.den);
}

// A {z, y, x} port of three W-bit fields.
template <class F, class P>
void set3(P& port, const uint32_t* v) {
  for (unsigned i = 0; i < 3; ++i) sc::vl::set_bits(port, i * unsigned(F::width), unsigned(F::width), v[i]);
}

template <class V, class F>
void drive(V& m, const IstIn& x) {
  m.in_k_i = uint8_t(x.k & 3u);
  m.in_nu_i = x.c[hls::kNU];
  m.in_nv_i = x.c[hls::kNV];
  m.in_nd_i = x.c[hls::kND];
  set3<F>(m.in_va_i, x.c + 3);
  set3<F>(m.in_vb_i, x.c + 6);
  set3<F>(m.in_vc_i, x.c + 9);
  set3<F>(m.in_o_i, x.o);
  set3<F>(m.in_d_i, x.d);
  m.in_tmin_i = x.tmin;
  m.in_tmax_i = x.tmax;
}

template <class V, class F, Rounding R>
void run_variant(const std::string& name, int stages) {
  using A = hls::Arith<F, R>;
  const uint64_t seed = fptest::seed_for("rtl.ist_watertight." + name);
  Stimulus<F, R> stim(seed, hls::IstKind::watertight);
  std::mt19937_64 rng(seed ^ 0x9e3779b97f4a7c15ull);
  Dut<V> dut(seed);
  std::array<uint64_t, 5> by_exit{};
  uint64_t total = 0;
  for (const bool full : {true, false}) {
    const uint64_t count = full ? 4096 : fptest::env_count("RAYCORE_RTL_IST_N", 500000) / 4;
    struct Item {
      IstIn x;
      Res expected;
    };
    const StreamSpec spec{name, count, full, kLevels * uint64_t(stages), "18*STAGES",
                          2000u + 64u * uint64_t(stages), 1};
    uint64_t mismatches = 0;
    V& m = *dut;
    const StreamStats st = stream(
        dut, spec, [&] { return stim.raw(); }, rng,
        [&](uint64_t) {
          Item it;
          it.x = stim.next();
          it.x.tmax = hls::t_key<F>(it.x.tmax);  // the interval's end is a key
          constexpr uint32_t ext = (1u << (hls::KeyFormat<F>::man_bits - F::man_bits)) - 1u;
          if ((rng() & 1u) && (it.x.tmax & hls::KeyFormat<F>::exp_mask)) it.x.tmax |= uint32_t(rng()) & ext;
          const hls::IstOut e = hls::ist_watertight<A>(it.x.k, it.x.c, it.x.o, it.x.d, it.x.tmin, it.x.tmax);
          it.expected = Res{uint32_t(e.exit), e.t, e.den, e.tk};
          drive<V, F>(m, it.x);
          return it;
        },
        [&] {  // junk inputs
          IstIn junk;
          junk.k = uint32_t(rng() & 3u);
          for (uint32_t& c : junk.c) c = uint32_t(rng()) & F::mask;
          junk.tmax = uint32_t(rng()) & hls::KeyFormat<F>::mask;
          drive<V, F>(m, junk);
        },
        [&](const Item& it, uint16_t seq, uint64_t cycle) {
          const Res got{uint32_t(m.out_exit_o), uint32_t(m.out_t_o), uint32_t(m.out_den_o), uint32_t(m.out_tk_o)};
          if (it.expected.exit < 5) ++by_exit[it.expected.exit];
          if (!(got == it.expected)) {
            ++mismatches;
            ADD_FAILURE() << mismatch(name + (full ? " fullrate" : " random"), seq, cycle, describe<F>(it.x),
                                      describe<F>(it.expected), describe<F>(got));
          }
        },
        [&] { return mismatches >= 5; });
    std::printf("ISTWTSUM %s %s vectors=%" PRIu64 " mismatches=%" PRIu64 " cycles=%" PRIu64
                " latency=%" PRIu64 "..%" PRIu64 "\n",
                name.c_str(), full ? "fullrate" : "random", st.checked, mismatches, st.cycles, st.min_lat,
                st.max_lat);
    EXPECT_EQ(st.checked, count) << name << ": not every test came back";
    total += st.checked;
  }
  static const char* kNames[] = {"hit", "distance", "beta (edges)", "gamma (unused)", "sum (det = 0)"};
  for (int e : {0, 1, 2, 4})
    EXPECT_GE(by_exit[size_t(e)], total / 100)
        << name << ": exit code " << e << " (" << kNames[e] << ") exercised too rarely";
  EXPECT_EQ(by_exit[3], 0u) << name << ": the watertight test has no gamma exit";
}

#define RAYCORE_RTL_IST_WATERTIGHT_VARIANT(prefix, module, fmt, mode, stages)               \
  TEST(RtlIstWatertight, prefix) {                                                          \
    run_variant<prefix, hls::fmt, Rounding::mode>(#fmt "_" #mode "_s" #stages, stages);     \
  }
#include "rtl_ist_watertight_variants.h"
#undef RAYCORE_RTL_IST_WATERTIGHT_VARIANT

}  // namespace
}  // namespace raycore::rtltest
