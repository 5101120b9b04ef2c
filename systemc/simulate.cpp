// systemc/simulate.cpp - set-up of a frame on the cycle model, and its report (see simulate.h).
#include "systemc/simulate.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "systemc/rtu_rtl.h"
#include "systemc/timing.h"
#include "systemc/top.h"

namespace raycore::sc {
namespace {

double user_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec);
}

template <class A>
SimResult run(const hls::Image& image, const scenes::Camera& cam, const scenes::Light& light,
              const hls::TraceConfig& tc, const SimConfig& cfg) {
  using F = typename A::Fmt;
  constexpr hls::Rounding R = A::rounding;
  const auto w0 = std::chrono::steady_clock::now();
  const double u0 = user_cpu_seconds();
  if (image.vtu_applied()) throw std::invalid_argument("simulate: the image is already VTU-translated");
  if (image.ist_kind() != tc.ist)
    throw std::invalid_argument(std::string("simulate: the image holds ") + hls::ist_kind_name(image.ist_kind()) +
                                " triangle records, the configuration asks for " + hls::ist_kind_name(tc.ist));
  if (tc.ist != hls::IstKind::wald)
    for (const auto& [view, unit] : {std::pair{cfg.vtu_view, "vtu"}, {cfg.ascache_view, "ascache"},
                                     {cfg.ist_view, "ist"}, {cfg.rtu_view, "rtu"}})
      if (view != UnitView::model && !(view == UnitView::rtl && std::string(unit) == "ist"))
        throw ConfigError(std::string("--ist watertight is in the golden tracer, the transaction model and "
                                      "--rtl ist (ist_unit.v with ist_watertight.v): ") +
                          unit + " has no " + (view == UnitView::twin ? "pin-level twin" : "RTL") +
                          " for its records yet (vtu.v, ascache.v and rtu.v are Wald's; use --ist wald "
                          "for --rtl/--pins " + unit + ")");
  SimResult res;
  res.frame.width = tc.width;
  res.frame.height = tc.height;
  res.frame.px.resize(size_t(tc.width) * size_t(tc.height));

  FrameCtx fc;
  fc.width = tc.width;
  fc.height = tc.height;
  fc.header = image.header();
  fc.frame = &res.frame;
  fc.primary_retired.assign(res.frame.px.size(), 0);
  fc.shadow_retired.assign(res.frame.px.size(), 0);
  fc.empty_tree = fc.header.node_count == 0;
  // The host's set-up registers, formed as for the golden tracer (hls::FrameSetup).
  const auto setup = hls::FrameSetup<F, R>::make(cam.position, light.position, tc.vtu, tc.anchor);
  const hls::Vtu<F, R>& vtu = setup.vtu;
  image.box(fc.box_lo, fc.box_hi);
  fc.vtu_on = tc.vtu;
  for (int i = 0; i < 3; ++i) {
    fc.box_stored_lo[i] = fc.box_lo[i];
    fc.box_stored_hi[i] = fc.box_hi[i];
    fc.light_stored[i] = setup.light_stored[i];  // relative to the anchor, as the image
  }
  if (tc.vtu) vtu.box_outward(fc.box_lo, fc.box_hi);  // as transform_image translates the box
  for (int i = 0; i < 3; ++i) {
    fc.light[i] = setup.light[i];
    fc.offset[i] = setup.offset[i];
  }
  fc.rgu_cam = hls::rgu_camera<A>(setup.origin, cam.forward, cam.right, cam.up, cam.yfov, tc.width,
                                  tc.height);
  fc.tmin = A::from_double(tc.tmin);
  fc.spawn = hls::resolved_spawn(tc);
  fc.margins = hls::frame_margins<A>(tc);
  if (cfg.stack_depth < 1 || cfg.stack_depth > uint32_t(kStackDepth))
    throw std::invalid_argument("stack depth must be 1..64");
  fc.stack_depth = cfg.stack_depth;
  if (cfg.mailbox > 64) throw std::invalid_argument("mailbox must be 0..64 entries");
  fc.mailbox = cfg.mailbox;
  const uint32_t rb = fc.header.tri_bytes;
  fc.tri_line_records = std::max<uint32_t>(1, (cfg.tri_cache.line_bytes + rb / 2) / rb);
  res.tri_line_bytes = fc.tri_line_records * rb;

  if (cfg.rtu_view != UnitView::model) {  // --rtl rtu: every RTU one Verilated rtu.v
    if (cfg.rtu_view == UnitView::twin)
      throw ConfigError("rtu has no pin-level SystemC twin: use --rtl rtu");
    for (UnitView v : {cfg.vtu_view, cfg.ist_view, cfg.trv_view, cfg.ascache_view, cfg.hit_view,
                       cfg.rgu_view, cfg.membus_view})
      if (v != UnitView::model)
        throw ConfigError("--rtl rtu is the whole RTU (every unit and the glue between them) with "
                          "the bus interface in RTL: give no other unit to --rtl or --pins");
    const PixelWrite write = [&fc](uint32_t pixel, bool shadow, const Best& b,
                                   const hls::ShadowSetup& ss, double& cos_light) {
      return write_pixel<A>(fc, pixel, shadow, b, ss, cos_light);
    };
    const RtuRtlRun r = run_rtl_rtus(hls::format_id<F>(), R, fc, cfg, image.bytes, vtu.c,
                                     hit_config<A>(fc), write);
    res.cycles = r.cycles;
    res.rtus = r.rtus;
    res.bus = r.bus;
  } else {
    Top<A> top("top", fc, cfg, image.bytes, tc.vtu, vtu);
    sc_core::sc_start();
    if (!top.error.empty()) throw std::runtime_error(top.error);
    res.cycles = top.cycles;
    res.pin_edges = top.pin_edges;
    for (const auto& r : top.rtus) res.rtus.push_back(r->stats());
    res.bus = top.bus.stats();
  }
  if (cfg.rtus > 0 && fc.retired == 0 && fc.width * fc.height > 0)
    throw std::runtime_error("cycle model: no ray retired");
  for (const RtuStats& s : res.rtus) {
    res.primary_rays += s.primary_rays;
    res.shadow_rays += s.shadow_rays;
  }
  res.issued = fc.issued;
  res.retired = fc.retired;
  res.primary_retired = std::move(fc.primary_retired);
  res.shadow_retired = std::move(fc.shadow_retired);
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  res.user_seconds = user_cpu_seconds() - u0;
  return res;
}

}  // namespace

