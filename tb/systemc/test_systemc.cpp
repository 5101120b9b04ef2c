// tb/systemc: the cycle model (systemc/) against the golden tracer on small frames (every pixel's
// tri, t bits, shadow decision and shade), determinism, randomised memory latency (every ray
// retires exactly once, no deadlock), and unit tests of ascache and membus.
//
// SystemC allows one elaboration per process, so each simulation runs in a forked child that
// sends a summary back through a pipe (and gtest_discover_tests runs each TEST in its own process).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <systemc>

#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "hls/image.h"
#include "scenes/generate.h"
#include "scenes/scene.h"
#include "sim/golden/golden.h"
#include "systemc/ascache.h"
#include "systemc/membus.h"
#include "systemc/simulate.h"
#include "systemc/timing.h"
#include "tb/systemc/frame_check.h"

namespace {

using namespace raycore::tb;  // NOLINT: the frame-check helpers

// The clock of Mrays/s (systemc/timing.h): the RTU's clock from a docs/timing.json, applied only
// when no clock was given; a missing or clock-less rtu entry keeps the assumed clock and says why.
TEST(TimedClock, FromTimingJsonOnlyWhenNoClockIsGiven) {
  const sc::TimedClock t = sc::timed_rtu_clock(
      R"({"fo4_ns": 0.0995, "designs": {"rtu": {"clock_mhz_28nm": 123.5, "worst_fo4": 385.6,
          "start": "trv_unit.slot_q", "end": "trv_unit.stack_q"}}})");
  ASSERT_TRUE(t.found) << t.why_not;
  EXPECT_DOUBLE_EQ(t.mhz, 123.5);
  EXPECT_DOUBLE_EQ(t.worst_fo4, 385.6);
  sc::SimConfig c;
  sc::apply_timed_clock(c, t);
  EXPECT_DOUBLE_EQ(c.clock_mhz, 123.5);
  EXPECT_EQ(c.clock_source, "timing");
  EXPECT_NE(c.clock_note.find("trv_unit.slot_q -> trv_unit.stack_q"), std::string::npos) << c.clock_note;
  EXPECT_EQ(sc::clock_json(c)["source"], "timing");
  sc::SimConfig given;
  given.clock_mhz = 250;
  given.clock_source = "option";
  sc::apply_timed_clock(given, t);
  EXPECT_DOUBLE_EQ(given.clock_mhz, 250);
  EXPECT_EQ(given.clock_source, "option");
  nlohmann::json j = nlohmann::json::parse(R"({"clock_mhz": 300})");
  sc::SimConfig from_file;
  sc::config_from_json(j, from_file);
  EXPECT_EQ(from_file.clock_source, "option");
  for (const char* bad : {"", "{", R"({"designs": {}})", R"({"designs": {"rtu": {"status": "timed out"}}})",
                          R"({"rtu": {"clock_mhz_28nm": -1}})"}) {
    const sc::TimedClock n = sc::timed_rtu_clock(bad);
    EXPECT_FALSE(n.found) << bad;
    EXPECT_FALSE(n.why_not.empty()) << bad;
    sc::SimConfig a;
    sc::apply_timed_clock(a, n);
    EXPECT_DOUBLE_EQ(a.clock_mhz, 500);
    EXPECT_EQ(a.clock_source, "assumed");
    EXPECT_NE(a.clock_note.find("assumed clock, not from timing"), std::string::npos) << a.clock_note;
  }
  EXPECT_NE(sc::timed_rtu_clock(R"({"designs": {"rtu": {"status": "timed out"}}})").why_not.find("timed out"),
            std::string::npos);
}

