// tb/systemc/frame_check.h - runs the cycle model on a small frame in a forked child (SystemC
// allows one elaboration per process) and checks it against the golden tracer: every pixel's tri,
// t bits, shadow decision and shade, every ray retired exactly once. Shared by test_systemc and
// test_pins.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "hls/image.h"
#include "scenes/generate.h"
#include "scenes/scene.h"
#include "sim/golden/golden.h"
#include "systemc/simulate.h"

namespace raycore::tb {

namespace hls = raycore::hls;
namespace sim = raycore::sim;
namespace sc = raycore::sc;
namespace scenes = raycore::scenes;
using hls::FormatId;
using hls::Rounding;
using hls::Vec3;

struct Summary {
  bool ok = false;
  bool refused = false;   // the error is a sc::ConfigError: a configuration the view is not built for
  char error[1024] = {};  // the refusals list every built model
  uint64_t cycles = 0, issued = 0, retired = 0, primary = 0, shadow = 0;
  uint64_t mismatches = 0, bad_retire = 0;  // pixels retired other than exactly once per ray
  uint64_t hash = 0;                        // of every pixel's results
  uint64_t tri_tests = 0, bus_bytes = 0;
  // The bus's L2 (if any) and its queue: accesses, hits, merges, stalled and queue-full cycles.
  uint64_t l2_accesses = 0, l2_hits = 0, l2_merges = 0, l2_stalls = 0, queue_full = 0;
  // The work counters of every RTU summed (stack_max: the largest), in kWorkNames' order.
  static constexpr int kWork = 25;
  uint64_t work[kWork] = {};
  int first_x = -1, first_y = -1;
};
inline constexpr int kWorkSetFull = 22;  // "cache set_full": misses refused by the caches' pin rule
inline constexpr int kWorkVtuPaired = 23;  // cycles with two lines at one RTU (memory and L2)
inline constexpr int kWorkFillWaits = 24;  // lines x cycles waiting for their cache's fill port
inline const char* const kWorkNames[Summary::kWork] = {
    "trv_busy",     "trv_node_miss", "trv_list_miss", "trv_ist_full", "inner_steps",
    "leaf_visits",  "pops",          "list_steps",    "trv_fused",    "stack_max",
    "ist_busy",     "ist_tri_miss",  "hit_busy",      "node.accesses", "list.accesses",
    "tri.accesses", "node.hits",     "list.hits",     "tri.hits",     "cache mshr_merges",
    "cache mshr_full", "cache fills", "cache set_full", "vtu_paired", "vtu_fill_waits"};
inline void sum_work(const sc::RtuStats& u, uint64_t* w) {
  const uint64_t v[Summary::kWork] = {
      u.trv_busy,      u.trv_node_miss, u.trv_list_miss, u.trv_ist_full,   u.inner_steps,
      u.leaf_visits,   u.pops,          u.list_steps,    u.trv_fused,      u.stack_max,
      u.ist_busy,      u.ist_tri_miss,  u.hit_busy,      u.node.accesses,  u.list.accesses,
      u.tri.accesses,  u.node.hits,     u.list.hits,     u.tri.hits,
      u.node.mshr_merges + u.list.mshr_merges + u.tri.mshr_merges,
      u.node.mshr_full + u.list.mshr_full + u.tri.mshr_full,
      u.node.fills + u.list.fills + u.tri.fills,
      u.node.set_full + u.list.set_full + u.tri.set_full,
      u.vtu_paired,    u.vtu_fill_waits};
  for (int i = 0; i < Summary::kWork; ++i) w[i] = i == 9 ? std::max(w[i], v[i]) : w[i] + v[i];
}

inline uint64_t frame_hash(const sim::Frame& f) {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](uint64_t v) {
    h ^= v;
    h *= 1099511628211ull;
  };
  for (const auto& p : f.px) {
    mix(uint64_t(uint32_t(p.tri)));
    mix(p.t_bits);
    mix(uint64_t(p.shadow_ray) | uint64_t(p.lit) << 1 | uint64_t(p.front) << 2 | uint64_t(p.shade) << 8);
    mix(uint64_t(uint32_t(p.shadow_tri)));
  }
  return h;
}

struct Case {
  const scenes::Scene* scene;
  const hls::Image* image;
  sim::TraceConfig tc;
  sc::SimConfig cfg;
};

