// `raycore simulate`: the cycle model (systemc/) on one frame, checked pixel by pixel against the
// golden tracer run in the same process; PNG + JSON report (render's keys plus "hardware", "sim",
// "golden_match").
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "sim/cli.h"
#include "sim/errors.h"
#include "sim/output.h"
#include "sim/run.h"
#include "sim/sc_options.h"
#include "systemc/simulate.h"

namespace raycore::cli {
namespace {


using sim::make_parent;

void run_simulate(const sim::RunOptions& o, const sc::SimOptions& so) {
  sim::TraceConfig cfg = sim::trace_config(o);
  sc::SimConfig scfg = sc::resolved_ist_latency(sc::finish_sim_options(so), cfg.ist);
  scfg.progress = !o.quiet;
  sim::Prepared p = sim::prepare(o, cfg);
  const std::string tag = p.scene.name + "-" + sim::config_tag(cfg) + "-cycle";
  const std::string png = o.png.empty() ? o.out_dir + "/" + tag + ".png" : o.png;
  const std::string rep = o.report.empty() ? o.out_dir + "/" + tag + ".json" : o.report;

  sim::TraceStats gs;
  const sim::Frame golden = sim::trace_golden(p.image, p.scene.camera, p.scene.light, cfg, &gs);
  const sc::SimResult r = sc::simulate(p.image, p.scene.camera, p.scene.light, cfg, scfg);
  uint64_t ndiff = 0;
  const auto diffs = sc::diff_frames(r.frame, golden, 5, &ndiff);

  nlohmann::json j;
  j["tool"] = "raycore simulate";
  j["tracer"] = "cycle";
  j["scene"] = sim::scene_json(p.scene);
  j["config"] = sim::config_json(cfg);
  j["config"].update(sc::config_json(scfg));
  j["image"] = sim::tree_json(p.tree, p.image);
  if (p.built) j["image"]["builder"] = sim::build_json(sim::build_options(o));
  j["rays"] = {{"primary", r.primary_rays}, {"shadow", r.shadow_rays}};
  j["work"] = {{"inner_steps", gs.inner_steps},
               {"leaf_visits", gs.leaf_visits},
               {"tri_tests", gs.tri_tests},
               {"primary_hits", gs.primary_hits}};
  j["hardware"] = sc::hardware_json(r, scfg);
  j["sim"] = sc::sim_json(r);
  j["golden"] = {{"wall_seconds", gs.seconds}, {"rays", {{"primary", gs.primary_rays}, {"shadow", gs.shadow_rays}}}};
  j["golden_match"] = ndiff == 0;
  j["golden_mismatches"] = ndiff;
  sim::FrameErrors fe;
  const bool have_ref = o.reference && !p.scene.tris.empty();
  if (have_ref) {
    fe = sim::measure_errors(r.frame, p.scene, p.image, cfg);
    sim::add_errors_json(j, fe, cfg.spawn.any_hit);
  }
  make_parent(png);
  make_parent(rep);
  sim::write_png(r.frame, png);
  sim::write_json(j, rep);
  if (!o.error_pixels.empty() && ndiff == 0) sim::write_error_pixels(fe, have_ref, o.error_pixels);
  if (!o.quiet) {
    const auto& hw = j["hardware"];
    std::printf("scene     %s: %zu triangles, image %zu bytes\n", p.scene.name.c_str(),
                p.scene.tris.size(), p.image.bytes.size());
    std::printf("config    %s, %dx%d, %d RTUs at %.0f MHz (%s), memory %u cycles, %u B/cycle\n",
                sim::config_tag(cfg).c_str(), cfg.width, cfg.height, scfg.rtus, scfg.clock_mhz,
                scfg.clock_source == "timing"   ? "the RTU's clock from static timing, 28 nm"
                : scfg.clock_source == "option" ? "given"
                                                : "assumed",
                scfg.mem_latency, scfg.mem_bandwidth);
    if (!scfg.clock_note.empty()) std::printf("clock     %s\n", scfg.clock_note.c_str());
    std::printf("hardware  %llu cycles, %llu primary + %llu shadow rays, %.3f rays/cycle "
                "(%.3f per RTU), %.1f Mrays/s\n",
                (unsigned long long)r.cycles, (unsigned long long)r.primary_rays,
                (unsigned long long)r.shadow_rays, hw["rays_per_cycle"].get<double>(),
                hw["rays_per_cycle_per_rtu"].get<double>(), hw["mrays_per_s"].get<double>());
    std::printf("units     %u trv pipes %.1f%%, %u ist %.1f%% busy; %.1f trv passes, %.1f tests, %.1f DRAM "
                "bytes per ray\n",
                scfg.trv_pipes, 100 * hw["utilisation"]["trv"].get<double>(), scfg.ist_units,
                100 * hw["utilisation"]["ist"].get<double>(), hw["per_ray"]["trv_steps"].get<double>(),
                hw["per_ray"]["tri_tests"].get<double>(), hw["per_ray"]["bus_bytes"].get<double>());
    std::printf("memory    hit rates node %.1f%%, list %.1f%%, tri %.1f%%, L2 %s; DRAM %.2f GB/s\n",
                100 * hw["caches"]["node"]["hit_rate"].get<double>(),
                100 * hw["caches"]["list"]["hit_rate"].get<double>(),
                100 * hw["caches"]["tri"]["hit_rate"].get<double>(),
                scfg.l2.size_bytes ? (std::to_string(int(std::lround(100 * hw["l2"]["hit_rate"].get<double>()))) +
                                      "% of " + std::to_string(scfg.l2.size_bytes / 1024) + " KB")
                                         .c_str()
                                   : "none",
                hw["bus"]["bandwidth_gb_s"].get<double>());
    std::printf("sim       %.2f s wall (%.2f s user), %.0f cycles/s, %.0f rays/s\n", r.wall_seconds,
                r.user_seconds, j["sim"]["cycles_per_second"].get<double>(),
                j["sim"]["rays_per_second"].get<double>());
    std::printf("golden    %s\n", ndiff == 0 ? "match (every pixel's tri, t, shadow and shade)"
                                             : ("MISMATCH: " + std::to_string(ndiff) + " pixels").c_str());
    if (have_ref) sim::print_errors(fe, cfg.spawn.any_hit);
    std::printf("wrote     %s\n          %s\n", png.c_str(), rep.c_str());
    if (!o.error_pixels.empty() && ndiff == 0) std::printf("          %s\n", o.error_pixels.c_str());
  }
  if (ndiff != 0)
    throw std::runtime_error("cycle model differs from the golden tracer in " + std::to_string(ndiff) +
                             " pixels (see `raycore compare`)");
}

void register_simulate(CLI::App& app) {
  auto o = std::make_shared<sim::RunOptions>();
  auto so = std::make_shared<sc::SimOptions>();
  auto* c = app.add_subcommand("simulate", "Cycle model (SystemC): one frame, checked against the golden tracer");
  sim::add_run_options(*c, *o);
  sc::add_sim_options(*c, *so);
  c->callback([o, so] { run_simulate(*o, *so); });
}

}  // namespace
RAYCORE_COMMAND(register_simulate);
}  // namespace raycore::cli
