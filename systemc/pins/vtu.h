// systemc/pins/vtu.h - the VTU at pin level: the pins of rtl/units/vtu.v (port.h turns the list
// into the signals, the bind template and the twin's ports, exactly as a Verilated --sc model has
// them: names, and types per toolchain.md pitfall 14), the SystemC twin behind those ports, and
// VtuPort: the cycle-level view the cycle model's vtu unit uses, with either the twin or the
// Verilated model bound in the same place (VtuPortT).
//
// The twin computes each record at the input through hls::Vtu (the one definition of the
// transform) and carries it through a ReadyChain of 2 * STAGES registers (each fp_sop's four
// phases, one register each at STAGES 2): the RTL's latency and handshake, cycle for cycle
// (tb/systemc/test_pins.cpp runs both side by side).
#pragma once

#include <systemc>

#include <cstdint>

#include "hls/image.h"
#include "hls/vtu.h"
#include "hls/wald.h"
#include "systemc/config.h"
#include "systemc/pins/port.h"

namespace raycore::sc::pins {

// One record on either side of the unit: kind 0, up to kVtuNodeLanes nodes (lane j translated
// iff bit j of nmask is set; the others pass unchanged); kind 1, one triangle record (the rest).
constexpr uint32_t kVtuNodeLanes = 4;
struct VtuRec {
  bool kind = false;
  uint64_t node[kVtuNodeLanes] = {};
  uint32_t nmask = 0;
  uint32_t k = 0, flags = 0, c[9] = {}, id = 0, tag = 0;
};

// The data pins of rtl/units/vtu.v (list format: port.h); vtu_on_i and cam_*_i are configuration.
#define RAYCORE_VTU_PINS(CFG, IN, OUT, E)                                                    \
  CFG(E, bool, vtu_on, one) CFG(E, uint32_t, cam, xyz)                                      \
  IN(E, bool, kind, one) IN(E, uint64_t, node, n4) IN(E, uint32_t, nmask, one)              \
  IN(E, uint32_t, k, one)                                                                   \
  IN(E, uint32_t, flags, one) IN(E, uint32_t, c, c9) IN(E, uint32_t, id, one)               \
  IN(E, uint32_t, tag, one)                                                                 \
  OUT(E, bool, kind, one) OUT(E, uint64_t, node, n4) OUT(E, uint32_t, k, one)               \
  OUT(E, uint32_t, flags, one) OUT(E, uint32_t, c, c9) OUT(E, uint32_t, id, one)            \
  OUT(E, uint32_t, tag, one)
RAYCORE_PINS_UNIT(VtuPins, RAYCORE_VTU_PINS, VtuRec, VtuRec);

// The SystemC twin of rtl/units/vtu.v (format F, rounding R; latency 2 x STAGES).
template <class F, hls::Rounding R>
class VtuTwin : public PinTwin<VtuPins> {
 public:
  VtuTwin(sc_core::sc_module_name name, unsigned stages)
      : PinTwin<VtuPins>(name, kVtuLevels * stages) {}

  // The transform of one record, as the RTL computes it (k = 3 is treated as k = 0; node lanes
  // outside nmask pass unchanged).
  static VtuRec compute(const VtuRec& in, bool on, const uint32_t cam[3]) {
    if (!on) return in;
    hls::Vtu<F, R> v;
    for (int i = 0; i < 3; ++i) v.c[i] = cam[i];
    VtuRec o = in;
    if (!in.kind) {
      for (uint32_t j = 0; j < kVtuNodeLanes; ++j)
        if ((in.nmask >> j) & 1u) o.node[j] = v.node(in.node[j]);
      return o;
    }
    hls::WaldTri<F> t;
    t.k = in.k == 3 ? 0 : in.k;
    t.flags = in.flags;
    for (int i = 0; i < 9; ++i) t.c[i] = in.c[i];
    t.id = in.id;
    const hls::WaldTri<F> r = v.tri(t);
    for (int i = 0; i < 9; ++i) o.c[i] = r.c[i];
    return o;
  }

 private:
  VtuRec step(const VtuRec& in) override {
    const uint32_t cam[3] = {cam_x_i.read(), cam_y_i.read(), cam_z_i.read()};
    return compute(in, vtu_on_i.read(), cam);
  }
};

// The cycle-level view of a pin-level VTU (port.h's Port) and its configuration pins.
class VtuPort : public Port<VtuPins> {
 public:
  void config(bool on, const uint32_t cam[3]) {
    s.vtu_on.write(on);
    s.cam_x.write(cam[0]);
    s.cam_y.write(cam[1]);
    s.cam_z.write(cam[2]);
  }
};
template <class M>
using VtuPortT = BoundPort<VtuPort, M>;

}  // namespace raycore::sc::pins
