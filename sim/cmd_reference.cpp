// `raycore reference SCENE`: the double-precision reference frame of a scene (timing and counts),
// optionally cross-checked against Embree (--embree-check) and written as JSON (--report).
//   raycore reference ../shared/scenes/sponza-paper.glb --width 800 --height 480 --embree-check
// Compiled only where sim/reference (raycore_reference) is linked.
#if defined(RAYCORE_HAVE_REFERENCE)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "scenes/options.h"
#include "sim/cli.h"
#include "sim/reference/embree_check.h"
#include "sim/reference/reference.h"

namespace raycore::cli {
namespace {

using Clock = std::chrono::steady_clock;

struct ReferenceArgs {
  std::string scene;
  scenes::SceneOverrides overrides;
  int width = 800, height = 480, threads = 0;
  bool embree = false;
  bool primary_only = false;
  size_t examples = 10;
  std::string report;
};

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void run_reference(const ReferenceArgs& a) {
  if (a.width <= 0 || a.height <= 0) throw UserError("--width and --height must be positive");
  scenes::Scene s = scenes::load_scene(a.scene, a.overrides);
  scenes::require_camera_and_light(s);
  const int threads = a.threads > 0 ? a.threads : int(std::max(1u, std::thread::hardware_concurrency()));

  auto t0 = Clock::now();
  const reference::Reference ref(s);
  const double build_s = seconds_since(t0);
  t0 = Clock::now();
  const sim::Frame f = ref.render(a.width, a.height, threads, !a.primary_only);
  const double trace_s = seconds_since(t0);
  uint64_t hits = 0, shadow_rays = 0, lit = 0;
  for (const auto& px : f.px) {
    hits += px.tri >= 0;
    shadow_rays += px.shadow_ray;
    lit += px.shadow_ray && px.lit;
  }
  const auto& st = ref.bvh().stats();
  nlohmann::json j;
  j["tool"] = "raycore reference";
  j["scene"] = {{"name", s.name}, {"source", s.source}, {"triangles", s.tris.size()}};
  j["size"] = {a.width, a.height};
  j["bvh"] = {{"nodes", st.nodes}, {"leaves", st.leaves}, {"depth", st.depth}, {"degenerate", st.degenerate},
              {"references", st.references},
              {"build_seconds", build_s}};
  j["rays"] = {{"primary", f.px.size()}, {"shadow", shadow_rays}};
  j["frame"] = {{"hits", hits}, {"lit", lit}};
  j["sim"] = {{"wall_seconds", trace_s}, {"threads", threads},
              {"rays_per_second", trace_s > 0 ? double(f.px.size() + shadow_rays) / trace_s : 0.0}};
  std::printf("scene     %s: %zu triangles (%llu degenerate), BVH %llu nodes, depth %llu, built in %.3f s\n",
              s.name.c_str(), s.tris.size(), (unsigned long long)st.degenerate, (unsigned long long)st.nodes,
              (unsigned long long)st.depth, build_s);
  std::printf("reference %dx%d on %d threads: %zu primary + %llu shadow rays in %.3f s (%.0f rays/s); "
              "%llu hits, %llu lit\n",
              a.width, a.height, threads, f.px.size(), (unsigned long long)shadow_rays, trace_s,
              trace_s > 0 ? double(f.px.size() + shadow_rays) / trace_s : 0.0, (unsigned long long)hits,
              (unsigned long long)lit);
  if (a.embree) {
    if (!reference::embree_available()) throw UserError("--embree-check: this build has no Embree");
    reference::EmbreeCheckOptions opt;
    opt.threads = threads;
    opt.max_examples = a.examples;
    t0 = Clock::now();
    const reference::EmbreeAgreement e = reference::embree_check(s, f, opt);
    const double es = seconds_since(t0);
    j["embree"] = reference::to_json(e);
    std::printf("embree    agreement %.4f%% of %llu pixels: %llu same triangle, %llu both miss, %llu ties; "
                "%llu disagree (%llu embree_miss, %llu embree_extra_hit, %llu different_surface; %llu near an "
                "edge, %llu explained by the float inputs) [%.2f s]\n",
                e.agreement_pct, (unsigned long long)e.pixels, (unsigned long long)e.agree_same_tri,
                (unsigned long long)e.agree_both_miss, (unsigned long long)e.agree_tie,
                (unsigned long long)e.disagree, (unsigned long long)e.embree_miss,
                (unsigned long long)e.embree_extra_hit, (unsigned long long)e.different_surface,
                (unsigned long long)e.disagree_near_edge, (unsigned long long)e.disagree_float_inputs, es);
    for (const auto& d : e.examples)
      std::printf("  (%d, %d) %-17s ref tri %d t %.9g margin %.3g | embree tri %d t %.9g margin %.3g%s%s\n", d.x, d.y,
                  d.cause.c_str(), d.ref_tri, d.ref_t, d.ref_edge_margin, d.embree_tri, d.embree_t,
                  d.embree_edge_margin, d.near_edge ? " (near edge)" : "", d.float_inputs ? " (float inputs)" : "");
  }
  if (!a.report.empty()) {
    std::ofstream out(a.report);
    out << j.dump(2) << "\n";
    if (!out) throw UserError("cannot write the report '" + a.report + "'");
    std::printf("wrote     %s\n", a.report.c_str());
  }
}

void register_reference(CLI::App& app) {
  auto a = std::make_shared<ReferenceArgs>();
  auto* c = app.add_subcommand("reference", "Double-precision reference frame (timing), optional Embree cross-check");
  c->add_option("scene", a->scene, "generator name or .gltf/.glb file")->required();
  scenes::add_scene_options(*c, a->overrides);
  c->add_option("--width", a->width, "image width (default 800)");
  c->add_option("--height", a->height, "image height (default 480)");
  c->add_option("--threads", a->threads, "threads (default: all cores)");
  c->add_flag("--primary-only", a->primary_only, "trace primary rays only (no shadow rays)");
  c->add_flag("--embree-check", a->embree, "compare the primary hits with Embree (FP32)");
  c->add_option("--examples", a->examples, "disagreements to list with --embree-check (default 10)");
  c->add_option("--report", a->report, "write a JSON report here");
  c->callback([a] { run_reference(*a); });
}

}  // namespace
RAYCORE_COMMAND(register_reference);
}  // namespace raycore::cli
#endif