TEST(GoldenMatch, Fp24RtzCorridor) {
  const Summary r = expect_match(corridor(), config(FormatId::fp24, Rounding::rtz, false, 64, 40));
  EXPECT_GT(r.shadow, 0u);
  EXPECT_GT(r.tri_tests, 0u);
}
TEST(GoldenMatch, Fp24RneCorridorVtu) {
  expect_match(corridor(), config(FormatId::fp24, Rounding::rne, true, 64, 40));
}
// Rounding mode raycore (RayCore's arithmetic: table rcp, guard-bit adders), with the VTU and the
// error-bound spawn (which uses its unit roundoff).
TEST(GoldenMatch, Fp24RaycoreCorridorVtu) {
  auto tc = config(FormatId::fp24, Rounding::raycore, true, 64, 40);
  tc.spawn.spawn = hls::Spawn::error_bound;
  expect_match(corridor(), tc);
}
TEST(GoldenMatch, Fp32RneCorridor) {
  expect_match(corridor(), config(FormatId::fp32, Rounding::rne, false, 64, 40));
}
TEST(GoldenMatch, Fp32RtzCorridorVtu) {
  expect_match(corridor(), config(FormatId::fp32, Rounding::rtz, true, 64, 40));
}
TEST(GoldenMatch, SpawnStrategies) {
  for (hls::Spawn sp : {hls::Spawn::skip_origin, hls::Spawn::ulp_offset, hls::Spawn::error_bound,
                        hls::Spawn::skip_offset, hls::Spawn::skip_slab, hls::Spawn::skip_back})
    for (bool vtu : {false, true}) {
      auto tc = config(FormatId::fp24, Rounding::rtz, vtu, 32, 20);
      tc.spawn.spawn = sp;
      tc.spawn.ulps = sim::default_spawn_ulps(tc.format, sp);
      expect_match(corridor(), tc);
    }
}
// Watertightness margins (--bary-margin, --trv-widen): the cycle model's ist and trv use the same
// registers as the golden tracer.
TEST(GoldenMatch, Margins) {
  struct Case {
    FormatId f;
    Rounding r;
    bool vtu;
    hls::Spawn sp;
    double eps;
    int32_t widen;
  };
  for (const Case& k : {Case{FormatId::fp24, Rounding::rtz, true, hls::Spawn::none, 0.008, 2},
                        Case{FormatId::fp24, Rounding::rne, false, hls::Spawn::skip_back, 0.008, 4},
                        Case{FormatId::fp24, Rounding::rtz, false, hls::Spawn::skip_origin, 0.03, 0},
                        Case{FormatId::fp32, Rounding::rne, true, hls::Spawn::none, 0.0, 8}}) {
    auto tc = config(k.f, k.r, k.vtu, 48, 30);
    tc.spawn.spawn = k.sp;
    tc.spawn.ulps = sim::default_spawn_ulps(tc.format, k.sp);
    tc.bary_margin = k.eps;
    tc.trv_widen = k.widen;
    expect_match(corridor(), tc);
  }
}
// The watertight test (--ist watertight: 48-byte fp24 records, the VTU shifting their vertices):
// the cycle model's ist and VTU use the golden tracer's functions, in every format and policy; the
// units without a watertight view refuse it.
TEST(GoldenMatch, Watertight) {
  struct Case {
    FormatId f;
    Rounding r;
    bool vtu;
    hls::Spawn sp;
  };
  for (const Case& k : {Case{FormatId::fp24, Rounding::rtz, true, hls::Spawn::none},
                        Case{FormatId::fp24, Rounding::rne, false, hls::Spawn::skip_back},
                        Case{FormatId::fp24, Rounding::raycore, true, hls::Spawn::skip_slab},
                        Case{FormatId::fp32, Rounding::rne, true, hls::Spawn::none}}) {
    auto tc = config(k.f, k.r, k.vtu, 48, 30);
    tc.spawn.spawn = k.sp;
    tc.spawn.ulps = sim::default_spawn_ulps(tc.format, k.sp);
    tc.ist = hls::IstKind::watertight;
    const Summary r = expect_match(corridor(), tc);
    EXPECT_GT(r.tri_tests, 0u);
  }
  auto tc = config(FormatId::fp24, Rounding::rtz, true, 16, 8);
  tc.ist = hls::IstKind::watertight;
  sc::SimConfig cfg;
  cfg.ist_view = sc::UnitView::twin;
  expect_refused(corridor(), tc, cfg, "--ist watertight is in the golden tracer, the transaction model and --rtl ist");
  cfg = {};
  cfg.vtu_view = sc::UnitView::twin;
  expect_refused(corridor(), tc, cfg, "vtu has no pin-level twin");
  cfg = {};
  cfg.ascache_view = sc::UnitView::rtl;
  expect_refused(corridor(), tc, cfg, "ascache has no RTL");
}
// Any-hit shadow rays: the same lit/shadowed decisions as closest-hit (so the same image), fewer
// triangle tests; the golden tracer and the cycle model end the walk at the same leaf.
TEST(GoldenMatch, AnyHitShadowRays) {
  for (bool seg : {false, true}) {
    auto tc = config(FormatId::fp24, Rounding::rtz, true, 48, 30);
    tc.spawn.segment = seg;
    const Summary closest = expect_match(corridor(), tc);
    tc.spawn.any_hit = true;
    const Summary any = expect_match(corridor(), tc);
    EXPECT_LE(any.tri_tests, closest.tri_tests);
    const hls::Image img = hls::build_image(corridor().tris, tc.format, tc.rounding);
    const sim::Frame fa = sim::trace_golden(img, corridor().camera, corridor().light, tc);
    tc.spawn.any_hit = false;
    const sim::Frame fc = sim::trace_golden(img, corridor().camera, corridor().light, tc);
    for (size_t i = 0; i < fa.px.size(); ++i) {
      ASSERT_EQ(fa.px[i].lit, fc.px[i].lit) << "pixel " << i;
      ASSERT_EQ(fa.px[i].shade, fc.px[i].shade) << "pixel " << i;
    }
  }
}
// --shadow-spawn all: every primary hit spawns a shadow ray (the light behind too); golden match in
// both shadow-ray forms, one shadow ray per primary hit, and the same image as front.
TEST(GoldenMatch, ShadowSpawnAll) {
  for (bool seg : {false, true}) {
    auto tc = config(FormatId::fp24, Rounding::rtz, seg, 48, 30);
    tc.spawn.segment = seg;
    const Summary front = expect_match(corridor(), tc);
    tc.spawn.spawn_all = true;
    const Summary all = expect_match(corridor(), tc);
    EXPECT_GT(all.shadow, front.shadow);
    const hls::Image img = hls::build_image(corridor().tris, tc.format, tc.rounding);
    sim::TraceStats st;
    const sim::Frame fa = sim::trace_golden(img, corridor().camera, corridor().light, tc, &st);
    EXPECT_EQ(all.shadow, st.primary_hits);
    tc.spawn.spawn_all = false;
    const sim::Frame ff = sim::trace_golden(img, corridor().camera, corridor().light, tc);
    for (size_t i = 0; i < fa.px.size(); ++i) {
      ASSERT_EQ(fa.px[i].shade, ff.px[i].shade) << "pixel " << i;
      ASSERT_EQ(fa.px[i].lit, ff.px[i].lit) << "pixel " << i;
      ASSERT_EQ(fa.px[i].front, ff.px[i].front) << "pixel " << i;
      ASSERT_EQ(fa.px[i].shadow_ray, fa.px[i].tri >= 0) << "pixel " << i;
    }
  }
}
// --store anchored: the image relative to the scene's box centre, camera and light relative to it
// (the VTU translates by camera - anchor): golden match with the VTU off and on, on a far scene.
TEST(GoldenMatch, AnchoredStore) {
  const scenes::Scene far = scenes::generate("far");
  for (bool vtu : {false, true}) {
    auto tc = config(FormatId::fp24, Rounding::rtz, vtu, 40, 24);
    tc.anchored = true;
    tc.anchor = hls::store_anchor(far.tris);
    EXPECT_GT(expect_match(far, tc).shadow, 0u);
  }
}
// The levers of issue 14 one by one and together, and the RayCore-like baseline: golden match.
TEST(GoldenMatch, ThroughputLevers) {
  const auto tc = config(FormatId::fp24, Rounding::rtz, true, 48, 30);
  sc::SimConfig base;
  base.trv_pipes = 1, base.ist_units = 1, base.rays_in_flight = 64, base.trv_fuse = false;
  base.l2.size_bytes = 0;
  const Summary b = expect_match(corridor(), tc, base);
  sc::SimConfig c = base;
  c.trv_fuse = true;
  const Summary fused = expect_match(corridor(), tc, c);
  EXPECT_LT(fused.cycles, b.cycles);
  c.trv_pipes = 4;
  c.ist_units = 2;
  const Summary wide = expect_match(corridor(), tc, c);
  EXPECT_LT(wide.cycles, fused.cycles);
  c.l2.size_bytes = 64 * 1024;
  const Summary l2 = expect_match(corridor(), tc, c);
  EXPECT_LT(l2.bus_bytes, wide.bus_bytes);  // the L2 serves repeats of the 6 RTUs' misses
  c.mailbox = 4;  // the same frame with fewer triangle tests
  const Summary mb = expect_match(corridor(), tc, c);
  EXPECT_LT(mb.tri_tests, l2.tri_tests);
  c.mailbox = 1;
  expect_match(corridor(), tc, c);
  c.stack_depth = 2;  // far too shallow: refused with the option's name
  expect_refused(corridor(), tc, c, "--stack-depth");
}
TEST(GoldenMatch, SegmentShadowRays) {
  auto tc = config(FormatId::fp24, Rounding::rtz, true, 48, 30);
  tc.spawn.segment = true;
  expect_match(corridor(), tc);
}
TEST(GoldenMatch, TinySceneAllFormats) {
  const scenes::Scene s = tiny_scene();
  for (FormatId f : {FormatId::fp24, FormatId::fp32})
    for (Rounding r : {Rounding::rtz, Rounding::rne})
      for (bool vtu : {false, true}) {
        const Summary x = expect_match(s, config(f, r, vtu, 32, 24));
        EXPECT_GT(x.shadow, 0u);
      }
}
// One RTU, few ray slots, tiny caches and one MSHR each: heavy looping, still the golden frame.
TEST(GoldenMatch, StarvedConfiguration) {
  sc::SimConfig cfg;
  cfg.rtus = 1;
  cfg.rays_in_flight = 3;
  cfg.node_cache = {256, 1, 64, 1, 2};
  cfg.list_cache = {256, 2, 32, 1, 1};
  cfg.tri_cache = {512, 2, 64, 1, 3};
  cfg.ist_queue = 2;
  cfg.mem_queue_depth = 1;
  cfg.mem_bandwidth = 3;
  expect_match(tiny_scene(), config(FormatId::fp24, Rounding::rtz, true, 16, 12), cfg);
}

