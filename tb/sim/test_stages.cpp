// The error budget by stage (sim/errors.h, issue 27): the stages add up to the totals on small
// frames of every kind of scene and configuration; the replayed hardware rays are the golden
// tracer's; and one constructed frame per stage whose error pixel lands in that stage.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "hls/fp.h"
#include "hls/image.h"
#include "hls/rgu.h"
#include "scenes/scene.h"
#include "sim/errors.h"
#include "sim/golden/golden.h"
#include "sim/reference/metrics.h"
#include "sim/run.h"

namespace {

namespace hls = raycore::hls;
namespace sim = raycore::sim;
namespace scenes = raycore::scenes;
using hls::FormatId;
using hls::Rounding;
using hls::Tri;
using hls::Vec3;
using sim::Stage;

struct Rendered {
  sim::Prepared p;
  sim::TraceConfig cfg;
  sim::Frame frame;
  sim::FrameErrors e;
};

// A frame as `raycore render` makes it (the same preparation, golden tracer and measurement),
// kept for the other tests of this file.
const Rendered& render(const std::string& scene, const std::string& format, const std::string& rounding,
                       const std::string& vtu, const std::string& spawn, const std::string& store = "world",
                       int w = 64, int h = 40, int threads = 2, const std::string& ist = "wald") {
  static std::map<std::string, Rendered> cache;
  const std::string key = scene + "/" + format + "/" + rounding + "/" + vtu + "/" + spawn + "/" + store + "/" +
                          std::to_string(w) + "x" + std::to_string(h) + "/" + std::to_string(threads) + "/" + ist;
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  sim::RunOptions o;
  o.scene = scene;
  o.format = format;
  o.rounding = rounding;
  o.vtu = vtu;
  o.spawn = spawn;
  o.store = store;
  o.shadow_hit = "closest";
  o.width = w;
  o.height = h;
  o.threads = threads;
  o.ist = ist;
  Rendered r;
  r.cfg = sim::trace_config(o);
  r.p = sim::prepare(o, r.cfg);
  r.frame = sim::trace_golden(r.p.image, r.p.scene.camera, r.p.scene.light, r.cfg);
  r.e = sim::measure_errors(r.frame, r.p.scene, r.p.image, r.cfg);
  return cache.emplace(key, std::move(r)).first->second;
}

void expect_adds_up(const sim::FrameErrors& e, const std::string& what) {
  ASSERT_TRUE(e.has_stages) << what << ": " << e.stages_note;
  const sim::StageBudget& b = e.stages;
  EXPECT_EQ(b.primary_errors, e.total.primary_errors) << what;
  EXPECT_EQ(b.shadow_errors, e.total.shadow_errors) << what;
  EXPECT_EQ(b.storage.primary + b.ray_generation.primary + b.traversal_intersection.primary + b.spawn.primary,
            e.total.primary_errors)
      << what;
  EXPECT_EQ(b.storage.shadow + b.ray_generation.shadow + b.traversal_intersection.shadow + b.spawn.shadow,
            e.total.shadow_errors)
      << what;
  EXPECT_EQ(b.spawn.primary, 0u) << what << ": a primary error is settled before the spawn";
  EXPECT_EQ(b.traversal_shadow_by_primary_ray + b.traversal_shadow_by_shadow_ray, b.traversal_intersection.shadow)
      << what;
  EXPECT_LE(b.traversal_vtu_primary, b.traversal_intersection.primary) << what;
  EXPECT_LE(b.traversal_vtu_shadow, b.traversal_intersection.shadow) << what;
  // The primary ray's traversal errors by kind (edge, order, deep, same) are all of them.
  EXPECT_EQ(b.traversal_kind[0] + b.traversal_kind[1] + b.traversal_kind[2] + b.traversal_kind[3] +
                b.traversal_kind[4],
            b.traversal_intersection.primary + b.traversal_shadow_by_primary_ray)
      << what;
  uint64_t charged = 0;
  for (Stage s : b.pixel) charged += s != Stage::none;
  EXPECT_EQ(charged, e.total.primary_errors + e.total.shadow_errors) << what;
  const auto j = sim::stages_json(b);
  EXPECT_EQ(j["error_pixels"].get<uint64_t>(), e.total.primary_errors + e.total.shadow_errors) << what;
}

bool same(const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

std::string budget_line(const sim::StageBudget& b) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "storage %llu+%llu raygen %llu+%llu trav %llu+%llu (vtu %llu+%llu; primary ray's crack %llu "
                "silhouette %llu order %llu deep %llu same %llu) spawn %llu+%llu",
                (unsigned long long)b.storage.primary, (unsigned long long)b.storage.shadow,
                (unsigned long long)b.ray_generation.primary, (unsigned long long)b.ray_generation.shadow,
                (unsigned long long)b.traversal_intersection.primary,
                (unsigned long long)b.traversal_intersection.shadow, (unsigned long long)b.traversal_vtu_primary,
                (unsigned long long)b.traversal_vtu_shadow, (unsigned long long)b.traversal_kind[0],
                (unsigned long long)b.traversal_kind[1], (unsigned long long)b.traversal_kind[2],
                (unsigned long long)b.traversal_kind[3], (unsigned long long)b.traversal_kind[4],
                (unsigned long long)b.spawn.primary,
                (unsigned long long)b.spawn.shadow);
  return buf;
}

