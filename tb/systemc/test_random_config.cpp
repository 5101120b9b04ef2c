// tb/systemc/test_random_config.cpp - randomised configurations of the cycle model, each frame
// checked against the golden tracer (every pixel, every ray retired once; a hang is killed after
// RAYCORE_CHILD_TIMEOUT seconds and fails). Seeded and reproducible: configuration i of seed S is
// the same on every machine, and each prints the line that rebuilds it.
//
//   RAYCORE_RANDOM_CONFIGS (default 48)      configurations in this run
//   RAYCORE_RANDOM_CONFIG_SEED (default 1)   the run's seed
//
// Drawn: RTUs, memory latency / bandwidth / queue depth / random-latency seed, the three caches
// (size, ways, line, MSHRs, hit latency), the shared L2 (off or on, size, ways, latency,
// bandwidth), rays in flight, stack depth, pipeline depths (vtu, trv, ist, hit), trv pipes and
// fusing, ist units and queue, tile size, number format and rounding, VTU, spawn strategy, shadow
// rays (unit / segment, any- / closest-hit) and the scene (corridor, a tiny box scene, the hard
// cases) at a small resolution. A stack depth below what a ray needs must be refused with the
// --stack-depth message (and only then); a frame that livelocks (no ray retires for 2^20 cycles:
// looping for the next chance thrashing a tiny cache) stops with the model's livelock error and
// is counted, not failed.
#include <gtest/gtest.h>

#include <systemc>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>

#include "tb/systemc/random_config.h"

namespace {

using namespace raycore::tb;  // NOLINT: the frame-check helpers

#ifndef RAYCORE_TEST_RTL

TEST(RandomConfig, GoldenMatchAndNoHang) {
  const uint64_t seed = env_u64("RAYCORE_RANDOM_CONFIG_SEED", 1);
  const uint64_t n = env_u64("RAYCORE_RANDOM_CONFIGS", 48);
  uint64_t refused = 0, livelocked = 0;
  for (uint64_t i = 0; i < n; ++i) {
    const Drawn d = draw(seed, i);
    SCOPED_TRACE("RAYCORE_RANDOM_CONFIG_SEED=" + std::to_string(seed) + " configuration " +
                 std::to_string(i) + ": " + d.line);
    std::printf("config %llu: %s\n", (unsigned long long)i, d.line.c_str());
    std::fflush(stdout);
    const scenes::Scene& s = scene_by_index(d.scene);
    const hls::Image img = hls::build_image(d.tc.anchored ? hls::relative_to(s.tris, d.tc.anchor) : s.tris,
                                            d.tc.format, d.tc.rounding);
    const sim::Frame golden = sim::trace_golden(img, s.camera, s.light, d.tc);
    const Summary r = run_child({&s, &img, d.tc, d.cfg}, golden);
    if (!r.ok && std::string(r.error).find("--stack-depth") != std::string::npos) {
      // Refused: some ray needs a deeper stack. It cannot need more than the tree is deep.
      EXPECT_LT(d.cfg.stack_depth, uint32_t(hls::analyze_image(img).max_depth) + 1) << r.error;
      ++refused;
      continue;
    }
    if (!r.ok && std::string(r.error).find("livelock") != std::string::npos) {
      // Looping for the next chance thrashed a cache too small for the rays in flight: the model
      // stops with this error (a property of the architecture, see systemc/README.md).
      ++livelocked;
      continue;
    }
    EXPECT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.mismatches, 0u) << "first differing pixel (" << r.first_x << ", " << r.first_y << ")";
    EXPECT_EQ(r.bad_retire, 0u);
    EXPECT_EQ(r.issued, r.retired);
    EXPECT_EQ(r.primary, uint64_t(d.tc.width) * uint64_t(d.tc.height));
    if (HasFailure()) break;  // the first failing configuration is the one to reproduce
  }
  std::printf("RANDOMCONFIGSUM seed %llu configurations %llu refused (stack) %llu livelocked %llu\n",
              (unsigned long long)seed, (unsigned long long)n, (unsigned long long)refused,
              (unsigned long long)livelocked);
  EXPECT_LT(refused + livelocked, n / 2 + 1) << "most configurations refused: the draw is too tight";
}

