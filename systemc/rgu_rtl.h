// systemc/rgu_rtl.h - the ray generation unit as RTL in the running frame (raycore simulate --rtl
// rgu): rtl/units/rgu_unit.v (rgu.v's tile walk and primary-ray datapath, the shadow-ray hand-off
// from the hit unit and the free ray slots), Verilated with --cc and stepped from C++ by Rgu<A>
// (systemc/rgu.h) in every cycle the RTU ticks, after the hit unit and the trv.
//
// The hit unit's slot freed and shadow ray of this cycle (RtuChannels::free_slots and shadow_q,
// then only the hit -> rgu wires) go in; the RTL decides which ray goes to the trv in which slot
// (a shadow ray first, else the next primary ray in the top free slot) and holds the free slots.
// Rgu<A> writes the primary ray into the C++ slot (which the other units read) and checks the
// RTL's schedule against the model's (start-up, primary rays left, a free slot).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "hls/fp.h"
#include "hls/image.h"
#include "hls/ray.h"
#include "hls/rgu.h"
#include "systemc/config.h"
#include "systemc/fifo.h"

namespace raycore::sc {

// The per-frame registers of rgu_unit.v.
struct RguRegs {
  hls::RguCamera cam;
  uint32_t width = 0, height = 0, rtu = 0, rtus = 0, tmin = 0, slots = 0;
};

// The unit's ray of a cycle (out_*).
struct RguIssue {
  bool valid = false, shadow = false;
  uint16_t slot = 0;
  hls::Ray ray{};  // a primary ray's (with its interval)
  uint32_t pixel = 0;
};

class RguRtl {
 public:
  virtual ~RguRtl() = default;
  virtual void config(const RguRegs& r) = 0;
  // One cycle: start_i, the slot the hit unit freed (-1: none), the shadow ray's slot (-1: none);
  // evaluates, returns the ray to the trv and clocks the edge.
  virtual RguIssue cycle(bool start, int freed, int shadow) = 0;
  virtual uint32_t free_slots() const = 0;  // free_count_o
  virtual bool busy() const = 0;            // busy_o: primary rays still to come
  virtual void stats(RtuStats& s) const = 0;  // primary_rays, shadow_rays, rgu_stall_no_slot
  virtual std::string name() const = 0;     // "Verilated rgu_unit FP24 rtz S=2"
};

// The Verilated rgu_unit of that format, rounding and STAGES (rgu_latency = 15 x STAGES) with tiles
// of `tile` pixels a side. Throws ConfigError for more slots than its parameters; nullptr when no
// model of that format, rounding, STAGES and tile is built.
std::unique_ptr<RguRtl> make_rtl_rgu_unit(hls::FormatId f, hls::Rounding r, unsigned stages,
                                          unsigned tile, const SimConfig& cfg);
// "rgu_unit FP24 rtz S=2 (8 x 8 tiles, slots 128), ..." or "none ...".
std::string rtl_rgu_unit_built();

}  // namespace raycore::sc