// Every kind of scene, format, VTU, store and spawn: each error pixel charged once, the stages'
// sums the totals, the per-pixel stages the error pixels.
TEST(ErrorStages, AddUpToTheTotals) {
  struct Case {
    const char *scene, *format, *rounding, *vtu, *spawn, *store;
  };
  const Case cases[] = {
      {"corridor", "fp24", "rtz", "off", "none", "world"},     {"corridor", "fp24", "rtz", "on", "none", "world"},
      {"corridor", "fp24", "rne", "on", "skip-back", "world"}, {"corridor", "fp32", "rne", "off", "none", "world"},
      {"far", "fp24", "rtz", "off", "none", "world"},          {"far", "fp24", "rtz", "on", "none", "world"},
      {"far", "fp24", "rtz", "on", "skip-slab", "anchored"},   {"grazing", "fp24", "raycore", "on", "none", "world"},
      {"slivers", "fp24", "rtz", "on", "ulp-offset", "world"}, {"coplanar", "fp24", "rne", "off", "error-bound", "world"},
      {"origin-far-camera", "fp24", "rtz", "on", "none", "anchored"},
  };
  for (const Case& c : cases) {
    const std::string what = std::string(c.scene) + " " + c.format + "-" + c.rounding + " vtu " + c.vtu + " " +
                             c.spawn + " " + c.store;
    const Rendered& r = render(c.scene, c.format, c.rounding, c.vtu, c.spawn, c.store);
    expect_adds_up(r.e, what);
    std::printf("stages: %-50s primary %llu shadow %llu: %s\n", what.c_str(),
                (unsigned long long)r.e.total.primary_errors, (unsigned long long)r.e.total.shadow_errors,
                budget_line(r.e.stages).c_str());
    if (std::string(c.vtu) == "off") {
      EXPECT_EQ(r.e.stages.traversal_vtu_primary + r.e.stages.traversal_vtu_shadow, 0u) << what << ": no VTU";
    }
  }
}

// The budget's per-pixel records (--error-pixels) are its counts: one per error pixel, row-major, each
// with the stage of its pixel, the hardware's hit of the frame, and for the primary ray's traversal
// errors the kind counted; the CSV has a line per record.
TEST(ErrorStages, ErrorPixelsAreTheBudget) {
  const Rendered& r = render("corridor", "fp24", "rtz", "on", "none", "world");
  ASSERT_TRUE(r.e.has_stages) << r.e.stages_note;
  const sim::StageBudget& b = r.e.stages;
  ASSERT_EQ(b.error_pixels.size(), b.primary_errors + b.shadow_errors);
  ASSERT_GT(b.error_pixels.size(), 0u) << "corridor 64 x 40 VTU on, spawn none has error pixels";
  uint64_t primary = 0, kinds[sim::kTraversalKinds] = {};
  size_t last = 0;
  for (size_t k = 0; k < b.error_pixels.size(); ++k) {
    const sim::ErrorPixel& p = b.error_pixels[k];
    const size_t i = size_t(p.y) * size_t(r.frame.width) + size_t(p.x);
    if (k > 0) {
      EXPECT_GT(i, last) << "row-major";
    }
    last = i;
    EXPECT_EQ(p.stage, b.pixel[i]) << p.x << "," << p.y;
    EXPECT_NE(p.stage, Stage::none);
    EXPECT_EQ(p.tri_b, r.frame.px[i].tri);
    primary += p.primary;
    if (p.stage == Stage::traversal_primary) {
      ++kinds[size_t(p.kind)];
      EXPECT_FALSE(std::isnan(p.tol)) << "a traversal error's tolerance is measured";
    }
    if (p.stage != Stage::storage && p.tri_a < 0) {
      EXPECT_TRUE(std::isnan(p.t_a));
    }
  }
  EXPECT_EQ(primary, b.primary_errors);
  for (int k = 0; k < sim::kTraversalKinds; ++k) EXPECT_EQ(kinds[k], b.traversal_kind[k]) << "kind " << k;
  const std::string path = testing::TempDir() + "error_pixels.csv";
  sim::write_error_pixels(r.e, true, path);
  std::FILE* in = std::fopen(path.c_str(), "r");
  ASSERT_NE(in, nullptr);
  char line[512];
  size_t lines = 0;
  std::string header;
  while (std::fgets(line, sizeof line, in)) {
    if (lines == 0) header = line;
    ++lines;
  }
  std::fclose(in);
  EXPECT_EQ(lines, b.error_pixels.size() + 1);
  EXPECT_EQ(header.rfind("x,y,error,stage,", 0), 0u) << header;
  sim::FrameErrors none;
  none.stages_note = "the frame is not the golden tracer's";
  EXPECT_THROW(sim::write_error_pixels(none, true, path), std::runtime_error);
  EXPECT_THROW(sim::write_error_pixels(r.e, false, path), std::runtime_error);
  EXPECT_THROW(sim::write_error_pixels(r.e.stages, "/nonexistent-dir/x.csv"), std::runtime_error);
}

