// scenes/gltf.h - glTF 2.0 (.gltf, .glb) loading and writing, and the range check against a number
// format. Every error is a SceneError whose message names the file and the mesh / primitive / node.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace raycore::scenes {

// Loads every TRIANGLES primitive (indexed with uint8/16/32 indices, or not) of the scene's nodes:
// the default scene, else scene 0, else every root node. Node transforms (matrix or TRS) are
// composed and applied in double precision. POSITION accessors may be FLOAT VEC3 or (normalised or
// not) BYTE / UNSIGNED_BYTE / SHORT / UNSIGNED_SHORT VEC3 (KHR_mesh_quantization), with any byte
// stride and sparse substitution. The camera is the first perspective camera node met in
// depth-first order; the light the first KHR_lights_punctual point light node. Non-TRIANGLES
// primitives are skipped and counted (one warning line); zero-area triangles (cross product of two
// edges exactly zero in double) are kept and counted. Warnings go to stats.warnings and, when
// print_warnings, to stderr (one line each, prefixed "warning: <file>:").
Scene load_gltf(const std::string& path, bool print_warnings = true);

// The same from memory. `name` is used in messages (and for Scene::name / source); `base_dir` is
// where external buffers (uri "x.bin") are looked up; empty: external files are refused.
Scene load_gltf_memory(const uint8_t* data, size_t size, const std::string& name,
                       const std::string& base_dir = "", bool print_warnings = false);

// Rejects (SceneError) any vertex, camera or light coordinate whose magnitude exceeds max_abs,
// naming the triangle and its mesh; format_name is used in the message ("fp24").
void check_range(const Scene& scene, double max_abs, const std::string& format_name);

// Writes the scene as glTF 2.0: binary .glb when the path ends in ".glb", else .gltf with the
// buffer embedded as a base64 data URI. One glTF mesh per MeshRange (indexed, vertices shared
// within a mesh), positions as FLOAT (so vertex coordinates are rounded to float32, relative to
// the root node's translation, see encode_glb), the camera as a node with a matrix, the light
// as a KHR_lights_punctual point light, Scene::extras as asset.extras. Deterministic: the same
// scene gives the same bytes.
void write_gltf(const Scene& scene, const std::string& path);

// The .glb bytes write_gltf writes. All meshes hang below one root node "model"; its translation is
// zero unless the scene is far from the origin (a bounds coordinate beyond 2^14), then it is the
// bounds centre rounded to integers, so that float32 vertices keep their precision.
std::vector<uint8_t> encode_glb(const Scene& scene);
// The .gltf text (JSON, buffer as base64 data URI).
std::string encode_gltf_json(const Scene& scene);

// Number of zero-area triangles (cross product of two edges exactly zero in double).
uint64_t count_degenerate(const std::vector<Tri>& tris);

}  // namespace raycore::scenes
