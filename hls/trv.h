// hls/trv.h - the traversal unit's datapath: clip a ray to the scene box, and at an inner node
// compute the split-plane distance and decide which children to visit (near/far order).
// The control (stack, leaf lists, looping) is the golden tracer's loop or the trv module's.
#pragma once

#include <cstdint>

#include "hls/fp.h"
#include "hls/ray.h"

namespace raycore::hls {

// Slab test against the scene box: narrows [tnear, tfar] to the box and accepts when the narrowed
// interval widened by `widen` ulps on each side is not empty: (t0 - widen ulps) <= (t1 + widen
// ulps) on the bit patterns (hls::add_ulps in hls/fp.h; hls/margins.h). tnear and tfar are the narrowed values,
// not widened (widen = 0: today's tnear <= tfar).
template <class A>
inline bool trv_clip_box(const uint32_t lo[3], const uint32_t hi[3], const Ray& r, uint32_t& tnear,
                         uint32_t& tfar, int32_t widen = 0) {
  using F = typename A::Fmt;
  uint32_t t0 = r.tmin, t1 = r.tmax;
  for (int a = 0; a < 3; ++a) {
    uint32_t tl = A::mul(A::sub(lo[a], r.o[a]), r.inv[a]);
    uint32_t th = A::mul(A::sub(hi[a], r.o[a]), r.inv[a]);
    if (A::lt(th, tl)) {
      const uint32_t x = tl;
      tl = th;
      th = x;
    }
    t0 = A::max(t0, tl);
    t1 = A::min(t1, th);
  }
  tnear = t0;
  tfar = t1;
  if (widen == 0) return A::le(t0, t1);  // no margin: skip the widening (the inner loop's case)
  return A::le(add_ulps<F>(t0, -widen), add_ulps<F>(t1, widen));
}

enum class Visit : uint8_t { first, second, both };

struct SplitStep {
  Visit visit;
  bool below_first;  // the first child to visit is the left (below the plane) one
  uint32_t tsplit;   // distance to the split plane along the ray
};

// pbrt's rule: the near child is the one on the origin's side (ties: by direction); visit only it
// if the plane is beyond tfar or behind the origin, only the far child if the plane is before
// tnear, else both (far child pushed with [tsplit, tfar]). With widen > 0 (hls/margins.h) the
// comparisons see tfar widened up and tnear widened down by widen ulps (hls::add_ulps), so a plane
// within widen ulps of the interval visits both children; the interval itself is not changed.
template <class A>
inline SplitStep trv_split(uint32_t split, uint32_t axis, const Ray& r, uint32_t tnear,
                           uint32_t tfar, int32_t widen = 0) {
  using F = typename A::Fmt;
  // widen = 0 compares the interval itself (add_ulps by 0 changes only a zero's sign, which no
  // comparison sees), so the inner loop's common case skips it.
  const uint32_t tfar_w = widen ? add_ulps<F>(tfar, widen) : tfar;
  const uint32_t tnear_w = widen ? add_ulps<F>(tnear, -widen) : tnear;
  const uint32_t ts = A::mul(A::sub(split, r.o[axis]), r.inv[axis]);
  const bool below = A::lt(r.o[axis], split) ||
                     (A::eq(r.o[axis], split) && (A::sign(r.d[axis]) || A::is_zero(r.d[axis])));
  Visit v;
  if (A::lt(tfar_w, ts) || !A::lt(A::zero, ts))
    v = Visit::first;
  else if (A::lt(ts, tnear_w))
    v = Visit::second;
  else
    v = Visit::both;
  return {v, below, ts};
}

}  // namespace raycore::hls
