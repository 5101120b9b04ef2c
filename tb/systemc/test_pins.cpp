// tb/systemc/test_pins.cpp - the pin-level units of the cycle model (systemc/pins/).
//
// Built twice (tb/systemc/CMakeLists.txt):
//   test_pins      (label unit): frames with the SystemC twins (--pins vtu,ist,hit) in the units'
//   test_pins      (label unit): frames with the SystemC twins (--pins vtu,ist,rgu) in the units'
//                  places give the same cycles, bus bytes, tests and bits as the transaction model
//                  (and the golden tracer's frame), across formats, roundings, STAGES, VTU on/off
//                  and randomised memory latency; bad latencies are refused with a message.
//   test_pins_rtl  (label rtl, RAYCORE_TEST_RTL): the same with the Verilated RTL (--rtl) bound in
//                  place, every subset of {vtu, ist}, hit with several spawn strategies, and all
//                  three; and unit lockstep tests: the SystemC twin and
//                  place, every subset of {vtu, ist}, rgu alone (1 and 3 RTUs, rtz and rne) and
//                  with vtu and ist; and unit lockstep tests: the SystemC twin and
//                  the Verilated --sc model side by side on the same clock, the same random
//                  stimulus (tb/rtl/stimulus.h) with random input gaps and random out_ready
//                  back-pressure; in_ready_o, out_valid_o and every output transaction are compared
//                  cycle by cycle, and the first difference is printed (the rgu, a source:
//                  whole frames started by start_i, out_valid_o and busy_o every cycle).
#define SC_INCLUDE_DYNAMIC_PROCESSES  // sc_spawn
#include <gtest/gtest.h>

#include <algorithm>

#include <systemc>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>

#include "scenes/gltf.h"
#include "systemc/ascache.h"
#include "systemc/ascache_rtl.h"
#include "systemc/pins/clock.h"
#include "systemc/pins/ist.h"
#include "systemc/pins/rgu.h"
#include "systemc/pins/rtl.h"
#include "systemc/pins/vtu.h"
#include "tb/systemc/frame_check.h"

#ifdef RAYCORE_TEST_RTL
#include "rtl_frame_models.h"
#include "tb/rtl/stimulus.h"
#endif