TEST(Determinism, SameConfigSameCyclesAndBits) {
  const auto& s = corridor();
  const auto tc = config(FormatId::fp24, Rounding::rtz, true, 48, 30);
  sc::SimConfig cfg;
  cfg.seed = 11;
  const Summary a = expect_match(s, tc, cfg);
  const Summary b = expect_match(s, tc, cfg);
  EXPECT_EQ(a.cycles, b.cycles);
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_EQ(a.bus_bytes, b.bus_bytes);
}

TEST(RandomLatency, SeedsCompleteAndMatch) {
  const auto& s = corridor();
  const auto tc = config(FormatId::fp24, Rounding::rtz, false, 32, 20);
  std::vector<uint64_t> cycles;
  for (uint64_t seed : {0ull, 1ull, 2ull, 3ull, 12345ull}) {
    sc::SimConfig cfg;
    cfg.seed = seed;
    cfg.rtus = 3;
    cycles.push_back(expect_match(s, tc, cfg).cycles);
  }
  // Random latency in [L, 2L] is slower than the fixed L on average.
  EXPECT_LT(cycles[0], (cycles[1] + cycles[2] + cycles[3] + cycles[4]) / 4);
}

// ---- ascache ----------------------------------------------------------------------------------

TEST(Ascache, LruHitMissAndFill) {
  // One set of two ways, 16-byte lines.
  sc::Ascache c("c", {32, 2, 16, 2, 1}, 1000, 16);
  ASSERT_EQ(c.sets(), 1u);
  sc::Cycle now = 0;
  auto fetch = [&](uint64_t line) {
    EXPECT_EQ(c.access(line), nullptr);
    ASSERT_TRUE(c.req().can_pop(~0ull));
    const sc::MemReq q = c.req().pop();
    EXPECT_EQ(q.addr, 1000 + line * 16);
    EXPECT_EQ(q.bytes, 16u);
    for (uint32_t i = 0; i < 16; ++i) q.data[i] = uint8_t(line * 16 + i);
    c.advance(++now);
    c.fill(q.tag);  // installed at this cycle's edge: a miss (merged) in its own cycle
    EXPECT_EQ(c.access(line), nullptr);
    EXPECT_EQ(c.mshrs_busy(), 1u);
    c.advance(++now);
    EXPECT_EQ(c.mshrs_busy(), 0u);
  };
  fetch(0);
  fetch(1);
  ASSERT_NE(c.access(1), nullptr);  // its first hit unpins it
  const uint8_t* p = c.access(0);   // 0 becomes the most recent
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p[5], 5);
  fetch(2);  // evicts 1, the least recently used
  EXPECT_TRUE(c.present(0));
  EXPECT_FALSE(c.present(1));
  EXPECT_TRUE(c.present(2));
  ASSERT_NE(c.access(2), nullptr);
  EXPECT_EQ(c.access(2)[3], 2 * 16 + 3);
  EXPECT_EQ(c.stats().accesses, 10u);
  EXPECT_EQ(c.stats().hits, 4u);
  EXPECT_EQ(c.stats().misses, 6u);
  EXPECT_EQ(c.stats().mshr_merges, 3u);
  EXPECT_EQ(c.stats().fills, 3u);
  EXPECT_EQ(c.stats().set_full, 0u);
}

