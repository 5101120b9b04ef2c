// tb/rtl/rtl_cosim.h - lockstep co-simulation of Verilated rtl/ modules (Verilator --cc, clocked
// directly from C++) against their C++ references.
//
// Dut<V> owns a Verilated model and its context (clock, reset). stream() drives one through its
// valid/ready handshake and checks every result in order: the loop every co-simulation test of a
// unit shares (test_rtl_ist, test_rtl_trv, test_rtl_vtu, and Cosim below).
//
// Cosim<V, Op> drives the Verilated model V (Verilator --cc, clocked directly from C++) with a
// stream of operands, through the module's valid/ready handshake, with random input gaps and
// random output back-pressure, and compares every result bit for bit, in order, with Op's
// reference (the hls/fp.h function). A 16-bit sequence number rides through the module's tag and
// is checked too, so a lost, duplicated or reordered result is caught. Op describes one module:
//
//   struct Op {
//     using Res = Result<F>;                 // what is compared
//     static const char* name();             // "fp_add"
//     template <class V> static void drive(V&, const Operands&);
//     template <class V> static Res read(const V&);
//     static Res expect(const Operands&);    // from hls/fp.h
//     static std::string describe(const Operands&);
//   };
//
// Results are counted with fptest::Tally (summary line `FPSUM <fmt> rtl.<module> <mode>.s<N>
// <set> vectors=... mismatches=...`; zero vectors or any mismatch fails the test; the first 10
// mismatches print their operands, the expected and the received result).
#pragma once

#include <gtest/gtest.h>
#include <verilated.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <type_traits>
#include <utility>

#include "hls/fp.h"
#include "tb/fp/fp_check.h"

namespace raycore::rtltest {

using hls::Rounding;

struct Operands {
  uint32_t a = 0, b = 0, c = 0;
  bool sub = false;
};
// Junk operands for the cycles without a valid input (any bits of the format).
template <class F, class Rng>
void randomize(Operands& x, Rng& rng) {
  x = {uint32_t(rng()) & F::mask, uint32_t(rng()) & F::mask, uint32_t(rng()) & F::mask,
       (rng() & 1u) != 0};
}
// An operator's operand set: Operands, or the adapter's own `X` (e.g. fp_sop's six operands, with a
// randomize() overload of its own).
template <class Op, class = void>
struct OperandsOf {
  using type = Operands;
};
template <class Op>
struct OperandsOf<Op, std::void_t<typename Op::X>> {
  using type = typename Op::X;
};

// Up to four result fields (a number, or lt/eq/min/max); `names` labels them in messages.
template <class F>
struct Result {
  std::array<uint32_t, 4> v{};
  int n = 1;
  bool operator==(const Result& o) const { return n == o.n && v == o.v; }
  bool operator!=(const Result& o) const { return !(*this == o); }
  static Result one(uint32_t x) {
    Result r;
    r.v[0] = x;
    return r;
  }
  static Result cmp(bool lt, bool eq, uint32_t mn, uint32_t mx) {
    Result r;
    r.n = 4;
    r.v = {uint32_t(lt), uint32_t(eq), mn, mx};
    return r;
  }
  std::string str() const {
    if (n == 1) return fptest::show<F>(v[0]);
    return "lt=" + std::to_string(v[0]) + " eq=" + std::to_string(v[1]) +
           " min=" + fptest::show<F>(v[2]) + " max=" + fptest::show<F>(v[3]);
  }
};

// A Verilated --cc model V (ports clk_i, rst_ni, in_valid_i, out_ready_i) with its own context.
template <class V>
class Dut {
 public:
  explicit Dut(uint64_t seed) : ctx_(std::make_unique<VerilatedContext>()) {
    // Registers without reset (the data registers) start with random bits (models are built with
    // --x-initial unique): a result must never depend on them.
    ctx_->randReset(2);
    ctx_->randSeed(int(seed & 0x7fffffffu) | 1);
    m_ = std::make_unique<V>(ctx_.get(), "top");
  }
  V& operator*() { return *m_; }
  V* operator->() { return m_.get(); }

