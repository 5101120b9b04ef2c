// systemc/rgu.h - ray generation: primary rays in tile order (hls::RguTiles: tile i of the frame
// belongs to RTU i mod N), one ray per cycle into a free slot, each computed by hls::rgu_primary
// from the camera registers (FrameCtx::rgu_cam); shadow rays handed over by hit go first.
#pragma once

#include <systemc>

#include "hls/rgu.h"
#include "systemc/slot.h"

namespace raycore::sc {

template <class A>
class Rgu : public sc_core::sc_module {
 public:
  Rgu(sc_core::sc_module_name name, FrameCtx& fc, RtuChannels& ch, RtuStats& st, int rtu, int rtus,
      uint32_t tile)
      : sc_core::sc_module(name), fc_(fc), ch_(ch), st_(st),
        walk_(fc.width, fc.height, int(tile), rtu, rtus) {}

  bool primaries_left() const { return !walk_.done(); }

  bool tick(Cycle now) {
    if (ch_.shadow_q.can_pop(now) && ch_.trv_q.can_push()) {
      const uint16_t s = ch_.shadow_q.pop();
      ch_.trv_q.push(s, now + 1);
      ++st_.shadow_rays;
      ++st_.rgu_busy;
      ++fc_.issued;
      return true;
    }
    if (!primaries_left()) return false;
    if (ch_.free_slots.empty() || !ch_.trv_q.can_push()) {
      ++st_.rgu_stall_no_slot;
      return false;
    }
    const uint16_t s = ch_.free_slots.back();
    ch_.free_slots.pop_back();
    Slot& sl = ch_.slots[s];
    sl.ray = hls::rgu_primary<A>(fc_.rgu_cam, uint32_t(walk_.x()), uint32_t(walk_.y()), fc_.tmin);
    sl.shadow = false;
    sl.pixel = walk_.pixel();
    sl.skip_id = ~0u;
    sl.state = SlotState::start;
    ch_.trv_q.push(s, now + 1);
    ++st_.primary_rays;
    ++st_.rgu_busy;
    ++fc_.issued;
    walk_.next();
    if (!primaries_left()) {
      st_.rgu_primary_end = now + 1;
      st_.rgu_busy_primary = st_.rgu_busy;
    }
    return true;
  }

  Cycle next_event(Cycle now) const {
    Cycle t = ch_.shadow_q.head_ready();
    if (primaries_left() && !ch_.free_slots.empty()) t = std::min(t, now + 1);
    return t;
  }

 private:
  FrameCtx& fc_;
  RtuChannels& ch_;
  RtuStats& st_;
  hls::RguTiles walk_;
};

}  // namespace raycore::sc
