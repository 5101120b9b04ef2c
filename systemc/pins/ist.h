// systemc/pins/ist.h - the intersection unit at pin level: the pins of rtl/units/ist.v (port.h
// turns the list into the signals, the bind template and the twin's ports, exactly as a Verilated
// --sc model has them), its SystemC twin IstTwin, and IstPort / IstPortT, the cycle-level view the
// cycle model's ist uses with either bound in the same place.
//
// The twin computes each test at the input through hls::ist_wald (the one definition of the test)
// and carries {exit, t, den, tag} through a ReadyChain of 10 * STAGES registers: the RTL's latency
// and handshake, cycle for cycle.
#pragma once

#include <systemc>

#include <cstdint>

#include "hls/ist.h"
#include "hls/margins.h"
#include "systemc/config.h"
#include "systemc/pins/port.h"

namespace raycore::sc::pins {

// One test in: projection axis, the record's nine constants, the ray, its interval, a tag.
struct IstIn {
  uint32_t k = 0, c[9] = {}, o[3] = {}, d[3] = {}, tmin = 0, tmax = 0, tag = 0;
};
// Its result: hls::IstExit code, t, den, the tag.
struct IstOutRec {
  uint32_t exit = 0, t = 0, den = 0, tag = 0;
};

// The data pins of rtl/units/ist.v (list format: port.h); eps_i and one_eps_i are the per-frame
// margin registers (hls::Margins: static while tests are in flight).
#define RAYCORE_IST_PINS(CFG, IN, OUT, E)                                                    \
  CFG(E, uint32_t, eps, one) CFG(E, uint32_t, one_eps, one)                                 \
  IN(E, uint32_t, k, one) IN(E, uint32_t, c, c9) IN(E, uint32_t, o, xyz)                    \
  IN(E, uint32_t, d, xyz) IN(E, uint32_t, tmin, one) IN(E, uint32_t, tmax, one)             \
  IN(E, uint32_t, tag, one)                                                                 \
  OUT(E, uint32_t, exit, one) OUT(E, uint32_t, t, one) OUT(E, uint32_t, den, one)           \
  OUT(E, uint32_t, tag, one)
RAYCORE_PINS_UNIT(IstPins, RAYCORE_IST_PINS, IstIn, IstOutRec);

// The cycle-level view of a pin-level ist (port.h's Port) and its configuration pins.
class IstPort : public Port<IstPins> {
 public:
  void config(const hls::Margins& m) {
    s.eps.write(m.eps);
    s.one_eps.write(m.one_eps);
  }
};
template <class M>
using IstPortT = BoundPort<IstPort, M>;

// The SystemC twin of rtl/units/ist.v for the arithmetic A (hls::Arith<F, R>).
template <class A>
class IstTwin : public PinTwin<IstPins> {
 public:
  IstTwin(sc_core::sc_module_name name, unsigned stages)
      : PinTwin<IstPins>(name, kIstLevels * stages) {}

  // One test as the RTL computes it (k = 3 is treated as k = 0) with the margin registers m.
  static IstOutRec compute(const IstIn& in, const hls::Margins& m) {
    const hls::IstOut x =
        hls::ist_wald<A>(in.k == 3 ? 0 : in.k, in.c, in.o, in.d, in.tmin, in.tmax, m);
    return IstOutRec{uint32_t(x.exit), x.t, x.den, in.tag};
  }

 private:
  IstOutRec step(const IstIn& in) override {
    hls::Margins m;
    m.eps = eps_i.read();
    m.one_eps = one_eps_i.read();
    return compute(in, m);
  }
};

}  // namespace raycore::sc::pins
