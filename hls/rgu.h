// hls/rgu.h - ray generation: a primary ray from the camera through a pixel centre.
//
// The direction is computed in double from the camera basis (scenes::primary_direction) and
// rounded once per component: the camera set-up is host data, as the light is, and the paper's
// subject (traversal, intersection, the VTU) starts from these rays. The reciprocal direction is
// formed by the format's rcp, as the hardware's ray set-up would.
#pragma once

#include "hls/fp.h"
#include "hls/ray.h"

namespace raycore::hls {

// origin: the camera position in the format (VTU off) or 0 (VTU on: the camera is at the origin).
template <class A>
inline Ray rgu_primary(const uint32_t origin[3], const double dir[3], uint32_t tmin) {
  Ray r;
  for (int i = 0; i < 3; ++i) {
    r.o[i] = origin[i];
    r.d[i] = A::from_double(dir[i]);
    r.inv[i] = A::rcp(r.d[i]);
  }
  r.tmin = tmin;
  r.tmax = A::Fmt::max_mag;
  return r;
}

}  // namespace raycore::hls