  // Reset: valid bits cleared, the pipeline is empty.
  void reset() {
    m_->clk_i = 0;
    m_->rst_ni = 1;
    m_->in_valid_i = 0;
    m_->out_ready_i = 0;
    m_->eval();
    m_->rst_ni = 0;
    m_->eval();
    for (int i = 0; i < 2; ++i) clock();
    m_->rst_ni = 1;
    m_->eval();
  }
  void clock() {
    m_->clk_i = 1;
    m_->eval();
    m_->clk_i = 0;
    m_->eval();
  }

 private:
  std::unique_ptr<VerilatedContext> ctx_;  // outlives the model (declared first)
  std::unique_ptr<V> m_;
};

// One stream through a unit: stream() below.
struct StreamSpec {
  std::string name;            // who is streaming, for messages
  uint64_t count = 0;          // items to send
  bool full = false;           // full rate: no input gaps, no back-pressure
  uint64_t latency = 0;        // the unit's latency in cycles
  std::string latency_name;    // how messages call it ("STAGES", "10*STAGES")
  uint64_t idle_limit = 1000;  // cycles without a result in flight before a deadlock is reported
  uint64_t max_errors = 10;    // protocol errors before the stream stops
  bool never_stall = false;    // no back-pressure (a unit built FREE: fp_delay), input gaps kept
};
// The failure message of a result that differs from the reference.
inline std::string mismatch(const std::string& where, uint64_t seq, uint64_t cycle,
                            const std::string& in, const std::string& expected,
                            const std::string& got) {
  return where + ": mismatch at item " + std::to_string(seq) + " (cycle " + std::to_string(cycle) +
         ")\n  inputs:   " + in + "\n  expected: " + expected + "\n  got:      " + got;
}
struct StreamStats {
  uint64_t issued = 0, checked = 0, cycles = 0, errors = 0;
  uint64_t min_lat = ~uint64_t(0), max_lat = 0;
};

// Streams spec.count items through dut's valid/ready handshake and checks each result in order.
// A 16-bit sequence number rides in in_tag_i / out_tag_o (a lost, duplicated or reordered result
// is a protocol error). Unless spec.full, the input has random gaps and the output random
// back-pressure, bursty: new rates (two draws of rate_bits()) every 256 cycles, each decision one
// draw of coin(), which also gives the junk tags.
//   issue(k) -> Item   the k-th item: drives the data inputs, returns what retire() needs
//   bubble()           drives junk on the data inputs (a cycle without valid: must be ignored)
//   retire(item, seq, cycle)  reads the outputs of item number seq and compares them
//   stop() -> bool     true stops the stream early (e.g. too many mismatches)
// Checks the latency (>= spec.latency; at full rate exactly that and one item per cycle).
template <class V, class RateBits, class Coin, class Issue, class Bubble, class Retire, class Stop>
StreamStats stream(Dut<V>& dut, const StreamSpec& spec, RateBits&& rate_bits, Coin&& coin,
                   Issue&& issue, Bubble&& bubble, Retire&& retire, Stop&& stop) {
  using Item = decltype(issue(uint64_t(0)));
  using Tag = std::remove_reference_t<decltype(dut->in_tag_i)>;
  struct Pending {
    Item item;
    uint16_t tag = 0;
    uint64_t cycle = 0;
  };
  V& m = *dut;
  const bool full = spec.full;
  dut.reset();  // an empty pipeline, whatever an earlier (stopped) run left behind
  StreamStats st;
  std::deque<Pending> inflight;
  uint64_t idle = 0;
  bool holding = false;  // inputs stay put while valid is high and not yet accepted
  Pending cur{};
  uint32_t p_gap = 0, p_stall = 0;  // in 1/8
  while ((st.issued < spec.count || !inflight.empty()) && !stop() && st.errors < spec.max_errors) {
    if (!full && (st.cycles & 255u) == 0) {
      static constexpr uint32_t kRates[] = {0, 1, 4, 7};
      p_gap = kRates[rate_bits() & 3u];
      p_stall = kRates[(rate_bits() >> 2) & 3u];
    }
    if (!holding) {
      if (st.issued < spec.count && (full || (coin() & 7u) >= p_gap)) {
        cur.item = issue(st.issued);
        cur.tag = uint16_t(st.issued);
        holding = true;
        m.in_tag_i = static_cast<Tag>(cur.tag);
        m.in_valid_i = 1;
      } else {
        bubble();
        m.in_tag_i = static_cast<Tag>(uint16_t(coin()));
        m.in_valid_i = 0;
      }
    }
    m.out_ready_i = (full || spec.never_stall || (coin() & 7u) >= p_stall) ? 1 : 0;
    m.eval();
    if (m.in_valid_i && m.in_ready_o) {
      cur.cycle = st.cycles;
      inflight.push_back(cur);
      ++st.issued;
      holding = false;
    } else if (full && holding) {
      ++st.errors;
      ADD_FAILURE() << spec.name << ": in_ready_o low at cycle " << st.cycles
                    << " with the output always ready (not one item per cycle)";
    }
    if (m.out_valid_o && m.out_ready_i) {
      idle = 0;
      if (inflight.empty()) {
        ++st.errors;
        ADD_FAILURE() << spec.name << ": out_valid_o at cycle " << st.cycles
                      << " with nothing in flight";
      } else {
        const Pending p = inflight.front();
        inflight.pop_front();
        const uint64_t lat = st.cycles - p.cycle;
        st.min_lat = std::min(st.min_lat, lat);
        st.max_lat = std::max(st.max_lat, lat);
        const uint16_t tag = uint16_t(m.out_tag_o);
        if (tag != p.tag) {
          ++st.errors;
          ADD_FAILURE() << spec.name << ": result out of order at cycle " << st.cycles << ": tag "
                        << tag << ", expected " << p.tag;
        }
        ++st.checked;
        retire(p.item, p.tag, st.cycles);
      }
    } else if (++idle > spec.idle_limit) {
      ADD_FAILURE() << spec.name << ": no result for " << idle << " cycles with "
                    << inflight.size() << " in flight (deadlock)";
      break;
    }
    dut.clock();
    ++st.cycles;
  }
  if (st.issued > 0) {
    EXPECT_GE(st.min_lat, spec.latency) << spec.name << ": latency below " << spec.latency_name;
    if (full) {
      EXPECT_EQ(st.max_lat, spec.latency)
          << spec.name << ": full-rate latency != " << spec.latency_name;
      EXPECT_EQ(st.cycles, spec.count + spec.latency)
          << spec.name << ": full rate is not one item per cycle";
    }
  }
  return st;
}

// How a stream is driven: full rate (input valid every cycle, output always ready: checks one
// operation per cycle and latency == STAGES) or with random stalls on both sides.
enum class Traffic { full_rate, stalls };

template <class V, class Op>
class Cosim {
 public:
  using Res = typename Op::Res;
  using X = typename OperandsOf<Op>::type;

