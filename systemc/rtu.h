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
#include "systemc/hit_rtl.h"
#include "systemc/ist.h"
#include "systemc/ist_rtl.h"
#include "systemc/membus.h"
#include "systemc/pins/clock.h"
#include "systemc/pins/rgu.h"
#include "systemc/pins/rtl.h"
#include "systemc/rgu.h"
#include "systemc/rgu_rtl.h"
#include "systemc/slot.h"
#include "systemc/trv.h"
#include "systemc/trv_rtl.h"
#include "systemc/vtu.h"

namespace raycore::sc {

template <class A>
class Rtu : public sc_core::sc_module {
  using F = typename A::Fmt;
  static constexpr hls::Rounding R = A::rounding;

 public:
  Rtu(sc_core::sc_module_name name, FrameCtx& fc, const SimConfig& cfg, int index, bool vtu_on,
      const hls::Vtu<F, R>& vtu, Membus& bus, pins::PinClock* clock)
      : sc_core::sc_module(name),
        node("node_cache", cfg.node_cache, fc.header.node_offset, cfg.node_cache.line_bytes),
        list("list_cache", cfg.list_cache, fc.header.list_offset, cfg.list_cache.line_bytes),
        tri("tri_cache", cfg.tri_cache, fc.header.tri_offset,
            fc.tri_line_records * uint32_t(fc.header.tri_bytes)),
        vtu_unit("vtu", vtu_on, vtu, cfg.vtu_depth, fc.header, {&node, &list, &tri},
                 cfg.node_cache.mshrs + cfg.list_cache.mshrs + cfg.tri_cache.mshrs),
        ch_(make_channels(cfg, ist_latency_for(cfg, hls::IstKind(fc.header.ist)))),
        rgu("rgu", fc, ch_, st_, index, cfg.rtus, cfg.tile, cfg.rgu_latency),
        trv("trv", fc, ch_, st_, cfg.trv_latency, cfg.trv_pipes, cfg.trv_fuse),
        ist("ist", fc, ch_, st_, ist_latency_for(cfg, hls::IstKind(fc.header.ist)), cfg.ist_units),
        hit("hit", fc, ch_, st_, cfg.hit_latency),
        slots_(cfg.rays_in_flight) {
    ch_.node = &node;
    ch_.list = &list;
    ch_.tri = &tri;
    bus.add_requester(&node.req(), &vtu_unit, kNodePort);
    bus.add_requester(&list.req(), &vtu_unit, kListPort);
    bus.add_requester(&tri.req(), &vtu_unit, kTriPort);
    bind_pins(fc, cfg, clock);
  }

