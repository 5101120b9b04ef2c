// tb/systemc/test_random_config.cpp - randomised configurations of the cycle model, each frame
// checked against the golden tracer (every pixel, every ray retired once; a hang is killed after
// RAYCORE_CHILD_TIMEOUT seconds and fails). Seeded and reproducible: configuration i of seed S is
// the same on every machine, and each prints the line that rebuilds it.
//
//   RAYCORE_RANDOM_CONFIGS (default 48)      configurations in this run
//   RAYCORE_RANDOM_CONFIG_SEED (default 1)   the run's seed
//   RAYCORE_RANDOM_CONFIG_FIRST (default 0)  the first configuration's index (to rerun one)
//
// Drawn: RTUs, memory latency / bandwidth / queue depth / random-latency seed, the three caches
// (size, ways, line, MSHRs, hit latency), the shared L2 (off or on, size, ways, latency,
// bandwidth), rays in flight, stack depth, pipeline depths (vtu, trv, ist, hit), trv pipes and
// fusing, ist units and queue, tile size, number format and rounding, VTU, spawn strategy, shadow
// rays (unit / segment, any- / closest-hit) and the scene (corridor, a tiny box scene, the hard
// cases) at a small resolution; the caches from 64 B up, and in 3 of 8 configurations one of them
// cut to two lines (random_config.h). A stack depth below what a ray needs must be refused with
// the --stack-depth message (and only then). Every other frame must finish: the caches' pin rule
// (systemc/ascache.h) guarantees forward progress, so the model's livelock stop (no ray retired
// and no traversal pass or triangle test for max(2^20, 4096 x memory latency) cycles) fails it.
// Until that rule (issue 26 part 4), looping for the next chance could thrash a cache smaller
// than the lines its rays need at once: RandomConfig.FormerLivelocks runs the configurations that
// livelocked then.
#include <gtest/gtest.h>

#include <systemc>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "tb/systemc/random_config.h"

