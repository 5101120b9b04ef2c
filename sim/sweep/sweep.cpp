// sim/sweep/sweep.cpp - job list, reports, Pareto front and tables of the sweep (see sweep.h).
#include "sim/sweep/sweep.h"

#include "sim/golden/golden.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace raycore::sweep {

namespace fs = std::filesystem;

const std::vector<std::string>& paper_scenes() {
  static const std::vector<std::string> v = {"corridor", "sponza-paper", "sibenik-paper"};
  return v;
}
const std::vector<std::string>& hard_scenes() {
  static const std::vector<std::string> v = {"far", "grazing", "slivers", "coplanar", "origin-far-camera"};
  return v;
}
const std::vector<std::string>& spawn_names() {
  static const std::vector<std::string> v = {"none",        "skip-origin", "ulp-offset", "error-bound",
                                             "skip-offset", "skip-slab:2", "skip-back"};
  return v;
}

const std::vector<std::string>& store_names() {
  static const std::vector<std::string> v = {"world", "anchored"};
  return v;
}

std::vector<std::string> default_stores(const std::string& scene) {
  if (scene == "far" || scene == "origin-far-camera") return {"world", "anchored"};
  return {"world"};
}

SpawnSpec spawn_spec(const std::string& spec) {
  SpawnSpec sp;
  // The margins: "+m<E>", "+w<N>" after the strategy.
  const size_t plus = spec.find('+');
  const std::string s = spec.substr(0, plus);
  for (size_t p = plus; p != std::string::npos;) {
    const size_t q = spec.find('+', p + 1);
    const std::string t = spec.substr(p + 1, q == std::string::npos ? std::string::npos : q - p - 1);
    p = q;
    const std::string v = t.size() > 1 ? t.substr(1) : std::string();
    size_t used = 0;
    try {
      if (!t.empty() && t[0] == 'm') {
        const double e = std::stod(v, &used);
        if (used == v.size() && std::isfinite(e) && e >= 0 && e <= 1) {
          sp.margin = e == 0 ? std::string() : v;
          continue;
        }
      } else if (!t.empty() && t[0] == 'w') {
        const long n = std::stol(v, &used);
        if (used == v.size() && n >= 0 && n <= 64) {
          sp.widen = int(n);
          continue;
        }
      }
    } catch (const std::exception&) {
    }
    throw std::invalid_argument("spawn '" + spec + "': '+" + t +
                                "' is not a margin (+m<E>, E in [0, 1]; +w<N>, N in 0..64)");
  }
  const size_t c = s.find(':');
  sp.strategy = s.substr(0, c);
  if (!sim::spawn_uses_ulps(sim::spawn_from_string(sp.strategy)) && c != std::string::npos)
    throw std::invalid_argument("spawn '" + s + "': " + sp.strategy + " takes no ulps");
  if (c != std::string::npos) {
    const std::string n = s.substr(c + 1);
    size_t used = 0;
    long v = 0;
    try {
      v = std::stol(n, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (n.empty() || used != n.size() || v < 1 || v > 1000000)
      throw std::invalid_argument("spawn '" + s + "': ulps must be an integer from 1 to 1000000");
    sp.ulps = int(v);
  }
  return sp;
}

FormatSpec format_spec(const std::string& n) {
  if (n == "fp24-rtz") return {n, "fp24", "rtz"};
  if (n == "fp24-rne") return {n, "fp24", "rne"};
  if (n == "fp32" || n == "fp32-rne") return {"fp32", "fp32", "rne"};
  if (n == "fp32-rtz") return {n, "fp32", "rtz"};
  if (n == "fp24-raycore") return {n, "fp24", "raycore"};  // the lead's rounding; not a default
  throw std::invalid_argument("unknown format '" + n + "' (fp24-rtz, fp24-rne, fp32, fp32-rtz, fp24-raycore)");
}

namespace {

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

std::string path_arg(const std::string& p, bool keep) {
  return keep ? p : fs::absolute(p).lexically_normal().string();
}

void require_nonempty(const std::vector<std::string>& v, const char* what) {
  if (v.empty()) throw std::invalid_argument(std::string("empty list of ") + what + ": nothing to sweep");
  std::set<std::string> seen;
  for (const auto& s : v)
    if (!seen.insert(s).second) throw std::invalid_argument(std::string("duplicate ") + what + " '" + s + "'");
}

std::string self_exe() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("raycore") : p.string();
}

}  // namespace

std::vector<Job> make_jobs(const Options& in) {
  Options o = in;
  if (o.scenes.empty() && in.scenes.empty()) {
    o.scenes = paper_scenes();
    o.scenes.insert(o.scenes.end(), hard_scenes().begin(), hard_scenes().end());
  }
  if (o.formats.empty()) o.formats = {"fp24-rtz", "fp24-rne", "fp32"};
  if (o.vtu.empty()) o.vtu = {"off", "on"};
  if (o.spawns.empty()) o.spawns = spawn_names();
  require_nonempty(o.scenes, "scenes");
  require_nonempty(o.formats, "formats");
  require_nonempty(o.vtu, "VTU values");
  require_nonempty(o.spawns, "spawns");
  for (const auto& s : o.scenes)
    if (!contains(paper_scenes(), s) && !contains(hard_scenes(), s))
      throw std::invalid_argument("unknown scene '" + s + "' (corridor, sponza-paper, sibenik-paper, far, "
                                  "grazing, slivers, coplanar, origin-far-camera)");
  for (const auto& f : o.formats) format_spec(f);
  for (const auto& v : o.vtu)
    if (v != "on" && v != "off") throw std::invalid_argument("unknown VTU value '" + v + "' (on, off)");
  for (const auto& s : o.spawns) spawn_spec(s);
  if (!o.stores.empty()) require_nonempty(o.stores, "stores");
  for (const auto& s : o.stores)
    if (!contains(store_names(), s)) throw std::invalid_argument("unknown store '" + s + "' (world, anchored)");
  if (o.shadow_spawn != "front" && o.shadow_spawn != "all")
    throw std::invalid_argument("unknown shadow spawn '" + o.shadow_spawn + "' (front, all)");
  if (o.width < 1 || o.height < 1 || o.hard_width < 1 || o.hard_height < 1)
    throw std::invalid_argument("image sizes must be >= 1");
  const std::string exe = o.raycore.empty() ? self_exe() : o.raycore;

  auto scene_arg = [&](const std::string& s) {
    if (s == "sponza-paper" || s == "sibenik-paper") {
      const fs::path p = fs::path(o.scenes_dir) / (s + ".glb");
      if (!fs::exists(p))
        throw std::invalid_argument("scene file '" + p.string() + "' not found (--scenes-dir)");
      return path_arg(p.string(), o.keep_paths);
    }
    return s;  // a generator name
  };
  const std::string out = path_arg(o.out, o.keep_paths);
  auto base = [&](Job& j, const std::string& scene, const FormatSpec& f, const std::string& vtu,
                  const std::string& spawn, const std::string& store) {
    j.scene = scene;
    j.scene_arg = scene_arg(scene);
    j.format_name = f.name;
    j.format = f.format;
    j.rounding = f.rounding;
    j.vtu = vtu == "on";
    j.spawn = spawn;
    j.store = store;
    j.shadow_spawn = o.shadow_spawn;
    const SpawnSpec sp = spawn_spec(spawn);
    const bool paper = contains(paper_scenes(), scene);
    j.width = paper ? o.width : o.hard_width;
    j.height = paper ? o.height : o.hard_height;
    // World ids are those of the sweeps before --store; anchored adds a suffix.
    j.id = scene + "-" + f.name + "-vtu" + vtu + "-" + sp.strategy + (sp.ulps ? std::to_string(sp.ulps) : "") +
           (sp.margin.empty() ? "" : "-m" + sp.margin) + (sp.widen ? "-w" + std::to_string(sp.widen) : "") +
           (store == "world" ? "" : "-" + store);
    j.argv = {exe, j.kind, j.scene_arg, "--format", f.format, "--rounding", f.rounding, "--vtu", vtu,
              "--spawn", sp.strategy, "--width", std::to_string(j.width), "--height", std::to_string(j.height),
              "--threads", std::to_string(o.threads), "--quiet",
              // the error study counts self-intersections: the nearest occluder is needed
              "--shadow-hit", "closest", "--shadow-spawn", o.shadow_spawn, "--store", store};
    if (sp.ulps) j.argv.insert(j.argv.end(), {"--spawn-ulps", std::to_string(sp.ulps)});
    if (!sp.margin.empty()) j.argv.insert(j.argv.end(), {"--bary-margin", sp.margin});
    if (sp.widen) j.argv.insert(j.argv.end(), {"--trv-widen", std::to_string(sp.widen)});
  };

  std::vector<Job> jobs;
  // Store outermost within a scene: the world configurations first, in the order of the sweeps
  // before --store, then the anchored ones.
  for (const auto& s : o.scenes)
    for (const auto& st : o.stores.empty() ? default_stores(s) : o.stores)
      for (const auto& fn : o.formats)
        for (const auto& v : o.vtu)
          for (const auto& sp : o.spawns) {
            Job j;
            j.kind = "simulate";
            base(j, s, format_spec(fn), v, sp, st);
            j.json = out + "/jobs/" + j.id + ".json";
            j.png = out + "/jobs/" + j.id + ".png";
            j.argv.insert(j.argv.end(), {"--report", j.json, "--png", j.png});
            jobs.push_back(j);
          }
  // Error maps: default sponza-paper and sibenik-paper where swept, the paper's two FP24
  // configurations and the two best (docs/robustness.md, "Beating the paper").
  std::vector<std::string> ms = o.map_scenes, mc = o.map_configs;
  if (ms.empty())
    for (const auto& s : {"sponza-paper", "sibenik-paper"})
      if (contains(o.scenes, s)) ms.push_back(s);
  if (mc.empty())
    mc = {"fp24-rtz:off:none", "fp24-rtz:on:none", "fp24-rtz:on:skip-slab:2", "fp24-rne:on:skip-back"};
  if (contains(ms, "none")) ms.clear();
  for (const auto& s : ms) {
    if (!contains(paper_scenes(), s) && !contains(hard_scenes(), s))
      throw std::invalid_argument("unknown error-map scene '" + s + "'");
    for (const auto& c : mc) {
      const size_t a = c.find(':'), b = c.find(':', a == std::string::npos ? a : a + 1);
      if (a == std::string::npos || b == std::string::npos)
        throw std::invalid_argument("error-map configuration '" + c + "' is not format:vtu:spawn");
      const std::string f = c.substr(0, a), v = c.substr(a + 1, b - a - 1), sp = c.substr(b + 1);
      if (v != "on" && v != "off") throw std::invalid_argument("unknown VTU value '" + v + "' in '" + c + "'");
      try {
        spawn_spec(sp);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string(e.what()) + " in '" + c + "'");
      }
      Job j;
      j.kind = "errormap";
      base(j, s, format_spec(f), v, sp, "world");
      j.json = out + "/maps/" + j.id + ".json";
      j.png = out + "/maps/" + j.id + ".png";
      j.argv.insert(j.argv.end(), {"--report", j.json, "--png", j.png});
      jobs.push_back(j);
    }
  }
  return jobs;
}