// Forward progress: a filled line is pinned (not a victim) until its first hit, and a miss takes
// an MSHR only while its set has a way neither pinned nor awaited by an MSHR.
TEST(Ascache, PinnedUntilFirstHit) {
  // One set of two ways, 16-byte lines, three MSHRs.
  sc::Ascache c("c", {32, 2, 16, 3, 1}, 0, 16);
  ASSERT_EQ(c.sets(), 1u);
  sc::Cycle now = 0;
  auto fill_next = [&] {  // a fill in a cycle of its own, then the next cycle
    ASSERT_TRUE(c.req().can_pop(~0ull));
    const sc::MemReq q = c.req().pop();
    for (uint32_t i = 0; i < 16; ++i) q.data[i] = uint8_t(q.addr + i);
    c.advance(++now);
    c.fill(q.tag);
    c.advance(++now);
  };
  EXPECT_EQ(c.access(0), nullptr);  // MSHR 0
  EXPECT_EQ(c.access(1), nullptr);  // MSHR 1: both ways awaited
  EXPECT_EQ(c.access(2), nullptr);  // an MSHR is free, but the set is not: refused
  EXPECT_EQ(c.stats().set_full, 1u);
  EXPECT_EQ(c.mshrs_busy(), 2u);
  EXPECT_EQ(c.access(1), nullptr);  // merged (a merge needs no way)
  EXPECT_EQ(c.stats().mshr_merges, 1u);
  fill_next();                      // line 0 in, pinned; line 1 still awaited
  EXPECT_EQ(c.access(2), nullptr);
  EXPECT_EQ(c.stats().set_full, 2u);
  fill_next();  // line 1 in, pinned: both ways pinned
  EXPECT_EQ(c.access(2), nullptr);
  EXPECT_EQ(c.stats().set_full, 3u);
  ASSERT_NE(c.access(1), nullptr);  // line 1's first hit unpins it (line 0 stays pinned)
  EXPECT_EQ(c.access(2), nullptr);  // now allocated
  EXPECT_EQ(c.stats().set_full, 3u);
  EXPECT_EQ(c.mshrs_busy(), 1u);
  ASSERT_NE(c.access(1), nullptr);  // line 1 the most recent: line 0, pinned, is still not the victim
  fill_next();
  EXPECT_TRUE(c.present(0));
  EXPECT_FALSE(c.present(1));
  EXPECT_TRUE(c.present(2));
  ASSERT_NE(c.access(0), nullptr);
  ASSERT_NE(c.access(2), nullptr);
  EXPECT_EQ(c.access(3), nullptr);  // nothing pinned: line 0, the least recent, goes
  fill_next();
  EXPECT_FALSE(c.present(0));
  EXPECT_TRUE(c.present(2));
  EXPECT_TRUE(c.present(3));
  EXPECT_EQ(c.stats().fills, 4u);
}

