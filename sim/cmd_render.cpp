// `raycore render`: the golden tracer on one frame, with the double-precision reference and the
// error metrics; writes a PNG and the JSON report of design.md.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "sim/cli.h"
#include "sim/errors.h"
#include "sim/output.h"
#include "sim/run.h"

namespace raycore::cli {
namespace {


void run_render(const sim::RunOptions& o) {
  sim::TraceConfig cfg = sim::trace_config(o);
  sim::Prepared p = sim::prepare(o, cfg);
  const std::string tag = p.scene.name + "-" + sim::config_tag(cfg);
  const std::string png = o.png.empty() ? o.out_dir + "/" + tag + ".png" : o.png;
  const std::string rep = o.report.empty() ? o.out_dir + "/" + tag + ".json" : o.report;

  sim::TraceStats st;
  const sim::Frame f = sim::trace_golden(p.image, p.scene.camera, p.scene.light, cfg, &st);

  nlohmann::json j;
  j["tool"] = "raycore render";
  j["tracer"] = "golden";
  j["scene"] = sim::scene_json(p.scene);
  j["config"] = sim::config_json(cfg);
  j["image"] = sim::tree_json(p.tree, p.image);
  if (p.built) j["image"]["builder"] = sim::build_json(sim::build_options(o));
  j["rays"] = {{"primary", st.primary_rays}, {"shadow", st.shadow_rays}};
  j["work"] = {{"inner_steps", st.inner_steps},
               {"leaf_visits", st.leaf_visits},
               {"tri_tests", st.tri_tests},
               {"primary_hits", st.primary_hits}};
  const double rays = double(st.primary_rays + st.shadow_rays);
  j["sim"] = {{"wall_seconds", st.seconds},
              {"rays_per_second", st.seconds > 0 ? rays / st.seconds : 0.0},
              {"threads", cfg.threads}};
  sim::FrameErrors fe;
  const bool have_ref = o.reference && !p.scene.tris.empty();
  if (have_ref) {
    fe = sim::measure_errors(f, p.scene, p.image, cfg);
    sim::add_errors_json(j, fe, cfg.spawn.any_hit);
  }
  std::filesystem::create_directories(std::filesystem::path(png).parent_path().empty()
                                          ? std::filesystem::path(".")
                                          : std::filesystem::path(png).parent_path());
  std::filesystem::create_directories(std::filesystem::path(rep).parent_path().empty()
                                          ? std::filesystem::path(".")
                                          : std::filesystem::path(rep).parent_path());
  sim::write_png(f, png);
  sim::write_json(j, rep);
  if (!o.error_pixels.empty()) sim::write_error_pixels(fe, have_ref, o.error_pixels);
  if (o.quiet) return;
  std::printf("scene     %s: %zu triangles, image %zu bytes (%llu nodes, depth %d), built in %.2f s\n",
              p.scene.name.c_str(), p.scene.tris.size(), p.image.bytes.size(),
              (unsigned long long)p.tree.nodes, p.tree.max_depth, p.tree.build_seconds);
  std::printf("config    %s, t_min %g, %dx%d\n", sim::config_tag(cfg).c_str(), cfg.tmin, cfg.width,
              cfg.height);
  std::printf("golden    %llu primary + %llu shadow rays in %.2f s (%.0f rays/s)\n",
              (unsigned long long)st.primary_rays, (unsigned long long)st.shadow_rays, st.seconds,
              st.seconds > 0 ? rays / st.seconds : 0.0);
  if (have_ref)
    sim::print_errors(fe, cfg.spawn.any_hit);
  else
    std::printf("errors    (no reference: %s)\n", o.reference ? "no scene triangles" : "--no-reference");
  std::printf("wrote     %s\n          %s\n", png.c_str(), rep.c_str());
  if (!o.error_pixels.empty()) std::printf("          %s\n", o.error_pixels.c_str());
}

void register_render(CLI::App& app) {
  auto o = std::make_shared<sim::RunOptions>();
  auto* c = app.add_subcommand("render", "Golden tracer: one frame, PNG + JSON report with error metrics");
  sim::add_run_options(*c, *o);
  c->callback([o] { run_render(*o); });
}

}  // namespace
RAYCORE_COMMAND(register_render);
}  // namespace raycore::cli
