// systemc/ist_rtl.h - the intersection unit as RTL in the running frame (raycore simulate --rtl
// ist): rtl/units/ist_unit.v (the ist input queue with looping on a triangle-cache miss, the
// triangle-cache accesses and the record decode, one ist.v per ist unit, the result delay),
// Verilated with --cc and stepped from C++ by Ist<A> (systemc/ist.h) in place of its model.
//
// Per cycle (Rtu::tick): tick(now) drives the cycle number, evaluates the unit, answers its ray
// reads from the C++ slots (the ray, the leaf-entry tmax and the skip id, which rgu, hit and trv
// write there) and its triangle-cache accesses in unit order (each the cycle model's
// Ascache::access), and returns the results that leave in this cycle, in the model's order (the trv
// reduces them: Trv<A>'s reduction in Ist<A>, or trv_unit.v's); it then limits RtuChannels::ist_q
// to the queue's room. ist_q is only the trv -> ist wire from here on: the trv ticks and pushes its
// hand-offs into it; edge(now) drives them into the RTL (one run of consecutive list positions of
// one slot per lane) and clocks the model.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hls/fp.h"
#include "hls/image.h"
#include "systemc/config.h"
#include "systemc/fifo.h"
#include "systemc/slot.h"

namespace raycore::sc {

// One cycle of ist_unit's ports (the waveform, --trace): masks by unit.
struct IstProbe {
  Cycle cycle = kNever;
  uint32_t acc_valid = 0,
           rsp_hit = 0;     // acc_valid_o / rsp_hit_i: triangle-cache accesses
  uint32_t res_valid = 0;   // res_valid_o: results leaving
  uint32_t hin = 0;         // hand-off entries in (hin_n_i summed)
  bool head_valid = false;  // head_valid_o: the queue is not empty
  bool busy = false;        // busy_o: tests or results inside
};

class IstRtl {
 public:
  virtual ~IstRtl() = default;
  // The unit's cycle up to the edge: the results leaving now (in order) into out.
  virtual bool tick(Cycle now, std::vector<IstRes>& out) = 0;
  virtual void edge(Cycle now) = 0;               // the trv's hand-offs in, then the clock edge
  virtual Cycle next_event(Cycle now) const = 0;  // the queue's head, or now + 1 while busy
  virtual void stats(RtuStats& s) const = 0;      // ist_busy, ist_tri_miss, tri_tests
  virtual std::string name() const = 0;           // "Verilated ist_unit FP24 rtz"
  virtual IstProbe probe(Cycle now) const = 0;
};

// The Verilated ist_unit of that format, rounding, STAGES (ist_latency = ist_levels(kind) x STAGES:
// ist.v's 10, ist_watertight.v's 18) and record kind (ist.v or ist_watertight.v inside) bound to
// an RTU's frame context, channels and triangle cache (ch.tri). Throws ConfigError for a
// configuration the built model cannot run (more ist units, slots, pipes or queue entries than its
// parameters, another triangle line, a longer triangle-cache hit latency, the mailbox); nullptr
// when no model of that format, rounding and STAGES is built.
std::unique_ptr<IstRtl> make_rtl_ist_unit(hls::FormatId f, hls::Rounding r, unsigned stages, hls::IstKind kind,
                                          FrameCtx& fc, RtuChannels& ch, const SimConfig& cfg);
// "ist_unit FP24 rtz S=2 (units 4, slots 128, queue 64), ..." or "none ...".
std::string rtl_ist_unit_built();

}  // namespace raycore::sc