// A golden frame in issue 27 part 2's zero configuration (FP24, VTU off, skip-back, anchored,
// --ist watertight --trv-widen 2) and its error budget.
struct ZeroRun {
  sim::RunOptions o;
  sim::TraceConfig cfg;
  sim::Prepared p;
  sim::Frame f;
  sim::FrameErrors e;
  static sim::RunOptions options(const std::string& scene, const char* rounding, int width, int height,
                                 const char* ist, const char* vtu, const char* store) {
    sim::RunOptions o;
    o.scene = scene;
    o.rounding = rounding;
    o.vtu = vtu;
    o.spawn = "skip-back";
    o.store = store;
    o.shadow_hit = "closest";
    o.ist = ist;
    o.trv_widen = 2;
    o.width = width;
    o.height = height;
    o.threads = 2;
    return o;
  }
  ZeroRun(const std::string& scene, const char* rounding, int width, int height, const char* ist = "watertight",
          const char* vtu = "off", const char* store = "anchored")
      : o(options(scene, rounding, width, height, ist, vtu, store)),
        cfg(sim::trace_config(o)),
        p(sim::prepare(o, cfg)),
        f(sim::trace_golden(p.image, p.scene.camera, p.scene.light, cfg)),
        e(sim::measure_errors(f, p.scene, p.image, cfg)) {
    expect_adds_up(e, scene + " " + ist + " " + rounding);
  }
};

// origin-far-camera's camera is 5.5 x 10^4 from the scene (an FP24 t ulp of 0.5 there). With the
// watertight test's t from the sheared vertices in FP32's 8/23 and the closest-hit compares on that
// key (2026-12-07) the zero configuration has no traversal/intersection error and no
// self-intersection; with the plane's t in FP24 it had 0 + 86, all orders of two hits.
TEST(ErrorStages, FarCameraZeroWithTheVerticesT) {
  const ZeroRun z("origin-far-camera", "rtz", 200, 120);
  const sim::StageBudget& b = z.e.stages;
  EXPECT_EQ(b.traversal_intersection.total(), 0u) << budget_line(b);
  EXPECT_EQ(z.e.stored.self_intersections, 0u);
  EXPECT_EQ(z.e.total.self_intersections, 0u);
}

// Issue 27 part 3: far at 10^6 stored in world coordinates with the VTU on (the zero configuration
// otherwise) within 2x of its anchored arithmetic error count. FP24's ulp there is 8 units: the
// watertight records' rounded vertices leave their scene triangles' cells, and flat ones lie in
// split planes; the kd-tree lists each stored triangle where it crosses (hls/kdtree.h). Before
// (2026-12-07, 200 x 120) world had 146 primary errors against anchored's 0 (800 x 480: 2,586 of
// which 1,339 deep against 6).
TEST(ErrorStages, FarWorldZeroConfigurationWithinTwiceAnchored) {
  const ZeroRun world("far:1e6", "rtz", 200, 120, "watertight", "on", "world");
  const ZeroRun anchored("far:1e6", "rtz", 200, 120, "watertight", "on", "anchored");
  const auto& w = world.e.stored;
  const auto& a = anchored.e.stored;
  EXPECT_LE(w.primary_errors, 2 * a.primary_errors + 2) << budget_line(world.e.stages);
  EXPECT_LE(w.shadow_errors, 2 * a.shadow_errors + 2) << budget_line(world.e.stages);
  EXPECT_EQ(w.self_intersections, 0u);
  EXPECT_GT(world.e.stages.storage.primary, 1000u) << "the store itself moves the geometry: " << budget_line(world.e.stages);
}

