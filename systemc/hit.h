// systemc/hit.h - the hit unit: for a finished primary ray the hit point and the shadow ray
// (hls::hit_shadow with the configured spawn strategy; with --shadow-spawn all also when the light
// is behind), handed to the rgu in the same slot; for a finished shadow ray the light decision;
// the pixel written to the frame (hls::shade_pixel, the golden tracer's inputs). One ray per cycle
// enters the unit (a primary hit, a primary miss or a finished shadow ray); everything happens when
// it leaves, hit_latency cycles later, as in a pipelined unit: the slot is freed (a miss, a shadow
// ray, a hit without a shadow ray), the pixel written, or the shadow ray handed to the rgu.
//
// Three views (SimConfig::hit_view): the transaction model (hls::hit_shadow at entry, applied at
// leave; default); the pin-level SystemC twin of rtl/units/hit.v (systemc/pins/hit.h, --pins hit),
// every ray driven into it (the result is read only for a primary hit); or the whole unit in RTL
// (--rtl hit: rtl/units/hit_unit.v, the hit queue, the slot read, hit.v and the decision to free
// the slot or keep the shadow ray, systemc/hit_rtl.h), whose leaving rays are applied here (the
// frame buffer is the host's) after checking the RTL's decision. Same cycles and bits.
#pragma once

#include <systemc>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "hls/hit.h"
#include "hls/trace.h"
#include "systemc/hit_rtl.h"
#include "systemc/pins/hit.h"
#include "systemc/slot.h"
#include "systemc/slot_unit.h"

namespace raycore::sc {

// The hit unit's per-frame registers (the light is the VTU's, translated at set-up).
template <class A>
pins::HitConfig hit_config(const FrameCtx& fc) {
  pins::HitConfig c;
  for (int i = 0; i < 3; ++i) c.light[i] = fc.light[i];
  c.tmin = fc.tmin;
  c.sp = fc.spawn;
  c.g = hls::hit_regs<A>(fc.spawn);
  return c;
}

// The frame buffer's write for a ray leaving the hit unit (the host's side of the unit, for every
// view of it, and for the RTU in RTL, systemc/rtu_rtl.h): the ray of `pixel`, a shadow ray or the
// primary, with its best hit b and the unit's results ss. Returns true when the slot keeps the
// shadow ray ss.ray (a primary hit that spawns one); cos_light is the pixel's primary cosine,
// written by the primary and read by its shadow ray. Counts the pixel's retired rays.
template <class A>
bool write_pixel(FrameCtx& fc, uint32_t pixel, bool shadow, const Best& b,
                 const hls::ShadowSetup& ss, double& cos_light) {
  using F = typename A::Fmt;
  hls::PixelResult& p = fc.frame->px[pixel];
  if (shadow) {
    p.lit = p.front && !b.found;  // --shadow-spawn all: a ray behind the light is not lit
    p.shadow_tri = b.found ? int32_t(b.id) : -1;
    p.shade = hls::shade_pixel(true, p.lit, cos_light);
    ++fc.shadow_retired[pixel];
    return false;
  }
  ++fc.primary_retired[pixel];
  if (!b.found) {
    p.shade = hls::shade_pixel(false, false, 0);
    return false;
  }
  p.tri = int32_t(b.id);
  p.t_bits = hls::key_t<F>(b.t);  // the record's t is the key: its top bits
  p.t = A::to_double(p.t_bits);
  p.hit = {A::to_double(ss.h[0]) + fc.offset[0], A::to_double(ss.h[1]) + fc.offset[1],
           A::to_double(ss.h[2]) + fc.offset[2]};
  p.front = ss.front;
  if (!ss.spawn) {
    p.shade = hls::shade_pixel(true, false, 0);
    return false;
  }
  p.shadow_ray = true;
  // The shade's cosine: a host-side computation in double from the unit's outputs (the shadow
  // direction and dens) and the triangle's plane; not part of the unit.
  const double nu = A::to_double(b.nu), nv = A::to_double(b.nv);
  double l2 = 0;
  for (int i = 0; i < 3; ++i) l2 += A::to_double(ss.ray.d[i]) * A::to_double(ss.ray.d[i]);
  cos_light = std::fabs(A::to_double(ss.dens)) / std::sqrt((1 + nu * nu + nv * nv) * l2);
  return true;
}

template <class A>
class Hit : public SlotUnit {
  using F = typename A::Fmt;

 public:
  Hit(sc_core::sc_module_name name, FrameCtx& fc, RtuChannels& ch, RtuStats& st, uint32_t latency)
      : SlotUnit(name, fc, ch, st, latency) {
    pipe_.reset(size_t(latency) + 2);  // one ray enters per cycle
  }

  // The pin-level view: hit.v's SystemC twin at port.
  void bind(pins::HitPort* port) { port_ = port; }
  // The whole unit in RTL (--rtl hit): it holds the queue, reads the slots and decides.
  void bind_rtl(HitRtl* r) { rtl_ = r; }
  const HitRtl* rtl() const { return rtl_; }
  bool wants_edge() const { return edge_; }