namespace {

using namespace raycore::tb;  // NOLINT: the frame-check helpers
namespace pins = raycore::sc::pins;
using raycore::sc::UnitView;


// The transaction model's frame, then the same configuration with the given views: equal.
void expect_same_frame(const scenes::Scene& s, const sim::TraceConfig& tc, sc::SimConfig cfg,
                       UnitView vtu, UnitView ist, UnitView rgu = UnitView::model) {
  const Summary model = expect_match(s, tc, cfg);
  cfg.vtu_view = vtu;
  cfg.ist_view = ist;
  cfg.rgu_view = rgu;
  const Summary p = expect_match(s, tc, cfg);
  const std::string what = std::string("vtu ") + sc::unit_view_name(vtu) + ", ist " +
                           sc::unit_view_name(ist) + ", rgu " + sc::unit_view_name(rgu) +
                           ", rtus " + std::to_string(cfg.rtus);
  expect_same_counts(model, p, what);
  EXPECT_EQ(p.shadow, model.shadow) << what;
  EXPECT_EQ(p.issued, model.issued) << what;
}

// The rgu as `view` (the primary rays from its pins), every other unit the model: the corridor
// at 32 x 20, FP24 rtz and rne, 1 and 3 RTUs.
void expect_rgu_view(UnitView view) {
  for (const Rounding r : {Rounding::rtz, Rounding::rne})
    for (const int rtus : {1, 3}) {
      sc::SimConfig cfg;
      cfg.rtus = rtus;
      expect_same_frame(corridor(), config(FormatId::fp24, r, true, 32, 20), cfg, UnitView::model,
                        UnitView::model, view);
    }
}

// Both units as `view`: the corridor, FP24 rtz, VTU on.
void expect_both_units(UnitView view) {
  expect_same_frame(corridor(), config(FormatId::fp24, Rounding::rtz, true, 48, 30), {}, view,
                    view);
}

// The corridor in FP24 rne with 2 RTUs and the memory latency randomised by `seed`, once per
// (vtu, ist) pair of views.
void expect_views_fp24_rne(uint64_t seed,
                           std::initializer_list<std::pair<UnitView, UnitView>> views) {
  sc::SimConfig cfg;
  cfg.seed = seed;
  cfg.rtus = 2;
  const auto tc = config(FormatId::fp24, Rounding::rne, true, 32, 20);
  for (const auto& [vtu, ist] : views) expect_same_frame(corridor(), tc, cfg, vtu, ist);
}

// The watertightness margins (--bary-margin 0.008 --trv-widen 2): the pin-level ist's eps_i /
// one_eps_i registers give the transaction model's frame and cycles.
sim::TraceConfig margins_config(Rounding r, bool vtu) {
  auto tc = config(FormatId::fp24, r, vtu, 48, 30);
  tc.bary_margin = 0.008;
  tc.trv_widen = 2;
  return tc;
}

// The hit unit as `view` (vtu and ist the model): the corridor (VTU on, FP24 with rounding r) with
// each spawn configuration, --rtus 1 and 3, gives the transaction model's cycles, frame, bus bytes,
// tests and ray counts.
void expect_hit_view(UnitView view, Rounding r, std::initializer_list<hls::SpawnParams> sps) {
  for (const int rtus : {1, 3})
    for (const hls::SpawnParams& sp : sps) {
      auto tc = config(FormatId::fp24, r, true, 32, 20);
      tc.spawn = sp;
      sc::SimConfig cfg;
      cfg.rtus = rtus;
      const Summary model = expect_match(corridor(), tc, cfg);
      cfg.hit_view = view;
      const Summary p = expect_match(corridor(), tc, cfg);
      const std::string what = std::string("hit ") + sc::unit_view_name(view) + " " +
                               sim::to_string(sp.spawn) + (sp.segment ? " segment" : "") +
                               (sp.spawn_all ? " all" : "") + " rtus " + std::to_string(rtus);
      expect_same_counts(model, p, what);
      EXPECT_EQ(p.issued, model.issued) << what;
      EXPECT_EQ(p.shadow, model.shadow) << what;
      EXPECT_EQ(p.retired, model.retired) << what;
    }
}
hls::SpawnParams spawn(hls::Spawn s, bool all = false, bool segment = false) {
  hls::SpawnParams sp;
  sp.spawn = s;
  sp.spawn_all = all;
  sp.segment = segment;
  return sp;
}

// --store anchored (the image relative to the scene's box centre, the VTU translating by camera -
// anchor): the VTU at pin level translates the set-up registers (box, light) from the image's
// coordinates, as the model does. Issue 24: it was given the light in world coordinates.
sim::TraceConfig anchored_config(const scenes::Scene& s, Rounding r, int w, int h) {
  auto tc = config(FormatId::fp24, r, true, w, h);
  tc.anchored = true;
  tc.anchor = hls::store_anchor(s.tris);
  return tc;
}

#ifndef RAYCORE_TEST_RTL

TEST(PinsFrame, HitTwinFp24Rtz) {
  expect_hit_view(UnitView::twin, Rounding::rtz,
                  {spawn(hls::Spawn::skip_origin), spawn(hls::Spawn::skip_back),
                   spawn(hls::Spawn::none, true), spawn(hls::Spawn::error_bound),
                   spawn(hls::Spawn::ulp_offset, false, true)});
}
TEST(PinsFrame, HitTwinFp24Rne) {
  expect_hit_view(UnitView::twin, Rounding::rne,
                  {spawn(hls::Spawn::skip_back), spawn(hls::Spawn::skip_slab, true),
                   spawn(hls::Spawn::skip_offset), spawn(hls::Spawn::error_bound, true, true)});
}
TEST(PinsFrame, HitLatencyNotAMultipleOfTheLevelsIsRefused) {
  const auto tc = config(FormatId::fp24, Rounding::rtz, true, 8, 8);
  sc::SimConfig cfg;
  cfg.hit_view = UnitView::twin;
  cfg.hit_latency = 20;
  expect_refused(tiny_scene(), tc, cfg, "--hit-latency must be 24 x STAGES");
}

TEST(PinsFrame, TwinsWithMargins) {
  expect_same_frame(corridor(), margins_config(Rounding::rtz, true), {}, UnitView::twin,
                    UnitView::twin);
}
TEST(PinsFrame, TwinsFp24RtzVtuOn) { expect_both_units(UnitView::twin); }
TEST(PinsFrame, TwinsEachUnitFp24RneRandomLatency) {
  expect_views_fp24_rne(5, {{UnitView::twin, UnitView::model}, {UnitView::model, UnitView::twin}});
}
TEST(PinsFrame, TwinsFp32StagesOneAndThree) {
  sc::SimConfig cfg;
  cfg.vtu_depth = 2;
  cfg.ist_latency = 10;
  expect_same_frame(tiny_scene(), config(FormatId::fp32, Rounding::rne, true, 32, 24), cfg,
                    UnitView::twin, UnitView::twin);
  cfg.vtu_depth = 6;
  cfg.ist_latency = 30;
  expect_same_frame(tiny_scene(), config(FormatId::fp24, Rounding::rtz, true, 32, 24), cfg,
                    UnitView::twin, UnitView::twin);
}
// One ist.v per ist unit: 1 and 3 units at pin level give the transaction model's cycles too
// (the default is 2), with 1 and 6 trv pipes.
TEST(PinsFrame, TwinsIstUnitsOneAndThree) {
  sc::SimConfig cfg;
  cfg.ist_units = 1;
  cfg.trv_pipes = 1;
  expect_same_frame(corridor(), config(FormatId::fp24, Rounding::rtz, true, 32, 20), cfg,
                    UnitView::model, UnitView::twin);
  cfg.ist_units = 3;
  cfg.trv_pipes = 6;
  cfg.trv_fuse = false;
  expect_same_frame(corridor(), config(FormatId::fp24, Rounding::rne, false, 32, 20), cfg,
                    UnitView::twin, UnitView::twin);
}
TEST(PinsFrame, TwinsFp24Raycore) {
  expect_same_frame(corridor(), config(FormatId::fp24, Rounding::raycore, true, 32, 20), {},
                    UnitView::twin, UnitView::twin);
}
TEST(PinsFrame, TwinsVtuOffBypassesTheUnit) {
  expect_same_frame(corridor(), config(FormatId::fp24, Rounding::rtz, false, 32, 20), {},
                    UnitView::twin, UnitView::twin);
}
TEST(PinsFrame, RguTwinRtusOneAndThree) { expect_rgu_view(UnitView::twin); }
// The twin at STAGES 1 and 3 in FP32 (the RTL is built at STAGES 2, FP24), 4 x 4 tiles, with
// randomised memory latency.
TEST(PinsFrame, RguTwinFp32OtherDepthsAndTiles) {
  sc::SimConfig cfg;
  cfg.rgu_latency = 15;
  cfg.rtus = 2;
  expect_same_frame(tiny_scene(), config(FormatId::fp32, Rounding::rne, false, 32, 24), cfg,
                    UnitView::model, UnitView::model, UnitView::twin);
  cfg.rgu_latency = 45;
  cfg.tile = 4;
  cfg.seed = 3;
  expect_same_frame(tiny_scene(), config(FormatId::fp24, Rounding::raycore, true, 32, 24), cfg,
                    UnitView::twin, UnitView::twin, UnitView::twin);
}
TEST(PinsFrame, RguLatencyAndTileRefused) {
  const auto tc = config(FormatId::fp24, Rounding::rtz, true, 8, 8);
  sc::SimConfig cfg;
  cfg.rgu_view = UnitView::twin;
  cfg.rgu_latency = 12;
  expect_refused(tiny_scene(), tc, cfg, "--rgu-latency must be 15 x STAGES");
  cfg.rgu_latency = 30;
  cfg.tile = 6;
  expect_refused(tiny_scene(), tc, cfg, "tile must be a power of two");
}
TEST(PinsFrame, VtuTwinAnchoredStore) {
  expect_same_frame(corridor(), anchored_config(corridor(), Rounding::rtz, 32, 20), {}, UnitView::twin,
                    UnitView::model);
}
TEST(PinsFrame, LatencyNotAMultipleOfTheLevelsIsRefused) {
  const auto tc = config(FormatId::fp24, Rounding::rtz, true, 8, 8);
  sc::SimConfig cfg;
  cfg.vtu_view = UnitView::twin;
  cfg.vtu_depth = 5;
  expect_refused(tiny_scene(), tc, cfg, "--vtu-depth must be 2 x STAGES");
  cfg = {};
  cfg.ist_view = UnitView::twin;
  cfg.ist_latency = 24;
  expect_refused(tiny_scene(), tc, cfg, "--ist-latency must be 10 x STAGES");
}

#else  // RAYCORE_TEST_RTL

TEST(PinsFrameRtl, VtuAndIstFp24RtzVtuOn) { expect_both_units(UnitView::rtl); }
// Issue 24: --store anchored with the VTU in RTL, alone and with every unit of the RTUs.
TEST(PinsFrameRtl, AnchoredStoreVtuOn) {
  const auto tc = anchored_config(corridor(), Rounding::rtz, 32, 20);
  expect_same_frame(corridor(), tc, {}, UnitView::rtl, UnitView::model);
  const Summary model = expect_match(corridor(), tc, {});
  sc::SimConfig cfg;
  cfg.vtu_view = cfg.ist_view = cfg.trv_view = cfg.ascache_view = cfg.hit_view = cfg.rgu_view =
      UnitView::rtl;
  expect_same_counts(model, expect_match(corridor(), tc, cfg), "--rtl all --store anchored");
}
TEST(PinsFrameRtl, WithMargins) {
  expect_same_frame(corridor(), margins_config(Rounding::rtz, true), {}, UnitView::rtl,
                    UnitView::rtl);
  expect_same_frame(corridor(), margins_config(Rounding::rne, false), {}, UnitView::model,
                    UnitView::rtl);
}
TEST(PinsFrameRtl, EachSubsetFp24RneRandomLatency) {
  expect_views_fp24_rne(7, {{UnitView::rtl, UnitView::model},
                            {UnitView::model, UnitView::rtl},
                            {UnitView::rtl, UnitView::twin}});
}
TEST(PinsFrameRtl, IstUnitsOneAndThree) {
  sc::SimConfig cfg;
  cfg.ist_units = 1;
  expect_same_frame(corridor(), config(FormatId::fp24, Rounding::rtz, true, 32, 20), cfg,
                    UnitView::rtl, UnitView::rtl);
  cfg.ist_units = 3;
  cfg.l2.size_bytes = 0;
  expect_same_frame(corridor(), config(FormatId::fp24, Rounding::rne, false, 32, 20), cfg,
                    UnitView::model, UnitView::rtl);
}
TEST(PinsFrameRtl, VtuAndIstFp24Raycore) {
  expect_same_frame(corridor(), config(FormatId::fp24, Rounding::raycore, true, 32, 20), {},
                    UnitView::rtl, UnitView::rtl);
}
TEST(PinsFrameRtl, HitFp24Rtz) {
  expect_hit_view(UnitView::rtl, Rounding::rtz,
                  {spawn(hls::Spawn::skip_origin), spawn(hls::Spawn::skip_back),
                   spawn(hls::Spawn::none, true), spawn(hls::Spawn::error_bound)});
}
TEST(PinsFrameRtl, HitFp24Rne) {
  expect_hit_view(UnitView::rtl, Rounding::rne,
                  {spawn(hls::Spawn::skip_back), spawn(hls::Spawn::ulp_offset, true),
                   spawn(hls::Spawn::skip_origin, false, true), spawn(hls::Spawn::none)});
}
// vtu, ist and hit all as Verilated RTL, FP24 raycore, skip-back with every hit spawning.
TEST(PinsFrameRtl, VtuIstHitFp24Raycore) {
  auto tc = config(FormatId::fp24, Rounding::raycore, true, 32, 20);
  tc.spawn = spawn(hls::Spawn::skip_back, true);
  sc::SimConfig cfg;
  const Summary model = expect_match(corridor(), tc, cfg);
  cfg.vtu_view = cfg.ist_view = cfg.hit_view = UnitView::rtl;
  const Summary p = expect_match(corridor(), tc, cfg);
  expect_same_counts(model, p, "vtu, ist, hit rtl");
}
TEST(PinsFrameRtl, HitMissingVariantIsNamed) {
  sc::SimConfig cfg;
  cfg.hit_view = UnitView::rtl;
  const auto tc = config(FormatId::fp32, Rounding::rtz, false, 8, 8);
  const Summary r = expect_refused(tiny_scene(), tc, cfg, "no Verilated hit_unit for fp32 rtz STAGES=2");
  EXPECT_NE(std::string(r.error).find("built: hit_unit FP24 rtz S=2"), std::string::npos) << r.error;
}
TEST(PinsFrameRtl, RguRtusOneAndThree) { expect_rgu_view(UnitView::rtl); }
TEST(PinsFrameRtl, RguWithVtuAndIst) {
  sc::SimConfig cfg;
  cfg.rtus = 3;
  expect_same_frame(corridor(), config(FormatId::fp24, Rounding::rtz, true, 32, 20), cfg,
                    UnitView::rtl, UnitView::rtl, UnitView::rtl);
  cfg.rtus = 2;
  cfg.seed = 9;
  expect_same_frame(corridor(), config(FormatId::fp24, Rounding::raycore, false, 32, 20), cfg,
                    UnitView::twin, UnitView::rtl, UnitView::rtl);
}
TEST(PinsFrameRtl, RguMissingVariantIsNamed) {
  sc::SimConfig cfg;
  cfg.rgu_view = UnitView::rtl;
  const Summary r = expect_refused(tiny_scene(), config(FormatId::fp32, Rounding::rtz, false, 8, 8),
                                   cfg, "no Verilated rgu_unit for fp32 rtz STAGES=2 with 8 x 8 tiles");
  EXPECT_NE(std::string(r.error).find("rgu_unit FP24 rtz S=2 (8 x 8 tiles"), std::string::npos)
      << r.error;
  cfg.tile = 4;
  expect_refused(tiny_scene(), config(FormatId::fp24, Rounding::rtz, false, 8, 8), cfg,
                 "no Verilated rgu_unit for fp24 rtz STAGES=2 with 4 x 4 tiles");
}
TEST(PinsFrameRtl, MissingVariantIsNamed) {
  sc::SimConfig cfg;
  cfg.ist_view = UnitView::rtl;
  const auto tc = config(FormatId::fp32, Rounding::rtz, false, 8, 8);
  const Summary r = expect_refused(tiny_scene(), tc, cfg, "no Verilated ist_unit for fp32 rtz STAGES=2");
  EXPECT_NE(std::string(r.error).find("built: ist_unit FP24 rtz S=2"), std::string::npos) << r.error;
}

// ---- the intersection unit whole in RTL (rtl/units/ist_unit.v, --rtl ist) ---------------------
// The queue with looping on a triangle-cache miss, the triangle-cache accesses, the ist.v
// pipelines and the result delay: the transaction model's frame, cycles and counters, with the
// trv as the model (the ist's results reduced in C++) and as RTL (reduced by trv_unit.v).
void expect_ist_rtl(const scenes::Scene& s, const sim::TraceConfig& tc, sc::SimConfig cfg,
                    const std::string& what) {
  const Summary model = expect_match(s, tc, cfg);
  cfg.ist_view = UnitView::rtl;
  const Summary p = expect_match(s, tc, cfg);
  expect_same_counts(model, p, "ist rtl, " + what);
  EXPECT_EQ(p.shadow, model.shadow) << what;
  cfg.trv_view = UnitView::rtl;
  const Summary q = expect_match(s, tc, cfg);
  expect_same_counts(model, q, "ist and trv rtl, " + what);
}
// Small caches and a 3-entry ist queue: triangle misses (looping), MSHRs full, the queue full for
// the trv, three ist units taking entries behind each other; 2 RTUs, randomised memory latency.
TEST(IstRtlFrame, SmallCachesQueueOfThreeRandomLatency) {
  sc::SimConfig cfg;
  cfg.node_cache = {1024, 2, 64, 2, 1};
  cfg.list_cache = {512, 2, 32, 2, 2};
  cfg.tri_cache = {1024, 2, 64, 2, 1};
  cfg.ist_queue = 3;
  cfg.ist_units = 3;
  cfg.trv_pipes = 2;
  cfg.rtus = 2;
  cfg.seed = 5;
  expect_ist_rtl(corridor(), config(FormatId::fp24, Rounding::rtz, true, 40, 24), cfg,
                 "small caches, queue 3");
}
// The result delay: a triangle-cache hit latency of 0 (results leave with the ist.v's output) and
// of 5 (through the delay ring), skip-origin shadow rays (the skip id read with the ray).
// ist_unit.v registers the triangle cache's answer: hit latency 1 (the default) bypasses its delay
// ring, 5 waits 4 cycles in it; 0 is refused.
TEST(IstRtlFrame, TriangleHitLatencyFiveSkipOriginZeroRefused) {
  auto tc = config(FormatId::fp24, Rounding::rne, true, 32, 20);
  tc.spawn = spawn(hls::Spawn::skip_origin, true);
  sc::SimConfig cfg;
  cfg.tri_cache.hit_latency = 5;
  expect_ist_rtl(corridor(), tc, cfg, "triangle hit latency 5");
  cfg.ist_view = UnitView::rtl;
  cfg.tri_cache.hit_latency = 0;
  expect_refused(tiny_scene(), tc, cfg, "a triangle-cache hit latency of 1 .. 15");
}
TEST(IstRtlFrame, Fp32RneAndFp24RaycoreOneUnit) {
  sc::SimConfig cfg;
  expect_ist_rtl(tiny_scene(), config(FormatId::fp32, Rounding::rne, true, 32, 24), cfg, "fp32");
  cfg.ist_units = 1;
  cfg.ist_view = UnitView::model;
  const auto tc = config(FormatId::fp24, Rounding::raycore, true, 32, 20);
  const Summary model = expect_match(corridor(), tc, cfg);
  cfg.ist_view = UnitView::rtl;
  expect_same_counts(model, expect_match(corridor(), tc, cfg), "raycore, 1 ist unit");
}
// The watertight test (--ist watertight): ist_unit.v with ist_watertight.v (18 levels: latency 36),
// 48-byte records one per triangle line; small caches and randomised latency too (misses
// looping), the trv as the model and as RTL.
TEST(IstRtlFrame, Watertight) {
  auto tc = config(FormatId::fp24, Rounding::rtz, true, 40, 24);
  tc.ist = hls::IstKind::watertight;
  sc::SimConfig cfg;
  expect_ist_rtl(corridor(), tc, cfg, "watertight");
  cfg.node_cache = {1024, 2, 64, 2, 1};
  cfg.tri_cache = {1024, 2, 64, 2, 1};
  cfg.ist_queue = 3;
  cfg.ist_units = 3;
  cfg.rtus = 2;
  cfg.seed = 7;
  tc.spawn = spawn(hls::Spawn::skip_back, true);
  expect_ist_rtl(corridor(), tc, cfg, "watertight, small caches, skip-back");
}
TEST(IstRtlFrame, RefusesWhatItCannotRun) {
  const auto tc = config(FormatId::fp24, Rounding::rtz, false, 8, 8);
  sc::SimConfig cfg;
  cfg.ist_view = UnitView::rtl;
  cfg.ist_queue = 65;
  expect_refused(tiny_scene(), tc, cfg, "an ist queue of at most 64 entries");
  cfg.ist_queue = 32;
  cfg.ist_units = 5;
  expect_refused(tiny_scene(), tc, cfg, "at most 4 --ist-units");
  cfg.ist_units = 2;
  cfg.tri_cache.line_bytes = 128;
  expect_refused(tiny_scene(), tc, cfg, "64-byte triangle cache lines");
  cfg.tri_cache.line_bytes = 64;
  cfg.tri_cache.hit_latency = 16;
  expect_refused(tiny_scene(), tc, cfg, "a triangle-cache hit latency of 1 .. 15");
  cfg.tri_cache.hit_latency = 1;
  cfg.mailbox = 2;
  expect_refused(tiny_scene(), tc, cfg, "no mailbox");
  cfg.mailbox = 0;
  cfg.ist_latency = 30;
  expect_refused(tiny_scene(), tc, cfg, "no Verilated ist_unit for fp24 rtz STAGES=3");
}

// ---- the traversal unit in RTL (rtl/units/trv_unit.v, --rtl trv) ------------------------------
// The frame with the Verilated trv_unit in trv's place: the transaction model's cycles, bus bytes,
// frame and every work counter (expect_same_frame), over the model's default levers (4 pipes,
// fuse), RayCore's baseline (1 pipe, no fuse, 1 ist unit, 64 slots), both FP24 roundings,
// raycore and FP32, several RTUs, randomised memory latency, small caches (misses, looping, ist
// queue full), margins, any-hit shadow rays and the other units in RTL too.
void expect_trv_rtl(const scenes::Scene& s, const sim::TraceConfig& tc, sc::SimConfig cfg,
                    UnitView vtu = UnitView::model, UnitView ist = UnitView::model,
                    UnitView rgu = UnitView::model) {
  const Summary model = expect_match(s, tc, cfg);
  cfg.trv_view = UnitView::rtl;
  cfg.vtu_view = vtu;
  cfg.ist_view = ist;
  cfg.rgu_view = rgu;
  const Summary p = expect_match(s, tc, cfg);
  const std::string what = "trv rtl, vtu " + std::string(sc::unit_view_name(vtu)) + ", ist " +
                           sc::unit_view_name(ist) + ", rgu " + sc::unit_view_name(rgu) +
                           ", pipes " + std::to_string(cfg.trv_pipes) +
                           (cfg.trv_fuse ? " fused" : "");
  expect_same_counts(model, p, what);
}
TEST(TrvRtlFrame, DefaultsFp24Rtz) {
  expect_trv_rtl(corridor(), config(FormatId::fp24, Rounding::rtz, true, 48, 30), {});
}
TEST(TrvRtlFrame, BaselineFp24RneThreeRtusRandomLatency) {
  sc::SimConfig cfg;
  cfg.rays_in_flight = 64;
  cfg.trv_pipes = 1;
  cfg.trv_fuse = false;
  cfg.ist_units = 1;
  cfg.l2.size_bytes = 0;
  cfg.rtus = 3;
  cfg.seed = 7;
  expect_trv_rtl(corridor(), config(FormatId::fp24, Rounding::rne, true, 40, 24), cfg);
}
TEST(TrvRtlFrame, SmallCachesMarginsTwoPipes) {
  sc::SimConfig cfg;  // misses, MSHRs full, looping, the ist queue full
  cfg.node_cache = {1024, 2, 64, 2, 1};
  cfg.list_cache = {512, 2, 32, 2, 2};
  cfg.ist_queue = 3;
  cfg.trv_pipes = 2;
  cfg.ist_units = 3;
  cfg.rays_in_flight = 128;
  cfg.rtus = 2;
  expect_trv_rtl(corridor(), margins_config(Rounding::rne, true), cfg);
}
TEST(TrvRtlFrame, AnyHitSkipBackSpawnAll) {
  auto tc = config(FormatId::fp24, Rounding::rne, true, 40, 24);
  tc.spawn.spawn = raycore::hls::Spawn::skip_back;
  tc.spawn.spawn_all = true;
  tc.spawn.any_hit = true;
  expect_trv_rtl(tiny_scene(), tc, {});
}
TEST(TrvRtlFrame, Fp32ThreePipes) {
  sc::SimConfig cfg;
  cfg.trv_pipes = 3;
  expect_trv_rtl(tiny_scene(), config(FormatId::fp32, Rounding::rne, true, 32, 24), cfg);
}
TEST(TrvRtlFrame, WithVtuAndIstRtl) {
  expect_trv_rtl(corridor(), config(FormatId::fp24, Rounding::rtz, true, 32, 20), {}, UnitView::rtl,
                 UnitView::rtl);
}
// Every unit with RTL in the frame: trv, vtu, ist and rgu (its primary rays), 3 RTUs.
TEST(TrvRtlFrame, WithVtuIstRguRtl) {
  sc::SimConfig cfg;
  cfg.rtus = 3;
  expect_trv_rtl(corridor(), config(FormatId::fp24, Rounding::rne, true, 32, 20), cfg, UnitView::rtl,
                 UnitView::rtl, UnitView::rtl);
}
// Every unit with RTL in the frame (--rtl all: vtu, ist, trv, hit, rgu), 3 RTUs, randomised memory
// latency, FP24 rne with skip-back shadow rays: the transaction model's frame, cycles and counters.
TEST(TrvRtlFrame, AllUnitsRtlThreeRtusRandomLatency) {
  sc::SimConfig cfg;
  cfg.rtus = 3;
  cfg.seed = 11;
  auto tc = config(FormatId::fp24, Rounding::rne, true, 40, 24);
  tc.spawn.spawn = raycore::hls::Spawn::skip_back;
  const Summary model = expect_match(corridor(), tc, cfg);
  cfg.vtu_view = cfg.ist_view = cfg.trv_view = cfg.hit_view = cfg.rgu_view = UnitView::rtl;
  const Summary p = expect_match(corridor(), tc, cfg);
  expect_same_counts(model, p, "all units rtl");
}
TEST(TrvRtlFrame, RefusesWhatTheModelCannotRun) {
  const auto tc = config(FormatId::fp24, Rounding::rtz, false, 8, 8);
  sc::SimConfig cfg;
  cfg.trv_view = UnitView::rtl;
  cfg.mailbox = 4;
  expect_refused(tiny_scene(), tc, cfg, "the RTL has no mailbox");
  cfg.mailbox = 0;
  cfg.trv_pipes = 6;
  expect_refused(tiny_scene(), tc, cfg, "is built for at most 5 --trv-pipes");
  cfg.trv_pipes = 5;
  cfg.trv_latency = 4;  // the split's write-back: the ray must not come back before it
  cfg.node_cache.hit_latency = 1;
  expect_refused(tiny_scene(), tc, cfg, "plus the node cache's hit latency must be at least 6");
  cfg.trv_latency = 5;
  sc::SimConfig least = cfg;  // 5 + 1, the least it runs: a ray back in the cycle after the
  least.trv_view = UnitView::model;  // split's write-back, its node and stack as written
  expect_trv_rtl(corridor(), tc, least);
  cfg.trv_latency = 5;
  cfg.trv_view = UnitView::twin;
  expect_refused(tiny_scene(), tc, cfg, "trv has no pin-level SystemC twin");
  cfg.trv_view = UnitView::rtl;  // not built: the message lists what is
  const Summary r = expect_refused(tiny_scene(), config(FormatId::fp24, Rounding::raycore, false, 8, 8),
                                   cfg, "no Verilated trv_unit for fp24 raycore");
  EXPECT_NE(std::string(r.error).find("trv_unit FP32 rne"), std::string::npos) << r.error;
}

// ---- the caches in RTL (rtl/units/ascache.v, HIT_LATENCY 0, --rtl ascache) --------------------
// The frame with the node, list and triangle caches of every RTU Verilated: the transaction
// model's cycles, bus bytes, frame and work counters, with every cache counter (hits, merges,
// MSHRs full, fills) equal; the binding itself checks each merge, full and new MSHR against its
// bookkeeping, the request queue's head whenever the bus takes it, and the RTL's counters.
void expect_ascache_rtl(const scenes::Scene& s, const sim::TraceConfig& tc, sc::SimConfig cfg,
                        const char* what) {
  const Summary model = expect_match(s, tc, cfg);
  cfg.ascache_view = UnitView::rtl;
  const Summary p = expect_match(s, tc, cfg);
  expect_same_counts(model, p, what);
}
// The frame's cache alone: Ascache as the model and Ascache with the Verilated cache bound, driven
// by the same random calls: cycles of 0..8 accesses (the RTL's 8 ports) by 32 requesters, each
// retrying its line 1..8 cycles after a miss until it hits (as the frame's rays and ist entries
// do: the pin rule's premise), then moving on along a stream with locality (the next line, a
// recent one, a window that drifts, a line of a hot set, a far one), the bus taking requests at
// random, fills of taken requests after a random delay, out of order, at most one a cycle (the
// fill port; installed at the cycle's edge). Every answer (a line and its bytes, or none), every
// request taken, the MSHRs busy and the counters are equal.
void ascache_lockstep(const sc::CacheConfig& cc, uint32_t line_bytes, uint64_t cycles,
                      uint64_t seed) {
  sc::Ascache a("model", cc, 0, line_bytes), b("rtl", cc, 0, line_bytes);
  auto r = sc::make_rtl_ascache(b.sets(), b.ways(), b.line_bytes(), b.mshrs_total());
  ASSERT_TRUE(r) << sc::rtl_ascache_built();
  b.bind_rtl(std::move(r));
  std::mt19937_64 rng(seed);
  struct Taken {
    sc::Cycle at;
    uint32_t tag;
    uint64_t line;
  };
  std::vector<Taken> taken;
  std::vector<uint64_t> recent(16, 0);
  const uint64_t window = 4ull * a.sets() * a.ways();
  uint64_t base = 0, fills = 0, hot = 0;
  struct Requester {
    uint64_t line;   // retried until it hits
    sc::Cycle next;  // first cycle it may access again
  };
  std::vector<Requester> req(32);
  for (Requester& q : req) q = {rng() % window, 0};
  for (sc::Cycle now = 0; now < cycles; ++now) {
    a.advance(now);
    b.advance(now);
    if (now % 64 == 0) base += rng() % 8;
    if (now % 1024 == 0) hot = rng() % a.sets();
    ASSERT_EQ(a.req().can_pop(now), b.req().can_pop(now)) << "cycle " << now;
    if (a.req().can_pop(now) && rng() % 3 != 0) {
      const sc::MemReq x = a.req().pop(), y = b.req().pop();
      ASSERT_EQ(x.addr, y.addr) << "cycle " << now;
      ASSERT_EQ(x.tag, y.tag) << "cycle " << now;
      taken.push_back({now + 1 + rng() % (rng() % 8 == 0 ? 150 : 40), x.tag, x.addr / line_bytes});
    }
    for (int f = 0; f < 1 && !taken.empty(); ++f) {
      const size_t i = rng() % taken.size();
      if (taken[i].at > now) continue;
      uint8_t* pa = a.mshr_data(taken[i].tag);
      uint8_t* pb = b.mshr_data(taken[i].tag);
      ++fills;
      for (uint32_t k = 0; k < line_bytes; ++k)
        pa[k] = pb[k] = uint8_t((taken[i].line * 131 + fills * 7 + k * 29) >> (k % 3));
      a.fill(taken[i].tag);
      b.fill(taken[i].tag);
      taken.erase(taken.begin() + long(i));
    }
    const int n = int(rng() % 9);
    for (int k = 0; k < n; ++k) {
      Requester& q = req[rng() % req.size()];
      if (q.next > now) continue;
      uint64_t& line = q.line;
      const uint8_t* pa = a.access(line);
      const uint8_t* pb = b.access(line);
      ASSERT_EQ(pa == nullptr, pb == nullptr) << "cycle " << now << " access " << k << " line " << line;
      if (!pa) {  // retried later
        q.next = now + 1 + rng() % 8;
        continue;
      }
      ASSERT_EQ(std::memcmp(pa, pb, line_bytes), 0) << "cycle " << now << " line " << line;
      recent[rng() % recent.size()] = line;
      const uint64_t c = rng() % 10;
      line = c < 3   ? line + 1
             : c < 6 ? recent[rng() % recent.size()]
             : c < 8 ? base + rng() % window
             : c < 9 ? hot + a.sets() * (rng() % 64)
                     : rng() % (1u << 20);
    }
    ASSERT_EQ(a.mshrs_busy(), b.mshrs_busy()) << "cycle " << now;
  }
  const sc::CacheStats &sa = a.stats(), &sb = b.stats();
  EXPECT_EQ(sa.hits, sb.hits);
  EXPECT_EQ(sa.misses, sb.misses);
  EXPECT_EQ(sa.mshr_merges, sb.mshr_merges);
  EXPECT_EQ(sa.mshr_full, sb.mshr_full);
  EXPECT_EQ(sa.set_full, sb.set_full);
  EXPECT_EQ(sa.fills, sb.fills);
  std::printf("ASCACHELOCKSTEP %s hits %llu misses %llu merges %llu mshr_full %llu set_full %llu "
              "fills %llu\n",
              b.rtl()->name().c_str(), (unsigned long long)sa.hits, (unsigned long long)sa.misses,
              (unsigned long long)sa.mshr_merges, (unsigned long long)sa.mshr_full,
              (unsigned long long)sa.set_full, (unsigned long long)sa.fills);
  // The stream exercises hits, evictions, merges, full MSHRs and sets full; every fill is hit
  // (pinned until then), but for lines still pinned at the end.
  EXPECT_GT(sa.hits, cycles / 20);
  EXPECT_GT(sa.fills, cycles / 100);
  EXPECT_GE(sa.hits + uint64_t(a.sets()) * a.ways(), sa.fills);
  EXPECT_GT(sa.mshr_merges, 0u);
  EXPECT_GT(sa.mshr_full, 0u);
  EXPECT_GT(sa.set_full, 0u);
}
TEST(AscacheRtlLockstep, Node32k) { ascache_lockstep({32 * 1024, 4, 64, 8, 1}, 64, 200000, 1); }
TEST(AscacheRtlLockstep, Node1k) { ascache_lockstep({1024, 2, 64, 2, 1}, 64, 200000, 2); }
TEST(AscacheRtlLockstep, List512Lines32) { ascache_lockstep({512, 2, 32, 2, 1}, 32, 200000, 3); }
TEST(AscacheRtlLockstep, Tri32kFp32Sets170) { ascache_lockstep({32 * 1024, 4, 48, 8, 1}, 48, 200000, 4); }

TEST(AscacheRtlFrame, DefaultsFp24Rtz) {
  expect_ascache_rtl(corridor(), config(FormatId::fp24, Rounding::rtz, true, 48, 30), {},
                     "defaults");
}
TEST(AscacheRtlFrame, SmallCachesNoL2RandomLatencyWithTrvRtl) {
  sc::SimConfig cfg;  // misses, merges, MSHRs full, evictions; more accesses than ports a cycle
  cfg.node_cache = {1024, 2, 64, 2, 1};
  cfg.list_cache = {512, 2, 32, 2, 2};
  cfg.trv_pipes = 4;
  cfg.l2.size_bytes = 0;
  cfg.rtus = 2;
  cfg.seed = 5;
  expect_ascache_rtl(corridor(), margins_config(Rounding::rne, true), cfg, "small caches");
  cfg.trv_view = UnitView::rtl;
  expect_ascache_rtl(corridor(), margins_config(Rounding::rne, true), cfg, "small caches, trv rtl");
}
TEST(AscacheRtlFrame, Fp32TriangleCacheOf170Sets) {
  expect_ascache_rtl(tiny_scene(), config(FormatId::fp32, Rounding::rne, true, 32, 24), {},
                     "fp32: 48-byte triangle lines, 170 sets");
}
// Every unit with RTL in the frame (--rtl all: vtu, ist, trv, ascache, hit, rgu), 3 RTUs,
// randomised memory latency, skip-back shadow rays.
TEST(AscacheRtlFrame, AllUnitsRtlThreeRtusRandomLatency) {
  sc::SimConfig cfg;
  cfg.rtus = 3;
  cfg.seed = 13;
  cfg.vtu_view = cfg.ist_view = cfg.trv_view = cfg.hit_view = cfg.rgu_view = UnitView::rtl;
  auto tc = config(FormatId::fp24, Rounding::rne, true, 40, 24);
  tc.spawn.spawn = raycore::hls::Spawn::skip_back;
  expect_ascache_rtl(corridor(), tc, cfg, "all units rtl");
}
TEST(AscacheRtlFrame, RefusesWhatIsNotBuilt) {
  const auto tc = config(FormatId::fp24, Rounding::rtz, false, 8, 8);
  sc::SimConfig cfg;
  cfg.ascache_view = UnitView::twin;
  expect_refused(tiny_scene(), tc, cfg, "ascache has no pin-level twin in the frame");
  cfg.ascache_view = UnitView::rtl;
  cfg.node_cache.size_bytes = 2048;  // 8 sets x 4 ways: not built; the message lists what is
  const Summary r = expect_refused(tiny_scene(), tc, cfg,
                                   "no Verilated ascache for the node_cache (8 sets x 4 ways");
  EXPECT_NE(std::string(r.error).find("128 sets x 4 ways x 64 B, 8 MSHRs"), std::string::npos)
      << r.error;
  cfg.node_cache.size_bytes = 32 * 1024;  // built, but more pipes than its 8 ports a cycle
  cfg.trv_pipes = 9;
  expect_refused(tiny_scene(), tc, cfg, "takes 8 accesses a cycle, the node_cache may get 9");
}

// ---- every subset of the units in RTL -----------------------------------------------------------
// The corridor (24 x 16, FP24 rne, VTU on, skip-back shadow rays, 2 RTUs, randomised memory
// latency, no L2 so that the bus interface can join) with each of the 2^7 subsets of {vtu, ist, trv,
// ascache, hit, rgu, membus} as Verilated RTL and the rest the transaction model: every frame equal
// to the model's in cycles, bits, bus bytes and work counters. Split by membus (two tests, run side
// by side by ctest -j).
void expect_every_subset(bool membus) {
  sc::SimConfig cfg;
  cfg.rtus = 2;
  cfg.seed = 21;
  cfg.l2.size_bytes = 0;
  auto tc = config(FormatId::fp24, Rounding::rne, true, 24, 16);
  tc.spawn.spawn = raycore::hls::Spawn::skip_back;
  const Summary model = expect_match(corridor(), tc, cfg);
  const char* names[6] = {"vtu", "ist", "trv", "ascache", "hit", "rgu"};
  UnitView sc::SimConfig::*views[6] = {&sc::SimConfig::vtu_view, &sc::SimConfig::ist_view,
                                       &sc::SimConfig::trv_view, &sc::SimConfig::ascache_view,
                                       &sc::SimConfig::hit_view,  &sc::SimConfig::rgu_view};
  for (unsigned mask = 0; mask < 64; ++mask) {
    if (mask == 0 && !membus) continue;  // the model itself
    sc::SimConfig c = cfg;
    std::string what = membus ? "membus" : "";
    for (unsigned u = 0; u < 6; ++u)
      if (mask & (1u << u)) {
        c.*views[u] = UnitView::rtl;
        what += (what.empty() ? "" : ",") + std::string(names[u]);
      }
    if (membus) c.membus_view = UnitView::rtl;
    expect_same_counts(model, expect_match(corridor(), tc, c), "--rtl " + what);
    if (::testing::Test::HasFailure()) return;  // the first subset that differs is enough
  }
}
TEST(RtlSubsets, EveryUnitSubsetWithoutMembus) { expect_every_subset(false); }
TEST(RtlSubsets, EveryUnitSubsetWithMembus) { expect_every_subset(true); }

// The waveform of an all-RTL frame (--rtl all,membus --trace): every unit's handshakes of RTU 0
// are in the VCD, with the frame equal to the model's.
TEST(RtlWaveform, AllRtlFrameHasEveryUnitOfRtu0) {
  sc::SimConfig cfg;
  cfg.rtus = 2;
  cfg.l2.size_bytes = 0;
  const auto tc = config(FormatId::fp24, Rounding::rtz, true, 16, 8);
  const Summary model = expect_match(corridor(), tc, cfg);
  cfg.vtu_view = cfg.ist_view = cfg.trv_view = cfg.ascache_view = cfg.hit_view = cfg.rgu_view =
      cfg.membus_view = UnitView::rtl;
  const std::string vcd = ::testing::TempDir() + "raycore_all_rtl.vcd";
  std::remove(vcd.c_str());
  cfg.trace_file = vcd;
  expect_same_counts(model, expect_match(corridor(), tc, cfg), "--rtl all,membus --trace");
  std::ifstream in(vcd);
  ASSERT_TRUE(in.good()) << "no waveform written to " << vcd;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* sig : {"clk_i", "rtu0_vtu_in_valid_i", "rtu0_vtu_out_valid_o",
                          "rtu0_rgu_out_valid_o", "rtu0_rgu_out_shadow_o", "rtu0_rgu_free_count_o",
                          "rtu0_trv_in_valid_i", "rtu0_trv_go_o", "rtu0_trv_fin_o",
                          "rtu0_trv_acc_valid_o", "rtu0_ist_hin_n_i", "rtu0_ist_acc_valid_o",
                          "rtu0_ist_res_valid_o", "rtu0_hit_fin_valid_i", "rtu0_hit_rd_valid_o",
                          "rtu0_hit_out_valid_o", "rtu0_hit_out_spawn_o", "rtu0_node_accesses",
                          "rtu0_list_hits", "rtu0_tri_fills"})
    EXPECT_NE(text.find(std::string(" ") + sig + " "), std::string::npos) << sig << " not in " << vcd;
  // The handshakes move: each of these one-bit signals is 1 in some cycle ("$var wire 1 <id>
  // <name> $end" declares it, a line "1<id>" sets it).
  for (const char* sig : {"rtu0_rgu_out_valid_o", "rtu0_rgu_out_shadow_o", "rtu0_hit_out_spawn_o",
                          "rtu0_hit_rd_valid_o", "rtu0_trv_in_valid_i", "rtu0_ist_head_valid_o"}) {
    std::istringstream lines(text);
    std::string line, id;
    while (id.empty() && std::getline(lines, line)) {
      std::istringstream f(line);
      std::string var, kind, width, code, name;
      if (f >> var >> kind >> width >> code >> name && var == "$var" && name == sig) id = code;
    }
    ASSERT_FALSE(id.empty()) << sig << " not declared in " << vcd;
    EXPECT_NE(text.find("\n1" + id + "\n"), std::string::npos) << sig << " (" << id << ") never 1";
  }
  std::remove(vcd.c_str());
}