// Wald's test in the same configuration with rne leaves orders of two hits there (2 at 200 x 120,
// among its cracks and silhouettes): the hardware's own test hits the exact ray's triangle A as
// well, at a t no smaller than its t for the triangle B it kept, the exact ray meeting B too (the
// records say so pixel by pixel).
TEST(ErrorStages, FarCameraWaldLeavesOrdersOfTwoHits) {
  const ZeroRun z("origin-far-camera", "rne", 200, 120, "wald");
  const sim::TraceConfig& cfg = z.cfg;
  const sim::Prepared& p = z.p;
  const sim::StageBudget& b = z.e.stages;
  EXPECT_GE(b.traversal_kind[size_t(sim::TraversalKind::order)], 1u) << budget_line(b);
  int orders = 0;
  for (const sim::ErrorPixel& ep : b.error_pixels) {
    if (ep.stage != Stage::traversal_primary || ep.kind != sim::TraversalKind::order) continue;
    ++orders;
    EXPECT_GE(ep.tri_a, 0);
    EXPECT_NE(ep.tri_a, ep.tri_b);
    EXPECT_GE(ep.t_a_hw, ep.t_b) << "pixel " << ep.x << "," << ep.y;
    EXPECT_GE(ep.edge_b, 0.0) << "pixel " << ep.x << "," << ep.y << ": the exact ray meets B too";
    const sim::HardwareRays rays(p.image, p.scene.camera, p.scene.light, cfg);
    const sim::IstVerdict va = rays.test(ep.x, ep.y, ep.tri_a), vb = rays.test(ep.x, ep.y, ep.tri_b);
    EXPECT_TRUE(va.hit && vb.hit);
    EXPECT_EQ(va.t, ep.t_a_hw);
    EXPECT_EQ(vb.t, ep.t_b) << "the frame's t is the test's";
  }
  EXPECT_EQ(uint64_t(orders), b.traversal_kind[size_t(sim::TraversalKind::order)]);
}

// An order is two hits the exact ray meets both of; where the hardware's test hits A at a t no
// smaller than its t for B but the exact ray passes outside B, B's outline was decided wrong: a
// silhouette. sponza-paper (../shared/scenes) 800 x 480 in the zero configuration with rne has one
// (pixel 599, 447: B at t 272.77 passed just outside, seen nearly edge-on, A 9952 behind it at
// 294.3; B was 9956, 0.0029 outside, until the watertight test's t came from the sheared vertices,
// then 10475, 6 x 10^-6 outside), an order before 2026-12-07.
TEST(ErrorStages, SilhouetteWhereTheExactRayPassesOutsideB) {
  if (RAYCORE_SANITIZED) {
    GTEST_SKIP() << "a full sponza-paper frame: the release build runs it (minutes under ASan)";
  }
  const std::string path = std::string(RAYCORE_SHARED_SCENES_DIR) + "/sponza-paper.glb";
  if (!std::ifstream(path).good()) {
    GTEST_SKIP() << path << " not found (../shared/scenes)";
  }
  const ZeroRun z(path, "rne", 800, 480);
  const sim::StageBudget& b = z.e.stages;
  bool found = false;
  for (const sim::ErrorPixel& ep : b.error_pixels) {
    if (ep.stage != Stage::traversal_primary) continue;
    if (ep.kind == sim::TraversalKind::order) {
      EXPECT_GE(ep.edge_b, 0.0) << "pixel " << ep.x << "," << ep.y;
    }
    if (ep.x != 599 || ep.y != 447) continue;
    found = true;
    EXPECT_EQ(ep.kind, sim::TraversalKind::silhouette) << budget_line(b);
    EXPECT_EQ(ep.tri_a, 9952);
    EXPECT_EQ(ep.tri_b, 10475);
    EXPECT_LT(ep.edge_b, 0.0);
    EXPECT_GE(ep.t_a_hw, ep.t_b);
  }
  EXPECT_TRUE(found) << budget_line(b);
}

// The budget is the same for any thread count.
TEST(ErrorStages, ThreadInvariant) {
  const Rendered& a = render("corridor", "fp24", "rtz", "on", "none", "world", 64, 40, 1);
  const Rendered& b = render("corridor", "fp24", "rtz", "on", "none", "world", 64, 40, 2);
  ASSERT_TRUE(a.e.has_stages && b.e.has_stages);
  EXPECT_EQ(a.e.stages.pixel, b.e.stages.pixel);
  EXPECT_EQ(budget_line(a.e.stages), budget_line(b.e.stages));
}