TEST(Ascache, MshrMergeAndFull) {
  sc::Ascache c("c", {1024, 4, 32, 2, 1}, 0, 32);
  EXPECT_EQ(c.access(7), nullptr);
  EXPECT_EQ(c.access(7), nullptr);  // merged into the same MSHR
  EXPECT_EQ(c.access(9), nullptr);
  EXPECT_EQ(c.access(11), nullptr);  // both MSHRs busy
  EXPECT_EQ(c.stats().mshr_merges, 1u);
  EXPECT_EQ(c.stats().mshr_full, 1u);
  EXPECT_EQ(c.req().size(), 2u);  // one request per distinct line
  EXPECT_EQ(c.mshrs_busy(), 2u);
  const sc::MemReq a = c.req().pop();
  EXPECT_EQ(a.addr, 7u * 32);
  c.advance(1);
  c.fill(a.tag);
  EXPECT_EQ(c.access(11), nullptr);  // the fill's MSHR is busy until the cycle's edge: full
  EXPECT_EQ(c.stats().mshr_full, 2u);
  EXPECT_EQ(c.mshrs_busy(), 2u);
  c.advance(2);
  EXPECT_EQ(c.mshrs_busy(), 1u);
  EXPECT_NE(c.access(7), nullptr);  // hit now, while line 9 is still outstanding
  EXPECT_EQ(c.access(11), nullptr);  // the freed MSHR takes it
  EXPECT_EQ(c.req().size(), 2u);
}

