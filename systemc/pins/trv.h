// systemc/pins/trv.h - the traversal unit's datapath at pin level: the pins of rtl/units/trv.v
// (port.h turns the list into the signals, the bind template and the twin's ports, exactly as a
// Verilated --sc model has them: toolchain.md pitfall 14, 1 bit bool, 2..32 bits uint32_t), its
// SystemC twin TrvTwin, and TrvPort / TrvPortT (either bound in the same place).
//
// One ray step per cycle, selected by in_op_i (systemc/pins/trv_step.h). The twin computes the
// step at the input through trv_step (hls/ underneath) and carries the result through a
// ReadyChain of 4 * STAGES registers: the RTL's latency and handshake, cycle for cycle.
#pragma once

#include <systemc>

#include <cstdint>

#include "systemc/pins/port.h"
#include "systemc/pins/trv_step.h"

namespace raycore::sc::pins {

// The data pins of rtl/units/trv.v (list format: port.h); widen_i is the per-frame interval
// widening register (hls::Margins::widen_ulps, 7 bits: static while steps are in flight).
#define RAYCORE_TRV_PINS(CFG, IN, OUT, E)                                                    \
  CFG(E, uint32_t, widen, one)                                                              \
  IN(E, bool, op, one) IN(E, uint32_t, axis, one) IN(E, uint32_t, split, one)               \
  IN(E, uint32_t, node, one) IN(E, uint32_t, child, one) IN(E, uint32_t, o, xyz)            \
  IN(E, uint32_t, d, xyz) IN(E, uint32_t, inv, xyz) IN(E, uint32_t, tnear, one)             \
  IN(E, uint32_t, tfar, one) IN(E, uint32_t, lo, xyz) IN(E, uint32_t, hi, xyz)              \
  IN(E, uint32_t, tag, one)                                                                 \
  OUT(E, bool, op, one) OUT(E, bool, hit, one) OUT(E, uint32_t, visit, one)                 \
  OUT(E, bool, below, one) OUT(E, uint32_t, tsplit, one) OUT(E, uint32_t, tnear, one)       \
  OUT(E, uint32_t, tfar, one) OUT(E, uint32_t, node, one) OUT(E, uint32_t, far_node, one)   \
  OUT(E, uint32_t, far_tfar, one) OUT(E, uint32_t, tag, one)
RAYCORE_PINS_UNIT(TrvPins, RAYCORE_TRV_PINS, TrvStepIn, TrvStepOut);

// The cycle-level view of a pin-level trv (port.h's Port) and its configuration pin.
class TrvPort : public Port<TrvPins> {
 public:
  void config(uint32_t widen) { s.widen.write(widen); }
};
template <class M>
using TrvPortT = BoundPort<TrvPort, M>;

// The SystemC twin of rtl/units/trv.v for the arithmetic A (hls::Arith<F, R>); stages = the RTL's
// STAGES (>= 1), tag_bits = its TAG_BITS.
template <class A>
class TrvTwin : public PinTwin<TrvPins> {
 public:
  TrvTwin(sc_core::sc_module_name name, unsigned stages, unsigned tag_bits = 16)
      : PinTwin<TrvPins>(name, 4 * stages),
        tag_mask_(tag_bits >= 32 ? ~0u : (1u << tag_bits) - 1u) {}

 private:
  // The RTL sees two bits of in_axis_i, TAG_BITS of in_tag_i and 7 of widen_i (trv_step).
  TrvStepOut step(const TrvStepIn& in) override {
    TrvStepIn x = in;
    x.axis &= 3u;
    x.tag &= tag_mask_;
    return trv_step<A>(x, widen_i.read());
  }

  uint32_t tag_mask_;
};

}  // namespace raycore::sc::pins
