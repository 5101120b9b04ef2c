// tb/rtl/test_lockstep_ascache.cpp - lockstep of the AS cache's SystemC twin (systemc/pins/ascache.h,
// i.e. raycore::sc::Ascache behind rtl/units/ascache.v's pins) and its Verilated RTL (--sc), side by
// side in one SystemC simulation, driven by the same stimulus.
//
// One test per line of RAYCORE_RTL_ASCACHE_VARIANTS (rtl/units/ascache.cmake); each runs
// RAYCORE_RTL_ASCACHE_CYCLES (default 1000000) clock cycles (one SystemC simulation per process:
// gtest_discover_tests runs each test alone). The stimulus:
//   - 12 requesters (ray slots, the access tag) each walking a line stream with locality: the
//     next line (1/2), a line another requester used recently (1/4: hits and merges), a line in a
//     window of 4x the cache's lines that drifts (1/5: conflicts, evictions), a random far line;
//     a miss of any kind is retried on the same line 1..8 cycles later, as the cycle model's
//     requesters loop. Issue rate changes every 512 cycles (10 % .. 100 % of cycles);
//   - the memory: req_ready_i random with bursty rates (back-pressure), each accepted request
//     filled after a random 1..64 cycles (sometimes 150), out of order, at most one fill per
//     cycle; the line's bytes are a hash of (line, fill number), so a stale line is caught.
// Every cycle every output of both models is compared: rsp_valid_o and, for a response, hit /
// merge / full / set full / tag and (on a hit) the line; req_valid_o and, for a request, line and tag;
// mshr_busy_o and the counters. The first difference stops the run and prints the cycle, the
// field, both values and the inputs of the last cycles. Also checked against the stimulus's own
// record: a hit's line is the last data filled for that line. At the end the counters (hits,
// misses, merges, mshr_full, set_full, fills) of the twin (Ascache::stats()) and the RTL (cnt_*_o)
// are compared, and each kind of transaction must have occurred (hits, misses, merges, mshr_full,
// requests, fills, LRU evictions; set_full in the small caches). The requesters retry a missed line until it hits, as
// the frame's do, so the pin rule holds (every fill is hit: ascache.v's forward progress). Summary line: `ASCACHESUM <variant> cycles=... accesses=...`.
#include <gtest/gtest.h>
#include <verilated.h>

#include <systemc>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "rtl_ascache_models.h"
#include "systemc/config.h"
#include "systemc/pins/ascache.h"

