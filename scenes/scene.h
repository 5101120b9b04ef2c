// scenes/scene.h - a scene as the rest of the project sees it: triangles in double precision
// (world space, node transforms applied), a pinhole camera and one point light.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
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
  std::vector<std::string> warnings;  // one line each (also printed to stderr by load_gltf)
};

// Bad input (file, glTF content, scene options, generator name): the message names the file and
// the mesh / primitive / node / triangle concerned. The CLI turns it into a clear non-zero exit.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A named run of consecutive triangles: one glTF mesh instance (mesh + the node that places it),
// or one part of a generated scene. Used in error messages and by the glTF writer.
struct MeshRange {
  std::string name;  // mesh name, or "mesh <index>" when unnamed
  std::string node;  // node name, or "node <index>" when unnamed ("" for generated parts)
  size_t first = 0;  // index of the first triangle in Scene::tris
  size_t count = 0;
};

struct Scene {
  std::string name;    // file stem or generator name
  std::string source;  // path it was loaded from, or "generated"
  std::vector<Tri> tris;
  Camera camera;
  Light light;
  LoadStats stats;
  std::vector<MeshRange> meshes;  // in triangle order; may be empty (then: one unnamed mesh)
  std::string extras;             // glTF asset.extras as JSON text ("" if none): generator notes
  Box bounds() const {
    Box b;
    for (const Tri& t : tris)
      for (const Vec3& v : t) b.extend(v);
    return b;
  }
  // "mesh 'x' (node 'y')" for the mesh holding triangle `tri`, for messages.
  std::string describe_triangle(size_t tri) const {
    std::string d = "triangle " + std::to_string(tri);
    for (const MeshRange& m : meshes)
      if (tri >= m.first && tri - m.first < m.count) {
        d += " (mesh '" + m.name + "'";
        if (!m.node.empty()) d += ", node '" + m.node + "'";
        d += ")";
        break;
      }
    return d;
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
