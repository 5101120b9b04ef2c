// systemc/ist.h - the intersection unit: one test (hls::ist_test: Wald's, or the watertight one
// with --ist watertight, the image's record kind) issued per cycle into a
// pipeline of ist_latency cycles (the sum of its stage latencies; an early exit frees the slot but
// the result still leaves after the full latency). The triangle record comes from the triangle
// cache; on a miss the request loops to the back of the input queue, at the end of the next
// cycle (the cache's answer is registered: a miss's entry waits a cycle outside the queue, and the
// queue's room counts it; it is ready the cycle after it is back). Every test of a leaf uses the
// leaf-entry tmax; results are reduced in list order (closest, ties to the earliest entry) so the
// outcome equals the golden tracer's sequential tests with tmax updated after each hit. A record
// whose id is the ray's skip_id (skip-origin) is not tested (as the golden tracer).
//
// Three views (SimConfig::ist_view): the transaction model (hls::ist_wald at issue, the result
// delayed by the latency; default); the pin-level SystemC twin of rtl/units/ist.v
// (systemc/pins/ist.h, --pins ist), one per unit, driven one test per cycle, its result, latency
// cycles later, joining the same result queue (a skipped record still occupies its issue slot, its
// result ignored); or the whole unit in RTL (--rtl ist: rtl/units/ist_unit.v, the queue, the
// triangle-cache accesses, the ist.v pipelines and the result delay, systemc/ist_rtl.h), whose
// results leaving are reduced here (or by trv_unit.v). Same cycles and bits.
#pragma once

#include <systemc>

#include "hls/ist.h"
#include "hls/wald.h"
#include "systemc/ist_rtl.h"
#include "systemc/pins/ist.h"
#include "systemc/slot.h"

#include <array>
#include <vector>

namespace raycore::sc {

template <class A>
class Ist : public sc_core::sc_module {
  using F = typename A::Fmt;

 public:
  Ist(sc_core::sc_module_name name, FrameCtx& fc, RtuChannels& ch, RtuStats& st, uint32_t latency,
      uint32_t units = 1)
      : sc_core::sc_module(name), fc_(fc), ch_(ch), st_(st), lat_(latency), units_(units) {
    if (units_ < 1 || units_ > 16) throw std::invalid_argument("ist units must be 1..16");
  }

  // The pin-level view: one ist.v (twin or RTL) per unit; unit u drives ports[u].
  void bind(const std::vector<pins::IstPort*>& ports) {
    if (ports.size() != units_) throw std::logic_error("ist: one pin-level unit per ist unit");
    ports_ = ports;
    for (pins::IstPort* p : ports_) p->config(fc_.margins);  // the per-frame margin registers
  }
  // The whole unit in RTL (--rtl ist): it holds the queue, issues the tests and delays the results.
  void bind_rtl(IstRtl* r) { rtl_ = r; }
  const IstRtl* rtl() const { return rtl_; }
  bool wants_edge() const { return edge_; }

  bool tick(Cycle now) {
    // Last cycle's leaves ended by their last result back in the trv's queue, the first of this
    // cycle's pushes, ready the next cycle (rtl/units/trv_unit.v registers them: rq_*).
    const bool back = !done_.empty();
    for (uint16_t s : done_) ch_.trv_q.push(s, now + 1);
    done_.clear();
    if (rtl_) {
      left_.clear();
      const bool active = rtl_->tick(now, left_) || back;
      for (const IstRes& o : left_) leave(o);
      return active;
    }
    bool active = back;
    edge_ = false;
    for (pins::IstPort* p : ports_) {
      if (!p->out_valid()) continue;  // a result the pin-level unit put out at the last edge
      const pins::IstOutRec x = p->out();
      const Side& e = side_[x.tag % side_.size()];
      IstRes o;
      o.slot = e.slot;
      o.pos = e.pos;
      if (!e.skip && x.exit == uint32_t(hls::IstExit::hit)) {
        o.hit = true;
        o.t = hls::t_key<F>(x.t);  // ist.v's F t as the key
        o.den = x.den;
        o.id = e.id;
        o.k = e.k;
        o.nu = e.nu;
        o.nv = e.nv;
        o.nd = e.nd;
      }
      ch_.ist_pipe.push(o, now + ch_.tri->hit_latency);
      --in_flight_;
      edge_ = true;
    }
    // Last cycle's misses back behind the others (before this cycle's hand-offs), ready next cycle.
    for (const IstReq& q : missed_) ch_.ist_q.push(q, now + 1);
    missed_.clear();
    // Results leaving the pipeline.
    while (ch_.ist_pipe.can_pop(now)) {
      leave(ch_.ist_pipe.pop());
      active = true;
    }
    // Issue one test per unit (they share the triangle cache: one access per unit and cycle). A
    // miss takes its unit's issue slot.
    bool more = true;  // the units after the first that finds nothing ready idle this cycle
    for (uint32_t u = 0; u < units_; ++u) {
      if (more && issue(now, u)) {
        active = true;
        continue;
      }
      more = false;
      idle_pins(u);
    }
    return active || edge_;
  }

  // The RTL's clock edge, after the trv's hand-offs of this cycle (RtuChannels::ist_q).
  void edge(Cycle now) {
    if (rtl_) rtl_->edge(now);
  }

  Cycle next_event(Cycle now) const {
    if (!done_.empty()) return now + 1;
    if (rtl_) return rtl_->next_event(now);
    if (!missed_.empty() || (!ports_.empty() && in_flight_ != 0)) return now + 1;
    return std::min(ch_.ist_pipe.head_ready(), ch_.ist_q.head_ready());
  }

