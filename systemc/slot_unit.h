// systemc/slot_unit.h - what an RTU's per-ray units share (trv, hit; ist has the same members):
// the module, the frame context, the RTU's channels and statistics, and the unit's latency in
// cycles. A unit takes ray slots from its queue in tick(now) and hands them on.
#pragma once

#include <systemc>

#include <cstdint>

#include "systemc/slot.h"

namespace raycore::sc {

class SlotUnit : public sc_core::sc_module {
 public:
  SlotUnit(sc_core::sc_module_name name, FrameCtx& fc, RtuChannels& ch, RtuStats& st,
           uint32_t latency)
      : sc_core::sc_module(name), fc_(fc), ch_(ch), st_(st), lat_(latency) {}

 protected:
  FrameCtx& fc_;
  RtuChannels& ch_;
  RtuStats& st_;
  uint32_t lat_;
};

}  // namespace raycore::sc