SimResult simulate(const hls::Image& image, const scenes::Camera& cam, const scenes::Light& light,
                   const hls::TraceConfig& tc, const SimConfig& cfg) {
  if (tc.width <= 0 || tc.height <= 0) throw std::invalid_argument("image size must be positive");
  if (image.format() != tc.format || image.rounding() != tc.rounding)
    throw std::invalid_argument("memory image format/rounding differ from the configuration");
  if (cfg.clock_mhz <= 0) throw std::invalid_argument("clock must be > 0 MHz");
  return hls::visit_format(tc.format, tc.rounding, [&](auto f, auto r) {
    using F = decltype(f);
    constexpr hls::Rounding R = decltype(r)::value;
    return run<hls::Arith<F, R>>(image, cam, light, tc, cfg);
  });
}

std::vector<PixelDiff> diff_frames(const hls::Frame& a, const hls::Frame& b, size_t max_list,
                                   uint64_t* count) {
  std::vector<PixelDiff> out;
  uint64_t n = 0;
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("diff_frames: frames differ in size");
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const auto& p = a.at(x, y);
      const auto& q = b.at(x, y);
      if (p.tri == q.tri && p.t_bits == q.t_bits && p.front == q.front && p.shadow_ray == q.shadow_ray && p.lit == q.lit &&
          p.shadow_tri == q.shadow_tri && p.shade == q.shade)
        continue;
      ++n;
      if (out.size() < max_list) out.push_back({x, y, p, q});
    }
  if (count) *count = n;
  return out;
}