  // The pin-level units of this RTU (SystemC twins or Verilated RTL in the units' places).
  void bind_pins(FrameCtx& fc, const SimConfig& cfg, pins::PinClock* clock) {
    if (cfg.ascache_view == UnitView::twin)
      throw ConfigError("ascache has no pin-level twin in the frame (the frame's caches answer "
                        "within the cycle; ascache.v's pin twin answers a cycle later): use "
                        "--rtl ascache");
    if (cfg.ascache_view == UnitView::rtl)
      for (Ascache* c : {&node, &list, &tri}) {
        auto r = make_rtl_ascache(c->sets(), c->ways(), c->line_bytes(), c->mshrs_total());
        if (!r)
          throw ConfigError(std::string("no Verilated ascache for the ") + c->basename() + " (" +
                            std::to_string(c->sets()) + " sets x " + std::to_string(c->ways()) +
                            " ways x " + std::to_string(c->line_bytes()) + " B, " +
                            std::to_string(c->mshrs_total()) + " MSHRs) in this build; built: " +
                            rtl_ascache_built());
        // A cycle's accesses to one cache: one per trv pipe (node, list), one per ist unit (tri).
        const uint32_t most = c == &tri ? cfg.ist_units : cfg.trv_pipes;
        if (most > r->ports())
          throw ConfigError("--rtl ascache: " + r->name() + " takes " +
                            std::to_string(r->ports()) + " accesses a cycle, the " +
                            c->basename() + " may get " + std::to_string(most) + " (" +
                            (c == &tri ? "--ist-units" : "--trv-pipes") + ")");
        c->bind_rtl(std::move(r));
      }
    if (cfg.trv_view == UnitView::twin)
      throw ConfigError("trv has no pin-level SystemC twin (its transaction model is the twin of "
                        "rtl/units/trv_unit.v): use --rtl trv");
    if (cfg.trv_view == UnitView::rtl) {
      trv_rtl_ = make_rtl_trv(hls::format_id<F>(), R, fc, ch_, cfg);
      rgu.set_entry_delay(0);  // trv_unit.v delays the entering ray itself (its clip)
      if (!trv_rtl_)
        throw ConfigError(std::string("no Verilated trv_unit for ") +
                          hls::format_name(hls::format_id<F>()) + " " + hls::rounding_name(R) +
                          " in this build; built: " + rtl_trv_built());
    }
    if (cfg.vtu_view != UnitView::model) {
      const unsigned stages = pin_stages("vtu", cfg.vtu_depth, kVtuLevels, "--vtu-depth");
      if (cfg.vtu_view == UnitView::twin)
        vtu_port_ = std::make_unique<pins::VtuPortT<pins::VtuTwin<F, R>>>(
            "vtu_pins", "SystemC twin", clock->clk, clock->rst_n, stages);
      else
        vtu_port_ = pins::make_rtl_vtu(hls::format_id<F>(), R, stages, "vtu_rtl", clock->clk,
                                       clock->rst_n);
      if (!vtu_port_) no_rtl("vtu", stages);
      vtu_unit.bind(vtu_port_.get());
    }
    if (cfg.ist_view == UnitView::rtl) {  // the whole unit: rtl/units/ist_unit.v
      const hls::IstKind kind = hls::IstKind(fc.header.ist);  // ist.v (10 levels) or ist_watertight.v (18)
      const bool wt = kind == hls::IstKind::watertight;
      const unsigned stages = pin_stages("ist", ist_latency_for(cfg, kind), ist_levels(kind), "--ist-latency");
      ist_rtl_ = make_rtl_ist_unit(hls::format_id<F>(), R, stages, kind, fc, ch_, cfg);
      if (!ist_rtl_)
        throw ConfigError(std::string("no Verilated ist_unit for ") +
                          hls::format_name(hls::format_id<F>()) + " " + hls::rounding_name(R) +
                          (wt ? " watertight" : "") + " STAGES=" + std::to_string(stages) +
                          " in this build; built: " + rtl_ist_unit_built());
      ist.bind_rtl(ist_rtl_.get());
    }
    if (cfg.ist_view == UnitView::twin) {  // one SystemC twin of rtl/units/ist.v per ist unit
      const unsigned stages = pin_stages("ist", ist_latency_for(cfg, hls::IstKind::wald), kIstLevels, "--ist-latency");
      std::vector<pins::IstPort*> ports;
      for (uint32_t u = 0; u < cfg.ist_units; ++u) {
        const std::string n = u == 0 ? std::string("ist") : "ist" + std::to_string(u);
        ist_ports_.push_back(std::make_unique<pins::IstPortT<pins::IstTwin<A>>>(
            (n + "_pins").c_str(), "SystemC twin", clock->clk, clock->rst_n, stages));
        ports.push_back(ist_ports_.back().get());
      }
      ist.bind(ports);
    }
    if (cfg.hit_view == UnitView::rtl) {  // the whole unit: rtl/units/hit_unit.v
      const unsigned stages = pin_stages("hit", cfg.hit_latency, kHitLevels, "--hit-latency");
      hit_rtl_ = make_rtl_hit_unit(hls::format_id<F>(), R, stages, ch_, cfg);
      if (!hit_rtl_)
        throw ConfigError(std::string("no Verilated hit_unit for ") +
                          hls::format_name(hls::format_id<F>()) + " " + hls::rounding_name(R) +
                          " STAGES=" + std::to_string(stages) + " in this build; built: " +
                          rtl_hit_unit_built());
      hit.bind_rtl(hit_rtl_.get());
    }
    if (cfg.hit_view == UnitView::twin) {  // the SystemC twin of rtl/units/hit.v
      const unsigned stages = pin_stages("hit", cfg.hit_latency, kHitLevels, "--hit-latency");
      hit_port_ = std::make_unique<pins::HitPortT<pins::HitTwin<A>>>(
          "hit_pins", "SystemC twin", clock->clk, clock->rst_n, stages);
      hit.bind(hit_port_.get());
    }
    if (cfg.rgu_view != UnitView::model) {
      const unsigned stages = pin_stages("rgu", cfg.rgu_latency, kRguLevels, "--rgu-latency");
      const uint32_t tile = cfg.tile;
      if (tile < 2 || tile > 256 || (tile & (tile - 1)) != 0)
        throw ConfigError("rgu at pin level walks tiles of 2^TILE_BITS pixels a side: tile must "
                          "be a power of two 2..256, not " + std::to_string(tile));
      if (uint32_t(fc.width) > 65535 || uint32_t(fc.height) > 65535)
        throw ConfigError("rgu at pin level: frames up to 65535 pixels a side (rgu.v's "
                          "COORD_BITS 16)");
      if (cfg.rgu_view == UnitView::twin) {  // the primary rays at rgu.v's pins
        rgu_port_ = std::make_unique<pins::RguPortT<pins::RguTwin<A>>>(
            "rgu_pins", "SystemC twin", clock->clk, clock->rst_n, stages, int(tile));
        rgu.bind(rgu_port_.get());
      } else {  // the whole unit: rtl/units/rgu_unit.v
        rgu_rtl_ = make_rtl_rgu_unit(hls::format_id<F>(), R, stages, tile, cfg);
        if (!rgu_rtl_)
          throw ConfigError(std::string("no Verilated rgu_unit for ") +
                            hls::format_name(hls::format_id<F>()) + " " + hls::rounding_name(R) +
                            " STAGES=" + std::to_string(stages) + " with " + std::to_string(tile) +
                            " x " + std::to_string(tile) + " tiles in this build; built: " +
                            rtl_rgu_unit_built());
        rgu.bind_rtl(rgu_rtl_.get());
      }
    }
  }
  pins::VtuPort* vtu_port() { return vtu_port_.get(); }
  pins::IstPort* ist_port() { return ist_ports_.empty() ? nullptr : ist_ports_[0].get(); }
  pins::HitPort* hit_port() { return hit_port_.get(); }
  pins::RguPort* rgu_port() { return rgu_port_.get(); }
  const TrvRtl* trv_rtl() const { return trv_rtl_.get(); }
  const IstRtl* ist_rtl() const { return ist_rtl_.get(); }
  const HitRtl* hit_rtl() const { return hit_rtl_.get(); }
  const RguRtl* rgu_rtl() const { return rgu_rtl_.get(); }
  bool wants_edge() const {
    return vtu_unit.wants_edge() || ist.wants_edge() || hit.wants_edge() || rgu.wants_edge();
  }

