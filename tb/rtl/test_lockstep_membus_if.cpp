// tb/rtl/test_lockstep_membus_if.cpp - lockstep co-simulation of the memory bus interface: the
// Verilated --sc model of rtl/units/membus_if.v and its SystemC twin systemc/pins/membus_if.h side
// by side in one SystemC simulation, with the same stimulus; in the "membus" tests also against
// systemc/membus.* itself (raycore::sc::Membus, the cycle model's bus).
//
// Per variant (rtl/units/membus_if.cmake) two tests, one simulation per process:
//   random: N requesters with random line requests (lengths 0..LEN, random addresses, tags) and
//     random gaps, random mem_ready_i back-pressure, a memory that returns each line after a random
//     latency (1..40) as beats on the shared data bus;
//   membus: mem_ready_i = 1 and the memory timed exactly as Membus (latency L, or with a seed
//     uniform in [L, 2L], the same splitmix draw; beats on cycles first .. first+beats-1). The same
//     requests go to a raycore::sc::Membus through TimedFifos: the cycle and requester of every
//     accepted request and the cycle, port and tag of every response (mem_resp) must equal the
//     RTL's (mem_valid_o && mem_ready_i; rsp_last_o), and Membus's copied line the beats' bytes.
// Checked every cycle, twin vs RTL: req_ready_o, mem_valid_o (and mem_addr/bytes/port/tag while
// valid), rsp_valid_o (and rsp_port/tag/data/beat/last while valid), outstanding_o, take_o (and
// take_tag/beat/last while taken). Every output
// transaction is also checked against the stimulus: the accepted request is the granted
// requester's, each routed beat is the memory's beat of the previous cycle for the right
// requester and tag. The first difference is printed and the run stops. Prints LOCKSTEP lines with
// the simulated cycles per second. RAYCORE_LOCKSTEP_MEMBUS_N requests per test (default 20000).
#include <gtest/gtest.h>
#include <systemc>

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <deque>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "systemc/fifo.h"
#include "systemc/membus.h"
#include "systemc/pins/membus_if.h"
#include "tb/fp/fp_check.h"

#include "rtl_membus_if_sc_models.h"

namespace raycore::rtltest {
namespace {

using sc::pins::port_bits;
using sc::pins::set_port_bits;

bool g_simulated = false;  // one SystemC simulation per process (toolchain.md pitfall 8)

uint64_t request_count() { return fptest::env_count("RAYCORE_LOCKSTEP_MEMBUS_N", 20000); }

enum class Mode { random, membus };

// Records Membus's responses.
struct Recorder : sc::MemClient {
  struct Ev {
    uint32_t port, tag;
    sc::Cycle now;
  };
  std::vector<Ev> ev;
  void mem_resp(uint32_t port, uint32_t tag, sc::Cycle now) override { ev.push_back({port, tag, now}); }
};

template <class V, unsigned N, unsigned ADDR, unsigned LEN, unsigned TAG, unsigned DEPTH,
          unsigned BEAT>
class Lockstep : public sc_core::sc_module {
  using Twin = sc::pins::MembusIfTwin<N, ADDR, LEN, TAG, DEPTH, BEAT>;
  using T = typename Twin::T;
  using S = sc::pins::MembusIfSignals<T>;
  static constexpr uint32_t kLatency = 20;  // membus mode: Membus's latency
  static constexpr uint64_t kSeed = 7;      // membus mode: latency uniform in [L, 2L]