namespace {
double ratio(uint64_t a, uint64_t b) { return b ? double(a) / double(b) : 0.0; }
nlohmann::json cache_json(const CacheStats& c) {
  return {{"accesses", c.accesses}, {"hits", c.hits},          {"misses", c.misses},
          {"hit_rate", ratio(c.hits, c.accesses)}, {"mshr_merges", c.mshr_merges},
          {"mshr_full", c.mshr_full}, {"set_full", c.set_full},  {"fills", c.fills},
          {"cycles_lost", c.cycles_lost}};
}
void add(CacheStats& a, const CacheStats& b) {
  a.accesses += b.accesses;
  a.hits += b.hits;
  a.misses += b.misses;
  a.mshr_merges += b.mshr_merges;
  a.mshr_full += b.mshr_full;
  a.set_full += b.set_full;
  a.fills += b.fills;
  a.cycles_lost += b.cycles_lost;
}
}  // namespace

nlohmann::json hardware_json(const SimResult& r, const SimConfig& cfg) {
  RtuStats t;
  for (const auto& s : r.rtus) {
    t.primary_rays += s.primary_rays;
    t.shadow_rays += s.shadow_rays;
    t.rgu_busy += s.rgu_busy;
    t.rgu_stall_no_slot += s.rgu_stall_no_slot;
    t.trv_busy += s.trv_busy;
    t.trv_node_miss += s.trv_node_miss;
    t.trv_list_miss += s.trv_list_miss;
    t.trv_ist_full += s.trv_ist_full;
    t.inner_steps += s.inner_steps;
    t.leaf_visits += s.leaf_visits;
    t.pops += s.pops;
    t.list_steps += s.list_steps;
    t.trv_fused += s.trv_fused;
    t.mailbox_skips += s.mailbox_skips;
    t.stack_max = std::max(t.stack_max, s.stack_max);
    t.ist_busy += s.ist_busy;
    t.ist_tri_miss += s.ist_tri_miss;
    t.tri_tests += s.tri_tests;
    t.hit_busy += s.hit_busy;
    t.vtu_busy += s.vtu_busy;
    t.vtu_paired += s.vtu_paired;
    t.vtu_fill_waits += s.vtu_fill_waits;
    add(t.node, s.node);
    add(t.list, s.list);
    add(t.tri, s.tri);
  }
  uint64_t rgu_stalled = 0;
  for (const auto& s : r.rtus)
    rgu_stalled += s.rgu_primary_end > s.rgu_busy_primary ? s.rgu_primary_end - s.rgu_busy_primary : 0;
  const double cyc = double(r.cycles);
  const double unit_cycles = cyc * double(r.rtus.size());  // per-unit utilisation: mean over RTUs
  const double rays = double(r.primary_rays + r.shadow_rays);
  const uint64_t trv_slots = r.cycles * uint64_t(r.rtus.size()) * cfg.trv_pipes;
  const uint64_t ist_slots = r.cycles * uint64_t(r.rtus.size()) * cfg.ist_units;
  const uint64_t rtu_cycles = r.cycles * uint64_t(r.rtus.size());
  // Every issue slot of the frame (cycles x RTUs x pipelines, the cycles the simulator skips
  // included) is busy, stalled (a reason below) or idle (nothing to do): the three add up to 1.
  auto share = [](uint64_t busy, uint64_t stalled, uint64_t slots) {
    const double n = slots ? double(slots) : 1.0;
    stalled = std::min(stalled, slots > busy ? slots - busy : 0);
    return nlohmann::json{{"slots", slots},
                          {"busy", double(busy) / n},
                          {"stalled", double(stalled) / n},
                          {"idle", double(slots - std::min(slots, busy + stalled)) / n}};
  };
  const nlohmann::json breakdown = {
      {"rgu", share(t.rgu_busy, rgu_stalled, rtu_cycles)},
      {"trv", share(t.trv_busy, t.trv_node_miss + t.trv_list_miss + t.trv_ist_full, trv_slots)},
      {"ist", share(t.ist_busy, t.ist_tri_miss, ist_slots)},
      {"hit", share(t.hit_busy, 0, rtu_cycles)},
      {"vtu", share(t.vtu_busy, 0, rtu_cycles)},
      {"membus", share(r.bus.busy_cycles, 0, r.cycles)},
      {"l2_bus", share(r.bus.l2_busy_cycles, 0, r.cycles)}};
  const uint64_t trv_used = t.trv_busy + t.trv_node_miss + t.trv_list_miss + t.trv_ist_full;
  const uint64_t trv_empty = trv_slots > trv_used ? trv_slots - trv_used : 0;
  nlohmann::json per_rtu = nlohmann::json::array();
  for (const auto& s : r.rtus)
    per_rtu.push_back({{"rays", s.primary_rays + s.shadow_rays},
                       {"trv", cyc ? double(s.trv_busy) / (cyc * cfg.trv_pipes) : 0.0},
                       {"ist", cyc ? double(s.ist_busy) / (cyc * cfg.ist_units) : 0.0}});
  return {
      {"cycles", r.cycles},
      {"clock_mhz", cfg.clock_mhz},
      {"clock", clock_json(cfg)},
      {"rtus", r.rtus.size()},
      {"rays_per_cycle", cyc ? rays / cyc : 0.0},
      {"rays_per_cycle_per_rtu", unit_cycles ? rays / unit_cycles : 0.0},
      {"mrays_per_s", cyc ? rays / cyc * cfg.clock_mhz : 0.0},
      {"work", {{"inner_steps", t.inner_steps}, {"leaf_visits", t.leaf_visits}, {"pops", t.pops},
                {"tri_tests", t.tri_tests}, {"trv_steps", t.trv_busy}, {"list_steps", t.list_steps},
                {"trv_fused", t.trv_fused}, {"stack_max", t.stack_max}, {"mailbox_skips", t.mailbox_skips}}},
      {"per_ray",
       {{"trv_steps", rays > 0 ? double(t.trv_busy) / rays : 0.0},
        {"inner_steps", rays > 0 ? double(t.inner_steps) / rays : 0.0},
        {"tri_tests", rays > 0 ? double(t.tri_tests) / rays : 0.0},
        {"bus_bytes", rays > 0 ? double(r.bus.bytes) / rays : 0.0}}},
      {"utilisation",
       {{"rgu", unit_cycles ? double(t.rgu_busy) / unit_cycles : 0.0},
        {"trv", trv_slots ? double(t.trv_busy) / double(trv_slots) : 0.0},
        {"ist", ist_slots ? double(t.ist_busy) / double(ist_slots) : 0.0},
        {"hit", unit_cycles ? double(t.hit_busy) / unit_cycles : 0.0},
        {"vtu", unit_cycles ? double(t.vtu_busy) / unit_cycles : 0.0},
        {"membus", cyc ? double(r.bus.busy_cycles) / cyc : 0.0},
        {"per_rtu", per_rtu},
        {"breakdown", breakdown}}},
      {"caches", {{"node", cache_json(t.node)}, {"list", cache_json(t.list)}, {"tri", cache_json(t.tri)}}},
      {"bus",
       {{"requests", r.bus.requests},
        {"bytes", r.bus.bytes},
        {"busy_cycles", r.bus.busy_cycles},
        {"bandwidth_gb_s", cyc ? double(r.bus.bytes) / cyc * cfg.clock_mhz * 1e-3 : 0.0},
        {"peak_gb_s", double(cfg.mem_bandwidth) * cfg.clock_mhz * 1e-3},
        {"mean_latency_cycles", ratio(r.bus.latency_sum, r.bus.requests)}}},
      {"l2",
       {{"size_kb", cfg.l2.size_bytes / 1024.0},
        {"accesses", r.bus.l2_accesses},
        {"hits", r.bus.l2_hits},
        {"merges", r.bus.l2_merges},
        {"stall_cycles", r.bus.l2_stall_cycles},
        {"hit_rate", ratio(r.bus.l2_hits + r.bus.l2_merges, r.bus.l2_accesses)},
        {"bytes", r.bus.l2_bytes},
        {"bandwidth_gb_s", cyc ? double(r.bus.l2_bytes) / cyc * cfg.clock_mhz * 1e-3 : 0.0},
        {"busy", cyc ? double(r.bus.l2_busy_cycles) / cyc : 0.0}}},
      {"stalls",
       {{"trv_node_miss", t.trv_node_miss},
        {"trv_list_miss", t.trv_list_miss},
        {"trv_ist_queue_full", t.trv_ist_full},
        {"ist_tri_miss", t.ist_tri_miss},
        {"rgu_no_free_slot", t.rgu_stall_no_slot},
        {"membus_queue_full", r.bus.queue_full_cycles},
        // Lines of one cache from the memory and the L2 in one cycle: the second waits for the
        // cache's fill port (lines x cycles waited); cycles with two lines at one RTU.
        {"vtu_fill_port_waits", t.vtu_fill_waits},
        {"vtu_two_lines_cycles", t.vtu_paired},
        // Every trv issue slot of the frame (cycles x RTUs, including the cycles the simulator
        // skips because nothing can happen) is a step, a slot lost above, or empty: no ray ready.
        {"trv_no_ray_ready", trv_empty}}}};
}