std::string shell_quote(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                                        "_-./:=,+@%") == std::string::npos)
    return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string command_line(const Job& j) {
  std::string l;
  for (const auto& a : j.argv) l += (l.empty() ? "" : " ") + shell_quote(a);
  return l;
}

nlohmann::json manifest_json(const Options& o, const std::vector<Job>& jobs) {
  nlohmann::json js = nlohmann::json::array();
  for (const auto& j : jobs)
    js.push_back({{"kind", j.kind}, {"id", j.id}, {"scene", j.scene}, {"scene_arg", j.scene_arg},
                  {"format_name", j.format_name}, {"format", j.format}, {"rounding", j.rounding},
                  {"vtu", j.vtu}, {"spawn", j.spawn}, {"store", j.store}, {"shadow_spawn", j.shadow_spawn},
                  {"width", j.width}, {"height", j.height},
                  {"json", j.json}, {"png", j.png}, {"command", command_line(j)}});
  return {{"tool", "raycore sweep"}, {"out", o.out}, {"shadow_spawn", o.shadow_spawn}, {"jobs", js}};
}

std::vector<Job> jobs_from_manifest(const nlohmann::json& m) {
  if (!m.contains("jobs") || !m["jobs"].is_array()) throw std::runtime_error("manifest has no \"jobs\" array");
  std::vector<Job> v;
  for (const auto& x : m["jobs"]) {
    Job j;
    try {
      j.kind = x.at("kind");
      j.id = x.at("id");
      j.scene = x.at("scene");
      j.scene_arg = x.at("scene_arg");
      j.format_name = x.at("format_name");
      j.format = x.at("format");
      j.rounding = x.at("rounding");
      j.vtu = x.at("vtu");
      j.spawn = x.at("spawn");
      j.store = x.value("store", std::string("world"));  // manifests before --store
      j.shadow_spawn = x.value("shadow_spawn", std::string("front"));
      j.width = x.at("width");
      j.height = x.at("height");
      j.json = x.at("json");
      j.png = x.at("png");
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error(std::string("manifest job: ") + e.what());
    }
    v.push_back(j);
  }
  if (v.empty()) throw std::runtime_error("manifest lists no jobs");
  return v;
}

