// tb/scenes/test_scene_files.cpp - the shared benchmark scenes load as their README says; the
// procedural scenes are deterministic and the shipped scenes/*.glb are exactly what they generate.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "scenes/generate.h"
#include "scenes/gltf.h"

#ifndef RAYCORE_SOURCE_DIR
#error "RAYCORE_SOURCE_DIR must be defined (CMAKE_SOURCE_DIR)"
#endif

namespace raycore::scenes {
namespace {

const std::string kShared = std::string(RAYCORE_SOURCE_DIR) + "/../shared/scenes/";
const std::string kShipped = std::string(RAYCORE_SOURCE_DIR) + "/scenes/";

bool exists(const std::string& p) { return std::ifstream(p).good(); }

std::vector<uint8_t> read_bytes(const std::string& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

void expect_box(const Box& b, Vec3 lo, Vec3 hi, double tol, const std::string& what) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b.lo[k], lo[k], tol) << what << " bounds lo[" << k << "]";
    EXPECT_NEAR(b.hi[k], hi[k], tol) << what << " bounds hi[" << k << "]";
  }
}

// ../shared/scenes/README.md, table "Benchmark scenes".
struct SharedScene {
  const char* file;
  size_t triangles;
  uint64_t degenerate;
  Vec3 lo, hi;
  double tol;  // the README rounds the box to this many units
};
// Shown by name in test listings (not as raw bytes).
inline void PrintTo(const SharedScene& s, std::ostream* os) { *os << s.file; }


class Shared : public ::testing::TestWithParam<SharedScene> {};

TEST_P(Shared, TrianglesBoundsDegenerates) {
  const SharedScene& e = GetParam();
  const std::string path = kShared + e.file;
  if (!exists(path)) GTEST_SKIP() << path << " not found (the shared scenes are not part of the repository)";
  const Scene s = load_gltf(path, false);
  EXPECT_EQ(s.tris.size(), e.triangles) << path;
  EXPECT_EQ(s.stats.degenerate_triangles, e.degenerate) << path;
  EXPECT_EQ(s.stats.skipped_primitives, 0u) << path;
  expect_box(s.bounds(), e.lo, e.hi, e.tol, path);
}

INSTANTIATE_TEST_SUITE_P(
    Readme, Shared,
    ::testing::Values(
        SharedScene{"dabrovic-sponza.glb", 66454, 1, {-17.403, -0.907, -7.799}, {17.417, 15.653, 7.801}, 0.0006},
        // The README says 13 zero-area triangles; exactly zero cross products (in double, of the
        // file's float32 vertices) are 9: 2 with a repeated vertex, 7 collinear. 12 have an area
        // below 1e-7 and 15 below 1e-6, so the README's 13 probably used another test.
        SharedScene{"sibenik.glb", 75284, 9, {-20.141, -15.312, -8.497}, {20.141, 15.300, 8.497}, 0.0006},
        SharedScene{"bunny.glb", 69451, 0, {-1.420, 0.495, -0.928}, {0.915, 2.810, 0.882}, 0.0006},
        SharedScene{"conference.glb", 331179, 53627, {-1020.13, -2.79, -1055.66}, {1685.81, 650.29, 668.49}, 0.006},
        // The paper frames: bounding boxes as the README's "With these transforms ..." paragraph.
        SharedScene{"sponza-paper.glb", 66454, 1, {-1740.3, -90.7, -780.1}, {1741.7, 1565.3, 779.9}, 0.06},
        // README: lo.x -2773.8, but its own transform gives 100 * -20.141 - 759.9 = -2774.0 (and the
        // file loads to -2774.01): the README's figure is off by 0.2; we test the transform's value.
        SharedScene{"sibenik-paper.glb", 75284, 9, {-2774.0, -1.2, -849.7}, {1254.2, 3060.0, 849.7}, 0.06}),
    [](const auto& p) {
      std::string n = p.param.file;
      n = n.substr(0, n.find('.'));
      for (char& c : n)
        if (c == '-') c = '_';
      return n;
    });