// The fill acts at its cycle's closing edge: its victim is chosen from the state at the cycle's
// start, the cycle's accesses still hit the victim's old line (its old bytes) and merge on the
// filled one, the fill's MSHR is free from the next cycle, and one fill per cycle, before the
// cycle's accesses.
TEST(Ascache, FillAtTheCyclesEdge) {
  sc::Ascache c("c", {32, 2, 16, 3, 1}, 0, 16);  // one set of two ways
  sc::Cycle now = 0;
  auto fill = [&](uint64_t line, uint8_t v, bool next_cycle = true) {
    EXPECT_EQ(c.access(line), nullptr);
    const sc::MemReq q = c.req().pop();
    std::memset(q.data, v, 16);
    if (next_cycle) c.advance(++now);
    c.fill(q.tag);
  };
  fill(0, 10);
  c.advance(++now);
  fill(1, 11);
  c.advance(++now);
  ASSERT_NE(c.access(0), nullptr);  // unpins 0 and 1, 1 the most recent
  ASSERT_NE(c.access(1), nullptr);
  EXPECT_EQ(c.access(2), nullptr);  // MSHR for line 2
  const sc::MemReq q = c.req().pop();
  std::memset(q.data, 12, 16);
  c.advance(++now);
  c.fill(q.tag);                        // victim: line 0, the least recent at the cycle's start
  const uint8_t* p = c.access(0);       // still there in the fill's cycle, its old bytes
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p[0], 10);
  EXPECT_EQ(c.access(2), nullptr);      // not yet: merged into the fill's MSHR
  EXPECT_EQ(c.stats().mshr_merges, 1u);
  EXPECT_THROW(c.fill(q.tag), std::logic_error);  // one fill per cycle (and after an access)
  c.advance(++now);
  EXPECT_FALSE(c.present(0));  // the hit in the fill's cycle did not save it
  EXPECT_TRUE(c.present(1));
  p = c.access(2);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p[0], 12);
  EXPECT_EQ(c.mshrs_busy(), 0u);
}

// ---- membus -------------------------------------------------------------------------------------

struct Recorder : sc::MemClient {
  struct Ev {
    uint32_t port, tag;
    sc::Cycle at;
  };
  std::vector<Ev> ev;
  void mem_resp(uint32_t port, uint32_t tag, sc::Cycle now) override { ev.push_back({port, tag, now}); }
};