 private:
  // A result leaving the unit: into its ray's leaf record (the closest, ties to the earliest list
  // position), the leaf's last result puts the ray back in the trv's queue in the next cycle.
  void leave(const IstRes& o) {
    if (ch_.ist_results) {  // the trv in RTL reduces them (systemc/trv_rtl.h)
      ch_.ist_results->push_back(o);
      return;
    }
    Slot& r = ch_.slots[o.slot];
    if (o.hit) {
      Best& b = r.leaf;
      if (!b.found || hls::key_lt<F>(o.t, b.t) || (hls::eq<hls::KeyFormat<F>>(o.t, b.t) && o.pos < b.pos))
        b = Best{true, o.t, o.den, o.pos, o.id, o.k, o.nu, o.nv, o.nd};
    }
    if (++r.results == r.list_count) {
      r.state = SlotState::leaf_done;
      done_.push_back(o.slot);  // back in the trv's queue in the next cycle (tick)
    }
  }

  // Unit u issues the test at the head of the queue (false: none ready).
  bool issue(Cycle now, uint32_t u) {
    if (!ch_.ist_q.can_pop(now)) return false;
    const uint32_t rb = fc_.header.tri_bytes;
    const IstReq q = ch_.ist_q.front();
    const uint32_t lb = ch_.tri->line_bytes();
    const uint64_t byte = uint64_t(q.tri) * rb;
    const uint8_t* line = ch_.tri->access(byte / lb);
    // The entry leaves the queue; its room is the trv's from the next cycle on (ist_room).
    ch_.ist_q.pop();
    if (ch_.ist_taken_at != now) ch_.ist_taken = 0;
    ch_.ist_taken_at = now;
    ++ch_.ist_taken;
    if (!line) {
      ++st_.ist_tri_miss;
      missed_.push_back(q);  // loop: back behind the others at the end of the next cycle
      idle_pins(u);
      return true;
    }
    ++st_.ist_busy;
    const hls::WaldTri<F> w = hls::decode_tri<F>(line + byte % lb, hls::IstKind(fc_.header.ist));
    const Slot& r = ch_.slots[q.slot];
    if (!ports_.empty()) {
      drive_pins(*ports_[u], q, w, r);
      return true;
    }
    IstRes o;
    o.slot = q.slot;
    o.pos = q.pos;
    if (w.id != r.skip_id) {
      ++st_.tri_tests;
      const hls::IstOut x = hls::ist_test_key<A>(w, r.ray.o, r.ray.d, r.ray.tmin, r.tmax, fc_.margins);
      if (x.exit == hls::IstExit::hit) {
        o.hit = true;
        o.t = x.tk;
        o.den = x.den;
        o.id = w.id;
        o.k = w.k;
        o.nu = w.c[hls::kNU];
        o.nv = w.c[hls::kNV];
        o.nd = w.c[hls::kND];
      }
    }
    ch_.ist_pipe.push(o, now + lat_ + ch_.tri->hit_latency);
    return true;
  }

  struct Side {  // what travels beside a test in the pin-level unit (its tag indexes this ring)
    uint16_t slot = 0;
    bool skip = false;
    uint32_t pos = 0, id = 0, k = 0, nu = 0, nv = 0, nd = 0;
  };

  void drive_pins(pins::IstPort& port, const IstReq& q, const hls::WaldTri<F>& w, const Slot& r) {
    if (!port.in_ready()) throw std::logic_error("ist: pin-level unit not ready with out_ready high");
    pins::IstIn in;
    in.k = w.k;
    for (int i = 0; i < 9; ++i) in.c[i] = w.c[i];
    for (int i = 0; i < 3; ++i) {
      in.o[i] = r.ray.o[i];
      in.d[i] = r.ray.d[i];
    }
    in.tmin = r.ray.tmin;
    in.tmax = hls::key_t<F>(r.tmax);  // ist.v (Wald's) compares in F: a Wald frame's keys are F values
    in.tag = next_tag_;
    Side& e = side_[next_tag_ % side_.size()];
    e = Side{q.slot, w.id == r.skip_id, q.pos, w.id, w.k, w.c[hls::kNU], w.c[hls::kNV], w.c[hls::kND]};
    if (!e.skip) ++st_.tri_tests;
    next_tag_ = (next_tag_ + 1) & 0xFFFFu;  // TAG_BITS 16
    port.drive(in);
    ++in_flight_;
    edge_ = true;
  }
  bool idle_pins(uint32_t u) {
    if (ports_.empty()) return false;
    ports_[u]->idle();
    edge_ |= in_flight_ != 0;
    return edge_;
  }

  FrameCtx& fc_;
  RtuChannels& ch_;
  RtuStats& st_;
  uint32_t lat_;
  uint32_t units_;
  std::vector<pins::IstPort*> ports_;  // pin-level view: one per unit (empty: the model)
  IstRtl* rtl_ = nullptr;              // the whole unit in RTL (--rtl ist)
  std::vector<IstRes> left_;           // its results leaving this cycle
  std::vector<uint16_t> done_;         // this cycle's ended leaves, back in the trv queue next
  std::vector<IstReq> missed_;         // this cycle's misses, back in the queue in the next
  std::array<Side, 1024> side_{};
  uint32_t next_tag_ = 0, in_flight_ = 0;
  bool edge_ = false;
};

}  // namespace raycore::sc
