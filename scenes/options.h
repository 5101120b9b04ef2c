// scenes/options.h - the scene options shared by every command that takes a scene (render, simulate,
// scene info): --camera, --look-at, --fov, --light, --scale; and load_scene (file or generator).
#pragma once

#include <optional>
#include <string>

#include "scenes/scene.h"

namespace CLI {
class App;
}

namespace raycore::scenes {

struct SceneOverrides {
  std::optional<Vec3> camera;      // --camera x,y,z: camera position
  std::optional<Vec3> look_at;     // --look-at x,y,z: camera target (+Y up)
  std::optional<double> fov_deg;   // --fov: full vertical field of view in degrees
  std::optional<Vec3> light;       // --light x,y,z: point light position (intensity 1 if new)
  double scale = 1.0;              // --scale s: geometry, scene camera and light, about the origin
  bool any() const { return camera || look_at || fov_deg || light || scale != 1.0; }
};

// "x,y,z" -> Vec3 (finite numbers, exactly three). SceneError naming `what` (e.g. "--camera").
Vec3 parse_vec3(const std::string& text, const std::string& what);

// Adds --camera, --look-at, --fov, --light, --scale to a (sub)command; values land in `o`.
void add_scene_options(CLI::App& app, SceneOverrides& o);

// Applies the overrides, in this order: --scale (multiplies every vertex and the scene's own camera
// and light positions), then --camera, --look-at, --fov, --light, which are given in the final
// (scaled) world frame. --camera without --look-at keeps the scene camera's orientation, or looks
// at the centre of the scene's bounds if the scene has no camera. --look-at alone turns the scene
// camera. A new camera gets the default yfov (50 degrees) unless --fov is given. Throws SceneError
// on a bad value (scale <= 0, fov outside (0, 180), look-at equal to the camera position, --look-at
// or --fov without any camera).
void apply_overrides(Scene& scene, const SceneOverrides& o);

// A camera at `eye` looking at `target`, +Y up (or +Z when looking straight up or down).
Camera look_at(Vec3 eye, Vec3 target, double yfov, double aspect);

// `what` is the name of a built-in generator (see generate.h) or a path to a .gltf / .glb file.
// Loads or generates it, then applies the overrides. Warnings go to stderr.
Scene load_scene(const std::string& what, const SceneOverrides& o = {});

// Throws SceneError saying which options to give when the scene has no camera or no light.
void require_camera_and_light(const Scene& scene);

}  // namespace raycore::scenes
