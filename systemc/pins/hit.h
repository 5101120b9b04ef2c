// systemc/pins/hit.h - the hit unit at pin level: the pins of rtl/units/hit.v (port.h turns the list
// into the signals, the bind template and the twin's ports, exactly as a Verilated --sc model has
// them), its SystemC twin HitTwin, and HitPort / HitPortT, the cycle-level view the cycle model's
// hit uses with either bound in the same place.
//
// The twin computes each hit at the input through hls::hit_shadow_regs (the one definition of the
// unit) with the register values on its pins, and carries the result through a ReadyChain of
// kHitLevels (systemc/config.h) x STAGES registers: the RTL's latency and handshake, cycle for cycle.
#pragma once

#include <systemc>

#include <cstdint>

#include "hls/hit.h"
#include "systemc/config.h"
#include "systemc/pins/port.h"

namespace raycore::sc::pins {

// One hit in: the primary ray, its t, the hit triangle's k, plane and den (hls::HitTri), a tag.
struct HitIn {
  uint32_t o[3] = {}, d[3] = {}, t = 0, k = 0, nu = 0, nv = 0, nd = 0, den = 0, id = 0, tag = 0;
};
// Its result: hls::ShadowSetup's fields, the tag.
struct HitOutRec {
  uint32_t h[3] = {};
  bool front = false, spawn = false;
  uint32_t dens = 0, o[3] = {}, d[3] = {}, inv[3] = {}, tmin = 0, tmax = 0, skip_id = 0, tag = 0;
};

// The data pins of rtl/units/hit.v (list format: port.h). The CFG pins are the per-frame registers
// (static while rays are in flight): the light, t_min, the strategy (hls::Spawn), segment or unit
// shadow rays, --shadow-spawn all, and hls::HitRegs.
#define RAYCORE_HIT_PINS(CFG, IN, OUT, E)                                                    \
  CFG(E, uint32_t, light, xyz) CFG(E, uint32_t, tmin, one) CFG(E, uint32_t, strategy, one)  \
  CFG(E, bool, segment, one) CFG(E, bool, all, one) CFG(E, uint32_t, back, one)             \
  CFG(E, uint32_t, scale, one) CFG(E, uint32_t, fixed, one) CFG(E, uint32_t, slab_scale, one) \
  IN(E, uint32_t, o, xyz) IN(E, uint32_t, d, xyz) IN(E, uint32_t, t, one)                   \
  IN(E, uint32_t, k, one) IN(E, uint32_t, nu, one) IN(E, uint32_t, nv, one)                 \
  IN(E, uint32_t, nd, one) IN(E, uint32_t, den, one) IN(E, uint32_t, id, one)               \
  IN(E, uint32_t, tag, one)                                                                 \
  OUT(E, uint32_t, h, xyz) OUT(E, bool, front, one) OUT(E, bool, spawn, one)                \
  OUT(E, uint32_t, dens, one) OUT(E, uint32_t, o, xyz) OUT(E, uint32_t, d, xyz)             \
  OUT(E, uint32_t, inv, xyz) OUT(E, uint32_t, tmin, one) OUT(E, uint32_t, tmax, one)        \
  OUT(E, uint32_t, skip_id, one) OUT(E, uint32_t, tag, one)
RAYCORE_PINS_UNIT(HitPins, RAYCORE_HIT_PINS, HitIn, HitOutRec);

// The per-frame registers as the unit's pins carry them.
struct HitConfig {
  uint32_t light[3] = {}, tmin = 0;
  hls::SpawnParams sp;
  hls::HitRegs g;
};

// The cycle-level view of a pin-level hit unit (port.h's Port) and its configuration pins.
class HitPort : public Port<HitPins> {
 public:
  void config(const HitConfig& c) {
    s.light_x.write(c.light[0]);
    s.light_y.write(c.light[1]);
    s.light_z.write(c.light[2]);
    s.tmin.write(c.tmin);
    s.strategy.write(uint32_t(c.sp.spawn));
    s.segment.write(c.sp.segment);
    s.all.write(c.sp.spawn_all);
    s.back.write(uint32_t(c.g.back));
    s.scale.write(c.g.scale);
    s.fixed.write(c.g.fixed);
    s.slab_scale.write(c.g.slab_scale);
  }
};
template <class M>
using HitPortT = BoundPort<HitPort, M>;

// The SystemC twin of rtl/units/hit.v for the arithmetic A (hls::Arith<F, R>).
template <class A>
class HitTwin : public PinTwin<HitPins> {
 public:
  HitTwin(sc_core::sc_module_name name, unsigned stages)
      : PinTwin<HitPins>(name, kHitLevels * stages) {}

  // One hit as the RTL computes it (k = 3 is treated as k = 0, strategy 7 as none).
  static HitOutRec compute(const HitIn& in, const HitConfig& c) {
    hls::Ray pr;
    for (int i = 0; i < 3; ++i) {
      pr.o[i] = in.o[i];
      pr.d[i] = in.d[i];
    }
    const hls::HitTri tri{in.id, in.k == 3 ? 0 : in.k, in.nu, in.nv, in.nd, in.den};
    const hls::ShadowSetup s = hls::hit_shadow_regs<A>(pr, in.t, tri, c.light, c.tmin, c.sp, c.g);
    HitOutRec r;
    for (int i = 0; i < 3; ++i) {
      r.h[i] = s.h[i];
      r.o[i] = s.ray.o[i];
      r.d[i] = s.ray.d[i];
      r.inv[i] = s.ray.inv[i];
    }
    r.front = s.front;
    r.spawn = s.spawn;
    r.dens = s.dens;
    r.tmin = s.ray.tmin;
    r.tmax = s.ray.tmax;
    r.skip_id = s.skip_id;
    r.tag = in.tag;
    return r;
  }

 private:
  HitOutRec step(const HitIn& in) override {
    HitConfig c;
    c.light[0] = light_x_i.read();
    c.light[1] = light_y_i.read();
    c.light[2] = light_z_i.read();
    c.tmin = tmin_i.read();
    const uint32_t st = strategy_i.read() & 7u;
    c.sp.spawn = st > uint32_t(hls::Spawn::skip_back) ? hls::Spawn::none : hls::Spawn(st);
    c.sp.segment = segment_i.read();
    c.sp.spawn_all = all_i.read();
    c.g.back = int32_t(back_i.read());
    c.g.scale = scale_i.read();
    c.g.fixed = fixed_i.read();
    c.g.slab_scale = slab_scale_i.read();
    return compute(in, c);
  }
};

}  // namespace raycore::sc::pins