namespace {

using namespace raycore::tb;  // NOLINT: the frame-check helpers

#ifndef RAYCORE_TEST_RTL

TEST(RandomConfig, GoldenMatchAndNoHang) {
  const uint64_t seed = env_u64("RAYCORE_RANDOM_CONFIG_SEED", 1);
  const uint64_t n = env_u64("RAYCORE_RANDOM_CONFIGS", 48);
  const uint64_t first = env_u64("RAYCORE_RANDOM_CONFIG_FIRST", 0);
  uint64_t refused = 0, set_full = 0;
  for (uint64_t i = first; i < first + n; ++i) {
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
    EXPECT_TRUE(r.ok) << r.error;  // a livelock stop fails here: the pin rule guarantees progress
    set_full += r.work[kWorkSetFull];
    EXPECT_EQ(r.mismatches, 0u) << "first differing pixel (" << r.first_x << ", " << r.first_y << ")";
    EXPECT_EQ(r.bad_retire, 0u);
    EXPECT_EQ(r.issued, r.retired);
    EXPECT_EQ(r.primary, uint64_t(d.tc.width) * uint64_t(d.tc.height));
    if (HasFailure()) break;  // the first failing configuration is the one to reproduce
  }
  std::printf("RANDOMCONFIGSUM seed %llu configurations %llu refused (stack) %llu livelocked 0 "
              "set_full refusals %llu\n",
              (unsigned long long)seed, (unsigned long long)n, (unsigned long long)refused,
              (unsigned long long)set_full);
  EXPECT_LT(refused, n / 2 + 1) << "most configurations refused: the draw is too tight";
}

// The configurations that livelocked before the caches' pin rule (RAYCORE_RANDOM_CONFIG_SEED=1,
// configurations 7, 26, 60, 75, 102 and 163 of 200 as drawn then: looping for the next chance
// thrashed the node or the triangle cache with 71-120 rays in flight, and the model stopped with
// "livelock"), rebuilt from the draw with the caches as drawn then (random_config.h's later cut of
// one cache to two lines undone; the whole line is checked against the one printed then), and the
// issue's two examples (16 KB node, 8 KB list, 1 KB triangle cache and 93 rays; a 1 KB node cache
// and 102 rays; the other caches the defaults) in the frames and dimensions of the first two
// (without the pin rule the second example livelocks in configuration 7's frame; the first
// finished there too). Each must finish: golden match, every ray retired once.
TEST(RandomConfig, FormerLivelocks) {
  struct Former {
    uint64_t index;
    sc::CacheConfig node, list, tri;  // as drawn then: size, ways, line, MSHRs, hit latency
    const char* line;                 // describe() then
  };
  const Former former[] = {
      {7, {256, 2, 64, 7, 3}, {512, 8, 32, 5, 2}, {2048, 4, 32, 5, 1},
       "scene far 18x17 fp32-rtz novtu spawn skip-offset unit any-hit margin 0 widen 0 | rtus 3 mem "
       "8/25B/q13 seed 197372 caches 256/2w/64B/7m/3 512/8w/32B/5m/2 2048/4w/32B/5m/1 l2 "
       "262144/8w/64B/20c/32B | rays 120 stack 43 vtu 10 trv 1x1 fuse mailbox 0 ist 17x2 q17 hit 10 "
       "tile 14 rgu 16"},
      {26, {128, 1, 64, 3, 3}, {256, 1, 32, 11, 3}, {2048, 2, 32, 6, 2},
       "scene origin-far-camera 17x15 fp24-raycore vtu spawn skip-offset segment any-hit margin 0 "
       "widen 0 | rtus 2 mem 3/52B/q21 seed 0 caches 128/1w/64B/3m/3 256/1w/32B/11m/3 "
       "2048/2w/32B/6m/2 l2 262144/8w/64B/20c/32B | rays 87 stack 14 vtu 4 trv 8x1 fuse mailbox 0 "
       "ist 5x2 q27 hit 25 tile 8 rgu 3"},
      {60, {1024, 1, 32, 4, 3}, {4096, 8, 32, 6, 1}, {128, 1, 64, 11, 2},
       "scene origin-far-camera 39x13 fp24-rtz novtu spawn skip-back segment any-hit margin 0 widen "
       "4 | rtus 3 mem 5/3B/q40 seed 40945 caches 1024/1w/32B/4m/3 4096/8w/32B/6m/1 "
       "128/1w/64B/11m/2 l2 262144/8w/64B/20c/32B | rays 107 stack 51 vtu 6 trv 8x4 fuse mailbox 0 "
       "ist 36x4 q64 hit 4 tile 10 rgu 29"},
      {75, {1024, 2, 64, 12, 2}, {1024, 8, 64, 7, 2}, {256, 1, 128, 6, 2},
       "scene origin-far-camera 18x28 fp32-rtz vtu spawn skip-offset unit closest-hit margin 0.03 "
       "widen 0 | rtus 7 mem 97/44B/q40 seed 445806 caches 1024/2w/64B/12m/2 1024/8w/64B/7m/2 "
       "256/1w/128B/6m/2 l2 65536/4w/64B/8c/20B | rays 89 stack 26 vtu 11 trv 5x1 mailbox 13 ist "
       "9x2 q43 hit 3 tile 6 rgu 0"},
      {102, {256, 1, 32, 10, 1}, {512, 2, 32, 5, 1}, {512, 2, 32, 7, 2},
       "scene grazing 40x23 fp24-rne vtu spawn skip-origin segment any-hit anchored margin "
       "0.000244141 widen 0 | rtus 2 mem 4/31B/q31 seed 567609 caches 256/1w/32B/10m/1 "
       "512/2w/32B/5m/1 512/2w/32B/7m/2 l2 262144/8w/64B/20c/32B | rays 118 stack 46 vtu 6 trv 3x1 "
       "fuse mailbox 12 ist 23x2 q25 hit 30 tile 10 rgu 39"},
      {163, {256, 2, 32, 8, 3}, {4096, 1, 128, 9, 2}, {128, 1, 64, 12, 3},
       "scene far 34x20 fp24-rne novtu spawn skip-origin unit closest-hit spawn-all margin 0.008 "
       "widen 0 | rtus 7 mem 5/53B/q20 seed 562861 caches 256/2w/32B/8m/3 4096/1w/128B/9m/2 "
       "128/1w/64B/12m/3 l2 262144/8w/64B/20c/32B | rays 71 stack 27 vtu 5 trv 3x3 fuse mailbox 0 "
       "ist 20x1 q52 hit 27 tile 2 rgu 0"},
  };
  std::vector<Drawn> cases;
  for (const Former& f : former) {
    Drawn d = draw(1, f.index);
    d.cfg.node_cache = f.node;
    d.cfg.list_cache = f.list;
    d.cfg.tri_cache = f.tri;
    if (d.cfg.l2.size_bytes == sc::SimConfig{}.l2.size_bytes)
      d.cfg.l2.size_bytes = 256 * 1024;  // the default L2 when they livelocked (512 KB since issue 26)
    EXPECT_EQ(describe(d), f.line) << "configuration " << f.index << " is not the one that livelocked";
    cases.push_back(d);
  }
  const sc::SimConfig def;
  for (size_t k = 0; k < 2; ++k) {  // the examples
    Drawn a = cases[k];
    a.cfg.node_cache = def.node_cache;
    a.cfg.list_cache = def.list_cache;
    a.cfg.tri_cache = def.tri_cache;
    a.cfg.tri_cache.size_bytes = 1024;
    a.cfg.rays_in_flight = 93;
    cases.push_back(a);
    Drawn b = a;
    b.cfg.tri_cache = def.tri_cache;
    b.cfg.node_cache.size_bytes = 1024;
    b.cfg.rays_in_flight = 102;
    cases.push_back(b);
  }
  for (Drawn& d : cases) {
    d.line = describe(d);
    SCOPED_TRACE(d.line);
    std::printf("former livelock: %s\n", d.line.c_str());
    std::fflush(stdout);
    const scenes::Scene& s = scene_by_index(d.scene);
    const hls::Image img = hls::build_image(d.tc.anchored ? hls::relative_to(s.tris, d.tc.anchor) : s.tris,
                                            d.tc.format, d.tc.rounding);
    const sim::Frame golden = sim::trace_golden(img, s.camera, s.light, d.tc);
    const Summary r = run_child({&s, &img, d.tc, d.cfg}, golden);
    EXPECT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.mismatches, 0u) << "first differing pixel (" << r.first_x << ", " << r.first_y << ")";
    EXPECT_EQ(r.bad_retire, 0u);
    EXPECT_EQ(r.issued, r.retired);
    EXPECT_EQ(r.primary, uint64_t(d.tc.width) * uint64_t(d.tc.height));
    std::printf("  %llu cycles, set_full refusals %llu\n", (unsigned long long)r.cycles,
                (unsigned long long)r.work[kWorkSetFull]);
  }
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
    const Drawn d = draw_views(seed, i);
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
    if (!m.ok) {  // the model's own stop (stack depth; a livelock fails: the pin rule)
      const std::string e = m.error;
      EXPECT_TRUE(e.find("--stack-depth") != std::string::npos) << e;
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