namespace raycore::rtltest {
namespace {

using sc::CacheConfig;
using sc::pins::AscacheSignals;
using sc::pins::AscacheTwin;

uint64_t cycles_from_env() {
  const char* s = std::getenv("RAYCORE_RTL_ASCACHE_CYCLES");
  if (s == nullptr || *s == '\0') return 1000000;
  return std::strtoull(s, nullptr, 10);
}

uint64_t mix(uint64_t x) {  // splitmix64
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

struct Geometry {
  const char* name;
  unsigned sets, ways, line_bytes, mshrs, hit_latency;
};

struct Counts {
  uint64_t accesses = 0, hits = 0, misses = 0, allocs = 0, merges = 0, full = 0, set_full = 0,
           requests = 0, fills = 0, evictions = 0, backpressure = 0;
};

template <class V, unsigned LB>
class Lockstep : public sc_core::sc_module {
 public:
  using Line = sc_dt::sc_bv<8 * LB>;
  SC_HAS_PROCESS(Lockstep);
  Lockstep(sc_core::sc_module_name name, const Geometry& g, uint64_t cycles)
      : sc_core::sc_module(name), g_(g), cycles_(cycles), twin_("twin", config(g)), rtl_("rtl") {
    sc::pins::bind_ascache(twin_, st_, clk_, rst_n_);
    sc::pins::bind_ascache(rtl_, sr_, clk_, rst_n_);
    SC_THREAD(run);
  }

  static CacheConfig config(const Geometry& g) {
    CacheConfig c;
    c.size_bytes = g.sets * g.ways * g.line_bytes;
    c.ways = g.ways;
    c.line_bytes = g.line_bytes;
    c.mshrs = g.mshrs;
    c.hit_latency = g.hit_latency;
    return c;
  }

  std::string mismatch;  // the first difference, empty if none
  Counts n;
  uint64_t cycles_run = 0;
  const AscacheTwin<LB>& twin() const { return twin_; }
  uint32_t rtl_cnt(int i) const {
    const sc_core::sc_signal<uint32_t>* c[6] = {&sr_.cnt_hits, &sr_.cnt_misses, &sr_.cnt_merges,
                                                &sr_.cnt_full, &sr_.cnt_fills, &sr_.cnt_set_full};
    return c[i]->read();
  }

 private:
  static constexpr unsigned kSlots = 12;

  struct Slot {
    uint32_t line = 0;
    uint64_t next = 0;  // first cycle it may issue
    bool busy = false;  // access in flight
  };
  struct Pending {  // an accepted request, waiting for its fill
    uint64_t due;
    uint32_t tag, line;
  };
  struct InRec {  // the inputs of one cycle (for the mismatch report)
    uint64_t cycle;
    bool acc, fill, ready;
    uint32_t acc_line, acc_tag, fill_tag, fill_line;
  };

  void edge() {
    sc_core::wait(half_);
    clk_.write(true);
    sc_core::wait(half_);
    clk_.write(false);
  }

  uint32_t rnd(uint32_t k) { return uint32_t(rng_() % k); }
  bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(rng_) < p; }

  uint32_t next_line(uint32_t cur) {
    const uint32_t lines = g_.sets * g_.ways;
    const uint32_t r = rnd(100);
    uint32_t l;
    if (r < 50) {
      l = cur + 1;
    } else if (r < 75 && !recent_.empty()) {
      l = recent_[rnd(uint32_t(recent_.size()))];
    } else if (r < 95) {
      l = window_ + rnd(4 * lines);
    } else {
      l = rnd(1u << 20);
    }
    l &= (1u << 26) - 1;
    recent_.push_back(l);
    if (recent_.size() > 16) recent_.pop_front();
    return l;
  }

  void fill_bytes(uint32_t line, uint64_t version, uint8_t* p) const {
    for (unsigned j = 0; j < LB; j += 8) {
      const uint64_t w = mix(uint64_t(line) << 32 ^ version << 8 ^ j);
      for (unsigned b = 0; b < 8; ++b) p[j + b] = uint8_t(w >> (8 * b));
    }
  }

  template <class T>
  bool same(const char* field, const T& twin, const T& rtl) {
    if (twin == rtl) return true;
    std::ostringstream os;
    os << "cycle " << cycle_ << ": " << field << " differs: twin " << twin << ", rtl " << rtl;
    fail(os.str());
    return false;
  }
  bool same_line(const char* field, const Line& twin, const Line& rtl) {
    if (twin == rtl) return true;
    std::ostringstream os;
    os << "cycle " << cycle_ << ": " << field << " differs:\n  twin 0x" << twin.to_string(sc_dt::SC_HEX_US, false)
       << "\n  rtl  0x" << rtl.to_string(sc_dt::SC_HEX_US, false);
    fail(os.str());
    return false;
  }
  void fail(const std::string& what) {
    if (!mismatch.empty()) return;
    std::ostringstream os;
    os << g_.name << ": first differing transaction, " << what;
    // The access a response belongs to: HIT_LATENCY - 1 cycles before (its edge ends that cycle).
    if (what.find("rsp_") != std::string::npos)
      for (const InRec& r : hist_)
        if (r.acc && r.cycle + g_.hit_latency - 1 == cycle_)
          os << "\n  (the response to the access of cycle " << r.cycle << ": line " << r.acc_line
             << ", tag " << r.acc_tag << ")";
    os << "\n  inputs of the last cycles"
       << " (edge at the end of each; outputs compared after it):";
    for (const InRec& r : hist_) {
      os << "\n    cycle " << r.cycle << ": ";
      if (r.acc) os << "access line " << r.acc_line << " tag " << r.acc_tag << "; ";
      if (r.fill) os << "fill mshr " << r.fill_tag << " (line " << r.fill_line << "); ";
      os << "req_ready " << r.ready;
    }
    mismatch = os.str();
  }

  // Compares every output after an edge; false on the first difference.
  bool compare() {
    if (!same("rsp_valid_o", st_.rsp_valid.read(), sr_.rsp_valid.read())) return false;
    if (st_.rsp_valid.read()) {
      if (!same("rsp_hit_o", st_.rsp_hit.read(), sr_.rsp_hit.read()) ||
          !same("rsp_merge_o", st_.rsp_merge.read(), sr_.rsp_merge.read()) ||
          !same("rsp_full_o", st_.rsp_full.read(), sr_.rsp_full.read()) ||
          !same("rsp_set_full_o", st_.rsp_set_full.read(), sr_.rsp_set_full.read()) ||
          !same("rsp_tag_o", st_.rsp_tag.read(), sr_.rsp_tag.read()))
        return false;
      if (st_.rsp_hit.read() && !same_line("rsp_data_o", st_.rsp_data.read(), sr_.rsp_data.read()))
        return false;
    }
    if (!same("req_valid_o", st_.req_valid.read(), sr_.req_valid.read())) return false;
    if (st_.req_valid.read() && (!same("req_line_o", st_.req_line.read(), sr_.req_line.read()) ||
                                 !same("req_tag_o", st_.req_tag.read(), sr_.req_tag.read())))
      return false;
    return same("mshr_busy_o", st_.mshr_busy.read(), sr_.mshr_busy.read()) &&
           same("cnt_hits_o", st_.cnt_hits.read(), sr_.cnt_hits.read()) &&
           same("cnt_misses_o", st_.cnt_misses.read(), sr_.cnt_misses.read()) &&
           same("cnt_merges_o", st_.cnt_merges.read(), sr_.cnt_merges.read()) &&
           same("cnt_full_o", st_.cnt_full.read(), sr_.cnt_full.read()) &&
           same("cnt_set_full_o", st_.cnt_set_full.read(), sr_.cnt_set_full.read()) &&
           same("cnt_fills_o", st_.cnt_fills.read(), sr_.cnt_fills.read());
  }

  void run() {
    rst_n_.write(false);
    st_.acc_valid.write(false);
    st_.fill_valid.write(false);
    st_.req_ready.write(false);
    edge();
    edge();
    rst_n_.write(true);
    std::vector<Slot> slots(kSlots);
    for (Slot& s : slots) s.line = next_line(rnd(1u << 16));
    std::vector<Pending> mem;
    std::map<uint32_t, uint64_t> last_fill;  // line -> version of its last fill
    uint64_t version = 0;
    double issue_p = 1.0, ready_p = 1.0;
    Line fill_bv;
    std::vector<uint8_t> bytes(LB), expect(LB);
    const auto t0 = std::chrono::steady_clock::now();
    for (cycle_ = 0; cycle_ < cycles_; ++cycle_) {
      if (cycle_ % 512 == 0) {
        issue_p = chance(0.3) ? 1.0 : std::uniform_real_distribution<double>(0.1, 1)(rng_);
        ready_p = chance(0.3) ? 1.0 : std::uniform_real_distribution<double>(0.05, 1)(rng_);
        if (chance(0.2)) window_ = rnd(1u << 20);
      }
      InRec in{cycle_, false, false, false, 0, 0, 0, 0};
      // Memory side: the request on the port now moves if ready is high at this edge.
      const bool ready = chance(ready_p);
      in.ready = ready;
      st_.req_ready.write(ready);
      if (st_.req_valid.read()) {
        if (ready) {
          ++n.requests;
          const uint64_t d = chance(0.05) ? 150 : 1 + rnd(64);
          mem.push_back({cycle_ + d, st_.req_tag.read(), st_.req_line.read()});
        } else {
          ++n.backpressure;
        }
      }
      // One due fill per cycle (a random one of those due: out of order).
      std::vector<size_t> due;
      for (size_t i = 0; i < mem.size(); ++i)
        if (mem[i].due <= cycle_) due.push_back(i);
      if (!due.empty()) {
        const size_t k = due[rnd(uint32_t(due.size()))];
        const Pending p = mem[k];
        mem.erase(mem.begin() + long(k));
        ++version;
        fill_bytes(p.line, version, bytes.data());
        last_fill[p.line] = version;
        sc::pins::line_to_bv<LB>(bytes.data(), fill_bv);
        st_.fill_valid.write(true);
        st_.fill_tag.write(p.tag);
        st_.fill_data.write(fill_bv);
        in.fill = true;
        in.fill_tag = p.tag;
        in.fill_line = p.line;
        ++n.fills;
      } else {
        st_.fill_valid.write(false);
      }
      // One access: a requester that is free and due, from a random start.
      bool acc = false;
      if (chance(issue_p)) {
        const uint32_t s0 = rnd(kSlots);
        for (uint32_t i = 0; i < kSlots && !acc; ++i) {
          Slot& s = slots[(s0 + i) % kSlots];
          if (s.busy || s.next > cycle_) continue;
          s.busy = true;
          acc = true;
          st_.acc_line.write(s.line);
          st_.acc_tag.write((s0 + i) % kSlots);
          in.acc = true;
          in.acc_line = s.line;
          in.acc_tag = (s0 + i) % kSlots;
          ++n.accesses;
        }
      }
      st_.acc_valid.write(acc);
      // The RTL sees the same inputs.
      sr_.req_ready.write(ready);
      sr_.fill_valid.write(in.fill);
      if (in.fill) {
        sr_.fill_tag.write(in.fill_tag);
        sr_.fill_data.write(fill_bv);
      }
      sr_.acc_valid.write(acc);
      if (acc) {
        sr_.acc_line.write(in.acc_line);
        sr_.acc_tag.write(in.acc_tag);
      }
      hist_.push_back(in);
      if (hist_.size() > 4 + g_.hit_latency) hist_.pop_front();

      edge();

      if (!compare()) break;
      // Responses back to the requesters.
      if (st_.rsp_valid.read()) {
        Slot& s = slots[st_.rsp_tag.read()];
        s.busy = false;
        if (st_.rsp_hit.read()) {
          ++n.hits;
          // The line must be the last data filled for it.
          const auto it = last_fill.find(s.line);
          if (it == last_fill.end()) {
            std::ostringstream os;
            os << "cycle " << cycle_ << ": hit on line " << s.line << ", which was never filled";
            fail(os.str());
            break;
          }
          fill_bytes(s.line, it->second, expect.data());
          sc::pins::bv_to_line<LB>(st_.rsp_data.read(), bytes.data());
          if (bytes != expect) {
            std::ostringstream os;
            os << "cycle " << cycle_ << ": hit on line " << s.line << " (both models agree) returns "
               << "data other than its last fill";
            fail(os.str());
            break;
          }
          s.line = next_line(s.line);
          s.next = cycle_ + rnd(4);
        } else {
          ++n.misses;
          if (st_.rsp_merge.read())
            ++n.merges;
          else if (st_.rsp_full.read())
            ++n.full;
          else if (st_.rsp_set_full.read())
            ++n.set_full;
          else
            ++n.allocs;
          s.next = cycle_ + 1 + rnd(8);
        }
      }
    }
    cycles_run = cycle_;
    seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // Evictions: at least the fills beyond the cache's capacity.
    n.evictions = n.fills > uint64_t(g_.sets) * g_.ways ? n.fills - uint64_t(g_.sets) * g_.ways : 0;
    sc_core::sc_stop();
  }

 public:
  double seconds_ = 0;

 private:
  Geometry g_;
  uint64_t cycles_;
  uint64_t cycle_ = 0;
  std::mt19937_64 rng_{0xA5CAC4Eull};
  std::deque<uint32_t> recent_;
  uint32_t window_ = 0;
  std::deque<InRec> hist_;
  const sc_core::sc_time half_{5, sc_core::SC_NS};
  sc_core::sc_signal<bool> clk_{"clk", false}, rst_n_{"rst_n", false};
  AscacheSignals<LB> st_, sr_;  // the twin's and the RTL's wires (same input values)
  AscacheTwin<LB> twin_;
  V rtl_;
};

template <class V, unsigned LB>
void run_lockstep(const Geometry& g) {
  const uint64_t cycles = cycles_from_env();
  auto* top = new Lockstep<V, LB>("lockstep", g, cycles);  // owned by the simulation (one per process)
  sc_core::sc_start();
  const Counts& n = top->n;
  const double rate = top->seconds_ > 0 ? double(top->cycles_run) / top->seconds_ : 0;
  std::printf("ASCACHESUM %s cycles=%llu accesses=%llu hits=%llu misses=%llu allocs=%llu merges=%llu "
              "mshr_full=%llu set_full=%llu requests=%llu fills=%llu backpressure_cycles=%llu "
              "cycles_per_s=%.0f\n",
              g.name, (unsigned long long)top->cycles_run, (unsigned long long)n.accesses,
              (unsigned long long)n.hits, (unsigned long long)n.misses,
              (unsigned long long)n.allocs, (unsigned long long)n.merges,
              (unsigned long long)n.full, (unsigned long long)n.set_full, (unsigned long long)n.requests,
              (unsigned long long)n.fills, (unsigned long long)n.backpressure, rate);
  ASSERT_TRUE(top->mismatch.empty()) << top->mismatch;
  EXPECT_EQ(top->cycles_run, cycles);
  // Counters at the end: the twin's Ascache::stats() and the RTL's cnt_*_o.
  const sc::CacheStats& s = top->twin().cache().stats();
  EXPECT_EQ(uint32_t(s.hits), top->rtl_cnt(0)) << "hits";
  EXPECT_EQ(uint32_t(s.misses), top->rtl_cnt(1)) << "misses";
  EXPECT_EQ(uint32_t(s.mshr_merges), top->rtl_cnt(2)) << "mshr merges";
  EXPECT_EQ(uint32_t(s.mshr_full), top->rtl_cnt(3)) << "mshr_full";
  EXPECT_EQ(uint32_t(s.fills), top->rtl_cnt(4)) << "fills";
  EXPECT_EQ(uint32_t(s.set_full), top->rtl_cnt(5)) << "set_full";
  // ... and the stimulus's own count of the responses it received.
  EXPECT_LE(s.hits - n.hits, g.hit_latency) << "responses still in flight at the end";
  EXPECT_EQ(s.fills, n.fills);
  // Every kind of transaction occurred (the stimulus reaches every path of the cache).
  const uint64_t min = cycles / 200;
  EXPECT_GE(n.hits, min) << "too few hits";
  EXPECT_GE(n.allocs, min) << "too few allocating misses";
  EXPECT_GE(n.merges, min) << "too few merged misses";
  EXPECT_GE(n.full, min) << "too few MSHR-full misses";
  // Every fill is hit before its line can go (pinned until its first hit: the requesters retry),
  // but for lines still pinned at the end.
  EXPECT_GE(s.hits + uint64_t(g.sets) * g.ways, s.fills) << "fills never hit";
  // Sets full: with 12 requesters, only in the small caches (the 16 KB one: test_pins.cpp's
  // AscacheRtlLockstep, 24 requesters and a hot set).
  if (g.sets * g.ways <= 16) {
    EXPECT_GE(n.set_full, 1u) << "no miss refused for a set whose ways are all pinned or awaited";
  }
  EXPECT_GE(n.backpressure, min) << "too few cycles of request back-pressure";
  EXPECT_GE(n.evictions, min) << "too few evictions";
}

#define RAYCORE_RTL_ASCACHE_VARIANT(prefix, name, sets, ways, lb, mshrs, lat) \
  TEST(LockstepAscache, name) {                                                   \
    run_lockstep<prefix, lb>(Geometry{#name, sets, ways, lb, mshrs, lat});        \
  }
#include "rtl_ascache_variants.h"
#undef RAYCORE_RTL_ASCACHE_VARIANT

}  // namespace
}  // namespace raycore::rtltest

int sc_main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