// The replayed rays are the golden tracer's: the primary ray starts at the camera register (world),
// with the spawn none the shadow ray starts at the frame's hit point, with skip-origin it skips the
// pixel's triangle; a frame the tracer did not make is refused.
TEST(HardwareRays, ReplayTheGoldenFrame) {
  int tampered = 0;
  for (const char* vtu : {"off", "on"})
    for (const char* spawn : {"none", "skip-origin"}) {
      const Rendered& r = render("corridor", "fp24", "rtz", vtu, spawn);
      const sim::HardwareRays rays(r.p.image, r.p.scene.camera, r.p.scene.light, r.cfg);
      const scenes::Scene st = sim::stored_scene(r.p.scene, r.p.image, r.cfg.anchor);
      int shadow = 0;
      for (int y = 0; y < r.frame.height; ++y)
        for (int x = 0; x < r.frame.width; ++x) {
          const sim::PixelResult& p = r.frame.at(x, y);
          const sim::PixelRays pr = rays.pixel(x, y, p);
          EXPECT_TRUE(same(pr.org, st.camera.position)) << vtu;
          EXPECT_NEAR(hls::length(pr.dir), 1.0, 1e-4);
          EXPECT_EQ(pr.hit, p.tri >= 0);
          EXPECT_EQ(pr.shadow, p.shadow_ray);
          if (!pr.shadow) continue;
          ++shadow;
          if (std::string(spawn) == "none") {
            EXPECT_TRUE(same(pr.shadow_org, p.hit)) << "pixel " << x << "," << y;
            EXPECT_EQ(pr.shadow_skip, -1);
          } else {
            EXPECT_EQ(pr.shadow_skip, p.tri);
          }
          // The unit shadow ray ends at the light register: |org + tmax dir - light| is a few ulps.
          const Vec3 end = pr.shadow_org + pr.shadow_dir * pr.shadow_tmax;
          EXPECT_LT(hls::length(end - st.light.position), 1e-3 * hls::length(st.light.position - pr.shadow_org) + 0.05);
        }
      EXPECT_GT(shadow, 100);
      // An error pixel's t bits changed (the budget replays the error pixels).
      sim::Frame bad = r.frame;
      bool changed = false;
      for (size_t i = 0; i < bad.px.size() && !changed; ++i)
        if (r.e.stages.pixel[i] != Stage::none && bad.px[i].tri >= 0) {
          bad.px[i].t_bits ^= 1;
          changed = true;
        }
      if (!changed) continue;
      ++tampered;
      const sim::FrameErrors e = sim::measure_errors(bad, r.p.scene, r.p.image, r.cfg);
      EXPECT_FALSE(e.has_stages) << "a frame the golden tracer did not make";
      EXPECT_NE(e.stages_note.find("another t"), std::string::npos) << e.stages_note;
    }
  EXPECT_GE(tampered, 1);
}

// ---- constructed frames: one stage each ---------------------------------------------------------

scenes::Scene scene_of(std::vector<Tri> tris, Vec3 cam, Vec3 light) {
  scenes::Scene s;
  s.name = "constructed";
  s.tris = std::move(tris);
  s.camera.present = true;
  s.camera.position = cam;  // looks down -Z, +Y up, +X right
  s.light.present = true;
  s.light.position = light;
  return s;
}

sim::TraceConfig config(int w, int h, hls::Spawn spawn) {
  sim::TraceConfig c;
  c.format = FormatId::fp24;
  c.rounding = Rounding::rtz;
  c.width = w;
  c.height = h;
  c.threads = 1;
  c.spawn.spawn = spawn;
  c.spawn.any_hit = false;
  return c;
}

struct Measured {
  sim::Frame frame;
  sim::FrameErrors e;
};

Measured measure(const scenes::Scene& s, const sim::TraceConfig& cfg) {
  const hls::Image img = hls::build_image(s.tris, cfg.format, cfg.rounding);
  Measured m;
  m.frame = sim::trace_golden(img, s.camera, s.light, cfg);
  m.e = sim::measure_errors(m.frame, s, img, cfg);
  return m;
}

// Storage alone: a 1 x 1 frame whose ray, straight down -Z from the origin, computes exactly in the
// format; the triangle's edge passes 10^-20 beside it (the scene: a miss), but its record's b_d =
// -10^-20 / 4 flushes to zero in FP24, so the stored edge runs through the ray (the stored scene and
// the hardware: a hit). A second triangle, off the ray, widens the scene box.
TEST(ErrorStages, ConstructedStorage) {
  const double d = 1e-20;
  const Tri edge = {Vec3{d, -2, -10}, Vec3{d + 4, -2, -10}, Vec3{d, 6, -10}};
  const Tri side = {Vec3{-4, -4, -12}, Vec3{-3, -4, -12}, Vec3{-4, -3, -12}};
  const auto s = scene_of({edge, side}, Vec3{0, 0, 0}, Vec3{0, 0, 5});
  const Measured m = measure(s, config(1, 1, hls::Spawn::skip_origin));
  ASSERT_TRUE(m.e.has_stages) << m.e.stages_note;
  EXPECT_EQ(m.frame.px[0].tri, 0) << "the hardware hits the flushed edge";
  EXPECT_EQ(m.e.total.primary_hit_vs_miss, 1u);
  EXPECT_EQ(m.e.total.shadow_errors, 0u);
  EXPECT_EQ(m.e.stages.storage.primary, 1u) << budget_line(m.e.stages);
  EXPECT_EQ(m.e.stages.pixel[0], Stage::storage);
  expect_adds_up(m.e, "storage");
}