struct PaperFrame {
  const char* file;
  Vec3 camera, target, light;
};
inline void PrintTo(const PaperFrame& f, std::ostream* os) { *os << f.file; }


class Paper : public ::testing::TestWithParam<PaperFrame> {};

TEST_P(Paper, CameraAndLight) {
  const PaperFrame& e = GetParam();
  const std::string path = kShared + e.file;
  if (!exists(path)) GTEST_SKIP() << path << " not found (the shared scenes are not part of the repository)";
  const Scene s = load_gltf(path, false);
  ASSERT_TRUE(s.camera.present) << path;
  ASSERT_TRUE(s.light.present) << path;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(s.camera.position[k], e.camera[k], 1e-3) << path << " camera[" << k << "]";
    EXPECT_NEAR(s.light.position[k], e.light[k], 1e-3) << path << " light[" << k << "]";
  }
  const Vec3 want = hls::normalize(e.target - e.camera);
  EXPECT_GT(hls::dot(want, s.camera.forward), 1 - 1e-9) << path << ": camera does not look at the README's target";
  EXPECT_NEAR(s.camera.yfov, 50 * M_PI / 180, 1e-9) << path;
  EXPECT_NEAR(hls::length(s.camera.up), 1, 1e-12);
  EXPECT_NEAR(hls::dot(s.camera.up, s.camera.forward), 0, 1e-12);
  EXPECT_GT(s.camera.up.y, 0) << "+Y up";
}

INSTANTIATE_TEST_SUITE_P(Readme, Paper,
                         ::testing::Values(PaperFrame{"sponza-paper.glb", {-1187.6875, 700.382813, 149.572266},
                                                      {1200, 500, 149.572266}, {0, 1300, 0}},
                                           PaperFrame{"sibenik-paper.glb", {-1633.30078, 643.249512, -666.711365},
                                                      {1200, 450, 0}, {-1200, 800, -200}}),
                         [](const auto& p) { return p.index == 0 ? std::string("sponza") : std::string("sibenik"); });

// ----------------------------------------------------------------------------------------------
class Generated : public ::testing::TestWithParam<std::string> {};

TEST_P(Generated, ShippedFileIsByteIdentical) {
  const std::string path = kShipped + GetParam() + ".glb";
  ASSERT_TRUE(exists(path)) << path << " is missing: run `raycore scene gen all` from the repository root";
  const std::vector<uint8_t> shipped = read_bytes(path), fresh = generate_glb(GetParam());
  ASSERT_EQ(fresh.size(), shipped.size()) << path << " differs from the generator's output (size)";
  size_t first = 0;
  while (first < fresh.size() && fresh[first] == shipped[first]) ++first;
  EXPECT_EQ(first, fresh.size()) << path << " differs from the generator's output at byte " << first
                                 << "; regenerate with `raycore scene gen all` if the change is intended";
}

