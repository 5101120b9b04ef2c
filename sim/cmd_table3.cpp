// `raycore table3`: the paper's Table 3 (self-intersections out of the shadow rays, 24-bit and
// 32-bit, original and VTU) on corridor, sponza-paper and sibenik-paper under the four shadow-ray
// conventions {unit, segment} x {front, all}, each cell next to the paper's figure as a ratio, with
// which convention comes closest, the lit-side share of the self-intersections, and every error
// metric against the scene (total) and against the stored scene (arithmetic); written into
// docs/results.md between markers.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

#include "hls/image.h"
#include "sim/analysis.h"
#include "sim/cli.h"
#include "sim/errors.h"
#include "sim/golden/golden.h"
#include "sim/output.h"
#include "sim/reference/metrics.h"
#include "sim/reference/reference.h"
#include "sim/run.h"

namespace raycore::cli {
namespace {

struct Table3Args {
  std::string scenes_dir = "../shared/scenes";
  std::string results = "docs/results.md";
  std::string json = "out/table3.json";
  int width = 800, height = 480, threads = 0;
  std::string shadow_ray = "both", shadow_spawn = "both";
};

struct PaperRow {
  const char* scene;
  long fp24_orig, fp24_vtu, fp32_orig, fp32_vtu;
  long at(bool fp24, bool vtu) const { return fp24 ? (vtu ? fp24_vtu : fp24_orig) : (vtu ? fp32_vtu : fp32_orig); }
};
// Kim, Nah, Park 2015, Table 3 (self-intersections out of 384,000 shadow rays).
constexpr PaperRow kPaper[] = {{"Spatial Partitioning II", 13091, 4524, 212, 2},
                               {"Sponza", 3172, 487, 0, 0},
                               {"Sibenik", 22310, 16767, 208, 117}};
constexpr double kPaperRays = 384000;

// A column pair of the table: a number format and rounding, original and VTU.
struct Width {
  const char* label;  // "24-bit rtz"
  hls::FormatId f;
  hls::Rounding r;
  bool fp24;  // compared with the paper's 24-bit column (else its 32-bit one)
};
const std::vector<Width>& widths() {
  static const std::vector<Width> w = {{"24-bit rtz", hls::FormatId::fp24, hls::Rounding::rtz, true},
                                       {"24-bit raycore", hls::FormatId::fp24, hls::Rounding::raycore, true},
                                       {"32-bit", hls::FormatId::fp32, hls::Rounding::rne, false}};
  return w;
}

struct Convention {
  bool segment, all;
  std::string name() const { return std::string(segment ? "segment" : "unit") + " / " + (all ? "all" : "front"); }
};

struct Cell {
  sim::FrameErrors e;
  double median_coord = 0;  // median over hit pixels of max |h_i| in the datapath's frame
  sim::HitSideStats side;
};

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}
std::string pct(uint64_t n, uint64_t d) { return fmt("%.1f%%", d ? 100.0 * double(n) / double(d) : 0.0); }
std::string reduction(double a, double b) { return a <= 0 ? "-" : fmt("%.1f%%", 100.0 * (a - b) / a); }
// Ours against the paper's count, both out of their pixels: "x0.45"; the paper's 0 gives "-".
std::string ratio(uint64_t ours, uint64_t pixels, long paper) {
  if (paper <= 0) return ours == 0 ? "=" : "-";
  return fmt("x%.3g", (double(ours) / double(pixels)) / (double(paper) / kPaperRays));
}
// Distance of a count from the paper's as |log10 ratio| of (count + 1) per 384,000 pixels.
double log_distance(uint64_t ours, uint64_t pixels, long paper) {
  const double o = double(ours) * kPaperRays / double(pixels);
  return std::fabs(std::log10((o + 1) / (double(paper) + 1)));
}

double median_coord(const sim::Frame& f, const hls::Vec3& cam, bool vtu) {
  std::vector<double> v;
  for (const auto& p : f.px) {
    if (p.tri < 0) continue;
    const hls::Vec3 h = vtu ? p.hit - cam : p.hit;
    v.push_back(std::max({std::fabs(h.x), std::fabs(h.y), std::fabs(h.z)}));
  }
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

void run_table3(const Table3Args& a) {
  struct SceneSpec {
    std::string label, what;
    int paper;
  };
  const std::vector<SceneSpec> specs = {{"corridor (for Spatial Partitioning II)", "corridor", 0},
                                        {"sponza-paper", a.scenes_dir + "/sponza-paper.glb", 1},
                                        {"sibenik-paper", a.scenes_dir + "/sibenik-paper.glb", 2}};
  std::vector<Convention> convs;
  for (bool seg : {false, true})
    for (bool all : {false, true})
      if ((a.shadow_ray == "both" || (a.shadow_ray == "segment") == seg) &&
          (a.shadow_spawn == "both" || (a.shadow_spawn == "all") == all))
        convs.push_back({seg, all});
  const auto& ws = widths();
  const size_t nc = ws.size() * 2;  // (width, vtu) per convention
  // cells[scene][convention][width * 2 + vtu]
  std::vector<std::vector<std::vector<Cell>>> cells(specs.size(),
      std::vector<std::vector<Cell>>(convs.size(), std::vector<Cell>(nc)));
  std::vector<std::string> names(specs.size());
  std::vector<uint64_t> pixels(specs.size());
  nlohmann::json out = nlohmann::json::array();
  for (size_t si = 0; si < specs.size(); ++si) {
    const auto& sp = specs[si];
    sim::RunOptions ro;
    ro.scene = sp.what;
    ro.width = a.width;
    ro.height = a.height;
    ro.threads = a.threads;
    ro.shadow_hit = "closest";  // the paper's self-intersection count needs the nearest occluder
    sim::TraceConfig base = sim::trace_config(ro);
    const scenes::Scene scene = sim::prepare(ro, base).scene;  // validated (the image is rebuilt below)
    names[si] = scene.name;
    std::fprintf(stderr, "table3: %s: reference...\n", sp.what.c_str());
    const sim::Frame ref = reference::render(scene, a.width, a.height, a.threads);
    for (size_t wi = 0; wi < ws.size(); ++wi) {
      const hls::Image img = hls::build_image(scene.tris, ws[wi].f, ws[wi].r);
      const scenes::Scene stored = sim::stored_scene(scene, img);
      const sim::Frame ref_st = reference::render(stored, a.width, a.height, a.threads);
      for (size_t ci = 0; ci < convs.size(); ++ci)
        for (bool vtu : {false, true}) {
          sim::TraceConfig c = base;
          c.format = ws[wi].f;
          c.rounding = ws[wi].r;
          c.vtu = vtu;
          c.spawn.spawn = hls::Spawn::none;  // the paper's baseline
          c.spawn.segment = convs[ci].segment;
          c.spawn.spawn_all = convs[ci].all;
          const sim::Frame f = sim::trace_golden(img, scene.camera, scene.light, c);
          Cell& cell = cells[si][ci][wi * 2 + (vtu ? 1 : 0)];
          cell.e.total = reference::compute_errors(f, ref, scene.tris);
          cell.e.stored = reference::compute_errors(f, ref_st, stored.tris);
          cell.median_coord = median_coord(f, scene.camera.position, vtu);
          cell.side = sim::hit_side_stats(f, img, scene.camera, scene.light, c);
          pixels[si] = cell.e.total.pixels;
          std::fprintf(stderr, "table3: %s %s %s: %llu self-intersections\n", sp.what.c_str(),
                       convs[ci].name().c_str(), sim::config_tag(c).c_str(),
                       (unsigned long long)cell.e.total.self_intersections);
          nlohmann::json j = {{"scene", scene.name},
                              {"config", sim::config_json(c)},
                              {"median_max_abs_hit_coordinate", cell.median_coord},
                              {"hit_side", sim::to_json(cell.side)}};
          sim::add_errors_json(j, cell.e, false);
          j.erase("reference");
          out.push_back(j);
        }
    }
  }

  std::ostringstream md;
  md << "Command: `build/bin/raycore table3 --width " << a.width << " --height " << a.height
     << "` (= `make table3`). " << a.width << " x " << a.height
     << " pixels, one primary ray per pixel, spawn `none` (t_min = 2^-12 only), closest-hit shadow "
        "rays. Conventions: `unit` shadow rays have a normalised direction (t_min in world units), "
        "`segment` ones run from the hit point to the light (t in (t_min, 1): t_min is a fraction of "
        "the light distance); `front` spawns a shadow ray only where the light is on the side the "
        "primary ray came from, `all` at every primary hit (the paper's \"384,000 shadow rays\"). "
        "FP24 `rtz` truncates every operation (correctly rounded toward zero); FP24 `raycore` is "
        "RayCore's own arithmetic (one guard bit in the adder, two in the 3-input adder, a 32-entry "
        "table reciprocal; docs/architecture.md); 32-bit is IEEE rne. "
        "The image is the same under front and all. Counts are out of all pixels; each cell's ratio "
        "is ours / the paper's as shares of the pixels (`=`: both 0; `-`: the paper's is 0, ours "
        "not).\n\n";

  // Table 1: self-intersections in the paper's layout, one row per scene and convention.
  std::ostringstream t3;
  t3 << "| scene | convention";
  for (const auto& w : ws) t3 << " | " << w.label << " original | " << w.label << " VTU | reduction";
  t3 << " | light in front (lit side), " << ws[0].label << " original / VTU |\n|---|---";
  for (size_t i = 0; i < ws.size(); ++i) t3 << "|---|---|---";
  t3 << "|---|\n";
  for (size_t si = 0; si < specs.size(); ++si) {
    const PaperRow& pr = kPaper[specs[si].paper];
    t3 << "| " << pr.scene << " (paper) | -";
    for (const auto& w : ws)
      t3 << " | " << pr.at(w.fp24, false) << " | " << pr.at(w.fp24, true) << " | "
         << reduction(double(pr.at(w.fp24, false)), double(pr.at(w.fp24, true)));
    t3 << " | - |\n";
    for (size_t ci = 0; ci < convs.size(); ++ci) {
      t3 << "| " << specs[si].label << " | " << convs[ci].name();
      for (size_t wi = 0; wi < ws.size(); ++wi) {
        const auto& o = cells[si][ci][wi * 2].e.total;
        const auto& v = cells[si][ci][wi * 2 + 1].e.total;
        t3 << " | " << o.self_intersections << " (" << ratio(o.self_intersections, o.pixels, pr.at(ws[wi].fp24, false))
           << ") | " << v.self_intersections << " (" << ratio(v.self_intersections, v.pixels, pr.at(ws[wi].fp24, true))
           << ") | " << reduction(double(o.self_intersections), double(v.self_intersections));
      }
      const auto& o = cells[si][ci][0].e.total;
      const auto& v = cells[si][ci][1].e.total;
      t3 << " | " << o.self_intersections_front << " (" << pct(o.self_intersections_front, o.self_intersections)
         << ") / " << v.self_intersections_front << " (" << pct(v.self_intersections_front, v.self_intersections)
         << ") |\n";
    }
  }

  // Table 2: how close each convention comes, per column group (24-bit, 32-bit).
  std::ostringstream close;
  close << "| convention";
  for (const auto& w : ws) close << " | " << w.label << ": mean factor from the paper";
  close << " |\n|---";
  for (size_t i = 0; i < ws.size(); ++i) close << "|---";
  close << "|\n";
  std::vector<double> best(ws.size(), HUGE_VAL);
  std::vector<size_t> best_ci(ws.size(), 0);
  std::vector<std::vector<double>> dist(convs.size(), std::vector<double>(ws.size(), 0));
  for (size_t ci = 0; ci < convs.size(); ++ci)
    for (size_t wi = 0; wi < ws.size(); ++wi) {
      double s = 0;
      for (size_t si = 0; si < specs.size(); ++si)
        for (bool vtu : {false, true}) {
          const auto& m = cells[si][ci][wi * 2 + (vtu ? 1 : 0)].e.total;
          s += log_distance(m.self_intersections, m.pixels, kPaper[specs[si].paper].at(ws[wi].fp24, vtu));
        }
      dist[ci][wi] = s / double(specs.size() * 2);
      if (dist[ci][wi] < best[wi]) {
        best[wi] = dist[ci][wi];
        best_ci[wi] = ci;
      }
    }
  for (size_t ci = 0; ci < convs.size(); ++ci) {
    close << "| " << convs[ci].name();
    for (size_t wi = 0; wi < ws.size(); ++wi) {
      const std::string f = fmt("%.3g", std::pow(10.0, dist[ci][wi]));
      close << " | " << (best_ci[wi] == ci ? "**" + f + "**" : f);
    }
    close << " |\n";
  }
  std::ostringstream words;
  words << "The mean factor is the geometric mean over the six cells of a column group (three scenes, "
           "original and VTU) of how far our count is from the paper's, as (count + 1) per 384,000 "
           "pixels (1 = equal). ";
  for (size_t wi = 0; wi < ws.size(); ++wi)
    words << "Closest in the " << ws[wi].label << " columns: **" << convs[best_ci[wi]].name()
          << "** (a factor of " << fmt("%.3g", std::pow(10.0, best[wi])) << "). ";
  bool same = true;
  for (size_t wi = 1; wi < ws.size(); ++wi) same = same && best_ci[wi] == best_ci[0];
  words << (same ? "One convention is closest in every column group."
                 : "No single convention is closest in every column group.")
        << "\n";

  // Table 3: every metric, total and arithmetic.
  std::ostringstream err;
  err << "| scene | convention | config | shadow rays | self-intersections (lit side) | shadow errors total "
         "(false shadow / light leak) | shadow errors arithmetic | primary errors total / arithmetic | "
         "median max-abs hit coordinate in the datapath | hit points behind their plane | "
         "self-intersections with the hit point behind | median distance of hit point from its plane (ulps) |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (size_t si = 0; si < specs.size(); ++si)
    for (size_t ci = 0; ci < convs.size(); ++ci)
      for (size_t k = 0; k < nc; ++k) {
        const Cell& c = cells[si][ci][k];
        const auto& m = c.e.total;
        const auto& s = c.e.stored;
        err << "| " << names[si] << " | " << convs[ci].name() << " | " << ws[k / 2].label
            << (k % 2 ? " VTU" : " original") << " | " << m.shadow_rays << " | " << m.self_intersections
            << " (" << m.self_intersections_front << ") | " << m.shadow_errors << " (" << m.false_shadow
            << " / " << m.light_leak << ") | " << s.shadow_errors << " | " << m.primary_errors << " / "
            << s.primary_errors << " | " << fmt("%.0f", c.median_coord) << " | "
            << pct(c.side.behind, c.side.shadow_rays) << " | " << c.side.self_behind << " | "
            << fmt("%.3g", c.side.median_plane_distance_ulps) << " |\n";
      }

  md << "### Self-intersections (the paper's Table 3 layout), per convention\n\n" << t3.str()
     << "\n### Which convention comes closest to the paper\n\n" << close.str() << "\n" << words.str()
     << "\n### All error metrics (total: against the scene; arithmetic: against the stored scene)\n\n"
     << err.str();
  sim::write_doc_section(a.results, "table3", md.str());
  sim::make_parent(a.json);
  sim::write_json(out, a.json);
  std::printf("%s\nwrote %s and %s\n", md.str().c_str(), a.results.c_str(), a.json.c_str());
}

void register_table3(CLI::App& app) {
  auto a = std::make_shared<Table3Args>();
  auto* c = app.add_subcommand("table3", "Reproduce the paper's Table 3 into docs/results.md");
  c->add_option("--scenes-dir", a->scenes_dir, "where sponza-paper.glb and sibenik-paper.glb are")
      ->capture_default_str();
  c->add_option("--results", a->results, "markdown file to update")->capture_default_str();
  c->add_option("--json", a->json, "JSON output")->capture_default_str();
  c->add_option("--width", a->width, "image width")->check(CLI::Range(1, 16384))->capture_default_str();
  c->add_option("--height", a->height, "image height")->check(CLI::Range(1, 16384))->capture_default_str();
  c->add_option("--threads", a->threads, "host threads (0: all)")->check(CLI::Range(0, 1024));
  c->add_option("--shadow-ray", a->shadow_ray, "unit, segment or both (see render --help)")
      ->check(CLI::IsMember({"unit", "segment", "both"}))
      ->capture_default_str();
  c->add_option("--shadow-spawn", a->shadow_spawn, "front, all or both (see render --help)")
      ->check(CLI::IsMember({"front", "all", "both"}))
      ->capture_default_str();
  c->callback([a] { run_table3(*a); });
}

}  // namespace
RAYCORE_COMMAND(register_table3);
}  // namespace raycore::cli