// Seconds a child may run before it is killed as hung (RAYCORE_CHILD_TIMEOUT, default 600).
inline unsigned child_timeout() {
  const char* e = std::getenv("RAYCORE_CHILD_TIMEOUT");
  const long v = e ? std::strtol(e, nullptr, 10) : 600;
  return v > 0 ? unsigned(v) : 600u;
}

// Runs the cycle model in a child process and compares with `golden` there. A child that runs
// longer than child_timeout() is killed (SIGALRM) and reported as died: a hang fails the test.
inline Summary run_child(const Case& c, const sim::Frame& golden) {
  int fd[2];
  if (pipe(fd) != 0) throw std::runtime_error("pipe");
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    alarm(child_timeout());
    Summary s;
    try {
      const sc::SimResult r = sc::simulate(*c.image, c.scene->camera, c.scene->light, c.tc, c.cfg);
      s.cycles = r.cycles;
      s.issued = r.issued;
      s.retired = r.retired;
      s.primary = r.primary_rays;
      s.shadow = r.shadow_rays;
      s.hash = frame_hash(r.frame);
      s.bus_bytes = r.bus.bytes;
      s.l2_accesses = r.bus.l2_accesses;
      s.l2_hits = r.bus.l2_hits;
      s.l2_merges = r.bus.l2_merges;
      s.l2_stalls = r.bus.l2_stall_cycles;
      s.queue_full = r.bus.queue_full_cycles;
      for (const auto& u : r.rtus) {
        s.tri_tests += u.tri_tests;
        sum_work(u, s.work);
      }
      std::vector<sc::PixelDiff> d = sc::diff_frames(r.frame, golden, 1, &s.mismatches);
      if (!d.empty()) {
        s.first_x = d[0].x;
        s.first_y = d[0].y;
      }
      for (size_t i = 0; i < r.frame.px.size(); ++i)
        if (r.primary_retired[i] != 1 || r.shadow_retired[i] != (r.frame.px[i].shadow_ray ? 1 : 0))
          ++s.bad_retire;
      s.ok = true;
    } catch (const sc::ConfigError& e) {
      s.refused = true;
      std::strncpy(s.error, e.what(), sizeof s.error - 1);
    } catch (const std::exception& e) {
      std::strncpy(s.error, e.what(), sizeof s.error - 1);
    }
    if (write(fd[1], &s, sizeof s) != ssize_t(sizeof s)) _exit(3);
    close(fd[1]);
    _exit(0);
  }
  close(fd[1]);
  Summary s;
  const ssize_t n = read(fd[0], &s, sizeof s);
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (n != ssize_t(sizeof s)) {
    s = Summary{};
    std::snprintf(s.error, sizeof s.error, "child died (status %d%s)", status,
                  WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM ? ": timed out, a hang?" : "");
  }
  return s;
}

inline sim::TraceConfig config(FormatId f, Rounding r, bool vtu, int w, int h) {
  sim::TraceConfig c;
  c.format = f;
  c.rounding = r;
  c.vtu = vtu;
  c.width = w;
  c.height = h;
  c.threads = 1;
  return c;
}

inline const scenes::Scene& corridor() {
  static const scenes::Scene s = scenes::generate("corridor");
  return s;
}

// A floor, a box standing on it and a wall behind: shadows, edges, a light above one side.
inline scenes::Scene tiny_scene() {
  scenes::Scene s;
  s.name = "tiny";
  auto quad = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    s.tris.push_back({a, b, c});
    s.tris.push_back({a, c, d});
  };
  quad({-4, 0, -8}, {4, 0, -8}, {4, 0, 0}, {-4, 0, 0});      // floor
  quad({-4, 0, -8}, {-4, 4, -8}, {4, 4, -8}, {4, 0, -8});    // back wall
  const double x0 = -1, x1 = 0.5, z0 = -5, z1 = -3.5, y1 = 1.5;  // box
  quad({x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1});
  quad({x0, 0, z1}, {x1, 0, z1}, {x1, y1, z1}, {x0, y1, z1});
  quad({x1, 0, z1}, {x1, 0, z0}, {x1, y1, z0}, {x1, y1, z1});
  quad({x0, 0, z0}, {x0, 0, z1}, {x0, y1, z1}, {x0, y1, z0});
  s.camera.present = true;
  s.camera.position = {0.3, 1.7, 2.5};
  s.light.present = true;
  s.light.position = {2.5, 5, -2};
  return s;
}

