// hls/ray.h - a ray as the hardware holds it: origin, direction, reciprocal direction and the
// interval (tmin, tmax), all numbers of the run's format.
#pragma once

#include <cstdint>

namespace raycore::hls {

struct Ray {
  uint32_t o[3] = {0, 0, 0};
  uint32_t d[3] = {0, 0, 0};
  uint32_t inv[3] = {0, 0, 0};  // rcp(d[i]); rcp(+-0) saturates to +-max
  uint32_t tmin = 0, tmax = 0;
};

// u and v axes of Wald's projection for dominant axis k.
constexpr int axis_u(uint32_t k) { return int(k == 2 ? 0 : k + 1); }
constexpr int axis_v(uint32_t k) { return int(k == 0 ? 2 : k - 1); }

}  // namespace raycore::hls
