// sim/frame.h - what a frame is, per pixel, for every tracer: the golden tracer, the cycle model
// and the double-precision reference. The error metrics compare two frames.
#pragma once

#include <cstdint>
#include <vector>

#include "hls/geom.h"

namespace raycore::sim {

struct PixelResult {
  int32_t tri = -1;            // scene index of the triangle seen by the primary ray, -1 = miss
  uint32_t t_bits = 0;         // primary hit distance in the run's number format (hardware runs)
  double t = 0;                // primary hit distance (exact value of t_bits for hardware runs)
  hls::Vec3 hit;               // hit point in world space (double; for hardware runs the exact
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

}  // namespace raycore::sim
