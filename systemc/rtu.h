// systemc/rtu.h - one ray-tracing unit: rgu -> trv <-> ist -> hit (-> rgu for shadow rays), the
// three AS caches and the vtu on their fill path. Units are ticked in a fixed order each cycle;
// every channel delivers at least one cycle after the push, so the order only decides who sees a
// freed queue slot first (deterministic).
#pragma once

#include <systemc>

#include <algorithm>
#include <memory>
#include <string>

#include "systemc/ascache.h"
#include "systemc/config.h"
#include "systemc/hit.h"
#include "systemc/ist.h"
#include "systemc/membus.h"
#include "systemc/rgu.h"
#include "systemc/slot.h"
#include "systemc/trv.h"
#include "systemc/vtu.h"

namespace raycore::sc {

template <class A>
class Rtu : public sc_core::sc_module {
  using F = typename A::Fmt;
  static constexpr hls::Rounding R = A::rounding;

 public:
  Rtu(sc_core::sc_module_name name, FrameCtx& fc, const SimConfig& cfg, int index, bool vtu_on,
      const hls::Vtu<F, R>& vtu, Membus& bus)
      : sc_core::sc_module(name),
        node("node_cache", cfg.node_cache, fc.header.node_offset, cfg.node_cache.line_bytes),
        list("list_cache", cfg.list_cache, fc.header.list_offset, cfg.list_cache.line_bytes),
        tri("tri_cache", cfg.tri_cache, fc.header.tri_offset,
            fc.tri_line_records * uint32_t(hls::tri_record_bytes<F>())),
        vtu_unit("vtu", vtu_on, vtu, cfg.vtu_depth, fc.header, {&node, &list, &tri},
                 cfg.node_cache.mshrs + cfg.list_cache.mshrs + cfg.tri_cache.mshrs),
        ch_(make_channels(cfg)),
        rgu("rgu", fc, ch_, st_, index, cfg.rtus, cfg.tile),
        trv("trv", fc, ch_, st_, cfg.trv_latency),
        ist("ist", fc, ch_, st_, cfg.ist_latency),
        hit("hit", fc, ch_, st_, cfg.hit_latency),
        slots_(cfg.rays_in_flight) {
    ch_.node = &node;
    ch_.list = &list;
    ch_.tri = &tri;
    bus.add_requester(&node.req(), &vtu_unit, kNodePort);
    bus.add_requester(&list.req(), &vtu_unit, kListPort);
    bus.add_requester(&tri.req(), &vtu_unit, kTriPort);
  }

  bool tick(Cycle now) {
    node.now = list.now = tri.now = now;
    bool a = vtu_unit.tick(now);
    a |= hit.tick(now);
    a |= ist.tick(now);
    a |= trv.tick(now);
    a |= rgu.tick(now);
    return a;
  }
  Cycle next_event(Cycle now) const {
    Cycle t = std::min({vtu_unit.next_event(), hit.next_event(), ist.next_event(), trv.next_event(),
                        rgu.next_event(now)});
    return t;
  }
  bool done() const { return !rgu.primaries_left() && ch_.free_slots.size() == slots_; }
  RtuStats stats() const {
    RtuStats s = st_;
    s.node = node.stats();
    s.list = list.stats();
    s.tri = tri.stats();
    s.vtu_busy = vtu_unit.busy();
    return s;
  }
  size_t in_flight() const { return slots_ - ch_.free_slots.size(); }
  uint64_t rgu_primaries() const { return st_.primary_rays; }

  Ascache node, list, tri;
  VtuUnit<F, R> vtu_unit;

 private:
  static RtuChannels make_channels(const SimConfig& cfg) {
    if (cfg.rays_in_flight == 0 || cfg.rays_in_flight > 65535)
      throw std::invalid_argument("rays in flight must be 1..65535");
    RtuChannels ch;
    ch.slots.resize(cfg.rays_in_flight);
    for (uint32_t i = cfg.rays_in_flight; i-- > 0;) ch.free_slots.push_back(uint16_t(i));
    ch.trv_q.reset(cfg.rays_in_flight);
    ch.ist_q.reset(std::max<uint32_t>(cfg.ist_queue, 1));
    ch.ist_pipe.reset(cfg.ist_latency + cfg.tri_cache.hit_latency + 2);
    ch.hit_q.reset(cfg.rays_in_flight);
    ch.shadow_q.reset(cfg.rays_in_flight);
    return ch;
  }

  RtuStats st_;
  RtuChannels ch_;

 public:
  Rgu<A> rgu;
  Trv<A> trv;
  Ist<A> ist;
  Hit<A> hit;

 private:
  size_t slots_;
};

}  // namespace raycore::sc
