// tb/systemc/random_config.h - one seeded draw of a cycle-model configuration (scene, frame,
// number format, spawn, store, and every register of systemc/config.h SimConfig), shared by the
// randomised-configuration tests (tb/systemc/test_random_config.cpp: the transaction model against
// the golden tracer; and, built with RAYCORE_TEST_RTL, the unit views against the model).
// Configuration i of seed S is the same on every machine; Drawn::line rebuilds it.
#pragma once

#include <cmath>
#include <cstdlib>
#include <algorithm>
#include <map>
#include <random>
#include <sstream>
#include <string>

#include "scenes/generate.h"
#include "tb/systemc/frame_check.h"

namespace raycore::tb {

inline uint64_t env_u64(const char* name, uint64_t def) {
  const char* e = std::getenv(name);
  return e && *e ? std::strtoull(e, nullptr, 10) : def;
}

inline const scenes::Scene& scene_by_index(int i) {
  static const char* names[] = {"corridor", "far", "grazing", "slivers", "coplanar", "origin-far-camera"};
  static std::map<int, scenes::Scene> cache;
  if (!cache.count(i)) cache[i] = i == 6 ? tiny_scene() : scenes::generate(names[i]);
  return cache[i];
}

struct Drawn {
  int scene = 0;
  sim::TraceConfig tc;
  sc::SimConfig cfg;
  std::string line;  // what was drawn, for the failure message
};

// What a drawn configuration is, in one line (the failure message prints it).
inline std::string describe(const Drawn& d) {
  const sc::SimConfig& c = d.cfg;
  std::ostringstream os;
  os << "scene " << scene_by_index(d.scene).name << " " << d.tc.width << "x" << d.tc.height << " "
     << hls::format_name(d.tc.format) << "-" << hls::rounding_name(d.tc.rounding) << (d.tc.vtu ? " vtu" : " novtu") << " spawn "
     << sim::to_string(d.tc.spawn.spawn) << (d.tc.spawn.segment ? " segment" : " unit")
     << (d.tc.spawn.any_hit ? " any-hit" : " closest-hit") << (d.tc.spawn.spawn_all ? " spawn-all" : "")
     << (d.tc.anchored ? " anchored" : "") << " margin " << d.tc.bary_margin << " widen "
     << d.tc.trv_widen << " | rtus " << c.rtus << " mem " << c.mem_latency
     << "/" << c.mem_bandwidth << "B/q" << c.mem_queue_depth << " seed " << c.seed << " caches "
     << c.node_cache.size_bytes << "/" << c.node_cache.ways << "w/" << c.node_cache.line_bytes << "B/"
     << c.node_cache.mshrs << "m/" << c.node_cache.hit_latency << " " << c.list_cache.size_bytes << "/"
     << c.list_cache.ways << "w/" << c.list_cache.line_bytes << "B/" << c.list_cache.mshrs << "m/"
     << c.list_cache.hit_latency << " " << c.tri_cache.size_bytes << "/" << c.tri_cache.ways << "w/"
     << c.tri_cache.line_bytes << "B/" << c.tri_cache.mshrs << "m/" << c.tri_cache.hit_latency << " l2 "
     << c.l2.size_bytes << "/" << c.l2.ways << "w/" << c.l2.line_bytes << "B/" << c.l2.latency << "c/"
     << c.l2.bandwidth << "B | rays " << c.rays_in_flight << " stack " << c.stack_depth << " vtu "
     << c.vtu_depth << " trv " << c.trv_latency << "x" << c.trv_pipes << (c.trv_fuse ? " fuse" : "")
     << " mailbox " << c.mailbox << " ist " << c.ist_latency << "x" << c.ist_units << " q" << c.ist_queue << " hit " << c.hit_latency
     << " tile " << c.tile << " rgu " << c.rgu_latency;
  const std::pair<const char*, sc::UnitView> views[] = {
      {"vtu", c.vtu_view}, {"ist", c.ist_view},         {"trv", c.trv_view},       {"ascache", c.ascache_view},
      {"hit", c.hit_view}, {"rgu", c.rgu_view},         {"membus", c.membus_view}, {"rtu", c.rtu_view}};
  std::string pins, rtl;
  for (const auto& [name, v] : views) {
    if (v == sc::UnitView::twin) pins += (pins.empty() ? "" : ",") + std::string(name);
    if (v == sc::UnitView::rtl) rtl += (rtl.empty() ? "" : ",") + std::string(name);
  }
  if (!pins.empty()) os << " | --pins " << pins;
  if (!rtl.empty()) os << " | --rtl " << rtl;
  return os.str();
}

inline Drawn draw(uint64_t seed, uint64_t index) {
  std::mt19937_64 g(seed * 0x9E3779B97F4A7C15ull + index);
  auto pick = [&](uint64_t lo, uint64_t hi) { return lo + g() % (hi - lo + 1); };
  auto pow2 = [&](int lo, int hi) { return uint32_t(1) << pick(uint64_t(lo), uint64_t(hi)); };
  Drawn d;
  d.scene = int(pick(0, 6));
  const FormatId f = pick(0, 2) ? FormatId::fp24 : FormatId::fp32;
  Rounding r = pick(0, 1) ? Rounding::rtz : Rounding::rne;
  // Every third fp24 rtz draw runs RayCore's arithmetic instead (by index: the random stream,
  // and so every other draw, stays as it was).
  if (f == FormatId::fp24 && r == Rounding::rtz && index % 3 == 2) r = Rounding::raycore;
  d.tc = config(f, r, pick(0, 1) == 1, int(pick(8, 40)), int(pick(6, 28)));
  const hls::Spawn spawns[] = {hls::Spawn::none,        hls::Spawn::skip_origin, hls::Spawn::ulp_offset,
                               hls::Spawn::error_bound, hls::Spawn::skip_offset, hls::Spawn::skip_slab,
                               hls::Spawn::skip_back};
  d.tc.spawn.spawn = spawns[pick(0, 6)];
  d.tc.spawn.ulps = sim::default_spawn_ulps(f, d.tc.spawn.spawn);
  d.tc.spawn.segment = pick(0, 3) == 0;
  d.tc.spawn.any_hit = pick(0, 1) == 1;
  sc::SimConfig& c = d.cfg;
  c.rtus = int(pick(1, 8));
  c.mem_latency = uint32_t(pick(0, 3) == 0 ? pick(1, 8) : pick(20, 300));
  c.mem_bandwidth = uint32_t(pick(1, 64));
  c.mem_queue_depth = uint32_t(pick(1, 48));
  c.seed = pick(0, 1) ? pick(1, 1000000) : 0;
  auto cache = [&](sc::CacheConfig& k) {
    k.line_bytes = pow2(5, 7);
    k.ways = pow2(0, 3);
    const uint32_t sets = pow2(1, 6);
    k.size_bytes = sets * k.ways * k.line_bytes;
    k.mshrs = uint32_t(pick(1, 12));
    k.hit_latency = uint32_t(pick(1, 3));
  };
  cache(c.node_cache);
  cache(c.list_cache);
  cache(c.tri_cache);
  if (pick(0, 1)) {
    c.l2.line_bytes = pow2(6, 7);
    c.l2.ways = pow2(0, 4);
    c.l2.size_bytes = pow2(2, 8) * c.l2.ways * c.l2.line_bytes;
    c.l2.latency = uint32_t(pick(1, 40));
    c.l2.bandwidth = uint32_t(pick(4, 64));
  }
  c.rays_in_flight = uint32_t(pick(0, 3) == 0 ? pick(1, 8) : pick(9, 160));
  c.stack_depth = uint32_t(pick(0, 7) == 0 ? pick(1, 12) : pick(13, 64));
  c.vtu_depth = uint32_t(pick(0, 12));
  c.trv_latency = uint32_t(pick(1, 8));
  c.trv_pipes = uint32_t(pick(1, 6));
  c.trv_fuse = pick(0, 1) == 1;
  c.ist_units = uint32_t(pick(1, 4));
  c.mailbox = pick(0, 1) ? uint32_t(pick(1, 16)) : 0;
  c.ist_latency = uint32_t(pick(1, 40));
  c.ist_queue = uint32_t(pick(1, 64));
  c.hit_latency = uint32_t(pick(1, 30));
  c.tile = uint32_t(pick(1, 16));
  // Drawn last: the earlier draws of a seed stay as they were.
  d.tc.spawn.spawn_all = pick(0, 2) == 0;
  d.tc.anchored = pick(0, 3) == 0;
  d.tc.anchor = d.tc.anchored ? hls::store_anchor(scene_by_index(d.scene).tris) : hls::Vec3{};
  // The watertightness margins, drawn after every earlier pick (hls/margins.h).
  const double margins[] = {0.0, 0.008, std::ldexp(1.0, -12), 0.03};
  d.tc.bary_margin = pick(0, 1) == 0 ? 0.0 : margins[pick(0, 3)];
  d.tc.trv_widen = pick(0, 1) == 0 ? 0 : int32_t(pick(0, 8));
  c.rgu_latency = uint32_t(pick(0, 40));  // the rgu's datapath latency (start-up)
  // Small caches under pressure (forward progress, issue 26 part 4), drawn after every earlier
  // pick: the caches above are 64 B .. 64 KB already (each at most 1 KB in 42% of the draws); in
  // 3 of 8 configurations one of them (node, list, triangle) is further cut to its two smallest
  // sets of one way (2 lines), whatever the rays in flight. This changed the caches of those
  // configurations from the draws before (every other dimension stays as it was).
  const uint64_t tight = pick(0, 7);
  if (tight < 3) {
    sc::CacheConfig& k = tight == 0 ? c.node_cache : tight == 1 ? c.list_cache : c.tri_cache;
    k.ways = 1;
    k.size_bytes = 2 * k.line_bytes;
  }
  d.line = describe(d);
  return d;
}

// The unit views of configuration `index` (the randomised-view test): draw(seed, index), then,
// from a stream of its own (the configuration's other draws stay as they were), a view for each
// unit: the transaction model, its SystemC twin at pin level (--pins: vtu, ist, hit, rgu) or its
// Verilated RTL (--rtl: vtu, ist, trv, ascache, hit, rgu, membus; or the whole RTU alone, --rtl
// rtu). A unit given a view then has, with probability 15/16 each, the dimensions that view is
// built for set to one it is built for (the format and rounding of the
// built RTL, the model's pipeline depths, the cache geometries, no L2 for the bus in RTL, ...):
// so most configurations run, and the rest keep dimensions drawn at random, which a view must
// either run exactly or refuse with sc::ConfigError's message.
inline Drawn draw_views(uint64_t seed, uint64_t index) {
  Drawn d = draw(seed, index);
  std::mt19937_64 g((seed * 0x9E3779B97F4A7C15ull + index) ^ 0xD1B54A32D192ED03ull);
  auto pick = [&](uint64_t lo, uint64_t hi) { return lo + g() % (hi - lo + 1); };
  auto snap = [&] { return pick(0, 15) != 0; };  // 15 in 16: a dimension the view is built for
  using sc::UnitView;
  sc::SimConfig& c = d.cfg;
  const sc::SimConfig def;
  auto view = [&](bool twin) {  // model 1/3, twin / rtl the rest
    const uint64_t v = pick(0, 5);
    if (v < 2) return UnitView::model;
    return twin && v < 4 ? UnitView::twin : UnitView::rtl;
  };
  if (pick(0, 5) == 0) {
    c.rtu_view = UnitView::rtl;
  } else {
    c.vtu_view = view(true);
    c.ist_view = view(true);
    c.hit_view = view(true);
    c.rgu_view = view(true);
    c.trv_view = view(false);
    c.ascache_view = view(false);
    c.membus_view = view(false);
  }
  const bool rtu = c.rtu_view == UnitView::rtl;
  // The model's own stops are RandomConfig's to count: here a stack deep enough, mostly.
  if (snap()) c.stack_depth = std::max<uint32_t>(c.stack_depth, 16);
  auto is_rtl = [&](UnitView v) { return v == UnitView::rtl || rtu; };
  const bool some_rtl = rtu || is_rtl(c.vtu_view) || is_rtl(c.ist_view) || is_rtl(c.hit_view) ||
                        is_rtl(c.rgu_view) || is_rtl(c.trv_view) || is_rtl(c.ascache_view) ||
                        is_rtl(c.membus_view);
  // The formats and roundings the RTL is built for: FP24 rtz, rne, raycore and FP32 rne
  // (rtl/units/*.cmake); the whole RTU FP24 rtz.
  if (some_rtl && snap()) {
    if (rtu) {
      d.tc.format = FormatId::fp24;
      d.tc.rounding = Rounding::rtz;
    } else if (d.tc.format == FormatId::fp32) {
      d.tc.rounding = Rounding::rne;
    } else if (d.tc.rounding == Rounding::raycore && is_rtl(c.trv_view)) {
      d.tc.rounding = Rounding::rtz;  // trv_unit has no raycore build (no arithmetic of its own)
    }
    d.tc.spawn.ulps = sim::default_spawn_ulps(d.tc.format, d.tc.spawn.spawn);
  }
  // Pipeline depths: the model's defaults (STAGES 2) for the RTL; a twin takes any multiple of its
  // operator levels (systemc/config.h kVtuLevels .. kRguLevels per STAGES).
  auto depth = [&](UnitView v, uint32_t& latency, uint32_t levels, uint32_t dflt) {
    if (v == UnitView::model || !snap()) return;
    latency = is_rtl(v) ? dflt : levels * uint32_t(pick(1, 3));
  };
  depth(rtu ? UnitView::rtl : c.vtu_view, c.vtu_depth, sc::kVtuLevels, def.vtu_depth);
  depth(rtu ? UnitView::rtl : c.ist_view, c.ist_latency, sc::kIstLevels, def.ist_latency);
  depth(rtu ? UnitView::rtl : c.hit_view, c.hit_latency, sc::kHitLevels, def.hit_latency);
  depth(rtu ? UnitView::rtl : c.rgu_view, c.rgu_latency, sc::kRguLevels, def.rgu_latency);
  if ((c.rgu_view != UnitView::model || rtu) && snap())
    c.tile = is_rtl(c.rgu_view) ? def.tile : uint32_t(1) << pick(1, 4);  // the rgu walks 2^k tiles
  // The trv and ist in RTL: no mailbox, at most the built pipes, ist units and ray slots.
  if ((is_rtl(c.trv_view) || is_rtl(c.ist_view)) && snap()) c.mailbox = 0;
  if ((is_rtl(c.trv_view) || is_rtl(c.hit_view) || is_rtl(c.rgu_view)) && snap()) {
    c.trv_pipes = std::min(c.trv_pipes, def.trv_pipes);
    c.ist_units = std::min(c.ist_units, def.ist_units);
    c.rays_in_flight = std::min<uint32_t>(c.rays_in_flight, 128);
  }
  if (is_rtl(c.trv_view) && snap()) c.list_cache.line_bytes = std::min<uint32_t>(c.list_cache.line_bytes, 64);
  if (is_rtl(c.ist_view) && snap()) c.tri_cache.line_bytes = def.tri_cache.line_bytes;  // its records per line
  // The caches in RTL: the geometries built (the model's default caches).
  if (is_rtl(c.ascache_view) && snap()) {
    c.node_cache = def.node_cache;
    c.list_cache = def.list_cache;
    c.tri_cache = def.tri_cache;
  }
  // The bus interface in RTL: no L2, the built queue and beat, a first beat a cycle later at least.
  if (is_rtl(c.membus_view) && snap()) {
    c.l2.size_bytes = 0;
    c.mem_queue_depth = def.mem_queue_depth;
    c.mem_bandwidth = def.mem_bandwidth;
    c.mem_latency = std::max<uint32_t>(c.mem_latency, 1);
  }
  // The whole RTU: its built structure (caches, slots, pipes, queue, tile, no mailbox, no L2).
  if (rtu && snap()) {
    c.node_cache = def.node_cache;
    c.list_cache = def.list_cache;
    c.tri_cache = def.tri_cache;
    c.tri_cache.hit_latency = uint32_t(pick(0, 5));
    c.rays_in_flight = std::min<uint32_t>(c.rays_in_flight, 128);
    c.trv_pipes = std::min(c.trv_pipes, def.trv_pipes);
    c.ist_units = std::min(c.ist_units, def.ist_units);
    c.ist_queue = std::min<uint32_t>(c.ist_queue, 32);
    c.mailbox = 0;
    c.l2.size_bytes = 0;
    c.rtus = std::min(c.rtus, 4);  // a Verilated rtu.v per RTU: fewer, for the run's time
  }
  d.line = describe(d);
  return d;
}

}  // namespace raycore::tb
