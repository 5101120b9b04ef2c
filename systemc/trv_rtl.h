// systemc/trv_rtl.h - the traversal unit as RTL in the running frame (raycore simulate --rtl trv):
// rtl/units/trv_unit.v (the ray slots' traversal state, the stacks, the ready queue, the pipes and
// the reduction of the ist's results), Verilated with --cc and stepped from C++ in the RTU's tick
// in place of Trv<A> (systemc/trv.h) and the result half of Ist<A>.
//
// Per cycle (Rtu::tick): the ist hands this cycle's results over (RtuChannels::ist_results) instead
// of reducing them; tick(now) drives them, the ist queue's room and the cycle number, evaluates the
// pipes and answers their cache accesses in the model's order (A0, B0, A1, ...: each the cycle
// model's Ascache::access, one evaluation after each hit), then takes the pipes' list entries into
// the ist queue and their finished rays into the hit queue, as Trv<A> does; the rgu ticks; edge(now)
// drives the rgu's ray of this cycle (RtuChannels::trv_q is then only the rgu -> trv wire) and
// clocks the model. The C++ slot keeps what the other units read: the ray (written by rgu and
// hit), and from the RTL the leaf-entry tmax (for the ist) and the best hit (for the hit unit).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "hls/fp.h"
#include "hls/image.h"
#include "systemc/config.h"
#include "systemc/fifo.h"
#include "systemc/slot.h"

namespace raycore::sc {

// One cycle of trv_unit's ports (the waveform, --trace): masks by pipe / ist port.
struct TrvProbe {
  Cycle cycle = kNever;
  bool in_valid = false;            // in_valid_i: a ray from the rgu
  uint32_t in_slot = 0;             // in_slot_i
  uint32_t res_valid = 0;           // res_valid_i: ist results
  uint32_t go = 0, fin = 0;         // go_o: pipes that took a ray; fin_o: rays finished
  uint32_t acc_valid = 0, rsp_hit = 0;  // acc_valid_o / rsp_hit_i: cache accesses A0 B0 A1 ..
  uint32_t ist_entries = 0;         // list entries handed to the ist (ist_n_o summed)
  bool head_valid = false;          // head_valid_o: the ready queue is not empty
};

class TrvRtl {
 public:
  virtual ~TrvRtl() = default;
  virtual bool tick(Cycle now) = 0;               // the pipes' cycle, up to the edge
  virtual void edge(Cycle now) = 0;               // the rgu's ray in, then the clock edge
  virtual Cycle next_event(Cycle now) const = 0;  // the ready queue's head
  virtual void stats(RtuStats& s) const = 0;      // the traversal counters
  virtual std::string name() const = 0;           // "Verilated trv_unit FP24 rtz"
  virtual TrvProbe probe(Cycle now) const = 0;    // this cycle's ports (zero if it did nothing)
};

// The Verilated trv_unit of that format and rounding bound to an RTU's frame context, channels and
// caches (ch.node, ch.list). Throws ConfigError for a configuration the built model
// cannot run (mailbox, more pipes, ist units or slots than its parameters, list lines over 64
// bytes); nullptr when no model of that format and rounding is built.
std::unique_ptr<TrvRtl> make_rtl_trv(hls::FormatId f, hls::Rounding r, FrameCtx& fc, RtuChannels& ch,
                                     const SimConfig& cfg);
// "trv_unit FP24 rtz (slots 128, stack 64, pipes 4, ist 4), ..." or "none ...".
std::string rtl_trv_built();

}  // namespace raycore::sc