 public:
  SC_HAS_PROCESS(Lockstep);
  Lockstep(sc_core::sc_module_name name, std::string variant, Mode mode, uint64_t count)
      : sc_core::sc_module(name),
        variant_(std::move(variant)),
        mode_(mode),
        count_(count),
        rng_(fptest::seed_for("lockstep.membus_if." + variant_)),
        image_(make_image(rng_)),
        twin_("twin"),
        rtl_("rtl"),
        bus_("membus", image_, kLatency, BEAT, DEPTH, kSeed),
        rng_draw_(kSeed) {
    sc::pins::bind_membus_if(twin_, st_, clk_, rst_n_);
    sc::pins::bind_membus_if(rtl_, sr_, clk_, rst_n_);
    fifos_.reserve(N);
    for (unsigned i = 0; i < N; ++i) fifos_.emplace_back(std::make_unique<sc::TimedFifo<sc::MemReq>>(1));
    for (unsigned i = 0; i < N; ++i) bus_.add_requester(fifos_[i].get(), &rec_, i);
    SC_THREAD(run);
  }

  uint64_t cycles = 0, accepted = 0, lines = 0, beats = 0, mismatches = 0, full_cycles = 0;
  std::string first_diff;

 private:
  struct Req {
    bool valid = false;
    uint64_t addr = 0, bytes = 0, tag = 0;
    bool in_bus = false;  // pushed to Membus's fifo
  };
  struct Line {
    uint32_t port = 0;
    uint64_t addr = 0, bytes = 0, tag = 0;
    sc::Cycle first = 0;
    uint64_t beats = 0, sent = 0;
    std::vector<uint8_t> buf;  // Membus's copy (membus mode)
  };
  struct Beat {
    bool valid = false;
    uint32_t port = 0;
    uint64_t tag = 0, index = 0;
    bool last = false;
    typename T::data_t data{};
  };

