// tb/rtl/rtl_cosim.h - lockstep co-simulation of a Verilated rtl/fp module against hls/fp.h.
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

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <random>
#include <string>

#include "hls/fp.h"
#include "tb/fp/fp_check.h"

namespace raycore::rtltest {

using hls::Rounding;

struct Operands {
  uint32_t a = 0, b = 0, c = 0;
  bool sub = false;
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

// How a stream is driven: full rate (input valid every cycle, output always ready: checks one
// operation per cycle and latency == STAGES) or with random stalls on both sides.
enum class Traffic { full_rate, stalls };

template <class V, class Op>
class Cosim {
 public:
  using Res = typename Op::Res;

  Cosim(std::string fmt, std::string mode, int stages, uint64_t seed)
      : fmt_(std::move(fmt)), mode_(std::move(mode)), stages_(stages), rng_(seed) {
    ctx_ = std::make_unique<VerilatedContext>();
    // Registers without reset (the data registers) start with random bits (models are built with
    // --x-initial unique): a result must never depend on them.
    ctx_->randReset(2);
    ctx_->randSeed(int(seed & 0x7fffffffu) | 1);
    m_ = std::make_unique<V>(ctx_.get(), "top");
    setup();
  }

  // Reset: valid bits cleared, the pipeline is empty.
  void setup() {
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

  // Streams `count` operand sets (next(k) gives the k-th) through the module and checks them all.
  // Returns the number of vectors checked.
  uint64_t run(const std::string& set, uint64_t count,
               const std::function<Operands(uint64_t)>& next, Traffic traffic) {
    fptest::Tally tally(fmt_, std::string("rtl.") + Op::name(), mode_ + ".s" + std::to_string(stages_),
                        set);
    const bool full = traffic == Traffic::full_rate;
    setup();  // an empty pipeline, whatever an earlier (stopped) run left behind
    std::deque<Pending> inflight;
    uint64_t issued = 0, cycles = 0, idle = 0, bad_protocol = 0;
    uint64_t min_lat = ~uint64_t(0), max_lat = 0;
    bool holding = false;
    Pending cur;
    uint32_t p_gap = 0, p_stall = 0;  // in 1/8
    while ((issued < count || !inflight.empty()) && !tally.stopped() && bad_protocol < 10) {
      if (!full && (cycles & 255u) == 0) {  // bursty: new stall rates every 256 cycles
        static constexpr uint32_t kRates[] = {0, 1, 4, 7};
        p_gap = kRates[rng_() & 3u];
        p_stall = kRates[(rng_() >> 2) & 3u];
      }
      // Inputs (clock low). Operands stay put while valid is high and not yet accepted.
      if (!holding) {
        if (issued < count && (full || (rng_() & 7u) >= p_gap)) {
          cur.x = next(issued);
          cur.expected = Op::expect(cur.x);
          cur.tag = uint16_t(issued);
          holding = true;
          Op::drive(*m_, cur.x);
          m_->in_tag_i = cur.tag;
          m_->in_valid_i = 1;
        } else {  // a bubble, with junk on the data inputs (must be ignored)
          Operands junk{uint32_t(rng_()), uint32_t(rng_()), uint32_t(rng_()), (rng_() & 1u) != 0};
          junk.a &= F_mask();
          junk.b &= F_mask();
          junk.c &= F_mask();
          Op::drive(*m_, junk);
          m_->in_tag_i = uint16_t(rng_());
          m_->in_valid_i = 0;
        }
      }
      m_->out_ready_i = (full || (rng_() & 7u) >= p_stall) ? 1 : 0;
      m_->eval();

      const bool in_fire = m_->in_valid_i && m_->in_ready_o;
      if (in_fire) {
        cur.cycle = cycles;
        inflight.push_back(cur);
        ++issued;
        holding = false;
      } else if (full && holding) {
        ++bad_protocol;
        ADD_FAILURE() << Op::name() << " " << fmt_ << " " << mode_ << " S=" << stages_
                      << ": in_ready_o low at cycle " << cycles
                      << " with the output always ready (not one operation per cycle)";
      }
      if (m_->out_valid_o && m_->out_ready_i) {
        idle = 0;
        if (inflight.empty()) {
          ++bad_protocol;
          ADD_FAILURE() << Op::name() << ": out_valid_o at cycle " << cycles
                        << " with nothing in flight";
        } else {
          const Pending p = inflight.front();
          inflight.pop_front();
          const uint64_t lat = cycles - p.cycle;
          min_lat = std::min(min_lat, lat);
          max_lat = std::max(max_lat, lat);
          const Res got = Op::read(*m_);
          const uint16_t tag = uint16_t(m_->out_tag_o);
          if (tag != p.tag) {
            ++bad_protocol;
            ADD_FAILURE() << Op::name() << ": result out of order at cycle " << cycles
                          << ": tag " << tag << ", expected " << p.tag;
          }
          tally.check(got, p.expected, [&] { return Op::describe(p.x); });
        }
      } else if (++idle > 1000u + 64u * unsigned(stages_)) {
        ADD_FAILURE() << Op::name() << ": no result for " << idle << " cycles with "
                      << inflight.size() << " in flight (deadlock)";
        break;
      }
      clock();
      ++cycles;
    }
    if (issued > 0) {
      EXPECT_GE(min_lat, uint64_t(stages_)) << "latency below STAGES";
      if (full) {
        EXPECT_EQ(max_lat, uint64_t(stages_)) << "full-rate latency != STAGES";
        EXPECT_EQ(cycles, count + uint64_t(stages_)) << "full rate: not one op per cycle";
      }
    }
    tally.note("cycles=" + std::to_string(cycles) + " latency=" + std::to_string(min_lat) + ".." +
               std::to_string(max_lat));
    tally.finish();
    return tally.vectors();
  }

 private:
  struct Pending {
    Operands x;
    Res expected;
    uint16_t tag = 0;
    uint64_t cycle = 0;
  };
  static uint32_t F_mask() { return Op::Fmt::mask; }
  void clock() {
    m_->clk_i = 1;
    m_->eval();
    m_->clk_i = 0;
    m_->eval();
  }

  std::string fmt_, mode_;
  int stages_;
  std::mt19937_64 rng_;
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<V> m_;
};

}  // namespace raycore::rtltest