double Area::get(const std::string& m, const std::string& f, const std::string& r) const {
  auto it = cells.find(m + "/" + f + "/" + r);
  return it == cells.end() ? -1.0 : it->second;
}

Area read_area(const std::string& path) {
  std::ifstream is(path);
  if (!is) throw std::runtime_error("cannot read area file '" + path + "'");
  Area a;
  std::string line;
  int n = 0;
  while (std::getline(is, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    std::string m, f, r;
    double c = 0;
    if (!(ls >> m >> f >> r >> c) || c < 0)
      throw std::runtime_error(path + ":" + std::to_string(n) + ": expected 'module format rounding cells'");
    a.cells[m + "/" + f + "/" + r] = c;
  }
  if (a.cells.empty()) throw std::runtime_error("area file '" + path + "' has no rows");
  return a;
}

AddedCells added_cells(const Area& a, const std::string& f, const std::string& r, bool vtu,
                       const std::string& spawn) {
  AddedCells c;
  // The units whose datapath width follows the format and rounding, and that have RTL: the ist and
  // the trv datapath (the hit unit has none; the vtu is counted whole below).
  for (const char* unit : {"ist", "trv"}) {
    const double x = a.get(unit, f, r), x0 = a.get(unit, "fp24", "rtz");
    if (x < 0 || x0 < 0 || c.format < 0)
      c.format = -1;
    else
      c.format += x - x0;
  }
  c.vtu = vtu ? a.get("vtu", f, r) : 0.0;
  const std::string st = spawn_spec(spawn).strategy;
  c.spawn = st == "none" ? 0.0 : a.get("spawn-" + st, f, r);
  c.total = c.format < 0 || c.vtu < 0 || c.spawn < 0 ? -1 : c.format + c.vtu + c.spawn;
  return c;
}

std::vector<bool> pareto_front(const std::vector<std::pair<double, double>>& p) {
  std::vector<bool> on(p.size(), true);
  for (size_t i = 0; i < p.size(); ++i)
    for (size_t k = 0; k < p.size() && on[i]; ++k) {
      if (k == i) continue;
      const bool no_worse = p[k].first <= p[i].first && p[k].second >= p[i].second;
      const bool better = p[k].first < p[i].first || p[k].second > p[i].second;
      if (no_worse && better) on[i] = false;
    }
  return on;
}

namespace {

const nlohmann::json& at(const nlohmann::json& j, const char* key, const Job& job) {
  if (!j.is_object() || !j.contains(key))
    throw std::runtime_error("report '" + job.json + "' has no \"" + key + "\"");
  return j[key];
}

}  // namespace

Row read_row(const Job& job, const nlohmann::json& r) {
  Row w;
  w.job = job;
  const auto& e = at(r, "errors", job);
  try {
    w.pixels = e.at("pixels");
    w.shadow_rays = e.at("shadow_rays");
    w.self_intersections = e.at("self_intersections");
    w.shadow_errors = e.at("shadow_errors");
    w.false_shadow = e.at("false_shadow");
    w.false_shadow_self = e.value("false_shadow_self", uint64_t(0));
    w.false_shadow_no_ray = e.value("false_shadow_no_ray", uint64_t(0));
    w.light_leak = e.at("light_leak");
    w.primary_errors = e.at("primary_errors");
    const auto& hw = at(r, "hardware", job);
    w.cycles = hw.at("cycles");
    w.rays_per_cycle = hw.at("rays_per_cycle");
    w.mrays_per_s = hw.at("mrays_per_s");
    w.golden_match = at(r, "golden_match", job).get<bool>();
    w.sim_seconds = r.contains("sim") ? r["sim"].value("wall_seconds", 0.0) : 0.0;
  } catch (const nlohmann::json::exception& x) {
    throw std::runtime_error("report '" + job.json + "': " + x.what());
  }
  w.self_intersections_front = e.value("self_intersections_front", w.self_intersections);
  w.error_pixels = w.shadow_errors + w.primary_errors;
  w.error_pct = w.pixels ? 100.0 * double(w.error_pixels) / double(w.pixels) : 0.0;
  if (r.contains("errors_stored")) {
    const auto& s = r["errors_stored"];
    try {
      w.stored.self_intersections = s.at("self_intersections");
      w.stored.shadow_errors = s.at("shadow_errors");
      w.stored.primary_errors = s.at("primary_errors");
    } catch (const nlohmann::json::exception& x) {
      throw std::runtime_error("report '" + job.json + "': errors_stored: " + x.what());
    }
    w.stored.error_pixels = w.stored.shadow_errors + w.stored.primary_errors;
    w.stored.error_pct = w.pixels ? 100.0 * double(w.stored.error_pixels) / double(w.pixels) : 0.0;
    auto d = [](uint64_t a, uint64_t b) { return int64_t(a) - int64_t(b); };
    w.storage = {d(w.self_intersections, w.stored.self_intersections), d(w.shadow_errors, w.stored.shadow_errors),
                 d(w.primary_errors, w.stored.primary_errors), d(w.error_pixels, w.stored.error_pixels)};
    w.has_stored = true;
  }
  if (r.contains("errors_by_stage") && !r["errors_by_stage"].contains("error")) {
    const auto& b = r["errors_by_stage"];
    try {
      auto st = [&](const char* k) { return StageErrors{b.at(k).at("primary").get<uint64_t>(), b.at(k).at("shadow").get<uint64_t>()}; };
      w.stages.storage = st("storage");
      w.stages.ray_generation = st("ray_generation");
      w.stages.traversal_intersection = st("traversal_intersection");
      w.stages.spawn = st("spawn");
      const auto& t = b.at("traversal_intersection");
      w.stages.traversal_vtu = t.value("vtu_primary", uint64_t(0)) + t.value("vtu_shadow", uint64_t(0));
    } catch (const nlohmann::json::exception& x) {
      throw std::runtime_error("report '" + job.json + "': errors_by_stage: " + x.what());
    }
    w.has_stages = true;
  }
  w.ok = true;
  return w;
}

void mark_pareto(std::vector<Row>& rows) {
  std::map<std::string, std::vector<size_t>> by_scene;
  for (size_t i = 0; i < rows.size(); ++i)
    if (rows[i].ok) by_scene[rows[i].job.scene].push_back(i);
  for (auto& [scene, idx] : by_scene) {
    std::vector<std::pair<double, double>> p;
    for (size_t i : idx) p.emplace_back(rows[i].error_pct, rows[i].rays_per_cycle);
    const auto on = pareto_front(p);
    for (size_t k = 0; k < idx.size(); ++k) rows[idx[k]].pareto = on[k];
  }
}

namespace {

std::string num(double v, int prec) {
  if (v < 0) return "";
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", prec, v);
  return b;
}
std::string cells_str(double v) { return v < 0 ? "?" : num(v, 0); }

std::vector<std::string> scene_order(const std::vector<Row>& rows) {
  std::vector<std::string> s;
  for (const auto& r : rows)
    if (!contains(s, r.job.scene)) s.push_back(r.job.scene);
  return s;
}

bool same_config(const Job& a, const Job& b) {
  return a.format_name == b.format_name && a.vtu == b.vtu && a.spawn == b.spawn && a.store == b.store;
}

// The configurations (format, VTU, spawn, store) of the rows of `scenes`, in the order they first
// appear (the job order: world before anchored within a scene).
std::vector<const Row*> configs(const std::vector<Row>& rows, const std::vector<std::string>& scenes,
                                const std::string& format = "") {
  std::vector<const Row*> v;
  for (const auto& r : rows) {
    if (!contains(scenes, r.job.scene) || (!format.empty() && r.job.format != format)) continue;
    bool seen = false;
    for (const Row* c : v) seen = seen || same_config(c->job, r.job);
    if (!seen) v.push_back(&r);
  }
  return v;
}

const Row* find_row(const std::vector<Row>& rows, const std::string& scene, const Job& cfg) {
  const Row* m = nullptr;
  for (const auto& r : rows)
    if (r.job.scene == scene && same_config(r.job, cfg)) m = &r;
  return m;
}

// "total (arithmetic)", or the total alone without arithmetic counts.
std::string two(uint64_t total, uint64_t arith, bool has) {
  return std::to_string(total) + (has ? " (" + std::to_string(arith) + ")" : std::string());
}

// "storage / ray gen. / trav.+int. (of which the VTU's geometry) / spawn" error pixels (primary +
// shadow), "-" for a report without errors_by_stage.
std::string stages_str(const Row& r) {
  if (!r.has_stages) return "-";
  const StageBudgetCounts& b = r.stages;
  auto t = [](const StageErrors& e) { return std::to_string(e.primary + e.shadow); };
  return t(b.storage) + " / " + t(b.ray_generation) + " / " + t(b.traversal_intersection) + " (" +
         std::to_string(b.traversal_vtu) + ") / " + t(b.spawn);
}

}  // namespace

std::string csv(const std::vector<Row>& rows) {
  std::ostringstream os;
  os << "scene,format,rounding,vtu,spawn,store,shadow_spawn,width,height,pixels,shadow_rays,self_intersections,"
        "shadow_errors,false_shadow,false_shadow_self,false_shadow_no_ray,light_leak,primary_errors,"
        "error_pixels,error_pct,self_intersections_front,"
        "self_intersections_stored,shadow_errors_stored,primary_errors_stored,error_pixels_stored,error_pct_stored,"
        "self_intersections_storage,shadow_errors_storage,primary_errors_storage,error_pixels_storage,"
        "cycles,rays_per_cycle,mrays_per_s,golden_match,cells_format,cells_vtu,"
        "cells_spawn,cells_added,pareto,sim_wall_seconds,"
        "storage_primary,storage_shadow,ray_generation_primary,ray_generation_shadow,"
        "traversal_intersection_primary,traversal_intersection_shadow,traversal_intersection_vtu,"
        "spawn_primary,spawn_shadow\n";
  for (const auto& r : rows) {
    const Job& j = r.job;
    auto u = [&](uint64_t v) { return r.has_stored ? std::to_string(v) : std::string(); };
    auto i = [&](int64_t v) { return r.has_stored ? std::to_string(v) : std::string(); };
    os << j.scene << "," << j.format << "," << j.rounding << "," << (j.vtu ? "on" : "off") << ","
       << j.spawn << "," << j.store << "," << j.shadow_spawn << "," << j.width << "," << j.height << ","
       << r.pixels << "," << r.shadow_rays << ","
       << r.self_intersections << "," << r.shadow_errors << "," << r.false_shadow << ","
       << r.false_shadow_self << "," << r.false_shadow_no_ray << "," << r.light_leak << ","
       << r.primary_errors << "," << r.error_pixels << "," << num(r.error_pct, 5) << ","
       << r.self_intersections_front << "," << u(r.stored.self_intersections) << ","
       << u(r.stored.shadow_errors) << "," << u(r.stored.primary_errors) << "," << u(r.stored.error_pixels)
       << "," << (r.has_stored ? num(r.stored.error_pct, 5) : "") << "," << i(r.storage.self_intersections)
       << "," << i(r.storage.shadow_errors) << "," << i(r.storage.primary_errors) << ","
       << i(r.storage.error_pixels) << "," << r.cycles << ","
       << num(r.rays_per_cycle, 6) << "," << num(r.mrays_per_s, 3) << ","
       << (r.golden_match ? "true" : "false") << "," << num(r.cells.format, 0) << ","
       << num(r.cells.vtu, 0) << "," << num(r.cells.spawn, 0) << "," << num(r.cells.total, 0) << ","
       << (r.pareto ? 1 : 0) << "," << num(r.sim_seconds, 2);
    const StageBudgetCounts& b = r.stages;
    for (uint64_t v : {b.storage.primary, b.storage.shadow, b.ray_generation.primary, b.ray_generation.shadow,
                       b.traversal_intersection.primary, b.traversal_intersection.shadow, b.traversal_vtu,
                       b.spawn.primary, b.spawn.shadow})
      os << "," << (r.has_stages ? std::to_string(v) : std::string());
    os << "\n";
  }
  return os.str();
}

nlohmann::json rows_json(const std::vector<Row>& rows) {
  nlohmann::json a = nlohmann::json::array();
  auto cell = [](double v) { return v < 0 ? nlohmann::json(nullptr) : nlohmann::json(v); };
  for (const auto& r : rows) {
    const Job& j = r.job;
    nlohmann::json stored = nullptr, storage = nullptr;
    if (r.has_stored) {
      stored = {{"self_intersections", r.stored.self_intersections}, {"shadow_errors", r.stored.shadow_errors},
                {"primary_errors", r.stored.primary_errors}, {"error_pixels", r.stored.error_pixels},
                {"error_pct", r.stored.error_pct}};
      storage = {{"self_intersections", r.storage.self_intersections},
                 {"shadow_errors", r.storage.shadow_errors}, {"primary_errors", r.storage.primary_errors},
                 {"error_pixels", r.storage.error_pixels}};
    }
    nlohmann::json stages = nullptr;
    if (r.has_stages) {
      auto st = [](const StageErrors& e) {
        return nlohmann::json{{"primary", e.primary}, {"shadow", e.shadow}, {"total", e.primary + e.shadow}};
      };
      stages = {{"storage", st(r.stages.storage)},
                {"ray_generation", st(r.stages.ray_generation)},
                {"traversal_intersection", st(r.stages.traversal_intersection)},
                {"spawn", st(r.stages.spawn)}};
      stages["traversal_intersection"]["vtu"] = r.stages.traversal_vtu;
    }
    a.push_back({{"scene", j.scene},
                 {"config", {{"format", j.format}, {"rounding", j.rounding}, {"vtu", j.vtu},
                             {"spawn", j.spawn}, {"store", j.store}, {"shadow_spawn", j.shadow_spawn},
                             {"width", j.width}, {"height", j.height}}},
                 {"errors_stored", stored},
                 {"errors_storage", storage},
                 {"errors_by_stage", stages},
                 {"errors", {{"pixels", r.pixels}, {"shadow_rays", r.shadow_rays},
                             {"self_intersections", r.self_intersections},
                             {"self_intersections_front", r.self_intersections_front},
                             {"shadow_errors", r.shadow_errors}, {"false_shadow", r.false_shadow},
                             {"false_shadow_self", r.false_shadow_self},
                             {"false_shadow_no_ray", r.false_shadow_no_ray}, {"light_leak", r.light_leak},
                             {"primary_errors", r.primary_errors}, {"error_pixels", r.error_pixels},
                             {"error_pct", r.error_pct}}},
                 {"hardware", {{"cycles", r.cycles}, {"rays_per_cycle", r.rays_per_cycle},
                               {"mrays_per_s", r.mrays_per_s}}},
                 {"golden_match", r.golden_match},
                 {"added_cells", {{"format", cell(r.cells.format)}, {"vtu", cell(r.cells.vtu)},
                                  {"spawn", cell(r.cells.spawn)}, {"total", cell(r.cells.total)}}},
                 {"pareto", r.pareto},
                 {"report", j.json}});
  }
  return a;
}

std::string markdown(const std::vector<Row>& rows) {
  std::ostringstream os;
  for (const auto& scene : scene_order(rows)) {
    const Row* first = nullptr;
    for (const auto& r : rows)
      if (r.job.scene == scene) {
        first = &r;
        break;
      }
    os << "#### " << scene << " (" << first->job.width << " x " << first->job.height << ")\n\n"
       << "| format | VTU | spawn | store | self-int. | shadow err. (false / of which self / no ray / leak) | "
          "arith. shadow err. | primary err. (arith.) | error pixels (arith.) | error % (arith.) | cycles | "
          "rays/cycle | golden match | added cells (format + VTU + spawn) | Pareto | error pixels by stage: "
          "storage / ray gen. / trav.+int. (VTU) / spawn |\n"
          "|---|---|---|---|---:|---|---:|---:|---:|---:|---:|---:|---|---|---|---|\n";
    for (const auto& r : rows) {
      if (r.job.scene != scene) continue;
      const Job& j = r.job;
      os << "| " << j.format_name << " | " << (j.vtu ? "on" : "off") << " | " << j.spawn << " | " << j.store
         << " | " << r.self_intersections << " | " << r.shadow_errors << " (" << r.false_shadow << " / "
         << r.false_shadow_self << " / " << r.false_shadow_no_ray << " / " << r.light_leak << ") | "
         << (r.has_stored ? std::to_string(r.stored.shadow_errors) : "-") << " | "
         << two(r.primary_errors, r.stored.primary_errors, r.has_stored) << " | "
         << two(r.error_pixels, r.stored.error_pixels, r.has_stored) << " | " << num(r.error_pct, 3)
         << (r.has_stored ? " (" + num(r.stored.error_pct, 3) + ")" : "") << " | " << r.cycles
         << " | " << num(r.rays_per_cycle, 4) << " | " << (r.golden_match ? "yes" : "**NO**") << " | "
         << cells_str(r.cells.total) << " (" << cells_str(r.cells.format) << " + " << cells_str(r.cells.vtu)
         << " + " << cells_str(r.cells.spawn) << ") | " << (r.pareto ? "**P**" : "") << " | " << stages_str(r)
         << " |\n";
    }
    os << "\n";
  }
  return os.str();
}

std::string compact_markdown(const std::vector<Row>& rows, const std::vector<std::string>& scenes) {
  const auto sc = scenes_present(rows, scenes);
  std::ostringstream os;
  os << "| format | VTU | spawn | store | added cells |";
  for (const auto& s : sc) os << " " << s << " self / shadow (arith.) / error px (arith.) / rays/cyc |";
  os << "\n|---|---|---|---|---:|";
  for (size_t i = 0; i < sc.size(); ++i) os << "---|";
  os << "\n";
  // One row per configuration, in the order they first appear among these scenes' rows.
  for (const Row* c : configs(rows, sc)) {
    os << "| " << c->job.format_name << " | " << (c->job.vtu ? "on" : "off") << " | " << c->job.spawn
       << " | " << c->job.store << " | " << cells_str(c->cells.total) << " |";
    for (const auto& s : sc) {
      const Row* m = find_row(rows, s, c->job);
      if (!m) {
        os << " - |";
        continue;
      }
      const bool h = m->has_stored;
      os << " " << m->self_intersections << " / " << two(m->shadow_errors, m->stored.shadow_errors, h) << " / "
         << (m->pareto ? "**" : "") << m->error_pixels << (m->pareto ? "**" : "")
         << (h ? " (" + std::to_string(m->stored.error_pixels) + ")" : "") << " / " << num(m->rays_per_cycle, 4)
         << (m->golden_match ? "" : " (!)") << " |";
    }
    os << "\n";
  }
  return os.str();
}

TargetCheck check_target(const std::vector<Row>& rows, const Row& m, const TargetSpec& t) {
  TargetCheck c;
  Job base = m.job, none = m.job;
  base.format_name = t.base_format;
  base.vtu = t.base_vtu;
  base.spawn = t.base_spawn;
  base.store = t.base_store;
  none.spawn = t.base_spawn;
  const Row* b = find_row(rows, m.job.scene, base);
  const Row* n = find_row(rows, m.job.scene, none);
  if (!m.ok || m.pixels == 0) return c;
  const double px = double(m.pixels);
  if (b && b->ok && b->rays_per_cycle > 0) {
    c.have = true;
    c.shadow_pct = 100.0 * double(m.shadow_errors) / px;
    c.speed = m.rays_per_cycle / b->rays_per_cycle;
    c.met6 = m.self_intersections == 0 && c.shadow_pct <= t.max_shadow_pct && c.speed >= 1.0 - t.max_slowdown;
  }
  if (m.has_stored && n && n->ok && n->rays_per_cycle > 0) {
    c.have15 = true;
    c.arith_shadow_pct = 100.0 * double(m.stored.shadow_errors) / px;
    c.speed_none = m.rays_per_cycle / n->rays_per_cycle;
    // <= 0.01% of the pixels as a count: 38 of 384000 (800 x 480), not 38.4 rounded up.
    const double max_count = std::floor(t.max_shadow_pct / 100.0 * px + 1e-9);
    c.met15 = m.self_intersections == 0 && double(m.stored.shadow_errors) <= max_count &&
              c.speed_none >= 1.0 - t.max_slowdown;
  }
  return c;
}

namespace {
std::string speed_str(double s) { return (s < 1.0 ? "-" : "+") + num(100.0 * std::fabs(s - 1.0), 2) + "%"; }
}  // namespace

std::string target_markdown(const std::vector<Row>& rows, const std::vector<std::string>& scenes,
                            const TargetSpec& t) {
  const auto sc = scenes_present(rows, scenes);
  std::ostringstream os;
  os << "| format | VTU | spawn | store |";
  for (const auto& s : sc) os << " " << s << " self / shadow % / speed / arith. shadow % / vs none |";
  os << " issue 6 met on | issue 15 met on |\n|---|---|---|---|";
  for (size_t i = 0; i < sc.size(); ++i) os << "---|";
  os << "---|---|\n";
  for (const Row* c : configs(rows, sc, t.format)) {
    os << "| " << c->job.format_name << " | " << (c->job.vtu ? "on" : "off") << " | " << c->job.spawn << " | "
       << c->job.store << " |";
    std::string meets, meets15;
    for (const auto& s : sc) {
      const Row* m = find_row(rows, s, c->job);
      const TargetCheck k = m ? check_target(rows, *m, t) : TargetCheck();
      if (!m || (!k.have && !k.have15)) {
        os << " - |";
        continue;
      }
      os << " " << m->self_intersections << " / ";
      if (k.have)
        os << (k.met6 ? "**" : "") << num(k.shadow_pct, 4) << (k.met6 ? "**" : "") << " / " << speed_str(k.speed);
      else
        os << "- / -";
      os << " / ";
      if (k.have15)
        os << (k.met15 ? "**" : "") << num(k.arith_shadow_pct, 4) << (k.met15 ? "**" : "") << " / "
           << speed_str(k.speed_none);
      else
        os << "- / -";
      os << " |";
      if (k.met6) meets += (meets.empty() ? "" : ", ") + s;
      if (k.met15) meets15 += (meets15.empty() ? "" : ", ") + s;
    }
    os << " " << (meets.empty() ? "-" : meets) << " | " << (meets15.empty() ? "-" : meets15) << " |\n";
  }
  return os.str();
}

std::vector<std::string> scenes_present(const std::vector<Row>& rows, const std::vector<std::string>& want) {
  std::vector<std::string> v;
  for (const auto& s : want)
    for (const auto& r : rows)
      if (r.job.scene == s) {
        v.push_back(s);
        break;
      }
  return v;
}

std::string plot_data(const std::vector<Row>& rows, std::vector<std::string>* order) {
  std::ostringstream os;
  const auto so = scene_order(rows);
  if (order) *order = so;
  bool first = true;
  for (const auto& s : so) {
    if (!first) os << "\n\n";
    first = false;
    os << "# " << s << "\n# error_pct rays_per_cycle pareto format vtu spawn label store\n";
    // Pareto points sorted by error, so a line through them draws the front.
    std::vector<const Row*> v;
    for (const auto& r : rows)
      if (r.job.scene == s && r.ok) v.push_back(&r);
    std::stable_sort(v.begin(), v.end(), [](const Row* a, const Row* b) {
      return a->pareto != b->pareto ? a->pareto > b->pareto : a->error_pct < b->error_pct;
    });
    for (const Row* r : v) {
      const Job& j = r->job;
      os << num(r->error_pct, 6) << " " << num(r->rays_per_cycle, 6) << " " << (r->pareto ? 1 : 0) << " "
         << j.format_name << " " << (j.vtu ? "on" : "off") << " " << j.spawn << " " << j.format_name
         << (j.vtu ? "/vtu/" : "/-/") << j.spawn << (j.store == "world" ? "" : "/" + j.store) << " " << j.store
         << "\n";
    }
  }
  return os.str();
}

}  // namespace raycore::sweep