// The rays of a frame as the rgu makes them and where they cross the plane z = -8 (camera at the
// origin, VTU off): the ideal ray's x (double), the hardware ray's exact x (long double from its
// bit patterns), and the x the ist computes (hu = t d_x with t = -8 rcp(d_z), rtz).
struct Crossing {
  int x = 0, y = 0;
  double ideal = 0;
  long double exact = 0;
  uint32_t hu = 0;  // FP24 bits
};

std::vector<Crossing> crossings(const scenes::Camera& cam, int w, int h) {
  using A = hls::Arith<hls::FP24, Rounding::rtz>;
  const uint32_t zero[3] = {0, 0, 0};
  const hls::RguCamera rc = hls::rgu_camera<A>(zero, cam.forward, cam.right, cam.up, cam.yfov, w, h);
  const uint32_t minus8 = A::from_double(-8.0);
  std::vector<Crossing> v;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const hls::Ray r = hls::rgu_primary<A>(rc, uint32_t(x), uint32_t(y), A::from_double(1.0 / 4096));
      Crossing c;
      c.x = x;
      c.y = y;
      const Vec3 dd = scenes::primary_direction(cam, x, y, w, h);
      c.ideal = -8.0 * dd.x / dd.z;
      c.exact = -8.0L * (long double)A::to_double(r.d[0]) / (long double)A::to_double(r.d[2]);
      const uint32_t t = A::mul(minus8, A::rcp(r.d[2]));
      c.hu = A::mul(t, r.d[0]);
      v.push_back(c);
    }
  return v;
}

// A right triangle in the plane z = -8 with a vertical edge at x = xe (an FP24 number), covering
// x <= xe (left) or x >= xe, 64 x 64: every constant of its record is exact in FP24 (powers of two
// and xe), so the stored triangle is the triangle.
Tri edge_triangle(double xe, bool left) {
  const double w = left ? -64 : 64;
  return {Vec3{xe, -32, -8}, Vec3{xe + w, -32, -8}, Vec3{xe, 32, -8}};
}

// Ray generation: a pixel whose ideal ray hits the triangle while the rgu's ray (and the ist's
// computation of it) crosses the plane beyond the edge: the exact trace of the hardware's ray
// already misses (P2), the hardware misses too.
TEST(ErrorStages, ConstructedRayGeneration) {
  using F = hls::FP24;
  using A = hls::Arith<F, Rounding::rtz>;
  const int w = 64, h = 48;
  scenes::Camera cam;
  const auto cs = crossings(cam, w, h);
  // Triangle on the ideal side: left (x <= xe) when the ideal crossing is left of both of the
  // hardware's, xe just below the nearer of them.
  const Crossing* pick = nullptr;
  double xe = 0;
  bool left = true;
  for (const Crossing& c : cs) {
    const long double hu = A::to_double(c.hu);
    const long double lo = std::min(c.exact, hu), hi = std::max(c.exact, hu);
    if (c.ideal < lo) {  // xe in (ideal, lo): the largest FP24 number below lo
      uint32_t b = A::from_double(double(lo));  // rtz: <= lo
      if ((long double)A::to_double(b) >= lo) b = hls::next_down<F>(b);
      const double x = A::to_double(b);
      if (x - c.ideal > 1e-9 && (!pick || x - c.ideal > xe - pick->ideal)) pick = &c, xe = x, left = true;
    } else if (c.ideal > hi) {  // xe in (hi, ideal): the smallest FP24 number above hi
      uint32_t b = hls::next_up<F>(A::from_double(double(hi)));
      const double x = A::to_double(b);
      if (c.ideal - x > 1e-9 && (!pick || c.ideal - x > pick->ideal - xe)) pick = &c, xe = x, left = false;
    }
  }
  ASSERT_NE(pick, nullptr) << "no pixel whose ideal and hardware rays straddle an FP24 number";
  const auto s = scene_of({edge_triangle(xe, left)}, Vec3{0, 0, 0}, Vec3{0, 0, 10});
  const Measured m = measure(s, config(w, h, hls::Spawn::skip_origin));
  ASSERT_TRUE(m.e.has_stages) << m.e.stages_note;
  const size_t i = size_t(pick->y) * w + size_t(pick->x);
  EXPECT_EQ(m.frame.px[i].tri, -1) << "the hardware misses at pixel " << pick->x << "," << pick->y;
  EXPECT_EQ(m.e.stages.pixel[i], Stage::ray_generation) << budget_line(m.e.stages);
  EXPECT_GE(m.e.stages.ray_generation.primary, 1u);
  EXPECT_EQ(m.e.stages.storage.total(), 0u) << "the stored scene is the scene";
  EXPECT_LE(m.e.total.primary_errors, uint64_t(h)) << "errors only along the edge's column";
  expect_adds_up(m.e, "ray generation");
}

