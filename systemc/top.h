// systemc/top.h - N RTUs sharing membus. One SC_THREAD advances the clock: each cycle it ticks
// membus and every RTU (each unit's tick is its clocked process body, called in a fixed order).
// Cycles in which nothing can happen are skipped to the next event (idle units cost no host time).
// With a trace file the thread waits one clock period per cycle and writes the top-level
// handshakes and counters to a VCD; without, it waits in chunks (no per-cycle kernel switches).
// Pin-level units (--pins / --rtl: SystemC twins or Verilated RTL) share one clock: the thread
// resets them before cycle 0, and gives a clock edge in every cycle in which one of them has work
// (inputs driven in that cycle's ticks are sampled at its edge; outputs are read in the next).
#pragma once

#include <systemc>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

#include "systemc/membus.h"
#include "systemc/pins/clock.h"
#include "systemc/rtu.h"

namespace raycore::sc {

template <class A>
class Top : public sc_core::sc_module {
  using F = typename A::Fmt;
  static constexpr hls::Rounding R = A::rounding;
  FrameCtx& fc_;
  const SimConfig& cfg_;
  std::unique_ptr<pins::PinClock> clock_;  // before the units bound to it (destroyed after them)

 public:
  SC_HAS_PROCESS(Top);
  Top(sc_core::sc_module_name name, FrameCtx& fc, const SimConfig& cfg, const std::vector<uint8_t>& mem,
      bool vtu_on, const hls::Vtu<F, R>& vtu)
      : sc_core::sc_module(name),
        fc_(fc),
        cfg_(cfg),
        bus("membus", mem, cfg.mem_latency, cfg.mem_bandwidth, cfg.mem_queue_depth, cfg.seed),
        period_(1000.0 / cfg.clock_mhz, sc_core::SC_NS) {
    bus.set_l2(cfg.l2);
    if (cfg.rtus < 1 || cfg.rtus > 64) throw std::invalid_argument("rtus must be 1..64");
    if (cfg.vtu_view != UnitView::model || cfg.ist_view == UnitView::twin ||
        cfg.hit_view == UnitView::twin ||
        cfg.rgu_view == UnitView::twin)
      clock_ = std::make_unique<pins::PinClock>(period_);
    for (int i = 0; i < cfg.rtus; ++i)
      rtus.push_back(std::make_unique<Rtu<A>>(("rtu" + std::to_string(i)).c_str(), fc, cfg, i,
                                              vtu_on, vtu, bus, clock_.get()));
    if (cfg.membus_view == UnitView::twin)
      throw ConfigError("membus has no pin-level twin in the frame: use --rtl membus");
    if (cfg.membus_view == UnitView::rtl) {  // after the RTUs: their caches are its requesters
      auto r = make_rtl_membus_for(cfg.rtus, cfg.mem_queue_depth, cfg.mem_bandwidth, cfg.l2);
      bus.bind_rtl(std::move(r), uint64_t(cfg.rtus) * (cfg.node_cache.mshrs +
                                                      cfg.list_cache.mshrs + cfg.tri_cache.mshrs));
    }
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
      // RTU 0's caches (any view; with --rtl ascache the RTL's answers) and, with --rtl trv,
      // trv_unit's ports: per cycle, as the C++ binding drove and read them.
      for (int c = 0; c < 3; ++c) {
        const std::string n = std::string("rtu0_") + (c == 0 ? "node" : c == 1 ? "list" : "tri");
        sc_core::sc_trace(tf_, cache_sig_[c][0], n + "_accesses");
        sc_core::sc_trace(tf_, cache_sig_[c][1], n + "_hits");
        sc_core::sc_trace(tf_, cache_sig_[c][2], n + "_fills");
      }
      if (rtus[0]->trv_rtl()) {
        sc_core::sc_trace(tf_, trv_sig_.in_valid, "rtu0_trv_in_valid_i");
        sc_core::sc_trace(tf_, trv_sig_.in_slot, "rtu0_trv_in_slot_i");
        sc_core::sc_trace(tf_, trv_sig_.res_valid, "rtu0_trv_res_valid_i");
        sc_core::sc_trace(tf_, trv_sig_.go, "rtu0_trv_go_o");
        sc_core::sc_trace(tf_, trv_sig_.fin, "rtu0_trv_fin_o");
        sc_core::sc_trace(tf_, trv_sig_.acc_valid, "rtu0_trv_acc_valid_o");
        sc_core::sc_trace(tf_, trv_sig_.rsp_hit, "rtu0_trv_rsp_hit_i");
        sc_core::sc_trace(tf_, trv_sig_.ist_entries, "rtu0_trv_ist_n_o");
        sc_core::sc_trace(tf_, trv_sig_.head_valid, "rtu0_trv_head_valid_o");
      }
      if (rtus[0]->ist_rtl()) {
        sc_core::sc_trace(tf_, ist_sig_.hin, "rtu0_ist_hin_n_i");
        sc_core::sc_trace(tf_, ist_sig_.acc_valid, "rtu0_ist_acc_valid_o");
        sc_core::sc_trace(tf_, ist_sig_.rsp_hit, "rtu0_ist_rsp_hit_i");
        sc_core::sc_trace(tf_, ist_sig_.res_valid, "rtu0_ist_res_valid_o");
        sc_core::sc_trace(tf_, ist_sig_.head_valid, "rtu0_ist_head_valid_o");
        sc_core::sc_trace(tf_, ist_sig_.busy, "rtu0_ist_busy_o");
      }
      if (rtus[0]->hit_rtl()) {
        sc_core::sc_trace(tf_, hit_sig_.fin, "rtu0_hit_fin_valid_i");
        sc_core::sc_trace(tf_, hit_sig_.in, "rtu0_hit_rd_valid_o");
        sc_core::sc_trace(tf_, hit_sig_.in_slot, "rtu0_hit_rd_slot_o");
        sc_core::sc_trace(tf_, hit_sig_.out, "rtu0_hit_out_valid_o");
        sc_core::sc_trace(tf_, hit_sig_.out_slot, "rtu0_hit_out_slot_o");
        sc_core::sc_trace(tf_, hit_sig_.spawn, "rtu0_hit_out_spawn_o");
        sc_core::sc_trace(tf_, hit_sig_.head_valid, "rtu0_hit_head_valid_o");
      }
      // RTU 0's pin-level units: their clock and handshakes (the signals the RTL sees).
      if (clock_) {
        sc_core::sc_trace(tf_, clock_->clk, "clk_i");
        sc_core::sc_trace(tf_, clock_->rst_n, "rst_ni");
      }
      if (pins::VtuPort* v = rtus[0]->vtu_port()) {
        sc_core::sc_trace(tf_, v->s.in_valid, "rtu0_vtu_in_valid_i");
        sc_core::sc_trace(tf_, v->s.in_kind, "rtu0_vtu_in_kind_i");
        sc_core::sc_trace(tf_, v->s.in_tag, "rtu0_vtu_in_tag_i");
        sc_core::sc_trace(tf_, v->s.out_valid, "rtu0_vtu_out_valid_o");
        sc_core::sc_trace(tf_, v->s.out_tag, "rtu0_vtu_out_tag_o");
        sc_core::sc_trace(tf_, v->s.out_node0, "rtu0_vtu_out_node0_o");
      }
      if (pins::IstPort* t = rtus[0]->ist_port()) {
        sc_core::sc_trace(tf_, t->s.in_valid, "rtu0_ist_in_valid_i");
        sc_core::sc_trace(tf_, t->s.in_tag, "rtu0_ist_in_tag_i");
        sc_core::sc_trace(tf_, t->s.out_valid, "rtu0_ist_out_valid_o");
        sc_core::sc_trace(tf_, t->s.out_tag, "rtu0_ist_out_tag_o");
        sc_core::sc_trace(tf_, t->s.out_exit, "rtu0_ist_out_exit_o");
        sc_core::sc_trace(tf_, t->s.out_t, "rtu0_ist_out_t_o");
      }
      if (pins::HitPort* h = rtus[0]->hit_port()) {
        sc_core::sc_trace(tf_, h->s.in_valid, "rtu0_hit_in_valid_i");
        sc_core::sc_trace(tf_, h->s.in_tag, "rtu0_hit_in_tag_i");
        sc_core::sc_trace(tf_, h->s.out_valid, "rtu0_hit_out_valid_o");
        sc_core::sc_trace(tf_, h->s.out_tag, "rtu0_hit_out_tag_o");
        sc_core::sc_trace(tf_, h->s.out_spawn, "rtu0_hit_out_spawn_o");
        sc_core::sc_trace(tf_, h->s.out_skip_id, "rtu0_hit_out_skip_id_o");
      }
      if (pins::RguPort* g = rtus[0]->rgu_port()) {
        sc_core::sc_trace(tf_, g->s.start, "rtu0_rgu_start_i");
        sc_core::sc_trace(tf_, g->s.busy, "rtu0_rgu_busy_o");
        sc_core::sc_trace(tf_, g->s.out_valid, "rtu0_rgu_out_valid_o");
        sc_core::sc_trace(tf_, g->s.out_ready, "rtu0_rgu_out_ready_i");
        sc_core::sc_trace(tf_, g->s.out_pixel, "rtu0_rgu_out_pixel_o");
        sc_core::sc_trace(tf_, g->s.out_d_x, "rtu0_rgu_out_d_x_o");
      }
      if (rtus[0]->rgu_rtl()) {
        sc_core::sc_trace(tf_, rgu_sig_.valid, "rtu0_rgu_out_valid_o");
        sc_core::sc_trace(tf_, rgu_sig_.shadow, "rtu0_rgu_out_shadow_o");
        sc_core::sc_trace(tf_, rgu_sig_.slot, "rtu0_rgu_out_slot_o");
        sc_core::sc_trace(tf_, rgu_sig_.pixel, "rtu0_rgu_out_pixel_o");
        sc_core::sc_trace(tf_, rgu_sig_.free, "rtu0_rgu_free_count_o");
        sc_core::sc_trace(tf_, rgu_sig_.busy, "rtu0_rgu_busy_o");
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
  uint64_t pin_edges = 0;  // clock edges given to the pin-level units (frame, without set-up)
  std::string error;       // why the frame stopped early ("" = it ran to its end)

 private:
  struct TrvSignals {
    sc_core::sc_signal<bool> in_valid, head_valid;
    sc_core::sc_signal<uint32_t> in_slot, res_valid, go, fin, acc_valid, rsp_hit, ist_entries;
  };
  struct IstSignals {
    sc_core::sc_signal<bool> head_valid, busy;
    sc_core::sc_signal<uint32_t> hin, acc_valid, rsp_hit, res_valid;
  };
  struct HitSignals {
    sc_core::sc_signal<bool> in, out, spawn, head_valid;
    sc_core::sc_signal<uint32_t> fin, in_slot, out_slot;
  };
  struct RguSignals {
    sc_core::sc_signal<bool> valid, shadow, busy;
    sc_core::sc_signal<uint32_t> slot, pixel, free;
  };
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

  // The thread: the frame, with an error (deadlock, livelock, a refused configuration) kept for
  // simulate() to throw as itself (not wrapped in SystemC's report of an uncaught exception).
  void run() {
    try {
      run_frame();
    } catch (const std::exception& e) {
      error = e.what();  // the thread ends; with no process left, sc_start returns
    }
  }

  void run_frame() {
    const bool tty = cfg_.progress && isatty(2);
    const auto t0 = std::chrono::steady_clock::now();
    auto last = t0;
    const uint64_t pixels = uint64_t(fc_.width) * uint64_t(fc_.height);
    Cycle now = 0, synced = 0;
    std::vector<bool> act(rtus.size());
    if (clock_) setup_pins();
    const sc_core::sc_time t0_sim = sc_core::sc_time_stamp();
    auto sync = [&](Cycle c) {  // SystemC time = t0_sim + c periods
      const sc_core::sc_time t = t0_sim + period_ * double(c);
      if (t > sc_core::sc_time_stamp()) wait(t - sc_core::sc_time_stamp());
      synced = c;
    };
    // Livelock guard, a safety net: looping for the next chance could thrash a cache that holds
    // fewer lines than the rays competing for it (each fill evicting a line before its ray came
    // back for it). The caches' pin rule (systemc/ascache.h: a fill is pinned until its first hit,
    // a miss takes an MSHR only while its set has a way neither pinned nor awaited) guarantees
    // progress, so this is not reached. No ray retired and no work done (a traversal pass that
    // read its line, or a triangle test) for stall_limit cycles stops the frame with an error
    // instead of running forever. The work is read only when no ray retired for stall_limit
    // cycles (a ray may legitimately take longer: one ray of thousands of tests through a
    // one-entry ist queue), so the stop comes within 2 x stall_limit cycles of the last work.
    const Cycle stall_limit = std::max<Cycle>(Cycle(1) << 20, Cycle(cfg_.mem_latency) * 4096);
    uint64_t retired_seen = 0, work_seen = 0;
    Cycle progress_at = 0;
    while (!all_done()) {
      if (fc_.retired != retired_seen) {
        retired_seen = fc_.retired;
        progress_at = now;
      } else if (now - progress_at > stall_limit) {
        const uint64_t work = work_done();
        if (work == work_seen) throw std::runtime_error(livelock_message(now, progress_at));
        work_seen = work;
        progress_at = now;
      }
      bool active = bus.tick(now);
      bool edge = false;
      for (size_t i = 0; i < rtus.size(); ++i) {
        act[i] = rtus[i]->tick(now);
        active |= act[i];
        if (clock_) edge |= rtus[i]->wants_edge();
      }
      if (tf_) trace(now, act);
      if (edge) {
        sync(now);
        clock_->edge();
        ++pin_edges;
        synced = now + 1;
      }
      Cycle next = now + 1;
      if (!active && !all_done()) {
        Cycle t = bus.next_event(now);
        for (const auto& r : rtus) t = std::min(t, r->next_event(now));
        if (t == kNever)
          throw std::runtime_error("cycle model: deadlock at cycle " + std::to_string(now) +
                                   " (no unit can make progress)");
        next = std::max(next, t);
      }
      if (tf_) sync(next);  // the trace sees every cycle boundary the model stops at
      now = next;
      if (!tf_ && now - synced >= (Cycle(1) << 16)) {
        sync(now);
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
    if (now > synced) sync(now);
  }

  // Before cycle 0: reset the pin-level units; with the VTU on and at pin level, the set-up
  // registers (scene box and light) are translated by RTU 0's VTU, as pseudo-nodes (an inner node
  // of axis i with split x leaves as hls::Vtu::shift(x, c[i])), three records of three lanes (lo,
  // hi, light; lane i = axis i); the box then steps outward one ulp (hls::Vtu::box_outward's
  // incrementers).
  void setup_pins() {
    clock_->reset();
    pins::VtuPort* p = rtus[0]->vtu_port();
    if (!p || !fc_.vtu_on) return;
    uint32_t* dst[9];
    uint32_t src[9];
    for (int i = 0; i < 3; ++i) {
      src[i] = fc_.box_stored_lo[i], dst[i] = &fc_.box_lo[i];
      src[3 + i] = fc_.box_stored_hi[i], dst[3 + i] = &fc_.box_hi[i];
      src[6 + i] = fc_.light_stored[i], dst[6 + i] = &fc_.light[i];
    }
    int sent = 0, got = 0;
    for (int cycle = 0; got < 3; ++cycle) {
      if (cycle > 3 + 1000) throw std::runtime_error("vtu: set-up records did not come out");
      if (p->out_valid()) {
        const pins::VtuRec o = p->out();
        for (uint32_t i = 0; i < 3; ++i) *dst[3 * o.tag + i] = uint32_t(o.node[i]);
        ++got;
      }
      if (sent < 3) {
        pins::VtuRec r;
        for (uint32_t i = 0; i < 3; ++i) r.node[i] = (uint64_t(i) << 56) | src[3 * sent + i];
        r.nmask = 7;
        r.tag = uint32_t(sent++);
        p->drive(r);
      } else {
        p->idle();
      }
      clock_->edge();
    }
    for (int i = 0; i < 3; ++i) {
      fc_.box_lo[i] = A::next_down(fc_.box_lo[i]);
      fc_.box_hi[i] = A::next_up(fc_.box_hi[i]);
    }
  }

  // Traversal passes that read their line and triangle tests issued, every RTU (the livelock guard).
  uint64_t work_done() const {
    uint64_t w = 0;
    for (const auto& r : rtus) {
      const RtuStats s = r->stats();
      w += s.trv_busy + s.ist_busy;
    }
    return w;
  }

  std::string livelock_message(Cycle now, Cycle since) const {
    uint64_t node = 0, list = 0, tri = 0, full = 0;
    for (const auto& r : rtus) {
      const RtuStats s = r->stats();
      node += s.node.misses, list += s.list.misses, tri += s.tri.misses;
      full += s.node.set_full + s.list.set_full + s.tri.set_full;
    }
    return "cycle model: livelock: no ray retired and no traversal pass or triangle test from "
           "cycle " + std::to_string(since) + " to " + std::to_string(now) + " (misses node " + std::to_string(node) + ", list " +
           std::to_string(list) + ", tri " + std::to_string(tri) + ", set_full refusals " +
           std::to_string(full) + "; the caches' pin rule should make this unreachable: a bug, " +
           "please report the configuration)";
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
    const Ascache* caches[3] = {&rtus[0]->node, &rtus[0]->list, &rtus[0]->tri};
    for (int c = 0; c < 3; ++c) {
      const Ascache::Probe p = caches[c]->probe(now);
      cache_sig_[c][0].write(p.accesses);
      cache_sig_[c][1].write(p.hits);
      cache_sig_[c][2].write(p.fills);
    }
    if (const TrvRtl* t = rtus[0]->trv_rtl()) {
      const TrvProbe p = t->probe(now);
      trv_sig_.in_valid.write(p.in_valid);
      trv_sig_.in_slot.write(p.in_slot);
      trv_sig_.res_valid.write(p.res_valid);
      trv_sig_.go.write(p.go);
      trv_sig_.fin.write(p.fin);
      trv_sig_.acc_valid.write(p.acc_valid);
      trv_sig_.rsp_hit.write(p.rsp_hit);
      trv_sig_.ist_entries.write(p.ist_entries);
      trv_sig_.head_valid.write(p.head_valid);
    }
    if (const IstRtl* t = rtus[0]->ist_rtl()) {
      const IstProbe p = t->probe(now);
      ist_sig_.hin.write(p.hin);
      ist_sig_.acc_valid.write(p.acc_valid);
      ist_sig_.rsp_hit.write(p.rsp_hit);
      ist_sig_.res_valid.write(p.res_valid);
      ist_sig_.head_valid.write(p.head_valid);
      ist_sig_.busy.write(p.busy);
    }
    if (const HitRtl* h = rtus[0]->hit_rtl()) {
      const HitProbe p = h->probe(now);
      hit_sig_.fin.write(p.fin);
      hit_sig_.in.write(p.in);
      hit_sig_.in_slot.write(p.in_slot);
      hit_sig_.out.write(p.out);
      hit_sig_.out_slot.write(p.out_slot);
      hit_sig_.spawn.write(p.spawn);
      hit_sig_.head_valid.write(p.head_valid);
    }
    if (const RguRtl* g = rtus[0]->rgu_rtl()) {
      const RguIssue x = rtus[0]->rgu.rtl_probe(now);
      rgu_sig_.valid.write(x.valid);
      rgu_sig_.shadow.write(x.valid && x.shadow);
      rgu_sig_.slot.write(x.slot);
      rgu_sig_.pixel.write(x.valid && !x.shadow ? x.pixel : 0);
      rgu_sig_.free.write(g->free_slots());
      rgu_sig_.busy.write(g->busy());
    }
  }

  sc_core::sc_time period_;
  sc_core::sc_trace_file* tf_ = nullptr;
  sc_core::sc_signal<uint64_t> sig_cycle_, sig_retired_, sig_bus_bytes_;
  sc_core::sc_signal<uint32_t> sig_bus_outstanding_;
  std::vector<std::unique_ptr<RtuSignals>> rsig_;
  sc_core::sc_signal<uint32_t> cache_sig_[3][3];  // RTU 0: node, list, tri x accesses, hits, fills
  TrvSignals trv_sig_;
  IstSignals ist_sig_;
  HitSignals hit_sig_;
  RguSignals rgu_sig_;
};

}  // namespace raycore::sc