  bool tick(Cycle now) {
    if (rtl_) return tick_rtl(now);
    bool active = false;
    edge_ = false;
    // A result leaving the unit: the slot is freed, the pixel written or the shadow ray handed
    // over now (hit_latency cycles after the ray entered).
    if (port_) {
      if (port_->out_valid()) {  // put out at the last edge
        const pins::HitOutRec x = port_->out();
        Done d;
        d.slot = side_[x.tag % side_.size()];
        for (int i = 0; i < 3; ++i) {
          d.ss.h[i] = x.h[i];
          d.ss.ray.o[i] = x.o[i];
          d.ss.ray.d[i] = x.d[i];
          d.ss.ray.inv[i] = x.inv[i];
        }
        d.ss.front = x.front;
        d.ss.spawn = x.spawn;
        d.ss.dens = x.dens;
        d.ss.ray.tmin = x.tmin;
        d.ss.ray.tmax = x.tmax;
        d.ss.skip_id = x.skip_id;
        --in_flight_;
        finish(d, now);
        active = edge_ = true;
      }
    } else {
      while (pipe_.can_pop(now)) {
        finish(pipe_.pop(), now);
        active = true;
      }
    }
    // A ray entering: a finished primary ray (hit or miss) or shadow ray, one per cycle.
    if (!ch_.hit_q.can_pop(now)) {
      if (port_) {
        port_->idle();
        edge_ |= in_flight_ != 0;
      }
      return active || edge_;
    }
    const uint16_t s = ch_.hit_q.pop();
    ++st_.hit_busy;
    const Slot& r = ch_.slots[s];
    const Best& b = r.best;
    const hls::HitTri ht{b.id, b.k, b.nu, b.nv, b.nd, b.den};
    if (port_) {
      drive(s, r, ht);
      return true;
    }
    Done d;
    d.slot = s;
    if (!r.shadow && b.found)  // the unit's result for a primary hit (others: not read)
      d.ss = hls::hit_shadow<A>(r.ray, hls::key_t<F>(b.t), ht, fc_.light, fc_.tmin, fc_.spawn);
    pipe_.push(d, now + lat_);
    return true;
  }

  // The RTL's clock edge, after the trv's finished rays of this cycle (RtuChannels::hit_q).
  void edge(Cycle now) {
    if (rtl_) rtl_->edge(now);
  }

  Cycle next_event(Cycle now) const {
    if (rtl_) return rtl_->next_event(now);
    if (port_ && in_flight_ != 0) return now + 1;
    return std::min(ch_.hit_q.head_ready(), pipe_.head_ready());
  }

 private:
  struct Done {
    uint16_t slot = 0;
    hls::ShadowSetup ss{};
  };

  // The RTL's cycle: the ray leaving (applied, its decision checked against the slot's kind).
  bool tick_rtl(Cycle now) {
    if (!configured_) {
      rtl_->config(regs());
      configured_ = true;
    }
    HitLeave x;
    const bool active = rtl_->tick(now, x);
    if (!active || (!x.free && !x.spawn)) return active;
    const Slot& r = ch_.slots[x.slot];
    const bool spawn = !r.shadow && r.best.found && x.ss.spawn;
    if (x.shadow != r.shadow || x.found != r.best.found || x.spawn != spawn || x.free == spawn)
      throw std::logic_error("--rtl hit: slot " + std::to_string(x.slot) + " leaves as " +
                             (x.spawn ? "a shadow ray" : "free") + " (kind " +
                             (x.shadow ? "shadow" : "primary") + ", " +
                             (x.found ? "hit" : "miss") + "); the slot's ray is " +
                             (r.shadow ? "a shadow ray" : "primary") +
                             (r.best.found ? " with a hit" : " without a hit"));
    finish(Done{x.slot, x.ss}, now);
    return true;
  }

  // The unit's per-frame registers (the light is the VTU's, translated at set-up).
  pins::HitConfig regs() const { return hit_config<A>(fc_); }

  // The unit's result for slot d.slot, at cycle now (when it leaves the unit).
  void finish(const Done& d, Cycle now) {
    const uint16_t s = d.slot;
    Slot& r = ch_.slots[s];
    if (!write_pixel<A>(fc_, r.pixel, r.shadow, r.best, d.ss, r.cos_light)) return retire(s, now);
    r.ray = d.ss.ray;
    r.skip_id = d.ss.skip_id;
    r.shadow = true;
    r.state = SlotState::start;
    ch_.shadow_q.push(s, now);
    ++fc_.retired;  // the primary ray
    ++st_.retired;
    fc_.last_retire = std::max(fc_.last_retire, now);
  }

  void retire(uint16_t s, Cycle now) {
    ch_.free_slots.push_back(s);
    ++fc_.retired;
    ++st_.retired;
    fc_.last_retire = std::max(fc_.last_retire, now);
  }

  // Drives slot s's ray into the pin-level unit (the registers are written with the first ray:
  // the light is the VTU's, translated at set-up).
  void drive(uint16_t s, const Slot& r, const hls::HitTri& ht) {
    if (!port_->in_ready()) throw std::logic_error("hit: pin-level unit not ready with out_ready high");
    if (!configured_) {
      port_->config(regs());
      configured_ = true;
    }
    pins::HitIn in;
    for (int i = 0; i < 3; ++i) {
      in.o[i] = r.ray.o[i];
      in.d[i] = r.ray.d[i];
    }
    in.t = hls::key_t<F>(r.best.t);
    in.k = ht.k;
    in.nu = ht.n_u;
    in.nv = ht.n_v;
    in.nd = ht.n_d;
    in.den = ht.den;
    in.id = ht.id;
    in.tag = next_tag_;
    side_[next_tag_ % side_.size()] = s;
    next_tag_ = (next_tag_ + 1) & 0xFFFFu;  // TAG_BITS 16
    port_->drive(in);
    ++in_flight_;
    edge_ = true;
  }

  TimedFifo<Done> pipe_;          // the model: results leaving after hit_latency
  pins::HitPort* port_ = nullptr;  // the pin-level view (nullptr: the model)
  HitRtl* rtl_ = nullptr;          // the whole unit in RTL (--rtl hit)
  std::array<uint16_t, 1024> side_{};  // slot of each tag in flight
  uint32_t next_tag_ = 0, in_flight_ = 0;
  bool edge_ = false, configured_ = false;
};

}  // namespace raycore::sc