// Traversal/intersection: a pixel whose ideal ray and the hardware's ray, traced exactly, hit the
// triangle, while the ist's computed hit point (hu, one rounding of t and one of t d_x) lies
// beyond its edge: the hardware misses.
TEST(ErrorStages, ConstructedTraversalIntersection) {
  using F = hls::FP24;
  using A = hls::Arith<F, Rounding::rtz>;
  const int w = 64, h = 48;
  scenes::Camera cam;
  const auto cs = crossings(cam, w, h);
  const Crossing* pick = nullptr;
  double xe = 0;
  bool left = true;
  double best = 0;
  for (const Crossing& c : cs) {
    const double hu = A::to_double(c.hu);
    if ((long double)hu > c.exact) {  // left triangle, xe just below hu: hu outside, exact inside
      const double x = A::to_double(hls::next_down<F>(c.hu));
      const double margin = std::min(double((long double)x - c.exact), x - c.ideal);
      if (margin > best) best = margin, pick = &c, xe = x, left = true;
    } else if ((long double)hu < c.exact) {  // right triangle, xe just above hu
      const double x = A::to_double(hls::next_up<F>(c.hu));
      const double margin = std::min(double(c.exact - (long double)x), c.ideal - x);
      if (margin > best) best = margin, pick = &c, xe = x, left = false;
    }
  }
  ASSERT_NE(pick, nullptr) << "no pixel whose computed hit point is an ulp beyond the exact one";
  ASSERT_GT(best, 1e-12);
  const auto s = scene_of({edge_triangle(xe, left)}, Vec3{0, 0, 0}, Vec3{0, 0, 10});
  const Measured m = measure(s, config(w, h, hls::Spawn::skip_origin));
  ASSERT_TRUE(m.e.has_stages) << m.e.stages_note;
  const size_t i = size_t(pick->y) * w + size_t(pick->x);
  EXPECT_EQ(m.frame.px[i].tri, -1) << "the hardware misses at pixel " << pick->x << "," << pick->y;
  EXPECT_EQ(m.e.stages.pixel[i], Stage::traversal_primary) << budget_line(m.e.stages);
  EXPECT_GE(m.e.stages.traversal_intersection.primary, 1u);
  EXPECT_EQ(m.e.stages.storage.total(), 0u);
  EXPECT_EQ(m.e.stages.traversal_vtu_primary, 0u) << "VTU off";
  // The exact ray is inside by less than an FP24 ulp of the hit point, next to an edge no other
  // triangle shares: the outline, decided at the format's precision.
  EXPECT_GE(m.e.stages.traversal_kind[size_t(sim::TraversalKind::silhouette)], 1u) << budget_line(m.e.stages);
  EXPECT_EQ(m.e.stages.traversal_kind[size_t(sim::TraversalKind::crack)], 0u) << budget_line(m.e.stages);
  EXPECT_EQ(m.e.stages.traversal_kind[size_t(sim::TraversalKind::deep)], 0u) << budget_line(m.e.stages);
  expect_adds_up(m.e, "traversal");
}

// The watertight test (--ist watertight) on the slivers hard case: Wald's test lets primary rays
// through the seams between the thin triangles (cracks: the exact ray hits a triangle next to an
// edge its neighbour continues across, the hardware hits neither); the watertight test, on the
// same rays, has no traversal/intersection error at all.
TEST(ErrorStages, WatertightClosesTheCracks) {
  const Rendered& wald = render("slivers", "fp24", "rtz", "on", "skip-back", "world", 200, 120);
  const Rendered& wt = render("slivers", "fp24", "rtz", "on", "skip-back", "world", 200, 120, 2, "watertight");
  expect_adds_up(wald.e, "wald");
  expect_adds_up(wt.e, "watertight");
  EXPECT_GE(wald.e.stages.traversal_kind[size_t(sim::TraversalKind::crack)], 3u) << budget_line(wald.e.stages);
  EXPECT_EQ(wt.e.stages.traversal_intersection.total(), 0u) << budget_line(wt.e.stages);
  EXPECT_EQ(wt.e.total.self_intersections, 0u);
}

// The watertight record's plane is its stored triangle's (n_d through the stored vertex A, and with
// the VTU through the shifted A): far at 10^5 in world coordinates, where an FP24 ulp is a unit,
// with Wald's plane (rounded from the exact triangle) the distance test disagreed with the rounded
// vertices (800 x 480 rtz VTU on skip-back: 1,375 "same triangle" errors, the right triangle at a
// wrong t); with the stored triangle's plane none, and fewer errors than Wald's test.
TEST(ErrorStages, WatertightPlaneIsTheStoredTriangles) {
  const Rendered& wald = render("far", "fp24", "rtz", "on", "skip-back", "world", 200, 120);
  const Rendered& wt = render("far", "fp24", "rtz", "on", "skip-back", "world", 200, 120, 2, "watertight");
  expect_adds_up(wt.e, "watertight");
  EXPECT_EQ(wt.e.stages.traversal_kind[size_t(sim::TraversalKind::same)], 0u) << budget_line(wt.e.stages);
  EXPECT_LT(wt.e.stages.traversal_intersection.total(), wald.e.stages.traversal_intersection.total())
      << budget_line(wt.e.stages) << " / " << budget_line(wald.e.stages);
  EXPECT_EQ(wt.e.total.self_intersections, 0u);
}