TEST_P(Generated, DeterministicAndSaneAndEqualToFile) {
  const std::string name = GetParam();
  const Scene a = generate(name), b = generate(name);
  ASSERT_EQ(a.tris.size(), b.tris.size());
  for (size_t i = 0; i < a.tris.size(); ++i)
    for (size_t k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(a.tris[i][k][c], b.tris[i][k][c]) << name << " triangle " << i;
  EXPECT_TRUE(a.camera.present) << name;
  EXPECT_TRUE(a.light.present) << name;
  EXPECT_NO_THROW(check_range(a, 3.6e19, "fp24"));
  EXPECT_FALSE(a.extras.empty()) << name << ": generator notes (asset.extras) missing";
  if (name != "corridor") {
    EXPECT_GE(a.tris.size(), 1000u) << name;
    EXPECT_LE(a.tris.size(), 20000u) << name;
  }
  // The shipped file loads to the same scene.
  const std::string path = kShipped + name + ".glb";
  if (!exists(path)) GTEST_SKIP() << path << " missing (see ShippedFileIsByteIdentical)";
  const Scene f = load_gltf(path, false);
  ASSERT_EQ(f.tris.size(), a.tris.size());
  for (size_t i = 0; i < a.tris.size(); ++i)
    for (size_t k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(f.tris[i][k][c], a.tris[i][k][c]) << path << " triangle " << i;
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(f.camera.position[c], a.camera.position[c]);
    EXPECT_EQ(f.camera.forward[c], a.camera.forward[c]);
    EXPECT_EQ(f.light.position[c], a.light.position[c]);
  }
}

INSTANTIATE_TEST_SUITE_P(All, Generated, ::testing::ValuesIn(generator_names()), [](const auto& p) {
  std::string n = p.param;
  for (char& c : n)
    if (c == '-') c = '_';
  return n;
});

// Möller-Trumbore in double with inclusive edges: nearest t > 0, or -1.
double nearest_hit(const std::vector<Tri>& tris, Vec3 o, Vec3 d) {
  double best = -1;
  for (const Tri& t : tris) {
    const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0], p = hls::cross(d, e2);
    const double det = hls::dot(e1, p);
    if (det == 0) continue;
    const double inv = 1 / det;
    const Vec3 s = o - t[0];
    const double u = hls::dot(s, p) * inv;
    if (u < 0 || u > 1) continue;
    const Vec3 q = hls::cross(s, e1);
    const double v = hls::dot(d, q) * inv;
    if (v < 0 || u + v > 1) continue;
    const double tt = hls::dot(e2, q) * inv;
    if (tt > 0 && (best < 0 || tt < best)) best = tt;
  }
  return best;
}

TEST(Corridor, PaperFrameClosedAndSized) {
  const Scene s = generate("corridor");
  EXPECT_GE(s.tris.size(), 20000u);
  EXPECT_LE(s.tris.size(), 60000u);
  const Box b = s.bounds();
  expect_box(b, {-886, -279, -886}, {1242, 279, 1003}, 0, "corridor");
  EXPECT_EQ(s.camera.position.x, 780.94);
  EXPECT_EQ(s.camera.position.y, 141.63);
  EXPECT_EQ(s.camera.position.z, 73.59);
  EXPECT_EQ(s.stats.degenerate_triangles, 0u);
  // Closed: every primary ray of a 64 x 40 image hits a wall, floor, ceiling or furniture.
  const int w = 64, h = 40;
  int misses = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (nearest_hit(s.tris, s.camera.position, primary_direction(s.camera, x, y, w, h)) < 0) {
        if (++misses <= 5) ADD_FAILURE() << "corridor: primary ray of pixel (" << x << ", " << y << ") escapes";
      }
  EXPECT_EQ(misses, 0);
  // The light is inside the building and not inside a piece of furniture: a ray from the light
  // straight up hits the ceiling (y = 279) first.
  const double t = nearest_hit(s.tris, s.light.position, {0, 1, 0});
  EXPECT_NEAR(s.light.position.y + t, 279, 1e-9);
}

TEST(HardCases, WhereTheyAre) {
  {
    const Scene s = generate("far");
    const Box b = s.bounds();
    const Vec3 c = (b.lo + b.hi) * 0.5;
    EXPECT_GT(hls::length(c), 0.9e5);
    EXPECT_LT(hls::length(c), 1.1e5);
    EXPECT_LT(hls::length(s.camera.position - c), 300);
    EXPECT_LT(hls::length(s.light.position - c), 300);
  }
  {
    const Scene s = generate("far:1e6");
    EXPECT_GT(hls::length(s.bounds().lo), 0.9e6);
    EXPECT_THROW(generate("far:abc"), SceneError);
  }
  {
    const Scene s = generate("origin-far-camera");
    const Box b = s.bounds();
    EXPECT_LT(std::max(hls::length(b.lo), hls::length(b.hi)), 200);
    EXPECT_GT(hls::length(s.camera.position), 1e4);
    EXPECT_LT(hls::length(s.light.position), 300);
    // The narrow field of view still sees the objects: the centre ray hits.
    EXPECT_GT(nearest_hit(s.tris, s.camera.position, primary_direction(s.camera, 400, 240, 800, 480)), 0);
  }
  EXPECT_THROW(generate("no-such-scene"), SceneError);
}

}  // namespace
}  // namespace raycore::scenes
