// systemc/rgu.h - ray generation: primary rays in tile order (tile i of the frame belongs to RTU
// i mod N), one ray per cycle into a free slot; shadow rays handed over by hit go first.
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
      : sc_core::sc_module(name), fc_(fc), ch_(ch), st_(st), rtu_(rtu), rtus_(rtus), tile_(int(tile)) {
    tiles_x_ = (fc.width + tile_ - 1) / tile_;
    tiles_ = tiles_x_ * ((fc.height + tile_ - 1) / tile_);
    tile_idx_ = rtu_;
    advance_to_valid();
  }

  bool primaries_left() const { return tile_idx_ < tiles_; }

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
    const int x = (tile_idx_ % tiles_x_) * tile_ + px_, y = (tile_idx_ / tiles_x_) * tile_ + py_;
    const hls::Vec3 dv = scenes::primary_direction(fc_.cam, x, y, fc_.width, fc_.height);
    const double dir[3] = {dv.x, dv.y, dv.z};
    Slot& sl = ch_.slots[s];
    sl.ray = hls::rgu_primary<A>(fc_.origin, dir, fc_.tmin);
    sl.shadow = false;
    sl.pixel = uint32_t(y) * uint32_t(fc_.width) + uint32_t(x);
    sl.skip_id = ~0u;
    sl.state = SlotState::start;
    ch_.trv_q.push(s, now + 1);
    ++st_.primary_rays;
    ++st_.rgu_busy;
    ++fc_.issued;
    next_pixel();
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
  bool pixel_ok() const {
    const int x = (tile_idx_ % tiles_x_) * tile_ + px_, y = (tile_idx_ / tiles_x_) * tile_ + py_;
    return x < fc_.width && y < fc_.height;
  }
  void step() {
    if (++px_ == tile_) {
      px_ = 0;
      if (++py_ == tile_) {
        py_ = 0;
        tile_idx_ += rtus_;
      }
    }
  }
  void advance_to_valid() {
    while (primaries_left() && !pixel_ok()) step();
  }
  void next_pixel() {
    step();
    advance_to_valid();
  }

  FrameCtx& fc_;
  RtuChannels& ch_;
  RtuStats& st_;
  int rtu_, rtus_, tile_;
  int tiles_x_ = 0, tiles_ = 0, tile_idx_ = 0, px_ = 0, py_ = 0;
};

}  // namespace raycore::sc