// Spawn: FP24 rne puts about half the hit points behind their plane; on a scene hundreds of units
// from the origin (corridor: ulps of 2^-10..2^-7 against t_min 2^-12) spawn none's shadow rays then
// cross their own triangle beyond t_min even when traced exactly: self-intersections charged to
// the spawn. Skipping the origin triangle removes almost all of them.
TEST(ErrorStages, SpawnCarriesTheSelfIntersections) {
  const Rendered& none = render("corridor", "fp24", "rne", "off", "none");
  expect_adds_up(none.e, "rne none");
  const auto& b = none.e.stages;
  EXPECT_GT(none.e.total.self_intersections, 100u);
  EXPECT_GT(b.spawn.shadow, 9 * none.e.total.shadow_errors / 10) << budget_line(b);
  const Rendered& skip = render("corridor", "fp24", "rne", "off", "skip-origin");
  expect_adds_up(skip.e, "rne skip-origin");
  EXPECT_LT(skip.e.stages.spawn.shadow * 20, b.spawn.shadow) << budget_line(skip.e.stages);
}

// The VTU's rounding of the geometry: with it on, corridor's extra self-intersections (the
// translated n_d truncated once more) are the shadow rays' traversal against the translated
// records, not their spawn; none with it off.
TEST(ErrorStages, VtuGeometryInTraversal) {
  const Rendered& off = render("corridor", "fp24", "rtz", "off", "none");
  const Rendered& on = render("corridor", "fp24", "rtz", "on", "none");
  expect_adds_up(off.e, "off");
  expect_adds_up(on.e, "on");
  EXPECT_EQ(off.e.stages.traversal_vtu_shadow, 0u);
  EXPECT_GT(on.e.stages.traversal_vtu_shadow, on.e.stages.spawn.shadow) << budget_line(on.e.stages);
  EXPECT_GT(on.e.stages.traversal_intersection.shadow, off.e.stages.traversal_intersection.shadow);
}

// Storage on a scene far from the origin: at 10^6 FP24's ulp is 8..16 units and most primary
// errors are the stored scene's, VTU on or off; stored relative to the scene's centre (anchored)
// storage is nearly nothing.
TEST(ErrorStages, FarSceneIsStorage) {
  for (const char* vtu : {"off", "on"}) {
    const Rendered& world = render("far:1000000", "fp24", "rtz", vtu, "none");
    expect_adds_up(world.e, std::string("far 1e6 world ") + vtu);
    EXPECT_GT(world.e.stages.storage.primary, world.e.total.primary_errors / 2) << vtu << " " << budget_line(world.e.stages);
    const Rendered& anch = render("far:1000000", "fp24", "rtz", vtu, "none", "anchored");
    expect_adds_up(anch.e, std::string("far 1e6 anchored ") + vtu);
    EXPECT_LE(anch.e.stages.storage.total(), 3u) << vtu << " " << budget_line(anch.e.stages);
  }
}

// The VTU's own rounding on a scene stored far from the origin (issue 27): its offsets are one
// sop each (hls/vtu.h), so the errors of its translated records (traversal against them, primary
// and shadow) stay within 2x of the same frame stored anchored, where the VTU translates by
// camera - anchor only. Measured (rtz, spawn none): 10^5 world 4 + 94, 10^6 world 0 + 4, anchored
// 10 + 1373; with the former mul, add3, sub chain 15208 + 5234 and 10962 + 6790.
TEST(ErrorStages, FarWorldVtuGeometryWithinTwiceAnchored) {
  const Rendered& anch = render("far:100000", "fp24", "rtz", "on", "none", "anchored");
  const uint64_t a = anch.e.stages.traversal_vtu_primary + anch.e.stages.traversal_vtu_shadow;
  for (const char* scene : {"far:100000", "far:1000000"}) {
    const Rendered& world = render(scene, "fp24", "rtz", "on", "none");
    expect_adds_up(world.e, scene);
    const uint64_t w = world.e.stages.traversal_vtu_primary + world.e.stages.traversal_vtu_shadow;
    EXPECT_LE(w, 2 * a) << scene << " " << budget_line(world.e.stages);
    EXPECT_LE(world.e.stages.traversal_vtu_primary, 2 * anch.e.stages.traversal_vtu_primary + 10)
        << scene << " " << budget_line(world.e.stages);
  }
}

}  // namespace
