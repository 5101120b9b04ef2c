// scenes/scene.h - a scene as the rest of the project sees it: triangles in double precision
// (world space, node transforms applied), a pinhole camera and one point light.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "hls/geom.h"

namespace raycore::scenes {

using hls::Box;
using hls::Tri;
using hls::Vec3;

// A pinhole camera: looks down -Z of its own frame with +Y up (glTF convention). `forward`, `up`,
// `right` are an orthonormal world-space basis; yfov in radians; aspect = width / height.
struct Camera {
  bool present = false;  // false: the scene had none (options must supply one)
  Vec3 position;
  Vec3 forward{0, 0, -1};
  Vec3 up{0, 1, 0};
  Vec3 right{1, 0, 0};
  double yfov = 0.8726646259971648;  // 50 degrees
  double aspect = 800.0 / 480.0;
};

struct Light {
  bool present = false;
  Vec3 position;
  double intensity = 1.0;
};

struct LoadStats {
  uint64_t skipped_primitives = 0;  // non-TRIANGLES primitives (skipped, warned)
  uint64_t degenerate_triangles = 0;  // zero-area triangles (kept)
};

struct Scene {
  std::string name;    // file stem or generator name
  std::string source;  // path it was loaded from, or "generated"
  std::vector<Tri> tris;
  Camera camera;
  Light light;
  LoadStats stats;
  Box bounds() const {
    Box b;
    for (const Tri& t : tris)
      for (const Vec3& v : t) b.extend(v);
    return b;
  }
};

// The direction of the primary ray through the centre of pixel (px, py) of a w x h image, pixel
// (0, 0) at the top left, normalised, in double precision. The image's aspect ratio (w / h) is used;
// yfov is the full vertical field of view. Shared by the golden tracer, the cycle model's ray
// generation and the double-precision reference, so all three trace the same rays.
inline Vec3 primary_direction(const Camera& cam, int px, int py, int w, int h) {
  const double t = std::tan(cam.yfov * 0.5);
  const double sx = (2.0 * (px + 0.5) / w - 1.0) * t * (double(w) / double(h));
  const double sy = (1.0 - 2.0 * (py + 0.5) / h) * t;
  return hls::normalize(cam.forward + cam.right * sx + cam.up * sy);
}

}  // namespace raycore::scenes