// ---- the bus interface in RTL (rtl/units/membus_if.v, --rtl membus; membus_l2.v with the L2) ---
// The frame with membus_if arbitrating the caches' requests and routing the memory's beats (the
// memory's timing stays in Membus): the transaction model's cycles, bus bytes, L2 and queue
// counters, frame and work counters; the binding checks every grant, every beat routed back and
// each line's last beat against the cycle the transaction model answers in. Without `l2`, the
// frame has no L2 (membus_if.v); with it, the configuration's (membus_l2.v).
Summary expect_membus_rtl(const scenes::Scene& s, const sim::TraceConfig& tc, sc::SimConfig cfg,
                          const char* what, bool l2 = false) {
  if (!l2) cfg.l2.size_bytes = 0;
  const Summary model = expect_match(s, tc, cfg);
  cfg.membus_view = UnitView::rtl;
  const Summary p = expect_match(s, tc, cfg);
  expect_same_counts(model, p, what);
  return model;
}
TEST(MembusRtlFrame, DefaultsSixRtus) {
  expect_membus_rtl(corridor(), config(FormatId::fp24, Rounding::rtz, true, 48, 30), {},
                    "6 RTUs, 18 requesters");
}
TEST(MembusRtlFrame, RandomLatencySmallCachesSixteenRtus) {
  sc::SimConfig cfg;  // queue full (32 outstanding), 48 requesters: every port of the model
  cfg.rtus = 16;
  cfg.seed = 3;
  cfg.node_cache = {1024, 2, 64, 2, 1};
  cfg.list_cache = {512, 2, 32, 2, 2};
  expect_membus_rtl(corridor(), margins_config(Rounding::rne, true), cfg, "16 RTUs, random latency");
}
// The model's default L2 (512 KB, 8 ways, 32 bytes per cycle) in RTL, 6 RTUs: hits and merges.
TEST(MembusRtlFrame, DefaultL2SixRtus) {
  const Summary m = expect_membus_rtl(corridor(), config(FormatId::fp24, Rounding::rtz, true, 48, 30),
                                      {}, "6 RTUs, the default L2", true);
  EXPECT_GT(m.l2_hits, 0u);
  EXPECT_GT(m.l2_merges, 0u);
}
// A 1 KB L2 (8 sets x 2 ways), small L1 caches, 4 RTUs and randomised memory latency: evictions and
// misses that wait for a way being filled or read (l2_stall_cycles; with 16 ways, at most 16
// misses are in flight, so the memory queue of 32 never fills here: RandomLatencySmallCaches-
// SixteenRtus has that case).
TEST(MembusRtlFrame, TinyL2RandomLatency) {
  sc::SimConfig cfg;
  cfg.rtus = 4;
  cfg.seed = 5;
  cfg.l2 = {1024, 2, 64, 3, 32};
  cfg.node_cache = {1024, 2, 64, 2, 1};
  cfg.list_cache = {512, 2, 64, 2, 2};
  const Summary m = expect_membus_rtl(corridor(), margins_config(Rounding::rne, true), cfg,
                                      "4 RTUs, 1 KB L2, random latency", true);
  EXPECT_GT(m.l2_hits, 0u);
  EXPECT_GT(m.l2_merges, 0u);
  EXPECT_GT(m.l2_stalls, 0u);
}
// Every unit of the RTUs and the bus interface in RTL (--rtl all,membus), 3 RTUs, randomised
// latency, the default L2.
TEST(MembusRtlFrame, WithEveryUnitRtl) {
  sc::SimConfig cfg;
  cfg.rtus = 3;
  cfg.seed = 17;
  cfg.vtu_view = cfg.ist_view = cfg.trv_view = cfg.ascache_view = cfg.hit_view = cfg.rgu_view =
      UnitView::rtl;
  expect_membus_rtl(corridor(), config(FormatId::fp24, Rounding::rne, true, 40, 24), cfg,
                    "every unit rtl, the default L2", true);
}
// FP32 (rne) with every unit and the bus in RTL, 2 RTUs, randomised latency, skip-back shadow
// rays: vtu.v, ist_unit, trv_unit, the caches' 48-byte triangle lines, hit_unit and rgu_unit at 32
// bits.
TEST(MembusRtlFrame, Fp32WithEveryUnitRtl) {
  sc::SimConfig cfg;
  cfg.rtus = 2;
  cfg.seed = 29;
  cfg.l2.size_bytes = 0;
  auto tc = config(FormatId::fp32, Rounding::rne, true, 32, 20);
  tc.spawn = spawn(hls::Spawn::skip_back);
  const Summary model = expect_match(corridor(), tc, cfg);
  cfg.vtu_view = cfg.ist_view = cfg.trv_view = cfg.ascache_view = cfg.hit_view = cfg.rgu_view =
      cfg.membus_view = UnitView::rtl;
  expect_same_counts(model, expect_match(corridor(), tc, cfg), "fp32 rne, --rtl all,membus");
}
TEST(MembusRtlFrame, RefusesWhatItCannotRun) {
  const auto tc = config(FormatId::fp24, Rounding::rtz, false, 8, 8);
  sc::SimConfig cfg;
  cfg.membus_view = UnitView::rtl;
  cfg.l2.size_bytes = 128 * 1024;  // membus_l2 is built for 512 KB and 1 KB
  const Summary l2 = expect_refused(tiny_scene(), tc, cfg, "--l2-kb 128");
  EXPECT_NE(std::string(l2.error).find("an L2 of 512 KB (8 ways, 64-byte lines, 32 bytes per cycle)"),
            std::string::npos) << l2.error;
  cfg.l2.size_bytes = 0;
  cfg.mem_bandwidth = 8;
  const Summary r = expect_refused(tiny_scene(), tc, cfg, "no Verilated membus_if");
  EXPECT_NE(std::string(r.error).find("32 outstanding, 16-byte beats"), std::string::npos) << r.error;
  cfg.mem_bandwidth = 16;
  cfg.rtus = 17;
  expect_refused(tiny_scene(), tc, cfg, "no Verilated membus_if for 17 RTUs");
  cfg.rtus = 2;
  cfg.membus_view = UnitView::twin;
  expect_refused(tiny_scene(), tc, cfg, "membus has no pin-level twin in the frame");
}

