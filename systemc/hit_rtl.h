// systemc/hit_rtl.h - the hit unit as RTL in the running frame (raycore simulate --rtl hit):
// rtl/units/hit_unit.v (the hit queue of finished rays, the slot read of the ray entering, hit.v,
// and the decision when it leaves: the slot freed or holding the shadow ray), Verilated with --cc
// and stepped from C++ by Hit<A> (systemc/hit.h) in place of its model.
//
// Per cycle (Rtu::tick): tick(now) drives the cycle number, evaluates the unit, answers its slot
// read (the ray, the best record and the kind, from the C++ slots that rgu, trv and hit write) and
// returns the ray that leaves in this cycle, if any: hit.v's results with the RTL's decision, which
// Hit<A> applies (the frame buffer, the slot freed or the shadow ray handed to the rgu) and checks
// against its own. RtuChannels::hit_q is only the trv -> hit wire from here on: the trv ticks and
// pushes its finished rays into it; edge(now) drives them into the RTL (one per lane, in push
// order) and clocks the model.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "hls/fp.h"
#include "hls/hit.h"
#include "hls/image.h"
#include "systemc/config.h"
#include "systemc/fifo.h"
#include "systemc/pins/hit.h"
#include "systemc/slot.h"

namespace raycore::sc {

// A ray leaving hit_unit.v: its slot, hit.v's results and the unit's decision.
struct HitLeave {
  uint16_t slot = 0;
  hls::ShadowSetup ss{};
  bool shadow = false, found = false;  // the kind the RTL carried (a shadow ray; it hit)
  bool free = false, spawn = false;    // out_free_o / out_spawn_o
};

// One cycle of hit_unit's ports (the waveform, --trace).
struct HitProbe {
  Cycle cycle = kNever;
  uint32_t fin = 0;                 // fin_valid_i: finished rays in (mask by lane)
  bool in = false;                  // rd_valid_o: a ray enters hit.v
  uint32_t in_slot = 0;             // rd_slot_o
  bool out = false, spawn = false;  // out_valid_o, out_spawn_o
  uint32_t out_slot = 0;            // out_slot_o
  bool head_valid = false;          // head_valid_o
};

class HitRtl {
 public:
  virtual ~HitRtl() = default;
  virtual void config(const pins::HitConfig& c) = 0;  // the per-frame registers
  // The unit's cycle up to the edge: true and the ray leaving in out if one leaves.
  virtual bool tick(Cycle now, HitLeave& out) = 0;
  virtual void edge(Cycle now) = 0;               // the trv's finished rays in, then the edge
  virtual Cycle next_event(Cycle now) const = 0;  // the queue's head, or now + 1 while busy
  virtual uint64_t busy() const = 0;              // hit_busy: rays that entered hit.v
  virtual std::string name() const = 0;           // "Verilated hit_unit FP24 rtz S=2"
  virtual HitProbe probe(Cycle now) const = 0;
};

// The Verilated hit_unit of that format, rounding and STAGES (hit_latency = 24 x STAGES) bound to
// an RTU's channels. Throws ConfigError for more slots or trv pipes than its parameters; nullptr
// when no model of that format, rounding and STAGES is built.
std::unique_ptr<HitRtl> make_rtl_hit_unit(hls::FormatId f, hls::Rounding r, unsigned stages,
                                          RtuChannels& ch, const SimConfig& cfg);
// "hit_unit FP24 rtz S=2 (slots 128, pipes 4), ..." or "none ...".
std::string rtl_hit_unit_built();

}  // namespace raycore::sc