  bool tick(Cycle now) {
    for (Ascache* c : {&node, &list, &tri}) c->advance(now);  // last cycle's fills installed
    bool a = vtu_unit.tick(now);
    a |= hit.tick(now);
    a |= ist.tick(now);
    if (trv_rtl_) {  // the RTL's cycle: pipes, then the rgu's ray and the clock edge
      a |= trv_rtl_->tick(now);
      a |= rgu.tick(now);
      trv_rtl_->edge(now);
    } else {
      a |= trv.tick(now);
      a |= rgu.tick(now);
    }
    ist.edge(now);  // the trv's hand-offs of this cycle into the ist's RTL (if bound)
    hit.edge(now);  // and its finished rays into the hit unit's
    return a;
  }
  Cycle next_event(Cycle now) const {
    Cycle t = std::min({vtu_unit.next_event(now), hit.next_event(now), ist.next_event(now),
                        trv_rtl_ ? trv_rtl_->next_event(now) : trv.next_event(),
                        rgu.next_event(now)});
    return t;
  }
  bool done() const { return !rgu.primaries_left() && rgu.free_slots() == slots_; }
  RtuStats stats() const {
    RtuStats s = st_;
    s.node = node.stats();
    s.list = list.stats();
    s.tri = tri.stats();
    s.vtu_busy = vtu_unit.busy();
    s.vtu_paired = vtu_unit.paired();
    s.vtu_fill_waits = vtu_unit.fill_waits();
    if (trv_rtl_) trv_rtl_->stats(s);
    if (ist_rtl_) ist_rtl_->stats(s);
    if (hit_rtl_) s.hit_busy = hit_rtl_->busy();
    if (rgu_rtl_) {
      rgu_rtl_->stats(s);
      s.rgu_busy = s.primary_rays + s.shadow_rays;
    }
    return s;
  }
  size_t in_flight() const { return slots_ - rgu.free_slots(); }
  uint64_t rgu_primaries() const { return st_.primary_rays; }