nlohmann::json sim_json(const SimResult& r) {
  const double rays = double(r.primary_rays + r.shadow_rays);
  return {{"wall_seconds", r.wall_seconds},
          {"user_cpu_seconds", r.user_seconds},
          {"cycles_per_second", r.wall_seconds > 0 ? double(r.cycles) / r.wall_seconds : 0.0},
          {"rays_per_second", r.wall_seconds > 0 ? rays / r.wall_seconds : 0.0},
          {"pin_clock_edges", r.pin_edges}};
}

const char* unit_view_name(UnitView v) {
  switch (v) {
    case UnitView::twin: return "twin";
    case UnitView::rtl: return "rtl";
    default: return "model";
  }
}

nlohmann::json config_json(const SimConfig& c) {
  auto cache = [](const CacheConfig& k) {
    return nlohmann::json{{"size_kb", k.size_bytes / 1024.0}, {"ways", k.ways}, {"line_bytes", k.line_bytes},
                          {"mshrs", k.mshrs}, {"hit_latency", k.hit_latency}};
  };
  return {{"rtus", c.rtus},
          {"clock_mhz", c.clock_mhz},
          {"mem_latency", c.mem_latency},
          {"mem_bandwidth", c.mem_bandwidth},
          {"mem_queue_depth", c.mem_queue_depth},
          {"seed", c.seed},
          {"vtu_depth", c.vtu_depth},
          {"vtu_view", unit_view_name(c.vtu_view)},
          {"node_cache", cache(c.node_cache)},
          {"list_cache", cache(c.list_cache)},
          {"tri_cache", cache(c.tri_cache)},
          {"l2", {{"size_kb", c.l2.size_bytes / 1024.0}, {"ways", c.l2.ways}, {"line_bytes", c.l2.line_bytes},
                  {"latency", c.l2.latency}, {"bandwidth", c.l2.bandwidth}}},
          {"rays_in_flight", c.rays_in_flight},
          {"stack_depth", c.stack_depth},
          {"trv_latency", c.trv_latency},
          {"trv_pipes", c.trv_pipes},
          {"trv_fuse", c.trv_fuse},
          {"mailbox", c.mailbox},
          {"ist_units", c.ist_units},
          {"ist_latency", c.ist_latency},
          {"ist_view", unit_view_name(c.ist_view)},
          {"trv_view", unit_view_name(c.trv_view)},
          {"ascache_view", unit_view_name(c.ascache_view)},
          {"membus_view", unit_view_name(c.membus_view)},
          {"ist_queue", c.ist_queue},
          {"hit_latency", c.hit_latency},
          {"hit_view", unit_view_name(c.hit_view)},
          {"tile", c.tile},
          {"rgu_latency", c.rgu_latency},
          {"rgu_view", unit_view_name(c.rgu_view)},
          {"rtu_view", unit_view_name(c.rtu_view)}};
}

