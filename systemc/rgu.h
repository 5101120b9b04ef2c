// systemc/rgu.h - ray generation: primary rays in tile order (hls::RguTiles: tile i of the frame
// belongs to RTU i mod N), one ray per cycle into a free slot, each computed by hls::rgu_primary
// from the camera registers (FrameCtx::rgu_cam); shadow rays handed over by hit go first.
//
// Start-up, as rtl/units/rgu.v: the host starts the unit in cycle 0; its walk divides rtu and N by
// the tile columns and loads the first tile (hls::RguTiles::startup() cycles), then the datapath
// takes `latency` cycles (SimConfig::rgu_latency = 15 x STAGES), so the first primary ray can be
// issued in cycle startup() + latency. After that the datapath, kept full by back-pressure, has a
// ray in every cycle until the RTU's last pixel.
//
// Two views (SimConfig::rgu_view): the transaction model (the ray computed at issue), or a
// pin-level rgu (systemc/pins/rgu.h: the SystemC twin or the Verilated rgu.v) started in cycle 0
// and clocked in every cycle of its start-up and in every cycle the model takes a ray, with
// out_ready_i high exactly then. The model's schedule decides when a primary ray is issued; the
// pins must agree (out_valid_o high then, low before the first ray, the pixel the model expects:
// else std::logic_error naming the cycle), and the ray's bits and pixel index in the slot are the
// pins'. rgu.v has no shadow path: shadow rays are forwarded here in the pin views. With --rtl rgu
// the whole unit is RTL (rtl/units/rgu_unit.v, systemc/rgu_rtl.h: rgu.v, the shadow-ray hand-off and
// the free slots), clocked in every cycle the RTU ticks: it decides which ray goes to the trv in
// which slot; the model's schedule is checked against it and the C++ slot gets the primary ray.
//
// A ray issued (primary or shadow) enters the trv's ready queue kTrvEntryDelay cycles later, the
// last of that cycle's pushes, ready the cycle after: rtl/units/trv_unit.v clips it against the
// scene box on its way (trv.v over three cycles). With the trv in RTL (--rtl trv) the ray goes to
// trv_unit.v in its cycle (set_entry_delay(0)), which delays it itself.
#pragma once

#include <systemc>

#include <deque>
#include <stdexcept>
#include <string>
#include <utility>

#include "hls/rgu.h"
#include "systemc/pins/rgu.h"
#include "systemc/rgu_rtl.h"
#include "systemc/slot.h"

namespace raycore::sc {

template <class A>
class Rgu : public sc_core::sc_module {
 public:
  Rgu(sc_core::sc_module_name name, FrameCtx& fc, RtuChannels& ch, RtuStats& st, int rtu, int rtus,
      uint32_t tile, uint32_t latency)
      : sc_core::sc_module(name), fc_(fc), ch_(ch), st_(st), rtu_(rtu), rtus_(rtus),
        walk_(fc.width, fc.height, int(tile), rtu, rtus),
        first_(Cycle(walk_.startup()) + latency) {}

  // The pin-level view (nullptr: the model): the port's configuration registers are written
  // here, start_i goes high in cycle 0.
  void bind(pins::RguPort* p) {
    port_ = p;
    if (!port_) return;
    port_->config(fc_.rgu_cam, fc_.width, fc_.height, rtu_, rtus_);
    port_->start(false);
    port_->out_ready(false);
  }
  // The whole unit in RTL (--rtl rgu): it holds the free slots (RtuChannels::free_slots is then the
  // hit -> rgu wire of the cycle).
  void bind_rtl(RguRtl* r) {
    rtl_ = r;
    ch_.free_slots.clear();
  }
  const RguRtl* rtl() const { return rtl_; }
  // The RTL's ray of the last cycle it ran (the waveform, --trace): none if not cycle `now`.
  RguIssue rtl_probe(Cycle now) const { return probe_cycle_ == now ? probe_ : RguIssue{}; }
  size_t free_slots() const { return rtl_ ? rtl_->free_slots() : ch_.free_slots.size(); }
  bool wants_edge() const { return edge_; }
  pins::RguPort* port() const { return port_; }
  Cycle first_primary() const { return first_; }

  bool primaries_left() const { return !walk_.done(); }