  Ascache node, list, tri;
  VtuUnit<F, R> vtu_unit;

 private:
  // A pin-level unit has levels x STAGES registers: the model's latency must be such a multiple.
  static unsigned pin_stages(const char* unit, uint32_t latency, uint32_t levels, const char* opt) {
    if (latency == 0 || latency % levels != 0 || latency / levels > 64)
      throw ConfigError(std::string(unit) + " at pin level has " + std::to_string(levels) +
                        " operator levels of STAGES registers: " + opt + " must be " +
                        std::to_string(levels) + " x STAGES (STAGES 1..64), not " +
                        std::to_string(latency));
    return latency / levels;
  }
  static void no_rtl(const char* unit, unsigned stages) {
    throw ConfigError(std::string("no Verilated ") + unit + " for " +
                      hls::format_name(hls::format_id<F>()) + " " + hls::rounding_name(R) +
                      " STAGES=" + std::to_string(stages) + " in this build; built: " +
                      pins::rtl_models_built());
  }

  static RtuChannels make_channels(const SimConfig& cfg, uint32_t ist_latency) {
    if (cfg.rays_in_flight == 0 || cfg.rays_in_flight > 65535)
      throw std::invalid_argument("rays in flight must be 1..65535");
    RtuChannels ch;
    ch.slots.resize(cfg.rays_in_flight);
    for (uint32_t i = cfg.rays_in_flight; i-- > 0;) ch.free_slots.push_back(uint16_t(i));
    ch.trv_q.reset(cfg.rays_in_flight);
    ch.ist_q.reset(std::max<uint32_t>(cfg.ist_queue, 1));
    ch.ist_pipe.reset(size_t(std::max<uint32_t>(cfg.ist_units, 1)) *
                      (ist_latency + cfg.tri_cache.hit_latency + 2));
    ch.hit_q.reset(cfg.rays_in_flight);
    ch.shadow_q.reset(cfg.rays_in_flight);
    return ch;
  }

  RtuStats st_;
  RtuChannels ch_;
  std::unique_ptr<pins::VtuPort> vtu_port_;
  std::vector<std::unique_ptr<pins::IstPort>> ist_ports_;
  std::unique_ptr<IstRtl> ist_rtl_;  // --rtl ist: rtl/units/ist_unit.v in the ist's place
  std::unique_ptr<HitRtl> hit_rtl_;  // --rtl hit: rtl/units/hit_unit.v in the hit unit's place
  std::unique_ptr<RguRtl> rgu_rtl_;  // --rtl rgu: rtl/units/rgu_unit.v in the rgu's place
  std::unique_ptr<TrvRtl> trv_rtl_;  // --rtl trv: rtl/units/trv_unit.v in trv's (and the ist
                                     // reduction's) place
  std::unique_ptr<pins::HitPort> hit_port_;
  std::unique_ptr<pins::RguPort> rgu_port_;

 public:
  Rgu<A> rgu;
  Trv<A> trv;
  Ist<A> ist;
  Hit<A> hit;

 private:
  size_t slots_;
};

}  // namespace raycore::sc