void config_from_json(const nlohmann::json& j, SimConfig& c) {
  if (!j.is_object()) throw std::runtime_error("config: expected a JSON object");
  auto num = [](const nlohmann::json& v, const std::string& key) {
    if (!v.is_number()) throw std::runtime_error("config: '" + key + "' must be a number");
    const double d = v.get<double>();
    if (!(d >= 0) || d > 4e9) throw std::runtime_error("config: '" + key + "' out of range");
    return d;
  };
  auto u32 = [&](const nlohmann::json& v, const std::string& key) { return uint32_t(num(v, key)); };
  auto unit_view = [](const nlohmann::json& v, const std::string& key) {
    if (v.is_string()) {
      const std::string s = v.get<std::string>();
      for (UnitView u : {UnitView::model, UnitView::twin, UnitView::rtl})
        if (s == unit_view_name(u)) return u;
    }
    throw std::runtime_error("config: '" + key + "' must be \"model\", \"twin\" or \"rtl\"");
  };
  auto cache = [&](const nlohmann::json& v, const std::string& key, CacheConfig& k) {
    if (!v.is_object()) throw std::runtime_error("config: '" + key + "' must be an object");
    for (auto it = v.begin(); it != v.end(); ++it) {
      const std::string n = key + "." + it.key();
      if (it.key() == "size_kb") k.size_bytes = uint32_t(num(*it, n) * 1024);
      else if (it.key() == "ways") k.ways = u32(*it, n);
      else if (it.key() == "line_bytes") k.line_bytes = u32(*it, n);
      else if (it.key() == "mshrs") k.mshrs = u32(*it, n);
      else if (it.key() == "hit_latency") k.hit_latency = u32(*it, n);
      else throw std::runtime_error("config: unknown key '" + n + "'");
    }
  };
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    if (k == "rtus") c.rtus = int(u32(*it, k));
    else if (k == "clock_mhz") c.clock_mhz = num(*it, k), c.clock_source = "option";
    else if (k == "mem_latency") c.mem_latency = u32(*it, k);
    else if (k == "mem_bandwidth") c.mem_bandwidth = u32(*it, k);
    else if (k == "mem_queue_depth") c.mem_queue_depth = u32(*it, k);
    else if (k == "seed") c.seed = uint64_t(num(*it, k));
    else if (k == "vtu_depth") c.vtu_depth = u32(*it, k);
    else if (k == "node_cache") cache(*it, k, c.node_cache);
    else if (k == "list_cache") cache(*it, k, c.list_cache);
    else if (k == "tri_cache") cache(*it, k, c.tri_cache);
    else if (k == "l2") {
      if (!it->is_object()) throw std::runtime_error("config: 'l2' must be an object");
      for (auto x = it->begin(); x != it->end(); ++x) {
        const std::string n = "l2." + x.key();
        if (x.key() == "size_kb") c.l2.size_bytes = uint32_t(num(*x, n) * 1024);
        else if (x.key() == "ways") c.l2.ways = u32(*x, n);
        else if (x.key() == "line_bytes") c.l2.line_bytes = u32(*x, n);
        else if (x.key() == "latency") c.l2.latency = u32(*x, n);
        else if (x.key() == "bandwidth") c.l2.bandwidth = u32(*x, n);
        else throw std::runtime_error("config: unknown key '" + n + "'");
      }
    }
    else if (k == "rays_in_flight") c.rays_in_flight = u32(*it, k);
    else if (k == "stack_depth") c.stack_depth = u32(*it, k);
    else if (k == "trv_latency") c.trv_latency = u32(*it, k);
    else if (k == "trv_pipes") c.trv_pipes = u32(*it, k);
    else if (k == "mailbox") c.mailbox = u32(*it, k);
    else if (k == "trv_fuse") {
      if (!it->is_boolean()) throw std::runtime_error("config: 'trv_fuse' must be true or false");
      c.trv_fuse = it->get<bool>();
    }
    else if (k == "ist_units") c.ist_units = u32(*it, k);
    else if (k == "ist_latency") c.ist_latency = u32(*it, k);
    else if (k == "ist_queue") c.ist_queue = u32(*it, k);
    else if (k == "hit_latency") c.hit_latency = u32(*it, k);
    else if (k == "tile") c.tile = u32(*it, k);
    else if (k == "rgu_latency") c.rgu_latency = u32(*it, k);
    else if (k == "rgu_view") c.rgu_view = unit_view(*it, k);
    else if (k == "rtu_view") c.rtu_view = unit_view(*it, k);
    else if (k == "vtu_view") c.vtu_view = unit_view(*it, k);
    else if (k == "ist_view") c.ist_view = unit_view(*it, k);
    else if (k == "trv_view") c.trv_view = unit_view(*it, k);
    else if (k == "ascache_view") c.ascache_view = unit_view(*it, k);
    else if (k == "membus_view") c.membus_view = unit_view(*it, k);
    else if (k == "hit_view") c.hit_view = unit_view(*it, k);
    else throw std::runtime_error("config: unknown key '" + k + "'");
  }
}

}  // namespace raycore::sc
