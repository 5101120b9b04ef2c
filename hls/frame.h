// hls/frame.h - what a frame is, per pixel, for every tracer: the golden tracer, the cycle model
// and the double-precision reference (the error metrics compare two frames), and the grey level a
// pixel is written with. Below sim/ and systemc/, which both use it (sim/frame.h names it there).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "hls/geom.h"

namespace raycore::hls {


struct PixelResult {
  int32_t tri = -1;            // scene index of the triangle seen by the primary ray, -1 = miss
  uint32_t t_bits = 0;         // primary hit distance in the run's number format (hardware runs)
  double t = 0;                // primary hit distance (exact value of t_bits for hardware runs)
  Vec3 hit;               // hit point in world space (double; for hardware runs the exact
                               //   value of the format's hit point, camera offset added back)
  bool front = false;          // primary hit with the light on the side the ray came from
  bool shadow_ray = false;     // a shadow ray was spawned (light in front; with --shadow-spawn
                               //   all, every primary hit)
  bool lit = false;            // the pixel is lit: light in front and the shadow ray reached it
  int32_t shadow_tri = -1;     // nearest triangle hit by the shadow ray before the light, -1 none
  uint8_t shade = 0;           // grey level written to the image
};

struct Frame {
  int width = 0, height = 0;
  std::vector<PixelResult> px;  // row-major, (0, 0) at the top left
  const PixelResult& at(int x, int y) const { return px[size_t(y) * size_t(width) + size_t(x)]; }
};


// Grey level of a pixel: 0 for a miss, 40 shadowed, 40 + 215 cos lit (the reference's shading, so
// images compare by eye); shared by the golden tracer and the cycle model.
inline uint8_t shade_pixel(bool hit, bool lit, double cos_light) {
  if (!hit) return 0;
  if (!lit) return 40;
  return uint8_t(40 + std::lround(215.0 * std::clamp(cos_light, 0.0, 1.0)));
}

}  // namespace raycore::hls