// Golden tracer in this process, cycle model in a child; asserts golden_match and that every ray
// retired exactly once.
inline Summary expect_match(const scenes::Scene& s, const sim::TraceConfig& tc, sc::SimConfig cfg = {}) {
  static std::map<std::string, hls::Image> images;  // built once per scene, format, policy, record kind
  const std::string key = s.name + hls::format_name(tc.format) + hls::rounding_name(tc.rounding) +
                          (tc.anchored ? "anchored" : "") + hls::ist_kind_name(tc.ist);
  hls::BuildOptions bo;
  bo.ist = tc.ist;
  if (!images.count(key))  // --store anchored: relative to tc.anchor (the caller's store_anchor)
    images[key] = hls::build_image(tc.anchored ? hls::relative_to(s.tris, tc.anchor) : s.tris, tc.format,
                                   tc.rounding, bo);
  const hls::Image& img = images[key];
  const sim::Frame golden = sim::trace_golden(img, s.camera, s.light, tc);
  const Summary r = run_child({&s, &img, tc, cfg}, golden);
  const std::string what = s.name + " " + hls::format_name(tc.format) + "-" + hls::rounding_name(tc.rounding) +
                           (tc.vtu ? "-vtu-" : "-novtu-") + sim::to_string(tc.spawn.spawn) +
                           (tc.spawn.segment ? "-segment" : "") + (tc.spawn.spawn_all ? "-all" : "") +
                           (tc.anchored ? "-anchored" : "") + "-" + hls::ist_kind_name(tc.ist) + " seed " +
                           std::to_string(cfg.seed) +
                           " rtus " + std::to_string(cfg.rtus);
  EXPECT_TRUE(r.ok) << what << ": " << r.error;
  EXPECT_EQ(r.mismatches, 0u) << what << ": first differing pixel (" << r.first_x << ", "
                              << r.first_y << ") (run `raycore compare` for details)";
  EXPECT_EQ(r.bad_retire, 0u) << what;
  EXPECT_EQ(r.issued, r.retired) << what;
  EXPECT_EQ(r.primary, uint64_t(tc.width) * uint64_t(tc.height)) << what;
  EXPECT_GT(r.cycles, 0u) << what;
  return r;
}

// The same frame twice (the transaction model's, then another view's): equal cycles, image, bus
// bytes, tests and every work counter.
inline void expect_same_counts(const Summary& model, const Summary& p, const std::string& what) {
  EXPECT_EQ(p.cycles, model.cycles) << what;
  EXPECT_EQ(p.hash, model.hash) << what;
  EXPECT_EQ(p.bus_bytes, model.bus_bytes) << what;
  EXPECT_EQ(p.l2_accesses, model.l2_accesses) << what;
  EXPECT_EQ(p.l2_hits, model.l2_hits) << what;
  EXPECT_EQ(p.l2_merges, model.l2_merges) << what;
  EXPECT_EQ(p.l2_stalls, model.l2_stalls) << what;
  EXPECT_EQ(p.queue_full, model.queue_full) << what;
  EXPECT_EQ(p.tri_tests, model.tri_tests) << what;
  for (int i = 0; i < Summary::kWork; ++i)
    EXPECT_EQ(p.work[i], model.work[i]) << what << ": " << kWorkNames[i];
}

// The cycle model refuses cfg (in the child) with an error that contains `message`.
inline Summary expect_refused(const scenes::Scene& s, const sim::TraceConfig& tc,
                              const sc::SimConfig& cfg, const std::string& message) {
  hls::BuildOptions bo;
  bo.ist = tc.ist;
  const hls::Image img = hls::build_image(s.tris, tc.format, tc.rounding, bo);
  const sim::Frame golden = sim::trace_golden(img, s.camera, s.light, tc);
  const Summary r = run_child({&s, &img, tc, cfg}, golden);
  EXPECT_FALSE(r.ok) << "expected refusal: " << message;
  EXPECT_NE(std::string(r.error).find(message), std::string::npos) << r.error;
  return r;
}

}  // namespace raycore::tb
