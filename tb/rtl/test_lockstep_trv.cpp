// tb/rtl/test_lockstep_trv.cpp - lockstep co-simulation of the traversal datapath: the Verilated
// --sc model of rtl/units/trv.v and its SystemC twin systemc/pins/trv.h, side by side in one
// SystemC simulation, driven by the same stimulus.
//
// One test per --sc variant (rtl/units/trv.cmake, rtl_trv_sc_variants.h); one simulation per
// process (toolchain.md pitfall 8: gtest_discover_tests runs each test alone). Each cycle both
// models see the same inputs: the directed edge cases of tb/rtl/trv_stim.h, then random split and
// clip steps (RAYCORE_LOCKSTEP_TRV_N, default 10^5 in all), with random input gaps and bursty
// random out_ready back-pressure; an item is held until accepted. Checked every cycle: in_ready_o
// and out_valid_o equal; every output transaction (out_valid_o && out_ready_i) equal in every
// defined field and the tag, leaving in the same cycle, and equal to hls/ (trv_expect). The first
// differing transaction is printed with its inputs and the run stops. Prints LOCKSTEP lines with
// the simulated cycles per second. The interval widening register widen_i (hls/margins.h, the same
// value into both) is 0 for the directed items, then a new random N in 0..8 every count/8 items,
// changed only when the pipeline has drained (it is a per-frame register).
#include <gtest/gtest.h>
#include <systemc>

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "hls/fp.h"
#include "systemc/pins/trv.h"
#include "tb/fp/fp_check.h"
#include "tb/rtl/trv_stim.h"

#include "rtl_trv_sc_models.h"

namespace raycore::rtltest {
namespace {

using hls::Rounding;
using sc::pins::TrvPortT;
using sc::pins::TrvTwin;

bool g_simulated = false;  // one SystemC simulation per process (toolchain.md pitfall 8)

uint64_t lockstep_count() { return fptest::env_count("RAYCORE_LOCKSTEP_TRV_N", 100000); }

// The harness: one clock, one reset, the twin and the RTL each bound to its own port (signal set)
// with identical inputs; one thread drives, samples and compares.
template <class V, class F, Rounding R>
class Lockstep : public sc_core::sc_module {
  using A = hls::Arith<F, R>;

 public:
  SC_HAS_PROCESS(Lockstep);
  Lockstep(sc_core::sc_module_name name, std::string variant, unsigned stages, uint64_t count)
      : sc_core::sc_module(name),
        variant_(std::move(variant)),
        stages_(stages),
        count_(count),
        stim_(fptest::seed_for("lockstep.trv." + variant_)),
        rng_(fptest::seed_for("lockstep.trv.traffic." + variant_)),
        twin_("twin", "twin", clk_, rst_n_, stages),
        rtl_("rtl", "rtl", clk_, rst_n_) {
    SC_THREAD(run);
  }

  uint64_t cycles = 0, checked = 0, mismatches = 0, directed = 0;
  std::string first_diff;

 private:
  struct Pending {
    TrvIn x;
    TrvOut expected;
    uint32_t tag = 0;
  };

  // The same input (tag = the harness's) into both; a bubble carries the junk with in_valid low.
  void both(TrvIn x, uint32_t tag, bool valid) {
    x.tag = tag;
    sc::pins::TrvPort* const ports[] = {&twin_, &rtl_};
    for (sc::pins::TrvPort* p : ports) {
      p->drive(x);
      if (!valid) p->idle();
    }
  }
  void half(double ns) { wait(sc_core::sc_time(ns, sc_core::SC_NS)); }
  void edge() {
    clk_.write(true);
    half(5);
    clk_.write(false);
  }

  void fail(const std::string& what) {
    if (mismatches++ == 0) first_diff = what;
  }

