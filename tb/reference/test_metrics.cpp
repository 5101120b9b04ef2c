// The error metrics (sim/reference/metrics.h) on hand-made frames with known counts.
#include <gtest/gtest.h>

#include <stdexcept>

#include "sim/reference/metrics.h"

namespace raycore::reference {
namespace {

sim::PixelResult miss() { return {}; }

// front (the light on the ray's side) defaults to shadow_ray: --shadow-spawn front, and the reference.
sim::PixelResult hit(int32_t tri, double t, bool shadow_ray, bool lit, int32_t shadow_tri = -1, int front = -1) {
  sim::PixelResult p;
  p.front = front < 0 ? shadow_ray : front != 0;
  p.tri = tri;
  p.t = t;
  p.shadow_ray = shadow_ray;
  p.lit = lit;
  p.shadow_tri = shadow_tri;
  return p;
}

struct Pair {
  sim::PixelResult test, ref;
};

// One pixel per case, with what it must count.
std::vector<Pair> cases() {
  return {
      /* 0 both miss                      */ {miss(), miss()},
      /* 1 hit vs miss                    */ {hit(0, 10, true, true), miss()},
      /* 2 miss vs hit                    */ {miss(), hit(0, 10, true, true)},
      /* 3 distance 2%                    */ {hit(0, 10.2, true, true), hit(0, 10, true, true)},
      /* 4 edge tie: other tri, 0.5%      */ {hit(1, 10.05, true, true), hit(0, 10, true, true)},
      /* 5 self-intersection, acne        */ {hit(2, 10, true, false, 2), hit(2, 10, true, true)},
      /* 6 light leak                     */ {hit(2, 10, true, true), hit(2, 10, true, false, 3)},
      /* 7 false shadow without a ray     */ {hit(2, 10, false, false), hit(2, 10, true, true)},
      /* 8 both shadowed, other occluders */ {hit(2, 10, true, false, 1), hit(2, 10, true, false, 3)},
      /* 9 self-hit on a primary error    */ {hit(1, 10, true, false, 1), hit(3, 20, true, true)},
      /* 10 leak: ref spawned no ray      */ {hit(2, 10, true, true), hit(2, 10, false, false)},
      /* 11 exactly 1% off: not an error  */ {hit(3, 101, true, true), hit(3, 100, true, true)},
      /* 12 'lit' without a shadow ray is shadowed (both) */ {hit(2, 5, false, true), hit(2, 5, false, false)},
      /* 13 --shadow-spawn all: a ray toward a light behind self-intersects, the pixel is shadowed
            as the reference's (no error; a self-intersection, not on the lit side) */
      {hit(2, 10, true, false, 2, 0), hit(2, 10, false, false)},
  };
}

void frames(const std::vector<Pair>& c, sim::Frame* test, sim::Frame* ref) {
  test->width = ref->width = int(c.size());
  test->height = ref->height = 1;
  test->px.clear();
  ref->px.clear();
  for (const Pair& p : c) {
    test->px.push_back(p.test);
    ref->px.push_back(p.ref);
  }
}

const std::vector<hls::Tri> kTris(4, hls::Tri{});

TEST(ReferenceMetrics, HandMadeFrameCounts) {
  sim::Frame test, ref;
  frames(cases(), &test, &ref);
  const ErrorMetrics m = compute_errors(test, ref, kTris);
  EXPECT_EQ(m.pixels, 14u);
  EXPECT_EQ(m.primary_rays, 14u);
  EXPECT_EQ(m.shadow_rays, 10u);  // 1, 3, 4, 5, 6, 8, 9, 10, 11, 13
  EXPECT_EQ(m.self_intersections, 3u);  // 5, 9, 13
  EXPECT_EQ(m.self_intersections_front, 2u);  // 5, 9
  EXPECT_DOUBLE_EQ(m.self_intersection_pct, 100.0 * 3 / 14);
  EXPECT_EQ(m.primary_hit_vs_miss, 1u);  // 1
  EXPECT_EQ(m.primary_miss_vs_hit, 1u);  // 2
  EXPECT_EQ(m.primary_distance, 2u);     // 3, 9
  EXPECT_EQ(m.primary_errors, 4u);
  EXPECT_EQ(m.primary_other_tri, 1u);    // 4
  EXPECT_EQ(m.shadow_compared, 9u);      // 4, 5, 6, 7, 8, 10, 11, 12, 13
  EXPECT_EQ(m.false_shadow, 2u);         // 5, 7
  EXPECT_EQ(m.false_shadow_self, 1u);    // 5
  EXPECT_EQ(m.false_shadow_no_ray, 1u);  // 7
  EXPECT_EQ(m.light_leak, 2u);           // 6, 10
  EXPECT_EQ(m.shadow_errors, 4u);
}

TEST(ReferenceMetrics, EachCaseAlone) {
  // Every case on its own frame: exactly the counters it should touch.
  const auto c = cases();
  struct Expect {
    uint64_t self, hit_vs_miss, miss_vs_hit, distance, false_shadow, light_leak;
  } expect[] = {{0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0}, {0, 0, 1, 0, 0, 0}, {0, 0, 0, 1, 0, 0}, {0, 0, 0, 0, 0, 0},
                {1, 0, 0, 0, 1, 0}, {0, 0, 0, 0, 0, 1}, {0, 0, 0, 0, 1, 0}, {0, 0, 0, 0, 0, 0}, {1, 0, 0, 1, 0, 0},
                {0, 0, 0, 0, 0, 1}, {0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0}, {1, 0, 0, 0, 0, 0}};
  ASSERT_EQ(sizeof expect / sizeof expect[0], c.size());
  for (size_t i = 0; i < c.size(); ++i) {
    sim::Frame test, ref;
    frames({c[i]}, &test, &ref);
    const ErrorMetrics m = compute_errors(test, ref, kTris);
    EXPECT_EQ(m.self_intersections, expect[i].self) << "case " << i;
    EXPECT_EQ(m.primary_hit_vs_miss, expect[i].hit_vs_miss) << "case " << i;
    EXPECT_EQ(m.primary_miss_vs_hit, expect[i].miss_vs_hit) << "case " << i;
    EXPECT_EQ(m.primary_distance, expect[i].distance) << "case " << i;
    EXPECT_EQ(m.false_shadow, expect[i].false_shadow) << "case " << i;
    EXPECT_EQ(m.light_leak, expect[i].light_leak) << "case " << i;
  }
}

TEST(ReferenceMetrics, ClassifyPixelIsWhatTheCountsCount) {
  // classify_pixel (the per-pixel verdict the error budget by stage uses) touches exactly the
  // counter compute_errors counts for the case.
  const auto c = cases();
  for (size_t i = 0; i < c.size(); ++i) {
    sim::Frame test, ref;
    frames({c[i]}, &test, &ref);
    const ErrorMetrics m = compute_errors(test, ref, kTris);
    const PixelError e = classify_pixel(c[i].test, c[i].ref);
    EXPECT_EQ(m.primary_hit_vs_miss, e == PixelError::primary_hit_vs_miss ? 1u : 0u) << "case " << i;
    EXPECT_EQ(m.primary_miss_vs_hit, e == PixelError::primary_miss_vs_hit ? 1u : 0u) << "case " << i;
    EXPECT_EQ(m.primary_distance, e == PixelError::primary_distance ? 1u : 0u) << "case " << i;
    EXPECT_EQ(m.false_shadow, e == PixelError::false_shadow ? 1u : 0u) << "case " << i;
    EXPECT_EQ(m.light_leak, e == PixelError::light_leak ? 1u : 0u) << "case " << i;
    EXPECT_EQ(m.primary_errors, is_primary_error(e) ? 1u : 0u) << "case " << i;
    EXPECT_EQ(m.shadow_errors, is_shadow_error(e) ? 1u : 0u) << "case " << i;
  }
}

TEST(ReferenceMetrics, IdenticalFramesHaveNoErrors) {
  sim::Frame test, ref;
  frames(cases(), &test, &ref);
  const ErrorMetrics m = compute_errors(ref, ref, kTris);
  EXPECT_EQ(m.primary_errors, 0u);
  EXPECT_EQ(m.shadow_errors, 0u);
  EXPECT_EQ(m.self_intersections, 0u);  // the reference frame has none
}

TEST(ReferenceMetrics, BadFramesAreRejected) {
  sim::Frame test, ref;
  frames(cases(), &test, &ref);
  sim::Frame small = test;
  small.width -= 1;
  small.px.pop_back();
  EXPECT_THROW(compute_errors(small, ref, kTris), std::invalid_argument);
  sim::Frame bad = test;
  bad.px[3].tri = 4;  // only 4 triangles
  try {
    compute_errors(bad, ref, kTris);
    FAIL() << "an out-of-range triangle index was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pixel 3"), std::string::npos) << e.what();
  }
  bad = test;
  bad.px.pop_back();  // size says 14, 13 pixels
  EXPECT_THROW(compute_errors(bad, ref, kTris), std::invalid_argument);
}

TEST(ReferenceMetrics, JsonKeys) {
  sim::Frame test, ref;
  frames(cases(), &test, &ref);
  const nlohmann::json j = to_json(compute_errors(test, ref, kTris));
  for (const char* k : {"pixels", "primary_rays", "shadow_rays", "self_intersections", "self_intersection_pct",
                        "self_intersections_front",
                        "shadow_errors", "false_shadow", "light_leak", "primary_errors", "primary_miss_vs_hit",
                        "primary_hit_vs_miss", "primary_distance"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["self_intersections"].get<uint64_t>(), 3u);
  EXPECT_EQ(j["primary_errors"].get<uint64_t>(), 4u);
  EXPECT_EQ(j["shadow_errors"].get<uint64_t>(), 4u);
  EXPECT_EQ(j["false_shadow"].get<uint64_t>(), 2u);
  EXPECT_EQ(j["light_leak"].get<uint64_t>(), 2u);
}

}  // namespace
}  // namespace raycore::reference
