// scenes/generate.h - the project's procedural scenes (deterministic; shipped as scenes/<name>.glb).
//
//   corridor           stand-in for the paper's "Spatial Partitioning II": furnished rooms joined by
//                      a long passage, bbox (-886, -279, -886) .. (1242, 279, 1003), camera at
//                      (780.94, 141.63, 73.59); the default scene of `make run`.
//   far                a mesh ~10^5 from the origin, camera beside it ("far:<distance>" for others)
//   grazing            large planes seen and lit at grazing angles
//   slivers            long thin triangles in fans and strips with shared edges
//   coplanar           adjacent, overlapping and nearly coplanar triangles (decal layers)
//   origin-far-camera  objects near the origin, camera ~5.5 * 10^4 away (the paper's limitation)
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace raycore::scenes {

// The shipped generators, in a fixed order.
std::vector<std::string> generator_names();
// True for a shipped name or "far:<distance>".
bool is_generator(const std::string& name);
// One line: what the scene stresses.
std::string generator_description(const std::string& name);

// The generator's own double-precision scene (before the glTF round trip).
Scene build_scene(const std::string& name);
// The .glb bytes of the scene (encode_glb(build_scene(name))): scenes/<name>.glb holds exactly these.
std::vector<uint8_t> generate_glb(const std::string& name);
// The scene as loaded back from those bytes, so generate(name) and load_gltf("scenes/<name>.glb")
// give identical triangles, camera and light (vertex coordinates are float32 relative to the
// file's root node). Scene::source is "generated".
Scene generate(const std::string& name);

}  // namespace raycore::scenes