TEST(Membus, LatencyBandwidthAndData) {
  std::vector<uint8_t> mem(256);
  for (size_t i = 0; i < mem.size(); ++i) mem[i] = uint8_t(i);
  sc::Membus bus("bus", mem, 10, 8, 4, 0);
  sc::TimedFifo<sc::MemReq> q(4);
  Recorder rec;
  bus.add_requester(&q, &rec, 5);
  uint8_t buf[2][64];
  q.push({64, 64, 0, buf[0]}, 0);
  q.push({224, 64, 1, buf[1]}, 0);  // runs past the end: zero-filled
  for (sc::Cycle t = 0; t < 40; ++t) bus.tick(t);
  ASSERT_EQ(rec.ev.size(), 2u);
  // First: accepted at 0, data after 10 cycles, 8 beats of 8 bytes -> 18. Second: accepted at 1,
  // waits for the data bus -> 26.
  EXPECT_EQ(rec.ev[0].at, 18u);
  EXPECT_EQ(rec.ev[0].tag, 0u);
  EXPECT_EQ(rec.ev[0].port, 5u);
  EXPECT_EQ(rec.ev[1].at, 26u);
  EXPECT_EQ(buf[0][0], 64);
  EXPECT_EQ(buf[0][63], 127);
  EXPECT_EQ(buf[1][31], 255);
  EXPECT_EQ(buf[1][32], 0);
  EXPECT_EQ(bus.stats().bytes, 128u);
  EXPECT_EQ(bus.stats().busy_cycles, 16u);
}

TEST(Membus, RoundRobinAndQueueDepth) {
  std::vector<uint8_t> mem(4096, 1);
  sc::Membus bus("bus", mem, 5, 64, 2, 0);
  Recorder rec;
  std::vector<sc::TimedFifo<sc::MemReq>> qs(3, sc::TimedFifo<sc::MemReq>(4));
  static uint8_t buf[12][64];
  for (uint32_t r = 0; r < 3; ++r) {
    bus.add_requester(&qs[r], &rec, r);
    for (uint32_t i = 0; i < 4; ++i) qs[r].push({r * 256 + i * 64, 64, i, buf[r * 4 + i]}, 0);
  }
  size_t max_out = 0;
  for (sc::Cycle t = 0; t < 200; ++t) {
    bus.tick(t);
    max_out = std::max<size_t>(max_out, bus.outstanding());
  }
  ASSERT_EQ(rec.ev.size(), 12u);
  EXPECT_LE(max_out, 2u);
  for (size_t i = 0; i < rec.ev.size(); ++i) {
    EXPECT_EQ(rec.ev[i].port, i % 3) << "response " << i;
    EXPECT_EQ(rec.ev[i].tag, i / 3) << "response " << i;
  }
  EXPECT_GT(bus.stats().queue_full_cycles, 0u);
}

// The shared L2: a second request for a line is served by the L2 (its latency, no memory bytes),
// one for a line still on its way from memory merges (waits for it), and LRU eviction refetches.
TEST(Membus, L2HitMergeAndEviction) {
  std::vector<uint8_t> mem(4096);
  for (size_t i = 0; i < mem.size(); ++i) mem[i] = uint8_t(i * 7);
  sc::Membus bus("bus", mem, 50, 16, 8, 0);
  bus.set_l2({2 * 64, 1, 64, 5, 64});  // 2 sets x 1 way x 64 B, hit latency 5, 64 B/cycle
  Recorder rec;
  sc::TimedFifo<sc::MemReq> q(8);
  bus.add_requester(&q, &rec, 0);
  static uint8_t buf[8][64];
  q.push({0, 64, 0, buf[0]}, 0);     // miss: memory, 50 + 4 beats -> 54
  q.push({0, 64, 1, buf[1]}, 0);     // merge: waits for the line -> 54 + 1 L2 beat
  q.push({128, 64, 2, buf[2]}, 100);  // same set as line 0: miss, evicts it
  q.push({0, 64, 3, buf[3]}, 200);   // miss again (evicted)
  q.push({128, 64, 4, buf[4]}, 300);  // miss (line 128 was evicted by line 0)
  q.push({128, 64, 5, buf[5]}, 400);  // hit: 400 + 5 + 1
  for (sc::Cycle t = 0; t < 500; ++t) bus.tick(t);
  ASSERT_EQ(rec.ev.size(), 6u);
  EXPECT_EQ(rec.ev[0].at, 54u);
  EXPECT_EQ(rec.ev[1].at, 55u);
  EXPECT_EQ(rec.ev[5].tag, 5u);
  EXPECT_EQ(rec.ev[5].at, 406u);
  EXPECT_EQ(buf[1][10], mem[10]);
  EXPECT_EQ(buf[5][3], mem[131]);
  const sc::MembusStats& s = bus.stats();
  EXPECT_EQ(s.requests, 4u);  // memory requests: 0, 128, 0, 128
  EXPECT_EQ(s.bytes, 256u);
  EXPECT_EQ(s.l2_accesses, 6u);
  EXPECT_EQ(s.l2_merges, 1u);
  EXPECT_EQ(s.l2_hits, 1u);
  EXPECT_THROW(bus.set_l2({100, 1, 64, 5, 64}), std::invalid_argument);
}