// ---- the paper's scene with every unit in RTL -------------------------------------------------
// sponza-paper (../shared/scenes) in a small frame of the paper's view (the whole kd-tree; the crop
// is in pixels), VTU on, every unit of the RTUs and the bus interface in RTL, randomised memory
// latency: the transaction model's cycles, bus bytes, frame and work counters.
TEST(AllRtlFrame, SponzaPaperSmallFrameWithBus) {
  const std::string path = std::string(RAYCORE_SHARED_SCENES_DIR) + "/sponza-paper.glb";
  if (!std::ifstream(path).good()) GTEST_SKIP() << path << " not found (../shared/scenes)";
  static const scenes::Scene s = scenes::load_gltf(path, false);
  sc::SimConfig cfg;
  cfg.rtus = 2;
  cfg.seed = 23;
  cfg.vtu_view = cfg.ist_view = cfg.trv_view = cfg.ascache_view = cfg.hit_view = cfg.rgu_view =
      UnitView::rtl;
  expect_membus_rtl(s, config(FormatId::fp24, Rounding::rtz, true, 64, 40), cfg,
                    "sponza-paper 64x40, every unit and the bus rtl");
}

// ---- the whole RTU in RTL (--rtl rtu) ----------------------------------------------------------
// Every RTU one Verilated rtl/units/rtu.v (its units and the glue between them: slot_ram,
// vtu_unit, the caches' wiring) with the Verilated bus (membus_l2 with the configuration's L2, the
// model's default 512 KB unless set; membus_if with --l2-kb 0): the transaction model's cycles,
// bus bytes, L2 counters, frame, ray counts and work counters.
void expect_rtu_rtl(const scenes::Scene& s, const sim::TraceConfig& tc, sc::SimConfig cfg,
                    const std::string& what) {
  const Summary model = expect_match(s, tc, cfg);
  cfg.rtu_view = UnitView::rtl;
  const Summary p = expect_match(s, tc, cfg);
  expect_same_counts(model, p, what);
  EXPECT_EQ(p.issued, model.issued) << what;
  EXPECT_EQ(p.primary, model.primary) << what;
  EXPECT_EQ(p.shadow, model.shadow) << what;
  EXPECT_EQ(p.retired, model.retired) << what;
}
TEST(RtuRtlFrame, CorridorVtuOnTwoRtus) {
  sc::SimConfig cfg;
  cfg.rtus = 2;
  expect_rtu_rtl(corridor(), config(FormatId::fp24, Rounding::rtz, true, 40, 24), cfg,
                 "corridor 40x24, VTU on, 2 RTUs");
}
// Shadow rays of each kind of hand-off (skip-origin's skip id through slot_ram, segment rays,
// spawn-all), randomised memory latency, 3 RTUs. With the VTU on: the model's cycles and every
// counter.
TEST(RtuRtlFrame, ShadowRaysRandomLatency) {
  for (const hls::SpawnParams& sp : {spawn(hls::Spawn::skip_origin), spawn(hls::Spawn::none, true),
                                     spawn(hls::Spawn::ulp_offset, false, true)}) {
    auto tc = config(FormatId::fp24, Rounding::rtz, true, 32, 20);
    tc.spawn = sp;
    sc::SimConfig cfg;
    cfg.rtus = 3;
    cfg.seed = 5;
    expect_rtu_rtl(corridor(), tc, cfg, "corridor 32x20, seed 5, " + sim::to_string(sp.spawn) +
                                            (sp.segment ? " segment" : "") +
                                            (sp.spawn_all ? " all" : ""));
  }
}
// RAYCORE_RTL_THREADS=2: the RTUs' models evaluated on two host threads (the even RTUs on this
// one, the odd on a second) give the same cycles, frame and counters; 3 RTUs (an uneven split),
// randomised memory latency. A value other than 1 or 2 is refused.
TEST(RtuRtlFrame, TwoHostThreads) {
  struct Env {
    explicit Env(const char* v) { setenv("RAYCORE_RTL_THREADS", v, 1); }
    ~Env() { unsetenv("RAYCORE_RTL_THREADS"); }
  };
  auto tc = config(FormatId::fp24, Rounding::rtz, true, 16, 10);
  tc.spawn = spawn(hls::Spawn::skip_origin);
  sc::SimConfig cfg;
  cfg.rtus = 3;
  cfg.seed = 9;
  {
    Env e("2");
    expect_rtu_rtl(corridor(), tc, cfg, "corridor 16x10, 3 RTUs, seed 9, two host threads");
  }
  Env e("3");
  cfg.l2.size_bytes = 0;
  cfg.rtu_view = UnitView::rtl;
  expect_refused(corridor(), tc, cfg, "RAYCORE_RTL_THREADS must be 1 or 2, not '3'");
}
// The VTU off: every line installed in the cycle of its last beat, none through vtu.v (rtu.v's
// fill path straight from the beat, BEAT_REG = 1: from the beat register). 1 and 2 RTUs, and 3
// with randomised memory latency: the model's cycles, bus bytes and every counter.
TEST(RtuRtlFrame, VtuOff) {
  for (const int rtus : {1, 2, 3}) {
    auto tc = config(FormatId::fp24, Rounding::rtz, false, 40, 24);
    tc.spawn = spawn(hls::Spawn::skip_origin);
    sc::SimConfig cfg;
    cfg.rtus = rtus;
    if (rtus == 3) cfg.seed = 7;
    expect_rtu_rtl(corridor(), tc, cfg, "corridor 40x24, VTU off, rtus " + std::to_string(rtus) +
                                            (rtus == 3 ? ", seed 7" : ""));
  }
}
// The registers that are not the RTU's structure: trv latency, cache hit latencies (the
// triangle cache's through ist_unit's delay ring), 2 trv pipes and 1 ist unit of the built 4 and
// 2, fewer rays in flight, a short stack, no fusing, a short ist queue; the VTU on, skip-back.
TEST(RtuRtlFrame, RegistersAwayFromTheDefaults) {
  auto tc = margins_config(Rounding::rtz, true);
  tc.spawn = spawn(hls::Spawn::skip_back);
  sc::SimConfig cfg;
  cfg.rtus = 2;
  cfg.seed = 11;
  cfg.trv_latency = 4;  // with the node cache's 2: an inner node's ray back in the cycle after
  cfg.node_cache.hit_latency = 2;  // its split's write-back (the least rtu.v runs)
  cfg.list_cache.hit_latency = 0;
  cfg.tri_cache.hit_latency = 5;
  cfg.trv_pipes = 2;
  cfg.ist_units = 1;
  cfg.rays_in_flight = 24;
  cfg.trv_fuse = false;
  cfg.ist_queue = 6;
  expect_rtu_rtl(corridor(), tc, cfg, "corridor, registers away from the defaults");
}
// Issue 24: --store anchored, the VTU on (rtu.v takes the host's translated registers). Without
// an L2 (--l2-kb 0: membus_if, chip.v's bus).
TEST(RtuRtlFrame, AnchoredStoreVtuOn) {
  sc::SimConfig cfg;
  cfg.rtus = 2;
  cfg.l2.size_bytes = 0;
  expect_rtu_rtl(corridor(), anchored_config(corridor(), Rounding::rtz, 32, 20), cfg,
                 "corridor 32x20, VTU on, --store anchored");
}
TEST(RtuRtlFrame, SponzaPaperSmallFrame) {
  const std::string path = std::string(RAYCORE_SHARED_SCENES_DIR) + "/sponza-paper.glb";
  if (!std::ifstream(path).good()) GTEST_SKIP() << path << " not found (../shared/scenes)";
  static const scenes::Scene s = scenes::load_gltf(path, false);
  sc::SimConfig cfg;
  cfg.rtus = 2;
  cfg.seed = 29;
  expect_rtu_rtl(s, config(FormatId::fp24, Rounding::rtz, true, 64, 40), cfg,
                 "sponza-paper 64x40, the whole RTU rtl");
}
// The caches' pin rule in the whole RTU (forward progress, issue 26 part 4): 128 rays and a slow
// memory, randomised per request, on 96 x 60 make misses refused for a set whose ways are all
// pinned or awaited (set_full) besides MSHRs full; every counter, set_full included, and the
// cycles equal. The RTL's caches are the defaults', so only rays, latency and frame can be tuned,
// and refusals are rare at these sizes and move with every change of timing (a single fixed
// configuration lost them three times: other primary rays, the ist queue's room from the cycle's
// start, the deferred push of a leaf's last result). So the test takes the first memory latency
// (300 .. 800) and seed (1 .. 3) whose model frame has a refusal, and runs the RTL on that one.
TEST(RtuRtlFrame, PinnedLinesAndSetsFull) {
  const std::string path = std::string(RAYCORE_SHARED_SCENES_DIR) + "/sponza-paper.glb";
  if (!std::ifstream(path).good()) GTEST_SKIP() << path << " not found (../shared/scenes)";
  static const scenes::Scene s = scenes::load_gltf(path, false);
  sc::SimConfig cfg;
  cfg.rtus = 1;
  cfg.rays_in_flight = 128;
  cfg.l2.size_bytes = 0;
  const auto tc = config(FormatId::fp24, Rounding::rtz, true, 96, 60);
  Summary model{};
  bool found = false;
  for (uint32_t lat = 300; lat <= 800 && !found; lat += 100)
    for (uint64_t seed = 1; seed <= 3 && !found; ++seed) {
      cfg.mem_latency = lat;
      cfg.seed = seed;
      model = expect_match(s, tc, cfg);
      found = model.work[kWorkSetFull] > 0;
    }
  ASSERT_TRUE(found) << "no miss refused for a full set at memory 300 .. 800, seeds 1 .. 3: the test "
                        "misses its point";
  cfg.rtu_view = UnitView::rtl;
  const Summary p = expect_match(s, tc, cfg);
  expect_same_counts(model, p, "sponza-paper 96x60, 128 rays, memory " + std::to_string(cfg.mem_latency) +
                                   " seed " + std::to_string(cfg.seed) + ", the whole RTU rtl");
}
// Issue 26 part 6: the L2 in the whole-RTU frame. The memory's and the L2's last beats meet at an
// RTU: vtu_unit takes the two lines in the order the bus took their requests (its age matrix), and
// with the VTU off two lines of one cache meet (the second waits a cycle for the cache's fill
// port, and the lines behind it with it). The model's cycles and counters, those two counted in
// both views (vtu_paired, vtu_fill_waits; the test asserts that they occur). A fast L2 (latency 1)
// and one RTU make the meetings common (corridor 48x32, VTU off: 21 cycles with two lines, 9
// line-cycles waiting for a fill port); with randomised memory
// latency the L2's line is sometimes the older one (2 RTUs, seed 29, VTU on; 3 RTUs, seed 5, VTU
// off: both diverge from the model if the memory's line is always taken first); the 1 KB L2
// (evictions, stalls) with 2 RTUs.
TEST(RtuRtlFrame, MemoryAndL2LinesTogether) {
  {
    sc::SimConfig cfg;
    cfg.rtus = 1;
    cfg.l2.latency = 1;
    const auto tc = config(FormatId::fp24, Rounding::rtz, false, 48, 32);
    const std::string what = "corridor 48x32, 1 RTU, L2 latency 1, VTU off";
    const Summary model = expect_match(corridor(), tc, cfg);
    EXPECT_GT(model.work[kWorkVtuPaired], 0u) << what << ": no two lines in one cycle";
    EXPECT_GT(model.work[kWorkFillWaits], 0u) << what << ": no line waited for its cache";
    cfg.rtu_view = UnitView::rtl;
    expect_same_counts(model, expect_match(corridor(), tc, cfg), what);
  }
  for (const auto& [rtus, seed, vtu] : {std::tuple{2, 29, true}, std::tuple{3, 5, false}}) {
    sc::SimConfig cfg;
    cfg.rtus = rtus;
    cfg.seed = uint64_t(seed);
    expect_rtu_rtl(corridor(), config(FormatId::fp24, Rounding::rtz, vtu, 48, 32), cfg,
                   "corridor 48x32, " + std::to_string(rtus) + " RTUs, seed " +
                       std::to_string(seed) + ", VTU " + (vtu ? "on" : "off"));
  }
  sc::SimConfig cfg;
  cfg.rtus = 2;
  cfg.seed = 5;
  cfg.l2.size_bytes = 1024;
  cfg.l2.ways = 2;
  cfg.l2.latency = 3;
  expect_rtu_rtl(corridor(), config(FormatId::fp24, Rounding::rtz, true, 32, 20), cfg,
                 "corridor 32x20, 2 RTUs, seed 5, a 1 KB L2");
}
TEST(RtuRtlFrame, RefusesWhatItCannotRun) {
  const auto tc = config(FormatId::fp24, Rounding::rtz, true, 8, 8);
  sc::SimConfig cfg;
  cfg.rtu_view = UnitView::rtl;
  cfg.l2.bandwidth = 16;
  expect_refused(tiny_scene(), tc, cfg, "an L2 of 64-byte lines (the caches') and --l2-bandwidth 32");
  cfg.l2.bandwidth = 32;
  cfg.l2.size_bytes = 128 * 1024;
  expect_refused(tiny_scene(), tc, cfg, "--mem-bandwidth 16 and --l2-kb 128 (8 ways");
  cfg.l2.size_bytes = 0;
  expect_refused(tiny_scene(), config(FormatId::fp24, Rounding::rne, true, 8, 8), cfg,
                 "no Verilated rtu for fp24 rne in this build; built: rtu FP24 rtz");
  cfg.rays_in_flight = 200;
  cfg.ist_units = 5;
  cfg.tri_cache.size_bytes = 64 * 1024;
  const Summary r = expect_refused(tiny_scene(), tc, cfg, "--rays-in-flight <= 128");
  EXPECT_NE(std::string(r.error).find("--ist-units <= 4"), std::string::npos) << r.error;
  EXPECT_NE(std::string(r.error).find("caches of 32 / 8 / 32 KB"), std::string::npos) << r.error;
  cfg = {};
  cfg.l2.size_bytes = 0;
  cfg.rtu_view = UnitView::rtl;
  cfg.ist_latency = 30;
  expect_refused(tiny_scene(), tc, cfg, "pipeline depths of STAGES 2");
  cfg.ist_latency = 20;
  cfg.trv_latency = 5;
  cfg.node_cache.hit_latency = 0;
  expect_refused(tiny_scene(), tc, cfg, "--trv-latency + the node cache's hit latency >= 6");
  cfg.trv_latency = 5;
  cfg.node_cache.hit_latency = 1;
  cfg.tri_cache.hit_latency = 0;
  expect_refused(tiny_scene(), tc, cfg, "a triangle-cache hit latency of 1 .. 15");
  cfg.tri_cache.hit_latency = 1;
  cfg.ist_view = UnitView::rtl;
  expect_refused(tiny_scene(), tc, cfg, "give no other unit to --rtl or --pins");
  cfg.ist_view = UnitView::model;
  cfg.rtu_view = UnitView::twin;
  expect_refused(tiny_scene(), tc, cfg, "rtu has no pin-level SystemC twin");
}

