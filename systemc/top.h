// systemc/top.h - N RTUs sharing membus. One SC_THREAD advances the clock: each cycle it ticks
// membus and every RTU (each unit's tick is its clocked process body, called in a fixed order).
// Cycles in which nothing can happen are skipped to the next event (idle units cost no host time).
// With a trace file the thread waits one clock period per cycle and writes the top-level
// handshakes and counters to a VCD; without, it waits in chunks (no per-cycle kernel switches).
#pragma once

#include <systemc>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

#include "systemc/membus.h"
#include "systemc/rtu.h"

namespace raycore::sc {

template <class A>
class Top : public sc_core::sc_module {
  using F = typename A::Fmt;
  static constexpr hls::Rounding R = A::rounding;
  FrameCtx& fc_;
  const SimConfig& cfg_;

 public:
  SC_HAS_PROCESS(Top);
  Top(sc_core::sc_module_name name, FrameCtx& fc, const SimConfig& cfg, const std::vector<uint8_t>& mem,
      bool vtu_on, const hls::Vtu<F, R>& vtu)
      : sc_core::sc_module(name),
        fc_(fc),
        cfg_(cfg),
        bus("membus", mem, cfg.mem_latency, cfg.mem_bandwidth, cfg.mem_queue_depth, cfg.seed),
        period_(1000.0 / cfg.clock_mhz, sc_core::SC_NS) {
    if (cfg.rtus < 1 || cfg.rtus > 64) throw std::invalid_argument("rtus must be 1..64");
    for (int i = 0; i < cfg.rtus; ++i)
      rtus.push_back(std::make_unique<Rtu<A>>(("rtu" + std::to_string(i)).c_str(), fc, cfg, i,
                                              vtu_on, vtu, bus));
    if (!cfg.trace_file.empty()) {
      std::string base = cfg.trace_file;
      if (base.size() > 4 && base.substr(base.size() - 4) == ".vcd") base.resize(base.size() - 4);
      sc_core::sc_report_handler::set_actions(sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
      tf_ = sc_core::sc_create_vcd_trace_file(base.c_str());
      tf_->set_time_unit(1, sc_core::SC_NS);
      sc_core::sc_trace(tf_, sig_cycle_, "cycle");
      sc_core::sc_trace(tf_, sig_retired_, "rays_retired");
      sc_core::sc_trace(tf_, sig_bus_outstanding_, "membus_outstanding");
      sc_core::sc_trace(tf_, sig_bus_bytes_, "membus_bytes");
      for (int i = 0; i < cfg.rtus; ++i) {
        auto p = std::make_unique<RtuSignals>();
        const std::string n = "rtu" + std::to_string(i) + "_";
        sc_core::sc_trace(tf_, p->busy, n + "active");
        sc_core::sc_trace(tf_, p->in_flight, n + "rays_in_flight");
        sc_core::sc_trace(tf_, p->trv_steps, n + "trv_busy");
        sc_core::sc_trace(tf_, p->ist_tests, n + "ist_busy");
        sc_core::sc_trace(tf_, p->node_miss, n + "node_misses");
        sc_core::sc_trace(tf_, p->tri_miss, n + "tri_misses");
        rsig_.push_back(std::move(p));
      }
    }
    SC_THREAD(run);
  }
  ~Top() override {
    if (tf_) sc_core::sc_close_vcd_trace_file(tf_);
  }

  Membus bus;
  std::vector<std::unique_ptr<Rtu<A>>> rtus;
  Cycle cycles = 0;

 private:
  struct RtuSignals {
    sc_core::sc_signal<bool> busy;
    sc_core::sc_signal<uint32_t> in_flight;
    sc_core::sc_signal<uint64_t> trv_steps, ist_tests, node_miss, tri_miss;
  };

  bool all_done() const {
    for (const auto& r : rtus)
      if (!r->done()) return false;
    return true;
  }

  void run() {
    const bool tty = cfg_.progress && isatty(2);
    const auto t0 = std::chrono::steady_clock::now();
    auto last = t0;
    const uint64_t pixels = uint64_t(fc_.width) * uint64_t(fc_.height);
    Cycle now = 0, synced = 0;
    std::vector<bool> act(rtus.size());
    while (!all_done()) {
      bool active = bus.tick(now);
      for (size_t i = 0; i < rtus.size(); ++i) {
        act[i] = rtus[i]->tick(now);
        active |= act[i];
      }
      if (tf_) trace(now, act);
      Cycle next = now + 1;
      if (!active && !all_done()) {
        Cycle t = bus.next_event(now);
        for (const auto& r : rtus) t = std::min(t, r->next_event(now));
        if (t == kNever)
          throw std::runtime_error("cycle model: deadlock at cycle " + std::to_string(now) +
                                   " (no unit can make progress)");
        next = std::max(next, t);
      }
      if (tf_) {  // the trace sees every cycle boundary the model stops at
        wait(period_ * double(next - synced));
        synced = next;
      }
      now = next;
      if (!tf_ && now - synced >= (Cycle(1) << 16)) {
        wait(period_ * double(now - synced));
        synced = now;
        if (tty) {
          const auto tn = std::chrono::steady_clock::now();
          if (std::chrono::duration<double>(tn - last).count() > 0.5) {
            last = tn;
            const double s = std::chrono::duration<double>(tn - t0).count();
            std::fprintf(stderr, "\r  %llu rays retired (%.1f%% of pixels' primaries), %llu cycles, %.0f rays/s   ",
                         (unsigned long long)fc_.retired,
                         100.0 * double(count_primaries()) / double(pixels ? pixels : 1),
                         (unsigned long long)now, double(fc_.retired) / s);
          }
        }
      }
    }
    if (tty) std::fprintf(stderr, "\r%100s\r", "");
    cycles = fc_.last_retire + 1;
    if (now > synced) wait(period_ * double(now - synced));
  }

  uint64_t count_primaries() const {
    uint64_t n = 0;
    for (const auto& r : rtus) n += r->rgu_primaries();
    return n;
  }

  void trace(Cycle now, const std::vector<bool>& act) {
    sig_cycle_.write(now);
    sig_retired_.write(fc_.retired);
    sig_bus_outstanding_.write(bus.outstanding());
    sig_bus_bytes_.write(bus.stats().bytes);
    for (size_t i = 0; i < rtus.size(); ++i) {
      const RtuStats s = rtus[i]->stats();
      rsig_[i]->busy.write(act[i]);
      rsig_[i]->in_flight.write(uint32_t(rtus[i]->in_flight()));
      rsig_[i]->trv_steps.write(s.trv_busy);
      rsig_[i]->ist_tests.write(s.ist_busy);
      rsig_[i]->node_miss.write(s.node.misses);
      rsig_[i]->tri_miss.write(s.tri.misses);
    }
  }

  sc_core::sc_time period_;
  sc_core::sc_trace_file* tf_ = nullptr;
  sc_core::sc_signal<uint64_t> sig_cycle_, sig_retired_, sig_bus_bytes_;
  sc_core::sc_signal<uint32_t> sig_bus_outstanding_;
  std::vector<std::unique_ptr<RtuSignals>> rsig_;
};

}  // namespace raycore::sc
