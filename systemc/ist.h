// systemc/ist.h - the intersection unit: one Wald test (hls::ist_wald) issued per cycle into a
// pipeline of ist_latency cycles (the sum of its stage latencies; an early exit frees the slot but
// the result still leaves after the full latency). The triangle record comes from the triangle
// cache; on a miss the request loops to the back of the input queue. Every test of a leaf uses the
// leaf-entry tmax; results are reduced in list order (closest, ties to the earliest entry) so the
// outcome equals the golden tracer's sequential tests with tmax updated after each hit. A record
// whose id is the ray's skip_id (skip-origin) is not tested (as the golden tracer).
#pragma once

#include <systemc>

#include "hls/ist.h"
#include "hls/wald.h"
#include "systemc/slot.h"

namespace raycore::sc {

template <class A>
class Ist : public sc_core::sc_module {
  using F = typename A::Fmt;

 public:
  Ist(sc_core::sc_module_name name, FrameCtx& fc, RtuChannels& ch, RtuStats& st, uint32_t latency)
      : sc_core::sc_module(name), fc_(fc), ch_(ch), st_(st), lat_(latency) {}

  bool tick(Cycle now) {
    bool active = false;
    // Results leaving the pipeline.
    while (ch_.ist_pipe.can_pop(now)) {
      const IstRes o = ch_.ist_pipe.pop();
      Slot& r = ch_.slots[o.slot];
      if (o.hit) {
        Best& b = r.leaf;
        if (!b.found || A::lt(o.t, b.t) || (A::eq(o.t, b.t) && o.pos < b.pos))
          b = Best{true, o.t, o.den, o.pos, o.id, o.k, o.nu, o.nv, o.nd};
      }
      if (++r.results == r.list_count) {
        r.state = SlotState::leaf_done;
        ch_.trv_q.push(o.slot, now + 1);
      }
      active = true;
    }
    // Issue one test.
    if (!ch_.ist_q.can_pop(now)) return active;
    constexpr uint32_t rb = uint32_t(hls::tri_record_bytes<F>());
    const IstReq q = ch_.ist_q.front();
    const uint32_t lb = ch_.tri->line_bytes();
    const uint64_t byte = uint64_t(q.tri) * rb;
    const uint8_t* line = ch_.tri->access(byte / lb);
    if (!line) {
      ++st_.ist_tri_miss;
      ch_.ist_q.pop();
      ch_.ist_q.push(q, now + 1);  // loop: try again behind the others
      return true;
    }
    ch_.ist_q.pop();
    ++st_.ist_busy;
    const hls::WaldTri<F> w = hls::decode_tri<F>(line + byte % lb);
    const Slot& r = ch_.slots[q.slot];
    IstRes o;
    o.slot = q.slot;
    o.pos = q.pos;
    if (w.id != r.skip_id) {
      ++st_.tri_tests;
      const hls::IstOut x = hls::ist_wald<A>(w.k, w.c, r.ray.o, r.ray.d, r.ray.tmin, r.tmax);
      if (x.exit == hls::IstExit::hit) {
        o.hit = true;
        o.t = x.t;
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

  Cycle next_event() const { return std::min(ch_.ist_pipe.head_ready(), ch_.ist_q.head_ready()); }

 private:
  FrameCtx& fc_;
  RtuChannels& ch_;
  RtuStats& st_;
  uint32_t lat_;
};

}  // namespace raycore::sc