  static std::vector<uint8_t> make_image(std::mt19937_64& rng) {
    std::vector<uint8_t> m(1u << 16);
    for (auto& b : m) b = uint8_t(rng());
    return m;
  }
  // Membus::draw_latency.
  uint32_t draw_latency() {
    uint64_t z = (rng_draw_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return kLatency + uint32_t(z % (uint64_t(kLatency) + 1));
  }
  uint8_t mem_byte(uint64_t a) const { return a < image_.size() ? image_[size_t(a)] : 0; }

  void fail(const std::string& what) {
    if (mismatches++ == 0) first_diff = variant_ + (mode_ == Mode::membus ? " membus" : " random") +
                                        ": " + what;
  }
  void half(double ns) { wait(sc_core::sc_time(ns, sc_core::SC_NS)); }

  // Inputs to both models.
  void drive(const std::vector<Req>& req, bool mem_ready, const Beat& beat) {
    typename T::valid_t valid{};
    typename T::addr_t addr{};
    typename T::bytes_t bytes{};
    typename T::tags_t tags{};
    for (unsigned i = 0; i < N; ++i) {
      // Idle requesters show junk on their fields (must be ignored).
      const Req& r = req[i];
      set_port_bits(valid, i, 1, r.valid ? 1u : 0u);
      set_port_bits(addr, i * ADDR, ADDR, r.valid ? r.addr : rng_());
      set_port_bits(bytes, i * LEN, LEN, r.valid ? r.bytes : rng_());
      set_port_bits(tags, i * TAG, TAG, r.valid ? r.tag : rng_());
    }
    for (S* s : {&st_, &sr_}) {
      s->req_valid.write(valid);
      s->req_addr.write(addr);
      s->req_bytes.write(bytes);
      s->req_tag.write(tags);
      s->mem_ready.write(mem_ready);
      s->beat_valid.write(beat.valid);
      s->beat_data.write(beat.data);
    }
  }

  // Twin vs RTL, every cycle.
  bool compare_pins() {
    std::ostringstream s;
    s << "cycle " << cycles << ": ";
    if (st_.req_ready.read() != sr_.req_ready.read()) {
      s << "req_ready_o twin=" << port_bits(st_.req_ready.read(), 0, N)
        << " rtl=" << port_bits(sr_.req_ready.read(), 0, N);
    } else if (st_.mem_valid.read() != sr_.mem_valid.read()) {
      s << "mem_valid_o twin=" << st_.mem_valid.read() << " rtl=" << sr_.mem_valid.read();
    } else if (sr_.mem_valid.read() &&
               (st_.mem_addr.read() != sr_.mem_addr.read() ||
                st_.mem_bytes.read() != sr_.mem_bytes.read() ||
                st_.mem_port.read() != sr_.mem_port.read() || st_.mem_tag.read() != sr_.mem_tag.read())) {
      s << "request transaction: twin port=" << st_.mem_port.read() << " addr=" << st_.mem_addr.read()
        << " bytes=" << st_.mem_bytes.read() << " tag=" << st_.mem_tag.read()
        << ", rtl port=" << sr_.mem_port.read() << " addr=" << sr_.mem_addr.read()
        << " bytes=" << sr_.mem_bytes.read() << " tag=" << sr_.mem_tag.read();
    } else if (st_.rsp_valid.read() != sr_.rsp_valid.read()) {
      s << "rsp_valid_o twin=" << port_bits(st_.rsp_valid.read(), 0, N)
        << " rtl=" << port_bits(sr_.rsp_valid.read(), 0, N);
    } else if (port_bits(sr_.rsp_valid.read(), 0, N) != 0 &&
               (st_.rsp_port.read() != sr_.rsp_port.read() || st_.rsp_tag.read() != sr_.rsp_tag.read() ||
                !(st_.rsp_data.read() == sr_.rsp_data.read()) ||
                st_.rsp_beat.read() != sr_.rsp_beat.read() || st_.rsp_last.read() != sr_.rsp_last.read())) {
      s << "response beat: twin port=" << st_.rsp_port.read() << " tag=" << st_.rsp_tag.read()
        << " beat=" << st_.rsp_beat.read() << " last=" << st_.rsp_last.read()
        << " data=" << st_.rsp_data.read() << ", rtl port=" << sr_.rsp_port.read()
        << " tag=" << sr_.rsp_tag.read() << " beat=" << sr_.rsp_beat.read()
        << " last=" << sr_.rsp_last.read() << " data=" << sr_.rsp_data.read();
    } else if (st_.outstanding.read() != sr_.outstanding.read()) {
      s << "outstanding_o twin=" << st_.outstanding.read() << " rtl=" << sr_.outstanding.read();
    } else if (st_.take.read() != sr_.take.read() ||
               (sr_.take.read() &&
                (st_.take_tag.read() != sr_.take_tag.read() ||
                 st_.take_beat.read() != sr_.take_beat.read() ||
                 st_.take_last.read() != sr_.take_last.read()))) {
      s << "take_*: twin take=" << st_.take.read() << " tag=" << st_.take_tag.read()
        << " beat=" << st_.take_beat.read() << " last=" << st_.take_last.read()
        << ", rtl take=" << sr_.take.read() << " tag=" << sr_.take_tag.read()
        << " beat=" << sr_.take_beat.read() << " last=" << sr_.take_last.read();
    } else {
      return true;
    }
    fail(s.str());
    return false;
  }

  void run() {
    rst_n_.write(false);
    std::vector<Req> req(N);
    Beat none;
    drive(req, false, none);
    for (int i = 0; i < 2; ++i) {
      half(5);
      clk_.write(true);
      half(5);
      clk_.write(false);
    }
    rst_n_.write(true);
    std::deque<Line> inflight;  // accepted, beats not all sent (memory order)
    sc::Cycle data_free = 0;
    Beat prev;  // the beat driven in the previous cycle (routed back now)
    uint64_t issued = 0, idle = 0;
    uint32_t p_req = 4, p_ready = 8;  // in 1/8
    const bool bus_mode = mode_ == Mode::membus;
    while ((accepted < count_ || !inflight.empty() || prev.valid) && mismatches == 0) {
      const sc::Cycle now = cycles;
      if (!bus_mode && (cycles & 255u) == 0) {
        static constexpr uint32_t kRates[] = {1, 3, 6, 8};
        p_req = kRates[rng_() & 3u];
        p_ready = kRates[(rng_() >> 2) & 3u];
      }
      // New requests from idle requesters.
      for (unsigned i = 0; i < N; ++i) {
        Req& r = req[i];
        if (r.valid || issued >= count_ || (rng_() & 7u) >= (bus_mode ? 2u : p_req)) continue;
        r.valid = true;
        r.in_bus = false;
        static constexpr uint64_t kLine[] = {64, 32, 96, 8, 16, 48};
        r.bytes = (rng_() % 8 == 0) ? rng_() % (bus_mode ? 300u : 301u) + (bus_mode ? 1u : 0u)
                                    : kLine[i % 6];
        r.bytes &= (uint64_t(1) << LEN) - 1;
        if (bus_mode && r.bytes == 0) r.bytes = 1;
        r.addr = (rng_() % (image_.size() + 512)) & ((ADDR >= 64 ? ~0ull : (1ull << ADDR) - 1));
        r.tag = rng_() & ((uint64_t(1) << TAG) - 1);
        ++issued;
      }
      // This cycle's beat from the memory.
      Beat beat;
      if (!inflight.empty() && inflight.front().first <= now) {
        Line& l = inflight.front();
        beat.valid = true;
        beat.port = l.port;
        beat.tag = l.tag;
        beat.index = l.sent;
        beat.last = l.sent + 1 == l.beats;
        for (unsigned j = 0; j < (8 * BEAT + 63) / 64; ++j) {
          uint64_t w = 0;
          for (unsigned b = 0; b < 8 && j * 8 + b < BEAT; ++b) {
            const uint64_t off = l.sent * BEAT + j * 8 + b;
            if (off < l.bytes) w |= uint64_t(mem_byte(l.addr + off)) << (8 * b);
          }
          set_port_bits(beat.data, 64 * j, std::min(64u, 8 * BEAT - 64 * j), w);
        }
      } else {
        for (unsigned j = 0; j < (8 * BEAT + 63) / 64; ++j)  // junk on the bus
          set_port_bits(beat.data, 64 * j, std::min(64u, 8 * BEAT - 64 * j), rng_());
      }
      const bool mem_ready = bus_mode || (rng_() & 7u) < p_ready;
      drive(req, mem_ready, beat);
      half(2.5);
      if (!compare_pins()) break;
      // The routed beat (registered): the previous cycle's beat, to its requester.
      const uint64_t rv = port_bits(sr_.rsp_valid.read(), 0, N);
      if (prev.valid != (rv != 0) || (prev.valid && rv != (uint64_t(1) << prev.port))) {
        fail("cycle " + std::to_string(now) + ": rsp_valid_o=" + std::to_string(rv) +
             ", expected the beat for requester " + (prev.valid ? std::to_string(prev.port) : "none"));
        break;
      }
      if (prev.valid) {
        ++beats;
        if (port_bits(sr_.rsp_port.read(), 0, 32) != prev.port ||
            port_bits(sr_.rsp_tag.read(), 0, TAG) != prev.tag ||
            port_bits(sr_.rsp_beat.read(), 0, LEN) != prev.index || sr_.rsp_last.read() != prev.last ||
            !(sr_.rsp_data.read() == prev.data)) {
          std::ostringstream s;
          s << "cycle " << now << ": routed beat differs from the memory's: expected port=" << prev.port
            << " tag=" << prev.tag << " beat=" << prev.index << " last=" << prev.last
            << " data=" << prev.data << "; rtl port=" << sr_.rsp_port.read()
            << " tag=" << sr_.rsp_tag.read() << " beat=" << sr_.rsp_beat.read()
            << " last=" << sr_.rsp_last.read() << " data=" << sr_.rsp_data.read();
          fail(s.str());
          break;
        }
      }
      // The accepted request (RTL): must be the granted requester's request.
      const bool acc = sr_.mem_valid.read() && mem_ready;
      const uint32_t gport = uint32_t(port_bits(sr_.mem_port.read(), 0, 32));
      const uint64_t ready_bits = port_bits(sr_.req_ready.read(), 0, N);
      if (acc) {
        const Req& r = req[gport];
        if (gport >= N || !r.valid || ready_bits != (uint64_t(1) << gport) ||
            port_bits(sr_.mem_addr.read(), 0, ADDR) != r.addr ||
            port_bits(sr_.mem_bytes.read(), 0, LEN) != r.bytes ||
            port_bits(sr_.mem_tag.read(), 0, TAG) != r.tag) {
          fail("cycle " + std::to_string(now) + ": accepted request " + std::to_string(accepted) +
               " is not requester " + std::to_string(gport) + "'s request");
          break;
        }
      } else if (ready_bits != 0) {
        fail("cycle " + std::to_string(now) + ": req_ready_o without an accepted request");
        break;
      }
      if (sr_.mem_valid.read() == false && port_bits(sr_.outstanding.read(), 0, 32) == DEPTH)
        ++full_cycles;
      // Membus, the same cycle: present the requests, tick, compare.
      if (bus_mode) {
        for (unsigned i = 0; i < N; ++i) {
          Req& r = req[i];
          if (r.valid && !r.in_bus) {
            sc::MemReq q;
            q.addr = r.addr;
            q.bytes = uint32_t(r.bytes);
            q.tag = uint32_t(r.tag);
            bufs_.emplace_back(std::make_unique<std::vector<uint8_t>>(r.bytes));
            q.data = bufs_.back()->data();
            pending_bufs_[i] = bufs_.back().get();
            fifos_[i]->push(q, now);
            r.in_bus = true;
          }
        }
        rec_.ev.clear();
        bus_.tick(now);
        int popped = -1;
        for (unsigned i = 0; i < N; ++i)
          if (req[i].valid && fifos_[i]->empty()) popped = int(i);
        if ((popped >= 0) != acc || (acc && uint32_t(popped) != gport)) {
          fail("cycle " + std::to_string(now) + ": Membus accepted requester " +
               std::to_string(popped) + ", the RTL " + (acc ? std::to_string(gport) : "none"));
          break;
        }
        const bool rtl_resp = rv != 0 && sr_.rsp_last.read();
        if (rec_.ev.size() != (rtl_resp ? 1u : 0u) ||
            (rtl_resp && (rec_.ev[0].port != prev.port || rec_.ev[0].tag != prev.tag))) {
          std::ostringstream s;
          s << "cycle " << now << ": Membus delivered " << rec_.ev.size() << " response(s)";
          if (!rec_.ev.empty()) s << " (port " << rec_.ev[0].port << " tag " << rec_.ev[0].tag << ")";
          s << ", the RTL " << (rtl_resp ? "a last beat for port " + std::to_string(prev.port) +
                                               " tag " + std::to_string(prev.tag)
                                         : std::string("none"));
          fail(s.str());
          break;
        }
        if (rtl_resp) {  // Membus's copy of the line equals the beats' bytes
          const auto& buf = *line_bufs_.front();
          const Line& l = done_lines_.front();
          for (uint64_t b = 0; b < l.bytes; ++b)
            if (buf[size_t(b)] != mem_byte(l.addr + b)) {
              fail("cycle " + std::to_string(now) + ": Membus's line bytes differ at offset " +
                   std::to_string(b));
              break;
            }
          line_bufs_.pop_front();
          done_lines_.pop_front();
        }
      }
      // State after the edge.
      if (beat.valid) {
        Line& l = inflight.front();
        if (++l.sent == l.beats) {
          if (bus_mode) done_lines_.push_back(l);
          inflight.pop_front();
          ++lines;
        }
      }
      prev = beat;
      if (acc) {
        Req& r = req[gport];
        Line l;
        l.port = gport;
        l.addr = r.addr;
        l.bytes = r.bytes;
        l.tag = r.tag;
        l.beats = std::max<uint64_t>(1, (r.bytes + BEAT - 1) / BEAT);
        const uint32_t lat = bus_mode ? draw_latency() : 1u + uint32_t(rng_() % 40);
        l.first = std::max<sc::Cycle>(now + lat, data_free);
        data_free = l.first + l.beats;
        inflight.push_back(l);
        if (bus_mode) line_bufs_.push_back(pending_bufs_[gport]);
        r.valid = false;
        ++accepted;
        idle = 0;
      } else if (++idle > 5000u) {
        fail("no request accepted for 5000 cycles (deadlock)");
        break;
      }
      half(2.5);
      clk_.write(true);
      half(5);
      clk_.write(false);
      ++cycles;
    }
    sc_core::sc_stop();
  }

  std::string variant_;
  Mode mode_;
  uint64_t count_;
  std::mt19937_64 rng_;
  std::vector<uint8_t> image_;
  sc_core::sc_signal<bool> clk_{"clk"}, rst_n_{"rst_n"};
  S st_, sr_;
  Twin twin_;
  V rtl_;
  sc::Membus bus_;
  Recorder rec_;
  std::vector<std::unique_ptr<sc::TimedFifo<sc::MemReq>>> fifos_;
  std::vector<std::unique_ptr<std::vector<uint8_t>>> bufs_;
  std::vector<uint8_t>* pending_bufs_[N] = {};
  std::deque<std::vector<uint8_t>*> line_bufs_;
  std::deque<Line> done_lines_;
  uint64_t rng_draw_;
};

template <class V, unsigned N, unsigned ADDR, unsigned LEN, unsigned TAG, unsigned DEPTH,
          unsigned BEAT>
void run_variant(const std::string& name, Mode mode) {
  if (g_simulated)
    GTEST_SKIP() << "one SystemC simulation per process: run one test per process "
                    "(ctest does; or --gtest_filter)";
  g_simulated = true;
  const uint64_t n = request_count();
  auto* ls = new Lockstep<V, N, ADDR, LEN, TAG, DEPTH, BEAT>("lockstep", name, mode, n);
  const auto t0 = std::chrono::steady_clock::now();
  sc_core::sc_start();
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("LOCKSTEP membus_if %s %s requests=%" PRIu64 " lines=%" PRIu64 " beats=%" PRIu64
              " queue_full_cycles=%" PRIu64 " cycles=%" PRIu64 " mismatches=%" PRIu64
              " seconds=%.2f cycles_per_s=%.0f\n",
              name.c_str(), mode == Mode::membus ? "membus" : "random", ls->accepted, ls->lines,
              ls->beats, ls->full_cycles, ls->cycles, ls->mismatches, sec,
              sec > 0 ? double(ls->cycles) / sec : 0.0);
  EXPECT_EQ(ls->mismatches, 0u) << ls->first_diff;
  EXPECT_EQ(ls->accepted, n) << name << ": not every request was accepted";
  EXPECT_EQ(ls->lines, n) << name << ": not every line came back";
}

#define RAYCORE_RTL_MEMBUS_IF_SC_VARIANT(prefix, n, addr, len, tag, depth, beat)       \
  TEST(LockstepMembusIf, prefix##_random) {                                            \
    run_variant<prefix, n, addr, len, tag, depth, beat>(#prefix, Mode::random);        \
  }                                                                                    \
  TEST(LockstepMembusIf, prefix##_membus) {                                            \
    run_variant<prefix, n, addr, len, tag, depth, beat>(#prefix, Mode::membus);        \
  }
#include "rtl_membus_if_sc_variants.h"
#undef RAYCORE_RTL_MEMBUS_IF_SC_VARIANT

}  // namespace
}  // namespace raycore::rtltest

int sc_main(int argc, char* argv[]) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