// ---- lockstep: twin vs Verilated model --------------------------------------------------------

uint64_t lockstep_count() {
  const char* s = std::getenv("RAYCORE_LOCKSTEP_N");
  return s && *s ? std::strtoull(s, nullptr, 10) : 20000;
}

struct LockResult {
  uint64_t sent = 0, received = 0, cycles = 0, stalled_out = 0, stalled_in = 0;
  std::string failure;  // the first difference
  double seconds = 0;
};

// Runs n items through a and b (same clock, same inputs); Item has a tag. drive(port, item)
// writes the inputs, same(a_out, b_out) compares transactions, show() prints one.
template <class Port, class Item, class Next, class Drive, class Same, class Show>
LockResult lockstep(pins::PinClock& clk, Port& a, Port& b, uint64_t n, std::mt19937_64& rng,
                    Next next, Drive drive, Same same, Show show) {
  LockResult r;
  const auto t0 = std::chrono::steady_clock::now();
  clk.reset();
  Item cur{};
  bool have = false;
  unsigned rate_in = 100, rate_out = 100;
  while (r.received < n) {
    if (r.cycles % 256 == 0) {  // bursty: new rates (some full rate)
      rate_in = (rng() & 3) == 0 ? 100 : unsigned(20 + rng() % 81);
      rate_out = (rng() & 3) == 0 ? 100 : unsigned(10 + rng() % 91);
    }
    const bool ready = rng() % 100 < rate_out;
    a.out_ready(ready);
    b.out_ready(ready);
    if (!have && r.sent < n && rng() % 100 < rate_in) {
      cur = next();
      cur.tag = uint32_t(r.sent & 0xFFFFu);
      have = true;
    }
    if (have) {
      drive(a, cur);
      drive(b, cur);
    } else {
      a.idle();
      b.idle();
    }
    pins::PinClock::settle();
    std::ostringstream where;
    where << "cycle " << r.cycles << " (item " << r.sent << " waiting, " << r.received
          << " out): ";
    if (a.in_ready() != b.in_ready()) {
      r.failure = where.str() + "in_ready_o twin " + std::to_string(a.in_ready()) + " rtl " +
                  std::to_string(b.in_ready());
      break;
    }
    if (a.out_valid() != b.out_valid()) {
      r.failure = where.str() + "out_valid_o twin " + std::to_string(a.out_valid()) + " rtl " +
                  std::to_string(b.out_valid());
      break;
    }
    if (a.out_valid() && ready) {
      const auto oa = a.out(), ob = b.out();
      if (!same(oa, ob)) {
        r.failure = where.str() + "output transaction " + std::to_string(r.received) +
                    " differs:\n  twin " + show(oa) + "\n  rtl  " + show(ob);
        break;
      }
      if (oa.tag != uint32_t(r.received & 0xFFFFu)) {
        r.failure = where.str() + "out of order: tag " + std::to_string(oa.tag);
        break;
      }
      ++r.received;
    }
    if (a.out_valid() && !ready) ++r.stalled_out;
    if (have && !a.in_ready()) ++r.stalled_in;
    if (have && a.in_ready()) {
      have = false;
      ++r.sent;
    }
    clk.edge();
    if (++r.cycles > 100 * n + 1000) {
      r.failure = where.str() + "no progress";
      break;
    }
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void report(const char* name, const LockResult& r, uint64_t n) {
  std::printf("LOCKSTEP %s transactions=%llu cycles=%llu out_stalls=%llu in_stalls=%llu "
              "%.0f cycles/s (two models)\n",
              name, (unsigned long long)r.received, (unsigned long long)r.cycles,
              (unsigned long long)r.stalled_out, (unsigned long long)r.stalled_in,
              r.seconds > 0 ? double(r.cycles) / r.seconds : 0.0);
  EXPECT_EQ(r.failure, "") << name;
  EXPECT_EQ(r.received, n) << name;
  EXPECT_GT(r.stalled_out, n / 20) << name << ": back-pressure exercised too rarely";
}

std::string hex(uint64_t v) {
  char b[24];
  std::snprintf(b, sizeof b, "%llx", (unsigned long long)v);
  return b;
}

template <class F, Rounding R, class V>
void vtu_lockstep(const char* name) {
  const uint64_t n = lockstep_count();
  pins::PinClock clk(sc_core::sc_time(2, sc_core::SC_NS));
  pins::VtuPortT<pins::VtuTwin<F, R>> twin("twin", "twin", clk.clk, clk.rst_n, 2u);
  pins::VtuPortT<V> rtl("rtl", "rtl", clk.clk, clk.rst_n);
  LockResult res;
  sc_core::sc_spawn([&] {
    std::mt19937_64 rng(2026);
    raycore::rtltest::Gen<F, R> gen(11);
    struct Item {
      pins::VtuRec rec;
      bool on = true;
      uint32_t cam[3] = {0, 0, 0};
      uint32_t tag = 0;
    };
    auto next = [&] {
      const auto g = gen.next();
      Item it;
      it.rec.kind = g.tri;
      it.rec.node[0] = g.node;
      for (uint32_t j = 1; j < pins::kVtuNodeLanes; ++j) it.rec.node[j] = gen.next().node;
      it.rec.nmask = uint32_t(rng() & 15u);
      it.rec.k = g.t.k;
      it.rec.flags = g.t.flags;
      for (int i = 0; i < 9; ++i) it.rec.c[i] = g.t.c[i];
      it.rec.id = g.t.id;
      it.on = g.on;
      for (int i = 0; i < 3; ++i) it.cam[i] = g.cam[i];
      return it;
    };
    auto drive = [](pins::VtuPort& p, const Item& it) {
      pins::VtuRec r = it.rec;
      r.tag = it.tag;
      p.config(it.on, it.cam);
      p.drive(r);
    };
    auto same = [](const pins::VtuRec& x, const pins::VtuRec& y) {
      if (x.kind != y.kind || x.tag != y.tag) return false;
      if (!x.kind) return std::equal(std::begin(x.node), std::end(x.node), std::begin(y.node));
      if (x.k != y.k || x.flags != y.flags || x.id != y.id) return false;
      for (int i = 0; i < 9; ++i)
        if (x.c[i] != y.c[i]) return false;
      return true;
    };
    auto show = [](const pins::VtuRec& x) {
      std::string s = "tag " + std::to_string(x.tag) + (x.kind ? " tri k " : " node ");
      if (!x.kind) {
        for (uint64_t v : x.node) s += " " + hex(v);
        return s;
      }
      s += std::to_string(x.k) + " flags " + hex(x.flags) + " id " + std::to_string(x.id) + " c";
      for (uint32_t c : x.c) s += " " + hex(c);
      return s;
    };
    res = lockstep<pins::VtuPort, Item>(clk, twin, rtl, n, rng, next, drive, same, show);
    sc_core::sc_stop();
  });
  sc_core::sc_start();
  report(name, res, n);
}

template <class A, class V>
void ist_lockstep(const char* name) {
  using F = typename A::Fmt;
  const uint64_t n = lockstep_count();
  pins::PinClock clk(sc_core::sc_time(2, sc_core::SC_NS));
  pins::IstPortT<pins::IstTwin<A>> twin("twin", "twin", clk.clk, clk.rst_n, 2u);
  pins::IstPortT<V> rtl("rtl", "rtl", clk.clk, clk.rst_n);
  LockResult res;
  uint64_t by_exit[5] = {};
  sc_core::sc_spawn([&] {
    std::mt19937_64 rng(2027);
    raycore::rtltest::Stimulus<F, A::rounding> gen(13);
    auto next = [&] {
      const raycore::rtltest::IstIn g = gen.next();
      pins::IstIn in;
      in.k = g.k;
      for (int i = 0; i < 9; ++i) in.c[i] = g.c[i];
      for (int i = 0; i < 3; ++i) {
        in.o[i] = g.o[i];
        in.d[i] = g.d[i];
      }
      in.tmin = g.tmin;
      in.tmax = g.tmax;
      return in;
    };
    auto drive = [](pins::IstPort& p, const pins::IstIn& in) { p.drive(in); };
    auto same = [&](const pins::IstOutRec& x, const pins::IstOutRec& y) {
      if (x.exit < 5) ++by_exit[x.exit];
      return x.exit == y.exit && x.t == y.t && x.den == y.den && x.tag == y.tag;
    };
    auto show = [](const pins::IstOutRec& x) {
      return "tag " + std::to_string(x.tag) + " exit " + std::to_string(x.exit) + " t " +
             hex(x.t) + " den " + hex(x.den);
    };
    // Four runs, each with its own margin registers (static within a run: hls/margins.h).
    const double eps[4] = {0.0, 0.008, std::ldexp(1.0, -12), 0.05 * double(rng() % 1000) / 1000};
    for (int k = 0; k < 4 && res.failure.empty(); ++k) {
      const hls::Margins mg = hls::make_margins<A>(eps[k], 0);
      twin.config(mg);
      rtl.config(mg);
      const uint64_t part = n / 4 + (k == 3 ? n % 4 : 0);
      const LockResult r =
          lockstep<pins::IstPort, pins::IstIn>(clk, twin, rtl, part, rng, next, drive, same, show);
      res.sent += r.sent;
      res.received += r.received;
      res.cycles += r.cycles;
      res.stalled_out += r.stalled_out;
      res.stalled_in += r.stalled_in;
      res.seconds += r.seconds;
      if (!r.failure.empty()) res.failure = "eps " + std::to_string(eps[k]) + ": " + r.failure;
    }
    sc_core::sc_stop();
  });
  sc_core::sc_start();
  report(name, res, n);
  for (int e = 0; e < 5; ++e) EXPECT_GT(by_exit[e], n / 100) << name << ": exit code " << e;
}

// The rgu (a source: configuration registers, start_i, busy_o and a valid/ready output): twin
// and Verilated model on one clock, RAYCORE_LOCKSTEP_RGU_FRAMES frames (default 40) of random
// size (1..90 x 1..60, one 200 x 120), RTU index of 1..8 RTUs and camera, random out_ready
// back-pressure (some frames at full rate); out_valid_o and busy_o are compared every cycle, each
// ray (o, d, inv, pixel) on its way out, and the count with hls::RguTiles's.
template <class A, class V>
void rgu_lockstep(const char* name) {
  const char* env = std::getenv("RAYCORE_LOCKSTEP_RGU_FRAMES");
  const int frames = env && *env ? std::atoi(env) : 40;
  pins::PinClock clk(sc_core::sc_time(2, sc_core::SC_NS));
  pins::RguPortT<pins::RguTwin<A>> twin("twin", "twin", clk.clk, clk.rst_n, 2u, 8);
  pins::RguPortT<V> rtl("rtl", "rtl", clk.clk, clk.rst_n);
  LockResult res;
  sc_core::sc_spawn([&] {
    std::mt19937_64 rng(2028);
    auto uni = [&](double lo, double hi) {
      return std::uniform_real_distribution<double>(lo, hi)(rng);
    };
    const auto t0 = std::chrono::steady_clock::now();
    twin.out_ready(false);
    rtl.out_ready(false);
    clk.reset();
    for (int k = 0; k < frames && res.failure.empty(); ++k) {
      const int w = k == 1 ? 200 : 1 + int(rng() % 90), h = k == 1 ? 120 : 1 + int(rng() % 60);
      const int rtus = 1 + int(rng() % 8), rtu = int(rng() % uint64_t(rtus));
      uint32_t origin[3];
      for (uint32_t& o : origin) o = A::from_double(uni(-50, 50));
      const hls::Vec3 f{uni(-1, 1), uni(-1, 1), -1}, r{1, 0, uni(-0.3, 0.3)}, up{0, 1, uni(-0.3, 0.3)};
      const hls::RguCamera cam = hls::rgu_camera<A>(origin, f, r, up, uni(0.1, 2.5), w, h);
      uint64_t expect = 0;
      for (hls::RguTiles t(w, h, 8, rtu, rtus); !t.done(); t.next()) ++expect;
      for (pins::RguPort* p : {static_cast<pins::RguPort*>(&twin), static_cast<pins::RguPort*>(&rtl)}) {
        p->config(cam, w, h, rtu, rtus);
        p->start(true);
      }
      clk.edge();
      twin.start(false);
      rtl.start(false);
      const bool full = k % 4 == 0;
      unsigned rate = 100;
      uint64_t got = 0;
      for (uint64_t c = 0;; ++c, ++res.cycles) {
        if (c % 64 == 0) rate = full ? 100 : unsigned(10 + rng() % 91);
        const bool ready = rng() % 100 < rate;
        twin.out_ready(ready);
        rtl.out_ready(ready);
        pins::PinClock::settle();
        std::ostringstream where;
        where << "frame " << k << " (" << w << "x" << h << ", rtu " << rtu << " of " << rtus
              << ") cycle " << c << " (" << got << " rays out): ";
        if (twin.out_valid() != rtl.out_valid() || twin.busy() != rtl.busy()) {
          res.failure = where.str() + "out_valid_o twin " + std::to_string(twin.out_valid()) +
                        " rtl " + std::to_string(rtl.out_valid()) + ", busy_o twin " +
                        std::to_string(twin.busy()) + " rtl " + std::to_string(rtl.busy());
          break;
        }
        if (twin.out_valid() && ready) {
          const pins::RguRay a = twin.out(), b = rtl.out();
          bool same = a.pixel == b.pixel;
          for (int i = 0; i < 3; ++i)
            same = same && a.o[i] == b.o[i] && a.d[i] == b.d[i] && a.inv[i] == b.inv[i];
          if (!same) {
            res.failure = where.str() + "ray differs: twin pixel " + std::to_string(a.pixel) +
                          " d " + hex(a.d[0]) + " " + hex(a.d[1]) + " " + hex(a.d[2]) +
                          ", rtl pixel " + std::to_string(b.pixel) + " d " + hex(b.d[0]) + " " +
                          hex(b.d[1]) + " " + hex(b.d[2]);
            break;
          }
          ++got;
        }
        if (twin.out_valid() && !ready) ++res.stalled_out;
        if (!twin.busy() && c > 0) break;
        clk.edge();
        if (c > 100000) {
          res.failure = where.str() + "busy_o still high";
          break;
        }
      }
      if (res.failure.empty() && got != expect)
        res.failure = "frame " + std::to_string(k) + ": " + std::to_string(got) + " rays, " +
                      "hls::RguTiles has " + std::to_string(expect);
      res.received += got;
    }
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    sc_core::sc_stop();
  });
  sc_core::sc_start();
  report(name, res, res.received);
  EXPECT_GT(res.received, 20000u) << name;
}

TEST(Lockstep, RguFp24Rtz) {
  rgu_lockstep<hls::Arith<hls::FP24, Rounding::rtz>, Vrgu_fp24_rtz_s2_sc>("rgu_fp24_rtz_s2");
}
TEST(Lockstep, RguFp24Rne) {
  rgu_lockstep<hls::Arith<hls::FP24, Rounding::rne>, Vrgu_fp24_rne_s2_sc>("rgu_fp24_rne_s2");
}
TEST(Lockstep, RguFp24Raycore) {
  rgu_lockstep<hls::Arith<hls::FP24, Rounding::raycore>, Vrgu_fp24_raycore_s2_sc>(
      "rgu_fp24_raycore_s2");
}
TEST(Lockstep, VtuFp24Rtz) {
  vtu_lockstep<hls::FP24, Rounding::rtz, Vvtu_fp24_rtz_s2_sc>("vtu_fp24_rtz_s2");
}
TEST(Lockstep, VtuFp24Rne) {
  vtu_lockstep<hls::FP24, Rounding::rne, Vvtu_fp24_rne_s2_sc>("vtu_fp24_rne_s2");
}
TEST(Lockstep, IstFp24Rtz) {
  ist_lockstep<hls::Arith<hls::FP24, Rounding::rtz>, Vist_fp24_rtz_s2_sc>("ist_fp24_rtz_s2");
}
TEST(Lockstep, IstFp24Rne) {
  ist_lockstep<hls::Arith<hls::FP24, Rounding::rne>, Vist_fp24_rne_s2_sc>("ist_fp24_rne_s2");
}
TEST(Lockstep, VtuFp24Raycore) {
  vtu_lockstep<hls::FP24, Rounding::raycore, Vvtu_fp24_raycore_s2_sc>("vtu_fp24_raycore_s2");
}
TEST(Lockstep, IstFp24Raycore) {
  ist_lockstep<hls::Arith<hls::FP24, Rounding::raycore>, Vist_fp24_raycore_s2_sc>(
      "ist_fp24_raycore_s2");
}

#endif  // RAYCORE_TEST_RTL

}  // namespace

extern "C" int sc_main(int argc, char* argv[]) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