  void set_entry_delay(uint32_t d) { entry_delay_ = d; }

  bool tick(Cycle now) {
    bool entered = false;  // the rays issued kTrvEntryDelay cycles ago into the trv's queue
    while (!entering_.empty() && entering_.front().second == now) {
      ch_.trv_q.push(entering_.front().first, now + 1);
      entering_.pop_front();
      entered = true;
    }
    return step(now) || entered;
  }

  Cycle next_event(Cycle now) const {
    Cycle t = ch_.shadow_q.head_ready();
    if (primaries_left() && free_slots() != 0) t = std::min(t, std::max(now + 1, first_));
    if (!entering_.empty()) t = std::min(t, entering_.front().second);
    return t;
  }

 private:
  bool step(Cycle now) {
    edge_ = false;
    if (rtl_) return tick_rtl(now);
    if (port_) {
      port_->out_ready(false);
      port_->start(now == 0 && primaries_left());
    }
    if (ch_.shadow_q.can_pop(now) && ch_.trv_q.can_push()) {
      issued_shadow(ch_.shadow_q.pop(), now);
      return true;
    }
    if (!primaries_left()) return false;
    if (now < first_) {  // start-up: the pin-level unit is clocked through it
      if (!port_) return false;
      if (port_->out_valid())
        throw std::logic_error(where(now) + "out_valid_o is high before the model's first primary "
                               "ray (cycle " + std::to_string(first_) + ")");
      edge_ = true;
      return true;
    }
    if (ch_.free_slots.empty() || !ch_.trv_q.can_push()) {
      ++st_.rgu_stall_no_slot;
      return false;
    }
    const uint16_t s = ch_.free_slots.back();
    ch_.free_slots.pop_back();
    Slot& sl = ch_.slots[s];
    if (port_) {
      if (!port_->out_valid())
        throw std::logic_error(where(now) + "the model issues the primary ray of pixel " +
                               std::to_string(walk_.pixel()) + " but out_valid_o is low");
      const pins::RguRay r = port_->out();
      if (r.pixel != walk_.pixel())
        throw std::logic_error(where(now) + "out_pixel_o is " + std::to_string(r.pixel) +
                               ", the model's next pixel " + std::to_string(walk_.pixel()));
      for (int i = 0; i < 3; ++i) {
        sl.ray.o[i] = r.o[i];
        sl.ray.d[i] = r.d[i];
        sl.ray.inv[i] = r.inv[i];
      }
      hls::rgu_interval<A>(sl.ray, fc_.tmin);  // tmin and tmax: not the unit's
      sl.pixel = r.pixel;
      port_->out_ready(true);
      edge_ = true;
    } else {
      sl.ray = hls::rgu_primary<A>(fc_.rgu_cam, uint32_t(walk_.x()), uint32_t(walk_.y()), fc_.tmin);
      sl.pixel = walk_.pixel();
    }
    issued_primary(s, now);
    return true;
  }

  std::string where(Cycle now) const {
    return "rgu of RTU " + std::to_string(rtu_) + " (" + (rtl_ ? rtl_->name() : port_->model()) +
           "), cycle " + std::to_string(now) + ": ";
  }

