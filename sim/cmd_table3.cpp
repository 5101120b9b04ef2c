// `raycore table3`: the paper's Table 3 (self-intersections out of the shadow rays, 24-bit and
// 32-bit, original and VTU) on corridor, sponza-paper and sibenik-paper, with shadow and primary
// errors added, next to the paper's figures; written into docs/results.md between markers.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <vector>

#include "hls/image.h"
#include "sim/cli.h"
#include "sim/analysis.h"
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
  std::string shadow_ray = "unit";
};

struct PaperRow {
  const char* scene;
  long fp24_orig, fp24_vtu, fp32_orig, fp32_vtu;
};
// Kim, Nah, Park 2015, Table 3 (self-intersections out of 384,000 shadow rays).
constexpr PaperRow kPaper[] = {{"Spatial Partitioning II", 13091, 4524, 212, 2},
                               {"Sponza", 3172, 487, 0, 0},
                               {"Sibenik", 22310, 16767, 208, 117}};

struct Cell {
  reference::ErrorMetrics m;
  double median_coord = 0;  // median over hit pixels of max |h_i| in the datapath's frame
  double seconds = 0;
  sim::HitSideStats side;
};

std::string pct(uint64_t n, uint64_t d) {
  char b[64];
  std::snprintf(b, sizeof b, "%.1f%%", d ? 100.0 * double(n) / double(d) : 0.0);
  return b;
}
std::string count_pct(uint64_t n, uint64_t d) {
  std::ostringstream os;
  os << n << " (" << pct(n, d) << ")";
  return os.str();
}
std::string reduction(double a, double b) {
  if (a <= 0) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100.0 * (a - b) / a);
  return buf;
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
  const std::vector<SceneSpec> specs = {{"corridor (stand-in for Spatial Partitioning II)", "corridor", 0},
                                        {"sponza-paper", a.scenes_dir + "/sponza-paper.glb", 1},
                                        {"sibenik-paper", a.scenes_dir + "/sibenik-paper.glb", 2}};
  struct Cfg {
    hls::FormatId f;
    hls::Rounding r;
    bool vtu;
  };
  const Cfg cfgs[4] = {{hls::FormatId::fp24, hls::Rounding::rtz, false},
                       {hls::FormatId::fp24, hls::Rounding::rtz, true},
                       {hls::FormatId::fp32, hls::Rounding::rne, false},
                       {hls::FormatId::fp32, hls::Rounding::rne, true}};
  nlohmann::json out = nlohmann::json::array();
  std::ostringstream md;
  const bool seg = a.shadow_ray == "segment";
  md << "Command: `build/bin/raycore table3 --width " << a.width << " --height " << a.height
     << (seg ? " --shadow-ray segment" : "") << "`" << (seg ? "" : " (= `make table3`)") << ". "
     << a.width << " x " << a.height
     << " pixels, one primary and at most one shadow ray per pixel, spawn `none` (t_min = 2^-12 "
        "only), shadow rays "
     << (seg ? "as segments (direction light - hit, t in (t_min, 1): t_min is a fraction of the "
               "light distance)"
             : "with unit directions (t_min in world units)")
     << ". FP24 = rtz (RayCore's), FP32 = rne (IEEE). "
        "Counts are out of all pixels (the paper's 384,000 shadow rays); `shadow rays` is how "
        "many were actually spawned (a pixel that misses, or whose light is behind the surface, "
        "spawns none).\n\n";
  std::ostringstream t3, err;
  t3 << "| scene | 24-bit original | 24-bit VTU | reduction | 32-bit original | 32-bit VTU | reduction |\n"
        "|---|---|---|---|---|---|---|\n";
  err << "| scene | config | shadow rays | self-intersections | shadow errors (false shadow / light leak) | "
         "primary errors | median max-abs hit coordinate in the datapath | hit points behind their plane | "
         "self-intersections with the hit point behind | median distance of hit point from its plane (ulps) |\n"
         "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& sp : specs) {
    sim::RunOptions ro;
    ro.scene = sp.what;
    ro.width = a.width;
    ro.height = a.height;
    ro.threads = a.threads;
    ro.shadow_ray = a.shadow_ray;
    ro.shadow_hit = "closest";  // the paper's self-intersection count needs the nearest occluder
    sim::TraceConfig base = sim::trace_config(ro);
    const scenes::Scene scene = [&] {
      sim::Prepared p = sim::prepare(ro, base);  // validates; builds an fp24 image we rebuild below
      return p.scene;
    }();
    std::fprintf(stderr, "table3: %s: reference...\n", sp.what.c_str());
    const sim::Frame ref = reference::render(scene, a.width, a.height, a.threads);
    Cell cells[4];
    for (int i = 0; i < 4; ++i) {
      sim::TraceConfig c = base;
      c.format = cfgs[i].f;
      c.rounding = cfgs[i].r;
      c.vtu = cfgs[i].vtu;
      c.spawn.spawn = hls::Spawn::none;  // the paper's baseline; keeps --shadow-ray
      const hls::Image img = hls::build_image(scene.tris, c.format, c.rounding);
      sim::TraceStats st;
      const sim::Frame f = sim::trace_golden(img, scene.camera, scene.light, c, &st);
      cells[i].m = reference::compute_errors(f, ref, scene.tris);
      cells[i].median_coord = median_coord(f, scene.camera.position, c.vtu);
      cells[i].seconds = st.seconds;
      cells[i].side = sim::hit_side_stats(f, img, scene.camera, scene.light, c);
      std::fprintf(stderr, "table3: %s %s: %llu self-intersections\n", sp.what.c_str(),
                   sim::config_tag(c).c_str(), (unsigned long long)cells[i].m.self_intersections);
      nlohmann::json j = {{"scene", scene.name}, {"config", sim::config_json(c)},
                          {"errors", reference::to_json(cells[i].m)},
                          {"median_max_abs_hit_coordinate", cells[i].median_coord},
                          {"golden_seconds", st.seconds},
                          {"hit_side", sim::to_json(cells[i].side)}};
      out.push_back(j);
    }
    const uint64_t px = cells[0].m.pixels;
    auto si = [&](int i) { return cells[i].m.self_intersections; };
    t3 << "| " << sp.label << " (ours) | " << count_pct(si(0), px) << " | " << count_pct(si(1), px)
       << " | " << reduction(double(si(0)), double(si(1))) << " | " << count_pct(si(2), px) << " | "
       << count_pct(si(3), px) << " | " << reduction(double(si(2)), double(si(3))) << " |\n";
    const PaperRow& pr = kPaper[sp.paper];
    t3 << "| " << pr.scene << " (paper) | " << count_pct(uint64_t(pr.fp24_orig), 384000) << " | "
       << count_pct(uint64_t(pr.fp24_vtu), 384000) << " | "
       << reduction(double(pr.fp24_orig), double(pr.fp24_vtu)) << " | "
       << count_pct(uint64_t(pr.fp32_orig), 384000) << " | " << count_pct(uint64_t(pr.fp32_vtu), 384000)
       << " | " << reduction(double(pr.fp32_orig), double(pr.fp32_vtu)) << " |\n";
    const char* names[4] = {"24-bit original", "24-bit VTU", "32-bit original", "32-bit VTU"};
    for (int i = 0; i < 4; ++i) {
      const auto& m = cells[i].m;
      char coord[32];
      std::snprintf(coord, sizeof coord, "%.0f", cells[i].median_coord);
      err << "| " << scene.name << " | " << names[i] << " | " << m.shadow_rays << " | "
          << m.self_intersections << " | " << m.shadow_errors << " (" << m.false_shadow << " / "
          << m.light_leak << ") | " << m.primary_errors << " | " << coord << " | "
          << pct(cells[i].side.behind, cells[i].side.shadow_rays) << " | " << cells[i].side.self_behind
          << " | " << cells[i].side.median_plane_distance_ulps << " |\n";
    }
  }
  md << "### Self-intersections (the paper's Table 3 layout)\n\n" << t3.str()
     << "\n### All error metrics\n\n" << err.str();

  // Replace the section between the markers (or append it).
  const std::string mark = seg ? "table3-segment" : "table3";
  const std::string begin = "<!-- " + mark + ":begin -->", end = "<!-- " + mark + ":end -->";
  std::string doc;
  {
    std::ifstream is(a.results);
    if (is) doc.assign(std::istreambuf_iterator<char>(is), {});
  }
  const std::string section = begin + "\n" + md.str() + end;
  const size_t b = doc.find(begin), e = doc.find(end);
  if (b != std::string::npos && e != std::string::npos && e > b)
    doc.replace(b, e + end.size() - b, section);
  else
    doc += (doc.empty() ? "# Results\n\n" : "\n") +
           std::string(seg ? "## Table 3 with segment shadow rays\n\n" : "## The paper's Table 3\n\n") +
           section + "\n";
  if (!std::filesystem::path(a.results).parent_path().empty())
    std::filesystem::create_directories(std::filesystem::path(a.results).parent_path());
  std::ofstream os(a.results);
  if (!(os << doc)) throw UserError("cannot write '" + a.results + "'");
  if (!std::filesystem::path(a.json).parent_path().empty())
    std::filesystem::create_directories(std::filesystem::path(a.json).parent_path());
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
  c->add_option("--shadow-ray", a->shadow_ray, "unit or segment (see render --help)")
      ->check(CLI::IsMember({"unit", "segment"}))
      ->capture_default_str();
  c->callback([a] { run_table3(*a); });
}

}  // namespace
RAYCORE_COMMAND(register_table3);
}  // namespace raycore::cli
