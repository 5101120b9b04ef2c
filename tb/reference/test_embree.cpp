// The Embree (FP32) cross-check of the reference's primary hits (sim/reference/embree_check.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "meshes.h"
#include "sim/reference/embree_check.h"

#if RAYCORE_HAVE_LOADER
#include "scenes/gltf.h"
#endif

namespace raycore::reference {
namespace {

void expect_agreement(const scenes::Scene& scene, int w, int h, double min_pct) {
  EmbreeCheckOptions opt;
  opt.threads = 2;
  const EmbreeAgreement a = embree_check(scene, w, h, opt);
  EXPECT_EQ(a.pixels, uint64_t(w) * uint64_t(h));
  EXPECT_EQ(a.agree + a.disagree, a.pixels);
  EXPECT_GT(a.agree_same_tri, a.pixels / 2) << scene.name << ": the camera should see the scene";
  EXPECT_GE(a.agreement_pct, min_pct) << scene.name << ": " << to_json(a).dump(1);
  std::printf("[ embree   ] %s %dx%d: agreement %.4f%% (%llu disagreements: %llu embree_miss, %llu "
              "embree_extra_hit, %llu different_surface; %llu near an edge)\n",
              scene.name.c_str(), w, h, a.agreement_pct, (unsigned long long)a.disagree,
              (unsigned long long)a.embree_miss, (unsigned long long)a.embree_extra_hit,
              (unsigned long long)a.different_surface, (unsigned long long)a.disagree_near_edge);
}

TEST(ReferenceEmbree, ProceduralWorldAgrees) {
  if (!embree_available()) GTEST_SKIP() << "built without Embree 3 (libembree-dev)";
  expect_agreement(testing::test_world(), 200, 120, 99.9);
}

#if RAYCORE_HAVE_LOADER
// A shared scene (../shared/scenes), with the scene's camera and light, or the given ones.
void shared_scene_agrees(const std::string& file, const scenes::Camera* cam = nullptr) {
  const std::string path = std::string(RAYCORE_SHARED_SCENES) + "/" + file;
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent (the shared scenes are not in the repo)";
  if (!embree_available()) GTEST_SKIP() << "built without Embree 3 (libembree-dev)";
  scenes::Scene s = scenes::load_gltf(path, false);
  if (cam) s.camera = *cam;
  if (!s.light.present) {
    s.light.present = true;
    const hls::Box b = s.bounds();
    s.light.position = (b.lo + b.hi) * 0.5;
  }
  ASSERT_TRUE(s.camera.present) << path << " has no camera";
  expect_agreement(s, 200, 120, 99.9);
}

TEST(ReferenceEmbree, SponzaPaperAgrees) { shared_scene_agrees("sponza-paper.glb"); }
TEST(ReferenceEmbree, SibenikPaperAgrees) { shared_scene_agrees("sibenik-paper.glb"); }
TEST(ReferenceEmbree, DabrovicSponzaInsideAgrees) {
  const scenes::Camera cam = testing::look_at({-12, 2, 0.5}, {12, 5, -1});
  shared_scene_agrees("dabrovic-sponza.glb", &cam);
}
#else
TEST(ReferenceEmbree, SharedScenesAgree) {
  GTEST_SKIP() << "the glTF loader (raycore_scenes) is not part of this build";
}
#endif

}  // namespace
}  // namespace raycore::reference