// The L2's victim rule (issue 26 part 6: the data a fill writes or a response reads is never
// another line's): a miss does not evict a way still being filled or still to be read by an
// accepted hit; it waits (l2_stall_cycles) until the way is free, and then evicts it.
TEST(Membus, L2VictimNeitherFillingNorRead) {
  std::vector<uint8_t> mem(4096);
  for (size_t i = 0; i < mem.size(); ++i) mem[i] = uint8_t(i * 3);
  sc::Membus bus("bus", mem, 50, 16, 8, 0);
  bus.set_l2({64, 1, 64, 5, 64});  // 1 set x 1 way x 64 B, hit latency 5, 64 B/cycle
  Recorder rec;
  sc::TimedFifo<sc::MemReq> q(8);
  bus.add_requester(&q, &rec, 0);
  static uint8_t buf[4][64];
  q.push({0, 64, 0, buf[0]}, 0);     // miss at 0: 50 + 4 beats -> 54
  q.push({64, 64, 1, buf[1]}, 0);    // the only way is filling until 54: accepted at 54 -> 108
  q.push({64, 64, 2, buf[2]}, 110);  // hit: 110 + 5 + 1 -> 116, reads the way until then
  q.push({0, 64, 3, buf[3]}, 111);   // the way is read until 116: accepted at 116 -> 170
  for (sc::Cycle t = 0; t < 300; ++t) bus.tick(t);
  ASSERT_EQ(rec.ev.size(), 4u);
  EXPECT_EQ(rec.ev[0].at, 54u);
  EXPECT_EQ(rec.ev[1].at, 108u);
  EXPECT_EQ(rec.ev[2].at, 116u);
  EXPECT_EQ(rec.ev[3].at, 170u);
  EXPECT_EQ(buf[2][5], mem[69]);
  EXPECT_EQ(buf[3][7], mem[7]);
  const sc::MembusStats& s = bus.stats();
  EXPECT_EQ(s.l2_stall_cycles, 53u + 5u);  // cycles 1..53 and 111..115
  EXPECT_EQ(s.requests, 3u);
  EXPECT_EQ(s.l2_hits, 1u);
}

TEST(Membus, RandomLatencyWithinBounds) {
  std::vector<uint8_t> mem(1024);
  sc::Membus bus("bus", mem, 20, 1024, 64, 99);
  Recorder rec;
  sc::TimedFifo<sc::MemReq> q(16);
  bus.add_requester(&q, &rec, 0);
  static uint8_t buf[16][16];
  for (uint32_t i = 0; i < 16; ++i) q.push({i * 16, 16, i, buf[i]}, 0);
  for (sc::Cycle t = 0; t < 200; ++t) bus.tick(t);
  ASSERT_EQ(rec.ev.size(), 16u);
  bool varied = false;
  for (const auto& e : rec.ev) {
    EXPECT_GE(e.at, e.tag + 20 + 1);  // accepted at cycle tag
    EXPECT_LE(e.at, e.tag + 40 + 1 + 16);
    if (e.at - e.tag != rec.ev[0].at - rec.ev[0].tag) varied = true;
  }
  EXPECT_TRUE(varied);
}

}  // namespace

extern "C" int sc_main(int argc, char* argv[]) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
