// systemc/hit.h - the hit unit: for a finished primary ray the hit point and the shadow ray
// (hls::hit_shadow with the configured spawn strategy; with --shadow-spawn all also when the light
// is behind), handed to the rgu in the same slot; for a finished shadow ray the light decision;
// the pixel written to the frame (hls::shade_pixel, the golden tracer's inputs). One ray per cycle, hit_latency cycles to the pixel write / hand-over.
#pragma once

#include <systemc>

#include <cmath>

#include "hls/hit.h"
#include "hls/trace.h"
#include "systemc/slot.h"
#include "systemc/slot_unit.h"

namespace raycore::sc {

template <class A>
class Hit : public SlotUnit {
 public:
  using SlotUnit::SlotUnit;

  bool tick(Cycle now) {
    if (!ch_.hit_q.can_pop(now)) return false;
    const uint16_t s = ch_.hit_q.pop();
    Slot& r = ch_.slots[s];
    hls::PixelResult& p = fc_.frame->px[r.pixel];
    const Cycle done = now + lat_;
    ++st_.hit_busy;
    if (r.shadow) {
      p.lit = p.front && !r.best.found;  // --shadow-spawn all: a ray behind the light is not lit
      p.shadow_tri = r.best.found ? int32_t(r.best.id) : -1;
      p.shade = hls::shade_pixel(true, p.lit, r.cos_light);
      ++fc_.shadow_retired[r.pixel];
      return retire(s, done);
    }
    ++fc_.primary_retired[r.pixel];
    if (!r.best.found) {
      p.shade = hls::shade_pixel(false, false, 0);
      return retire(s, done);
    }
    const Best& b = r.best;
    p.tri = int32_t(b.id);
    p.t_bits = b.t;
    p.t = A::to_double(b.t);
    const hls::HitTri ht{b.id, b.k, b.nu, b.nv, b.nd, b.den};
    const hls::ShadowSetup ss = hls::hit_shadow<A>(r.ray, b.t, ht, fc_.light, fc_.tmin, fc_.spawn);
    p.hit = {A::to_double(ss.h[0]) + fc_.offset[0], A::to_double(ss.h[1]) + fc_.offset[1],
             A::to_double(ss.h[2]) + fc_.offset[2]};
    p.front = ss.front;
    if (!ss.spawn) {
      p.shade = hls::shade_pixel(true, false, 0);
      return retire(s, done);
    }
    p.shadow_ray = true;
    const double nu = A::to_double(b.nu), nv = A::to_double(b.nv);
    double l2 = 0;
    for (int i = 0; i < 3; ++i) l2 += A::to_double(ss.ray.d[i]) * A::to_double(ss.ray.d[i]);
    r.cos_light = std::fabs(A::to_double(ss.dens)) / std::sqrt((1 + nu * nu + nv * nv) * l2);
    r.ray = ss.ray;
    r.skip_id = ss.skip_id;
    r.shadow = true;
    r.state = SlotState::start;
    ch_.shadow_q.push(s, done);
    ++fc_.retired;  // the primary ray
    ++st_.retired;
    fc_.last_retire = std::max(fc_.last_retire, done);
    return true;
  }

  Cycle next_event() const { return ch_.hit_q.head_ready(); }

 private:
  bool retire(uint16_t s, Cycle done) {
    ch_.free_slots.push_back(s);
    ++fc_.retired;
    ++st_.retired;
    fc_.last_retire = std::max(fc_.last_retire, done);
    return true;
  }
};

}  // namespace raycore::sc