  // The RTL's cycle: the hit unit's freed slot and shadow ray of this cycle in, the ray out.
  bool tick_rtl(Cycle now) {
    if (!configured_) {  // the per-frame registers (fc_ is complete by the first cycle)
      RguRegs g;
      g.cam = fc_.rgu_cam;
      g.width = uint32_t(fc_.width);
      g.height = uint32_t(fc_.height);
      g.rtu = uint32_t(rtu_);
      g.rtus = uint32_t(rtus_);
      g.tmin = fc_.tmin;
      g.slots = uint32_t(ch_.slots.size());
      rtl_->config(g);
      configured_ = true;
    }
    int freed = -1, shadow = -1;
    if (!ch_.free_slots.empty()) {
      if (ch_.free_slots.size() > 1) throw std::logic_error(where(now) + "two slots freed in a cycle");
      freed = ch_.free_slots.back();
      ch_.free_slots.clear();
    }
    if (ch_.shadow_q.can_pop(now)) {
      shadow = ch_.shadow_q.pop();
      if (ch_.shadow_q.can_pop(now)) throw std::logic_error(where(now) + "two shadow rays in a cycle");
    }
    // After the last primary ray, a cycle with neither a freed slot nor a shadow ray changes
    // nothing in the RTL (rgu.v is idle, nothing stalls): neither evaluate nor clock it.
    if (freed < 0 && shadow < 0 && !primaries_left()) return false;
    // What the model does in this cycle, against what the RTL does.
    const bool model_primary = shadow < 0 && primaries_left() && now >= first_ &&
                               (freed >= 0 || rtl_->free_slots() != 0);
    const RguIssue x = rtl_->cycle(now == 0 && primaries_left(), freed, shadow);
    probe_ = x;
    probe_cycle_ = now;
    if (x.valid != (shadow >= 0 || model_primary) || (x.valid && x.shadow != (shadow >= 0)) ||
        (shadow >= 0 && x.slot != uint16_t(shadow)))
      throw std::logic_error(where(now) + "the RTL " +
                             (x.valid ? std::string(x.shadow ? "issues a shadow ray" : "issues a primary ray") +
                                            " in slot " + std::to_string(x.slot)
                                      : std::string("issues no ray")) +
                             "; the model " +
                             (shadow >= 0 ? "hands over the shadow ray of slot " + std::to_string(shadow)
                              : model_primary ? std::string("issues a primary ray")
                                              : std::string("issues no ray")));
    // A full trv queue holds every slot: then there is neither a free slot nor a shadow ray.
    if (x.valid && !ch_.trv_q.can_push())
      throw std::logic_error(where(now) + "a ray for the trv, whose queue is full");
    if (shadow >= 0) {
      issued_shadow(x.slot, now);
      return true;
    }
    if (!primaries_left()) return false;
    if (now < first_) return true;  // start-up: the RTL is clocked through it
    if (!x.valid) {
      ++st_.rgu_stall_no_slot;
      return false;
    }
    if (x.pixel != walk_.pixel())
      throw std::logic_error(where(now) + "out_pixel_o is " + std::to_string(x.pixel) +
                             ", the model's next pixel " + std::to_string(walk_.pixel()));
    Slot& sl = ch_.slots[x.slot];
    sl.ray = x.ray;
    sl.pixel = x.pixel;
    issued_primary(x.slot, now);
    return true;
  }

  // Slot s holds the shadow ray the hit unit handed over: to the trv.
  void issued_shadow(uint16_t s, Cycle now) {
    enter_trv(s, now);
    ++st_.shadow_rays;
    ++st_.rgu_busy;
    ++fc_.issued;
  }

  // Slot s holds the primary ray of the walk's pixel (its ray and pixel written): to the trv.
  void issued_primary(uint16_t s, Cycle now) {
    Slot& sl = ch_.slots[s];
    sl.shadow = false;
    sl.skip_id = ~0u;
    sl.state = SlotState::start;
    enter_trv(s, now);
    ++st_.primary_rays;
    ++st_.rgu_busy;
    ++fc_.issued;
    walk_.next();
    if (!primaries_left()) {
      st_.rgu_primary_end = now + 1;
      st_.rgu_busy_primary = st_.rgu_busy;
    }
  }

  // Slot s issued in cycle now: into the trv's queue now (the trv in RTL delays it itself) or
  // kTrvEntryDelay cycles later (tick).
  void enter_trv(uint16_t s, Cycle now) {
    if (entry_delay_ == 0)
      ch_.trv_q.push(s, now + 1);
    else
      entering_.emplace_back(s, now + entry_delay_);
  }

  FrameCtx& fc_;
  RtuChannels& ch_;
  RtuStats& st_;
  int rtu_, rtus_;
  uint32_t entry_delay_ = kTrvEntryDelay;
  std::deque<std::pair<uint16_t, Cycle>> entering_;  // issued rays and their entry cycles
  hls::RguTiles walk_;
  Cycle first_;                      // the first cycle a primary ray can be issued in
  pins::RguPort* port_ = nullptr;    // pin-level view
  RguRtl* rtl_ = nullptr;            // the whole unit in RTL (--rtl rgu)
  RguIssue probe_{};                 // its ray of cycle probe_cycle_
  Cycle probe_cycle_ = kNever;
  bool edge_ = false, configured_ = false;
};

}  // namespace raycore::sc