  Cosim(std::string fmt, std::string mode, int stages, uint64_t seed)
      : fmt_(std::move(fmt)), mode_(std::move(mode)), stages_(stages), rng_(seed), dut_(seed) {
    dut_.reset();
  }

  // Streams `count` operand sets (next(k) gives the k-th) through the module and checks them all.
  // Returns the number of vectors checked.
  uint64_t run(const std::string& set, uint64_t count,
               const std::function<X(uint64_t)>& next, Traffic traffic) {
    fptest::Tally tally(fmt_, std::string("rtl.") + Op::name(), mode_ + ".s" + std::to_string(stages_),
                        set);
    const StreamSpec spec{
        std::string(Op::name()) + " " + fmt_ + " " + mode_ + " S=" + std::to_string(stages_),
        count, traffic == Traffic::full_rate, uint64_t(stages_), "STAGES",
        1000u + 64u * uint64_t(stages_)};
    struct Item {
      X x;
      Res expected;
    };
    V& m = *dut_;
    const StreamStats st = stream(
        dut_, spec, rng_, rng_,
        [&](uint64_t k) {
          Item it{next(k), {}};
          it.expected = Op::expect(it.x);
          Op::drive(m, it.x);
          return it;
        },
        [&] {  // junk operands
          X junk;
          randomize<typename Op::Fmt>(junk, rng_);
          Op::drive(m, junk);
        },
        [&](const Item& it, uint16_t, uint64_t) {
          tally.check(Op::read(m), it.expected, [&] { return Op::describe(it.x); });
        },
        [&] { return tally.stopped(); });
    tally.note("cycles=" + std::to_string(st.cycles) + " latency=" + std::to_string(st.min_lat) +
               ".." + std::to_string(st.max_lat));
    tally.finish();
    return tally.vectors();
  }

 private:
  std::string fmt_, mode_;
  int stages_;
  std::mt19937_64 rng_;
  Dut<V> dut_;
};

}  // namespace raycore::rtltest