  void run() {
    rst_n_.write(false);
    twin_.idle();
    rtl_.idle();
    half(5);
    edge();
    half(5);
    edge();
    rst_n_.write(true);
    const uint64_t nd = TrvStim<F, R>::directed_count();
    std::deque<Pending> inflight;
    uint64_t issued = 0, idle = 0;
    bool holding = false;
    Pending cur;
    uint32_t p_gap = 0, p_stall = 0;
    uint32_t widen = 0;
    uint64_t next_change = nd;  // the directed items run without widening
    const uint64_t chunk = std::max<uint64_t>(1, count_ / 8);
    twin_.config(widen);
    rtl_.config(widen);
    while ((issued < count_ || !inflight.empty()) && mismatches == 0) {
      if ((cycles & 255u) == 0) {
        static constexpr uint32_t kRates[] = {0, 1, 4, 7};  // in 1/8
        p_gap = kRates[rng_() & 3u];
        p_stall = kRates[(rng_() >> 2) & 3u];
      }
      // Inputs (after the falling edge): a new item, the held one, or a bubble with junk.
      if (!holding && issued >= next_change && inflight.empty()) {  // drained: a new N
        widen = uint32_t(rng_() % 9);
        twin_.config(widen);
        rtl_.config(widen);
        next_change += chunk;
      }
      if (!holding) {
        if (issued < count_ && issued < next_change && (rng_() & 7u) >= p_gap) {
          cur.x = issued < nd ? stim_.directed(issued) : stim_.random();
          cur.tag = uint32_t(issued & 0xffffu);
          cur.expected = trv_expect<A>(cur.x, widen);
          holding = true;
          both(cur.x, cur.tag, true);
        } else {
          both(stim_.random(), uint32_t(rng_() & 0xffffu), false);
        }
      }
      const bool ready = (rng_() & 7u) >= p_stall;
      twin_.out_ready(ready);
      rtl_.out_ready(ready);
      half(2.5);  // combinational outputs settle
      // Handshake signals must agree every cycle.
      const bool tw_in_ready = twin_.in_ready(), rt_in_ready = rtl_.in_ready();
      const bool tw_valid = twin_.out_valid(), rt_valid = rtl_.out_valid();
      if (tw_in_ready != rt_in_ready || tw_valid != rt_valid) {
        std::ostringstream s;
        s << "cycle " << cycles << ": handshake differs: twin in_ready=" << tw_in_ready
          << " out_valid=" << tw_valid << ", rtl in_ready=" << rt_in_ready
          << " out_valid=" << rt_valid;
        fail(s.str());
        break;
      }
      if (holding && rt_in_ready) {
        inflight.push_back(cur);
        ++issued;
        if (issued <= nd) ++directed;
        holding = false;
      }
      if (rt_valid && ready) {
        idle = 0;
        const TrvOut tw = twin_.out(), rt = rtl_.out();
        if (inflight.empty()) {
          fail("cycle " + std::to_string(cycles) + ": output transaction with nothing in flight");
          break;
        }
        const Pending p = inflight.front();
        inflight.pop_front();
        ++checked;
        const bool ok_pair = same(tw, rt) && tw.tag == rt.tag;
        const bool ok_ref = same(rt, p.expected) && rt.tag == p.tag;
        if (!ok_pair || !ok_ref) {
          std::ostringstream s;
          s << variant_ << ": first differing output transaction #" << (checked - 1)
            << " (cycle " << cycles << ", item tag " << p.tag << ")\n  inputs: "
            << describe<F>(p.x) << "\n  twin:   " << describe<F>(tw) << " tag=" << tw.tag
            << "\n  rtl:    " << describe<F>(rt) << " tag=" << rt.tag
            << "\n  hls:    " << describe<F>(p.expected) << " tag=" << p.tag;
          fail(s.str());
          break;
        }
      } else if (++idle > 2000u) {
        fail("no output for 2000 cycles with " + std::to_string(inflight.size()) +
             " in flight (deadlock)");
        break;
      }
      half(2.5);
      edge();  // rising edge, 5 ns high, falling edge
      ++cycles;
    }
    sc_core::sc_stop();
  }

  std::string variant_;
  unsigned stages_;
  uint64_t count_;
  TrvStim<F, R> stim_;
  std::mt19937_64 rng_;
  sc_core::sc_signal<bool> clk_{"clk"}, rst_n_{"rst_n"};
  TrvPortT<TrvTwin<A>> twin_;
  TrvPortT<V> rtl_;
};

template <class V, class F, Rounding R>
void run_variant(const std::string& name, unsigned stages) {
  if (g_simulated)
    GTEST_SKIP() << "one SystemC simulation per process: run one test per process "
                    "(ctest does; or --gtest_filter)";
  g_simulated = true;
  const uint64_t n = lockstep_count();
  auto* ls = new Lockstep<V, F, R>("lockstep", name, stages, n);  // owned by the simulation
  const auto t0 = std::chrono::steady_clock::now();
  sc_core::sc_start();
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("LOCKSTEP trv %s items=%" PRIu64 " directed=%" PRIu64 " cycles=%" PRIu64
              " mismatches=%" PRIu64 " seconds=%.2f cycles_per_s=%.0f\n",
              name.c_str(), ls->checked, ls->directed, ls->cycles, ls->mismatches, sec,
              sec > 0 ? double(ls->cycles) / sec : 0.0);
  EXPECT_EQ(ls->mismatches, 0u) << ls->first_diff;
  EXPECT_EQ(ls->checked, n) << name << ": not every item came back";
}

#define RAYCORE_RTL_TRV_SC_VARIANT(prefix, module, fmt, mode, stages)            \
  TEST(LockstepTrv, prefix) {                                                    \
    run_variant<prefix, hls::fmt, Rounding::mode>(#fmt "_" #mode "_s" #stages, stages); \
  }
#include "rtl_trv_sc_variants.h"
#undef RAYCORE_RTL_TRV_SC_VARIANT

}  // namespace
}  // namespace raycore::rtltest

int sc_main(int argc, char* argv[]) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
