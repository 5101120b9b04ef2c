// scenes/options.cpp - scene overrides, load_scene.
#include "scenes/options.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>

#include "scenes/generate.h"
#include "scenes/gltf.h"

namespace raycore::scenes {

Vec3 parse_vec3(const std::string& text, const std::string& what) {
  Vec3 v;
  size_t commas = 0;
  for (char c : text) commas += c == ',';
  if (commas != 2)
    throw SceneError(what + ": '" + text + "' is not x,y,z (three numbers separated by commas)");
  size_t pos = 0;
  for (int k = 0; k < 3; ++k) {
    const size_t end = k < 2 ? text.find(',', pos) : text.size();
    const std::string part = text.substr(pos, end - pos);
    const char* b = part.c_str();
    char* e = nullptr;
    const double d = std::strtod(b, &e);
    while (e && (*e == ' ' || *e == '\t')) ++e;
    if (part.empty() || e == b || *e != '\0')
      throw SceneError(what + ": '" + part + "' in '" + text + "' is not a number (expected x,y,z)");
    if (!std::isfinite(d)) throw SceneError(what + ": '" + part + "' in '" + text + "' is not finite");
    v[k] = d;
    pos = end + 1;
  }
  return v;
}

void add_scene_options(CLI::App& app, SceneOverrides& o) {
  auto vec = [&app](const std::string& name, std::optional<Vec3>& dst, const std::string& help) {
    app.add_option_function<std::string>(
           name,
           [&dst, name](const std::string& s) {
             try {
               dst = parse_vec3(s, name);
             } catch (const SceneError& e) {
               throw CLI::ValidationError(e.what());
             }
           },
           help)
        ->type_name("X,Y,Z");
  };
  vec("--camera", o.camera, "Camera position (overrides the scene's)");
  vec("--look-at", o.look_at, "Camera target, +Y up (overrides the scene camera's direction)");
  app.add_option_function<double>(
         "--fov", [&o](const double& d) { o.fov_deg = d; }, "Full vertical field of view, degrees")
      ->check(CLI::Range(0.0, 180.0))
      ->type_name("DEG");
  vec("--light", o.light, "Point light position (overrides the scene's)");
  app.add_option("--scale", o.scale, "Scale geometry, camera and light positions about the origin")
      ->check(CLI::PositiveNumber)
      ->type_name("S");
}

Camera look_at(Vec3 eye, Vec3 target, double yfov, double aspect) {
  const Vec3 d = target - eye;
  const double len = hls::length(d);
  if (!(len > 0) || !std::isfinite(len)) throw SceneError("--look-at: the target equals the camera position");
  Camera c;
  c.present = true;
  c.position = eye;
  c.forward = d * (1.0 / len);
  Vec3 up{0, 1, 0};
  if (std::fabs(c.forward.y) > 0.999999) up = {0, 0, c.forward.y > 0 ? -1.0 : 1.0};
  c.right = hls::normalize(hls::cross(c.forward, up));
  c.up = hls::cross(c.right, c.forward);
  c.yfov = yfov;
  c.aspect = aspect;
  return c;
}

void apply_overrides(Scene& scene, const SceneOverrides& o) {
  if (!(o.scale > 0) || !std::isfinite(o.scale))
    throw SceneError("--scale: " + std::to_string(o.scale) + " is not a positive number");
  if (o.scale != 1.0) {
    for (Tri& t : scene.tris)
      for (Vec3& v : t) v = v * o.scale;
    scene.camera.position = scene.camera.position * o.scale;
    scene.light.position = scene.light.position * o.scale;
    scene.stats.degenerate_triangles = count_degenerate(scene.tris);
  }
  if (o.fov_deg && !(*o.fov_deg > 0 && *o.fov_deg < 180))
    throw SceneError("--fov: " + std::to_string(*o.fov_deg) + " degrees is not in (0, 180)");
  const double yfov = o.fov_deg ? *o.fov_deg * (M_PI / 180.0) : scene.camera.yfov;
  if (o.camera || o.look_at) {
    if (!o.camera && !scene.camera.present)
      throw SceneError(scene.source + ": --look-at needs a camera position: the scene has none, give --camera");
    const Vec3 eye = o.camera ? *o.camera : scene.camera.position;
    if (o.look_at) {
      scene.camera = look_at(eye, *o.look_at, yfov, scene.camera.aspect);
    } else if (scene.camera.present) {
      scene.camera.position = eye;
    } else {
      // No direction anywhere: look at the centre of the geometry (down -Z if there is none).
      const Box b = scene.bounds();
      const Vec3 centre = (b.lo + b.hi) * 0.5;
      if (!b.empty() && hls::length(centre - eye) > 0) scene.camera = look_at(eye, centre, yfov, scene.camera.aspect);
      else scene.camera = look_at(eye, eye + Vec3{0, 0, -1}, yfov, scene.camera.aspect);
    }
  }
  if (o.fov_deg) {
    if (!scene.camera.present)
      throw SceneError(scene.source + ": --fov needs a camera: the scene has none, give --camera");
    scene.camera.yfov = yfov;
  }
  if (o.light) {
    if (!scene.light.present) scene.light.intensity = 1.0;
    scene.light.present = true;
    scene.light.position = *o.light;
  }
}

Scene load_scene(const std::string& what, const SceneOverrides& o) {
  Scene s = is_generator(what) ? generate(what) : load_gltf(what, true);
  apply_overrides(s, o);
  return s;
}

void require_camera_and_light(const Scene& scene) {
  if (!scene.camera.present)
    throw SceneError(scene.source + ": the scene has no (perspective) camera: give --camera X,Y,Z (and --look-at X,Y,Z)");
  if (!scene.light.present)
    throw SceneError(scene.source + ": the scene has no point light: give --light X,Y,Z");
}

}  // namespace raycore::scenes
