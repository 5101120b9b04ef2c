// tb/scenes/test_options.cpp - scene options: parsing, overrides, load_scene.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "scenes/generate.h"
#include "scenes/gltf.h"
#include "scenes/options.h"

namespace raycore::scenes {
namespace {

Scene small_scene(bool with_camera, bool with_light) {
  Scene s;
  s.name = s.source = "small";
  s.tris = {{Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{0, 2, 0}}, {Vec3{0, 0, 4}, Vec3{2, 0, 4}, Vec3{0, 2, 4}}};
  if (with_camera) {
    s.camera.present = true;
    s.camera.position = {1, 1, 10};
  }
  if (with_light) s.light = {true, {3, 3, 3}, 7};
  return s;
}

void expect_vec(Vec3 got, Vec3 want, double tol, const std::string& what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], tol) << what << "[" << k << "]";
}

TEST(ParseVec3, GoodAndBad) {
  expect_vec(parse_vec3("1,2.5,-3e2", "--camera"), {1, 2.5, -300}, 0, "plain");
  expect_vec(parse_vec3(" 1, 2 ,3 ", "--camera"), {1, 2, 3}, 0, "spaces");
  for (const char* bad : {"", "1,2", "1,2,3,4", "1,x,3", "nan,0,0", "1,inf,0", "1,,3", "1 2 3"}) {
    try {
      parse_vec3(bad, "--camera");
      ADD_FAILURE() << "'" << bad << "' parsed";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("--camera"), std::string::npos) << e.what();
    }
  }
}

TEST(Overrides, ScaleMultipliesGeometryCameraAndLight) {
  Scene s = small_scene(true, true);
  SceneOverrides o;
  o.scale = 2;
  apply_overrides(s, o);
  expect_vec(s.tris[1][1], {4, 0, 8}, 0, "vertex");
  expect_vec(s.camera.position, {2, 2, 20}, 0, "camera");
  expect_vec(s.light.position, {6, 6, 6}, 0, "light");
  EXPECT_EQ(s.light.intensity, 7);
  o.scale = -1;
  EXPECT_THROW(apply_overrides(s, o), SceneError);
}

TEST(Overrides, CameraLookAtFovLight) {
  Scene s = small_scene(false, false);
  SceneOverrides o;
  o.camera = Vec3{0, 0, 0};
  o.look_at = Vec3{0, 0, -10};
  o.fov_deg = 90;
  o.light = Vec3{1, 2, 3};
  apply_overrides(s, o);
  ASSERT_TRUE(s.camera.present);
  expect_vec(s.camera.forward, {0, 0, -1}, 0, "forward");
  expect_vec(s.camera.up, {0, 1, 0}, 0, "up");
  expect_vec(s.camera.right, {1, 0, 0}, 0, "right");
  EXPECT_DOUBLE_EQ(s.camera.yfov, M_PI / 2);
  ASSERT_TRUE(s.light.present);
  expect_vec(s.light.position, {1, 2, 3}, 0, "light");
  EXPECT_EQ(s.light.intensity, 1);
  EXPECT_NO_THROW(require_camera_and_light(s));
  // Looking straight down still gives an orthonormal basis.
  o.look_at = Vec3{0, -5, 0};
  apply_overrides(s, o);
  expect_vec(s.camera.forward, {0, -1, 0}, 0, "down");
  EXPECT_NEAR(hls::dot(s.camera.up, s.camera.forward), 0, 1e-15);
  EXPECT_NEAR(hls::length(hls::cross(s.camera.right, s.camera.up) + s.camera.forward), 0, 1e-15);
}

TEST(Overrides, CameraOnlyLooksAtSceneCentreOrKeepsOrientation) {
  Scene s = small_scene(false, true);
  SceneOverrides o;
  o.camera = Vec3{1, 1, 12};
  apply_overrides(s, o);
  ASSERT_TRUE(s.camera.present);
  expect_vec(s.camera.forward, {0, 0, -1}, 1e-15, "towards the bounds centre (1, 1, 2)");
  // A scene camera keeps its direction when only the position is overridden.
  Scene t = small_scene(true, true);
  t.camera.forward = {1, 0, 0};
  t.camera.right = {0, 0, 1};
  apply_overrides(t, o);
  expect_vec(t.camera.position, {1, 1, 12}, 0, "moved");
  expect_vec(t.camera.forward, {1, 0, 0}, 0, "kept");
}

TEST(Overrides, ClearErrors) {
  {
    Scene s = small_scene(false, true);
    SceneOverrides o;
    o.look_at = Vec3{0, 0, 0};
    EXPECT_THROW(apply_overrides(s, o), SceneError);
  }
  {
    Scene s = small_scene(false, true);
    SceneOverrides o;
    o.fov_deg = 40;
    EXPECT_THROW(apply_overrides(s, o), SceneError);
  }
  {
    Scene s = small_scene(true, true);
    SceneOverrides o;
    o.fov_deg = 180;
    EXPECT_THROW(apply_overrides(s, o), SceneError);
    o.fov_deg.reset();
    o.look_at = s.camera.position;
    EXPECT_THROW(apply_overrides(s, o), SceneError);
  }
  try {
    require_camera_and_light(small_scene(false, true));
    ADD_FAILURE() << "no camera accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("--camera"), std::string::npos) << e.what();
  }
  try {
    require_camera_and_light(small_scene(true, false));
    ADD_FAILURE() << "no light accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("--light"), std::string::npos) << e.what();
  }
}

TEST(Options, CommandLine) {
  {
    CLI::App app;
    SceneOverrides o;
    add_scene_options(app, o);
    std::vector<std::string> args = {"--scale", "3", "--light", "4,5,6", "--fov", "60", "--look-at", "0,0,0",
                                     "--camera", "1,2,3"};
    std::reverse(args.begin(), args.end());  // CLI11 takes the vector in reverse order
    app.parse(args);
    ASSERT_TRUE(o.camera && o.look_at && o.light && o.fov_deg);
    expect_vec(*o.camera, {1, 2, 3}, 0, "camera");
    expect_vec(*o.light, {4, 5, 6}, 0, "light");
    EXPECT_EQ(*o.fov_deg, 60);
    EXPECT_EQ(o.scale, 3);
  }
  for (std::vector<std::string> bad : {std::vector<std::string>{"--camera", "1,2"}, {"--scale", "0"},
                                       {"--fov", "200"}, {"--light", "a,b,c"}}) {
    CLI::App app;
    SceneOverrides o;
    add_scene_options(app, o);
    std::reverse(bad.begin(), bad.end());
    EXPECT_THROW(app.parse(bad), CLI::ParseError) << bad.back();
  }
}

TEST(LoadScene, GeneratorNameOrPath) {
  SceneOverrides o;
  o.scale = 0.5;
  const Scene s = load_scene("origin-far-camera", o);
  const Scene g = generate("origin-far-camera");
  ASSERT_EQ(s.tris.size(), g.tris.size());
  EXPECT_EQ(s.tris[7][2].x, g.tris[7][2].x * 0.5);
  EXPECT_EQ(s.camera.position.z, g.camera.position.z * 0.5);
  try {
    load_scene("/nonexistent/scene.glb");
    ADD_FAILURE() << "loaded a missing file";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.glb"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace raycore::scenes