#else  // RAYCORE_TEST_RTL

// The unit views (draw_views: each unit the model, its twin or its RTL, or the whole RTU in RTL)
// of the same configurations: the transaction model's frame first (checked against the golden
// tracer as above), then the views'. A view runs the frame exactly (golden match, the model's
// cycles, bus bytes, tests and every work counter) or refuses it with a sc::ConfigError naming
// what it is built for; any other error, a crash or a hang fails. At least half must run.
//   RAYCORE_RANDOM_VIEW_CONFIGS (default 32)  configurations in this run (make bench: more)
//   RAYCORE_RANDOM_CONFIG_SEED (default 1)    the run's seed
TEST(RandomViews, ExactOrRefused) {
  const uint64_t seed = env_u64("RAYCORE_RANDOM_CONFIG_SEED", 1);
  const uint64_t n = env_u64("RAYCORE_RANDOM_VIEW_CONFIGS", 32);
  uint64_t ran = 0, refused = 0, model_stopped = 0;
  for (uint64_t i = 0; i < n; ++i) {
    const Drawn d = draw_views(seed, i, true);
    SCOPED_TRACE("RAYCORE_RANDOM_CONFIG_SEED=" + std::to_string(seed) + " view configuration " +
                 std::to_string(i) + ": " + d.line);
    std::printf("views %llu: %s\n", (unsigned long long)i, d.line.c_str());
    std::fflush(stdout);
    const scenes::Scene& s = scene_by_index(d.scene);
    const hls::Image img = hls::build_image(d.tc.anchored ? hls::relative_to(s.tris, d.tc.anchor) : s.tris,
                                            d.tc.format, d.tc.rounding);
    const sim::Frame golden = sim::trace_golden(img, s.camera, s.light, d.tc);
    sc::SimConfig model_cfg = d.cfg;
    model_cfg.vtu_view = model_cfg.ist_view = model_cfg.trv_view = model_cfg.ascache_view =
        model_cfg.hit_view = model_cfg.rgu_view = model_cfg.membus_view = model_cfg.rtu_view =
            sc::UnitView::model;
    const Summary m = run_child({&s, &img, d.tc, model_cfg}, golden);
    if (!m.ok) {  // the model's own stops (stack depth, livelock): RandomConfig counts them
      const std::string e = m.error;
      EXPECT_TRUE(e.find("--stack-depth") != std::string::npos || e.find("livelock") != std::string::npos) << e;
      std::printf("  the model stopped: %.160s\n", m.error);
      ++model_stopped;
      continue;
    }
    ASSERT_EQ(m.mismatches, 0u) << "the transaction model differs from golden";
    const Summary v = run_child({&s, &img, d.tc, d.cfg}, golden);
    if (v.refused) {
      EXPECT_GT(std::string(v.error).size(), 20u) << "a refusal says what is built: " << v.error;
      std::printf("  refused: %s\n", v.error);
      ++refused;
      continue;
    }
    EXPECT_TRUE(v.ok) << v.error;
    EXPECT_EQ(v.mismatches, 0u) << "first differing pixel (" << v.first_x << ", " << v.first_y << ")";
    EXPECT_EQ(v.bad_retire, 0u);
    EXPECT_EQ(v.issued, v.retired);
    expect_same_counts(m, v, "views against the model");
    EXPECT_EQ(v.shadow, m.shadow);
    ++ran;
    if (HasFailure()) break;  // the first failing configuration is the one to reproduce
  }
  std::printf("RANDOMVIEWSUM seed %llu configurations %llu ran exactly %llu refused %llu model stopped %llu\n",
              (unsigned long long)seed, (unsigned long long)n, (unsigned long long)ran,
              (unsigned long long)refused, (unsigned long long)model_stopped);
  EXPECT_GE(2 * ran, n - model_stopped) << "most views refused: the draw is too far from what is built";
}

#endif  // RAYCORE_TEST_RTL

}  // namespace

extern "C" int sc_main(int argc, char* argv[]) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
