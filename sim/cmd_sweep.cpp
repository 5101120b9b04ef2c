// `raycore sweep`: the speed-against-error sweep of issue 6. `--list` prints one shell command per
// job (each one `raycore simulate` or `raycore errormap` process writing one JSON report) and
// writes DIR/manifest.json; the jobs run anywhere (GNU parallel, scripts/sweep.sh); `--collect DIR`
// merges the reports into DIR/sweep.{csv,json,md} and the plot data. `--run` does all three in
// this process, one job after another (for machines without parallel).
//
// `raycore errormap`: the golden tracer's frame (bit for bit the cycle model's when golden_match)
// against the double-precision reference, as an image of the error pixels (docs/sweep.md).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "sim/cli.h"
#include "sim/golden/golden.h"
#include "sim/output.h"
#include "sim/reference/metrics.h"
#include "sim/reference/reference.h"
#include "sim/run.h"
#include "sim/sweep/errormap.h"
#include "sim/sweep/sweep.h"

namespace raycore::cli {
namespace {

namespace fs = std::filesystem;

struct SweepArgs {
  sweep::Options o;
  bool list = false, run = false, allow_missing = false;
  std::string list_format = "lines";
  std::string collect;  // DIR
  std::string area, doc;
};

using sim::make_parent;
using sim::write_text;

std::vector<sweep::Job> jobs_or_error(const sweep::Options& o) {
  try {
    return sweep::make_jobs(o);
  } catch (const std::invalid_argument& e) {
    throw UserError(std::string("sweep: ") + e.what());
  }
}

void do_list(const SweepArgs& a, const std::vector<sweep::Job>& jobs) {
  const std::string manifest = a.o.out + "/manifest.json";
  make_parent(manifest);
  sim::write_json(sweep::manifest_json(a.o, jobs), manifest);
  for (const auto& j : jobs) {
    if (a.list_format == "tsv")
      std::printf("%s\t%s\t%s\t%s\n", j.id.c_str(), j.json.c_str(), j.png.c_str(),
                  sweep::command_line(j).c_str());
    else
      std::printf("%s\n", sweep::command_line(j).c_str());
  }
  std::fflush(stdout);
}

void do_collect(const SweepArgs& a, const std::string& dir) {
  const std::string mpath = dir + "/manifest.json";
  nlohmann::json m;
  {
    std::ifstream is(mpath);
    if (!is) throw UserError("sweep --collect: no '" + mpath + "' (run `raycore sweep --list --out " + dir + "` first)");
    try {
      is >> m;
    } catch (const nlohmann::json::exception& e) {
      throw UserError("sweep --collect: '" + mpath + "' is not JSON: " + e.what());
    }
  }
  std::vector<sweep::Job> jobs;
  try {
    jobs = sweep::jobs_from_manifest(m);
  } catch (const std::runtime_error& e) {
    throw UserError("sweep --collect: '" + mpath + "': " + e.what());
  }
  sweep::Area area;
  if (!a.area.empty()) {
    try {
      area = sweep::read_area(a.area);
    } catch (const std::runtime_error& e) {
      throw UserError(std::string("sweep --collect: ") + e.what());
    }
  }
  std::vector<sweep::Row> rows;
  std::vector<std::string> missing, bad;
  nlohmann::json maps = nlohmann::json::array();
  for (const auto& j : jobs) {
    std::ifstream is(j.json);
    if (!is) {
      missing.push_back(j.json);
      continue;
    }
    nlohmann::json r;
    try {
      is >> r;
    } catch (const nlohmann::json::exception& e) {
      bad.push_back(j.json + " (" + e.what() + ")");
      continue;
    }
    if (j.kind == "errormap") {
      maps.push_back({{"scene", j.scene}, {"id", j.id}, {"png", j.png},
                      {"crop", r.value("crop_png", std::string())}, {"label", j.format_name + (j.vtu ? " VTU on " : " VTU off ") + j.spawn},
                      {"errors", r.value("errors", nlohmann::json::object())},
                      {"map", r.value("map", nlohmann::json::object())}});
      continue;
    }
    try {
      sweep::Row w = sweep::read_row(j, r);
      if (!area.empty()) w.cells = sweep::added_cells(area, j.format, j.rounding, j.vtu, j.spawn);
      else w.cells = {-1, -1, -1, -1};
      rows.push_back(w);
    } catch (const std::runtime_error& e) {
      bad.push_back(e.what());
    }
  }
  if ((!missing.empty() || !bad.empty()) && !a.allow_missing) {
    std::ostringstream os;
    os << "sweep --collect: " << missing.size() << " of " << jobs.size() << " job results missing and "
       << bad.size() << " unreadable in '" << dir << "'";
    for (size_t i = 0; i < missing.size() && i < 8; ++i) os << "\n  missing: " << missing[i];
    for (size_t i = 0; i < bad.size() && i < 8; ++i) os << "\n  bad: " << bad[i];
    os << "\n(rerun the failed jobs, see DIR/joblog.tsv; or --allow-missing)";
    throw UserError(os.str());
  }
  if (rows.empty()) throw UserError("sweep --collect: no simulate results in '" + dir + "'");
  sweep::mark_pareto(rows);
  std::vector<std::string> order;
  write_text(dir + "/sweep.csv", sweep::csv(rows));
  std::string shadow_spawn;
  for (const auto& r : rows)
    if (shadow_spawn.find(r.job.shadow_spawn) == std::string::npos)
      shadow_spawn += (shadow_spawn.empty() ? "" : ",") + r.job.shadow_spawn;
  sim::write_json({{"tool", "raycore sweep"}, {"shadow_spawn", shadow_spawn}, {"rows", sweep::rows_json(rows)},
                   {"error_maps", maps}, {"area_file", a.area}},
                  dir + "/sweep.json");
  const std::string md = sweep::markdown(rows);
  const std::string compact = sweep::compact_markdown(rows, sweep::paper_scenes());
  const std::string compact_hard = sweep::compact_markdown(rows, sweep::hard_scenes());
  write_text(dir + "/sweep.md", md);
  write_text(dir + "/sweep-paper.md", compact);
  write_text(dir + "/sweep-hard.md", compact_hard);
  std::vector<std::string> target_scenes = sweep::paper_scenes();
  target_scenes.insert(target_scenes.end(), sweep::hard_scenes().begin(), sweep::hard_scenes().end());
  const std::string target = sweep::target_markdown(rows, target_scenes);
  write_text(dir + "/sweep-target.md", target);
  write_text(dir + "/plot.dat", sweep::plot_data(rows, &order));
  {
    std::ostringstream os;
    for (const auto& s : order) os << s << "\n";
    write_text(dir + "/plot_scenes.txt", os.str());
    std::ostringstream ms;
    for (const auto& x : maps)
      ms << x["scene"].get<std::string>() << "\t" << x["png"].get<std::string>() << "\t"
         << x["crop"].get<std::string>() << "\t" << x["label"].get<std::string>() << "\t"
         << x["map"].value("error_pixels", uint64_t(0)) << "\n";
    write_text(dir + "/maps.tsv", ms.str());
  }
  uint64_t mismatches = 0;
  for (const auto& r : rows) mismatches += r.golden_match ? 0 : 1;
  if (!a.doc.empty()) {
    std::ostringstream sec;
    sec << "Collected from `" << dir << "` (" << rows.size() << " simulate jobs, " << maps.size()
        << " error maps; golden_match true in " << rows.size() - mismatches << " of " << rows.size()
        << "; --shadow-spawn " << shadow_spawn
        << ").\n\nErrors are counted twice: total (against the scene) and, in parentheses or marked "
           "arith., arithmetic (against the scene as the memory image stores it, sim/errors.h); storage = "
           "total - arithmetic. Self-intersections are a property of the frame alone: the same in both.\n\n"
           "### The paper's scenes (self-intersections / shadow errors / error pixels = shadow + "
           "primary / rays per cycle; **bold** = on the scene's Pareto front of error pixels vs rays per "
           "cycle)\n\n"
        << compact << "\n### The hard cases\n\n" << compact_hard
        << "\n### The targets (**bold** = met)\n\n"
           "- Issue 6 (bold on shadow %): 0 self-intersections, shadow errors (total) <= 0.01% of the pixels, "
           "<= 5% slower than fp24-rtz VTU on spawn none store world (speed = rays per cycle against it).\n"
           "- Issue 15 (bold on arith. shadow %): 0 self-intersections, arithmetic shadow errors <= 0.01% of "
           "the pixels (38 at 800 x 480, 9 at 400 x 240), <= 5% slower than the same format, VTU and store "
           "with spawn none (vs none).\n\n"
        << target << "\n### Every job\n\n" << md;
    sim::write_doc_section(a.doc, "sweep", sec.str());
  }
  std::printf("sweep: %zu rows (%zu Pareto), %zu error maps; golden_match %s; wrote %s/sweep.{csv,json,md}%s%s\n",
              rows.size(), size_t(std::count_if(rows.begin(), rows.end(), [](const sweep::Row& r) { return r.pareto; })),
              size_t(maps.size()), mismatches ? "FALSE in some rows" : "true in every row", dir.c_str(),
              a.doc.empty() ? "" : " and ", a.doc.c_str());
  if (!missing.empty() || !bad.empty())
    std::fprintf(stderr, "sweep: %zu results missing, %zu unreadable (--allow-missing)\n", missing.size(), bad.size());
  if (mismatches)
    throw std::runtime_error("sweep: the cycle model differs from the golden tracer in " +
                             std::to_string(mismatches) + " jobs (golden_match false; see sweep.csv)");
}

void run_sweep(SweepArgs& a) {
  const int modes = int(a.list) + int(a.run) + int(!a.collect.empty());
  if (modes != 1) throw UserError("sweep: give exactly one of --list, --run, --collect DIR");
  if (!a.collect.empty()) {
    do_collect(a, a.collect);
    return;
  }
  const auto jobs = jobs_or_error(a.o);
  if (a.list) {
    do_list(a, jobs);
    return;
  }
  // --run: the jobs one after another in this process's shell, then collect.
  {
    const std::string manifest = a.o.out + "/manifest.json";
    make_parent(manifest);
    sim::write_json(sweep::manifest_json(a.o, jobs), manifest);
  }
  int failed = 0;
  for (const auto& j : jobs) {
    std::fprintf(stderr, "sweep: %s\n", j.id.c_str());
    if (std::system(sweep::command_line(j).c_str()) != 0) {
      ++failed;
      std::fprintf(stderr, "sweep: job failed: %s\n", sweep::command_line(j).c_str());
    }
  }
  do_collect(a, a.o.out);
  if (failed) throw std::runtime_error("sweep: " + std::to_string(failed) + " jobs failed");
}

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> v;
  std::string cur;
  for (char c : s) {
    if (c == ',') {
      if (!cur.empty()) v.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) v.push_back(cur);
  return v;
}

void register_sweep(CLI::App& app) {
  auto a = std::make_shared<SweepArgs>();
  auto* c = app.add_subcommand("sweep",
                               "Speed against error: scenes x format x VTU x spawn x store as independent jobs "
                               "(--list | parallel; --collect DIR), see docs/sweep.md");
  c->add_flag("--list", a->list, "print one command line per job (and write OUT/manifest.json)");
  c->add_option("--list-format", a->list_format, "lines (commands) or tsv (id, json, png, command)")
      ->check(CLI::IsMember({"lines", "tsv"}))
      ->capture_default_str();
  c->add_option("--collect", a->collect, "merge the job reports of this sweep directory");
  c->add_flag("--run", a->run, "run every job here, one after another, then collect");
  auto list_opt = [&](const char* name, std::vector<std::string>* v, const std::string& help) {
    const std::string opt = name;
    c->add_option_function<std::string>(
        name,
        [v, opt](const std::string& s) {
          *v = split_list(s);
          if (v->empty()) throw UserError("sweep: " + opt + " is an empty list: nothing to sweep");
        },
        help);
  };
  list_opt("--scenes", &a->o.scenes,
           "comma-separated: corridor, sponza-paper, sibenik-paper, far, grazing, slivers, coplanar, "
           "origin-far-camera (default all)");
  list_opt("--formats", &a->o.formats, "comma-separated: fp24-rtz, fp24-rne, fp32 (rne), fp32-rtz, "
                                        "fp24-raycore (default fp24-rtz,fp24-rne,fp32)");
  list_opt("--vtu", &a->o.vtu, "comma-separated: off, on (default both)");
  list_opt("--spawns", &a->o.spawns,
           "comma-separated strategies (" + sim::spawn_choices() + "), each optionally with :ULPS "
           "(--spawn-ulps) and the watertightness margins +mE (--bary-margin) and +wN (--trv-widen), "
           "e.g. skip-slab:2, skip-back+m0.008+w2 (default none,skip-origin,ulp-offset,error-bound,"
           "skip-offset,skip-slab:2,skip-back)");
  list_opt("--stores", &a->o.stores,
           "comma-separated: world, anchored (--store of every job; default world, and also anchored for "
           "far and origin-far-camera)");
  c->add_option("--shadow-spawn", a->o.shadow_spawn,
                "--shadow-spawn of every job: front (a shadow ray only where the light is in front) or all "
                "(at every primary hit, as the paper counts)")
      ->check(CLI::IsMember({"front", "all"}))
      ->capture_default_str();
  list_opt("--map-scenes", &a->o.map_scenes,
           "error maps for these scenes (default sponza-paper,sibenik-paper when swept; none: no maps)");
  list_opt("--map-configs", &a->o.map_configs,
           "error-map configurations format:vtu:spawn (default fp24-rtz:off:none,fp24-rtz:on:none,"
           "fp24-rtz:on:skip-slab:2,fp24-rne:on:skip-back)");
  c->add_option("--width", a->o.width, "image width, paper scenes")->check(CLI::Range(1, 16384))->capture_default_str();
  c->add_option("--height", a->o.height, "image height, paper scenes")->check(CLI::Range(1, 16384))->capture_default_str();
  c->add_option("--hard-width", a->o.hard_width, "image width, hard cases")->check(CLI::Range(1, 16384))
      ->capture_default_str();
  c->add_option("--hard-height", a->o.hard_height, "image height, hard cases")->check(CLI::Range(1, 16384))
      ->capture_default_str();
  c->add_option("--scenes-dir", a->o.scenes_dir, "where sponza-paper.glb and sibenik-paper.glb are")
      ->capture_default_str();
  c->add_option("--out", a->o.out, "sweep directory (manifest, jobs/, maps/, results)")->capture_default_str();
  c->add_option("--raycore", a->o.raycore, "the raycore binary in the job lines (default: this one)");
  c->add_option("--threads", a->o.threads, "host threads per job")->check(CLI::Range(0, 1024))->capture_default_str();
  c->add_flag("--keep-paths", a->o.keep_paths, "keep relative paths relative in the job lines (for "
                                               "parallel --transferfile/--return)");
  c->add_option("--area", a->area, "collect: added-hardware table from scripts/sweep_area.sh");
  c->add_option("--doc", a->doc, "collect: also write the tables into this markdown file, between "
                                 "<!-- sweep:begin --> and <!-- sweep:end -->");
  c->add_flag("--allow-missing", a->allow_missing, "collect: merge what is there");
  c->callback([a] { run_sweep(*a); });
}

// ---- raycore errormap --------------------------------------------------------------------------

struct MapArgs {
  int crop_w = 100, crop_h = 60, zoom = 4;
};

void run_errormap(const sim::RunOptions& o, const MapArgs& ma) {
  sim::TraceConfig cfg = sim::trace_config(o);
  sim::Prepared p = sim::prepare(o, cfg);
  if (p.scene.tris.empty()) throw UserError("errormap: the scene has no triangles (needs the reference)");
  const std::string tag = p.scene.name + "-" + sim::config_tag(cfg) + "-errors";
  const std::string png = o.png.empty() ? o.out_dir + "/" + tag + ".png" : o.png;
  const std::string rep = o.report.empty() ? o.out_dir + "/" + tag + ".json" : o.report;
  std::string crop = png;
  if (crop.size() > 4 && crop.substr(crop.size() - 4) == ".png") crop.resize(crop.size() - 4);
  crop += "-crop.png";
  sim::TraceStats st;
  const sim::Frame f = sim::trace_golden(p.image, p.scene.camera, p.scene.light, cfg, &st);
  const sim::Frame ref = reference::render(p.scene, cfg.width, cfg.height, cfg.threads);
  const auto m = reference::compute_errors(f, ref, p.scene.tris);
  const auto cls = sweep::classify(f, ref);
  const auto rgb = sweep::error_map_rgb(f, cls);
  const sweep::Window w = sweep::worst_window(cls, f.width, f.height, ma.crop_w, ma.crop_h);
  make_parent(png);
  make_parent(rep);
  make_parent(crop);
  sweep::write_rgb_png(png, rgb, f.width, f.height);
  sweep::write_rgb_png(crop, sweep::crop_zoom(rgb, f.width, w, ma.zoom), w.w * ma.zoom, w.h * ma.zoom);
  nlohmann::json j;
  j["tool"] = "raycore errormap";
  j["tracer"] = "golden";
  j["scene"] = sim::scene_json(p.scene);
  j["config"] = sim::config_json(cfg);
  j["errors"] = reference::to_json(m);
  j["map"] = sweep::counts_json(cls);
  j["worst_window"] = {{"x", w.x}, {"y", w.y}, {"w", w.w}, {"h", w.h}, {"error_pixels", w.errors}, {"zoom", ma.zoom}};
  j["png"] = png;
  j["crop_png"] = crop;
  j["colours"] = {{"primary", "yellow"}, {"false_shadow_self", "red"}, {"false_shadow_other", "magenta"},
                  {"light_leak", "cyan"}, {"self_intersection_no_error", "orange"}, {"ok", "grey (shade / 3)"}};
  sim::write_json(j, rep);
  if (!o.quiet)
    std::printf("errormap  %s %s: %llu error pixels (worst %dx%d window at %d,%d: %llu)\n  wrote %s, %s, %s\n",
                p.scene.name.c_str(), sim::config_tag(cfg).c_str(),
                (unsigned long long)(m.shadow_errors + m.primary_errors), w.w, w.h, w.x, w.y,
                (unsigned long long)w.errors, png.c_str(), crop.c_str(), rep.c_str());
}

void register_errormap(CLI::App& app) {
  auto o = std::make_shared<sim::RunOptions>();
  auto ma = std::make_shared<MapArgs>();
  auto* c = app.add_subcommand("errormap", "Golden frame vs the reference as an image of the error pixels "
                                           "(+ enlarged crop of the worst window)");
  sim::add_run_options(*c, *o);
  c->add_option("--crop-width", ma->crop_w, "worst-window width")->check(CLI::Range(1, 4096))->capture_default_str();
  c->add_option("--crop-height", ma->crop_h, "worst-window height")->check(CLI::Range(1, 4096))->capture_default_str();
  c->add_option("--zoom", ma->zoom, "crop enlargement")->check(CLI::Range(1, 16))->capture_default_str();
  c->callback([o, ma] { run_errormap(*o, *ma); });
}

}  // namespace
RAYCORE_COMMAND(register_sweep);
RAYCORE_COMMAND(register_errormap);
}  // namespace raycore::cli
