// sim/sweep/throughput.cpp - see throughput.h.
#include "sim/sweep/throughput.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "sim/sweep/sweep.h"

namespace raycore::sweep {

std::vector<std::string> TpConfig::args() const {
  return {"--trv-pipes",   std::to_string(trv_pipes), "--ist-units",  std::to_string(ist_units),
          "--rays-in-flight", std::to_string(rays),   "--stack-depth", std::to_string(stack),
          "--trv-fuse",    fuse ? "on" : "off",       "--l2-kb",      std::to_string(l2_kb),
          "--mailbox",     std::to_string(mailbox),   "--node-cache-kb", std::to_string(node_kb),
          "--shadow-hit",  any_hit ? "any" : "closest"};
}

const std::vector<TpConfig>& tp_configs() {
  static const std::vector<TpConfig> all = [] {
    std::vector<TpConfig> v;
    // The ladder: RayCore-like baseline (one trv and one ist per RTU, closest-hit shadow rays, no
    // L2), then one lever at a time on top of the step before.
    TpConfig c;
    c.any_hit = false;
    auto step = [&](const char* name, const char* lever) {
      c.name = name;
      c.lever = lever;
      c.ladder = true;
      v.push_back(c);
    };
    step("base", "one trv and one ist per RTU, closest-hit shadow rays, 64 rays, no L2");
    c.any_hit = true;
    step("any-hit", "shadow rays end at the first leaf with a hit");
    c.fuse = true;
    step("fuse", "list fetch fused into the leaf's node step, node fetch into the pop");
    c.trv_pipes = 2;
    step("trv2", "2 trv pipes (2-port node and list caches)");
    c.ist_units = 2;
    step("ist2", "2 ist units (2-port triangle cache)");
    c.trv_pipes = 4;
    step("trv4", "4 trv pipes");
    c.rays = 96;
    step("rays96", "96 rays in flight");
    c.l2_kb = 256;
    step("l2-256k", "256 KB L2 shared by the 6 RTUs");
    // Issue 26 part 2: sibenik-paper's 61-65 passes and corridor's 40 tests per ray saturate 4 trv
    // pipes and 2 ist units (95% and 99% busy) below 0.08 rays/cycle: more of both.
    c.ist_units = 4;
    step("ist4", "4 ist units (4-port triangle cache)");
    c.trv_pipes = 5;
    step("trv5", "5 trv pipes (5-port node and list caches)");
    c.node_kb = 32;
    step("node32k", "32 KB node cache (fewer passes lost to node misses)");
    // Issue 26 part 2's DRAM budget at the timed clock: sponza-paper's 3.0 bytes per ray are 8%
    // above its first touches (2.8) with 256 KB; 1.10 GB/s at 541 MHz, 1.03 with 512 KB.
    c.l2_kb = 512;
    step("l2-512k", "512 KB L2 (fewer lines fetched twice; the defaults from here)");
    c.stack = 16;
    step("stack16", "16-entry stacks (the three scenes need 11-14)");
    c.mailbox = 8;
    step("mailbox8", "8-entry mailbox per ray (a triangle is not tested twice)");
    // The grid (fused, any-hit, 96 rays, 16-entry stacks, the 16 KB node cache).
    std::set<std::vector<std::string>> seen;
    for (const auto& x : v) seen.insert(x.args());
    for (int l2 : {0, 256})
      for (int p : {1, 2, 3, 4, 5, 6})
        for (int i : {1, 2, 3, 4}) {
          TpConfig g;
          g.trv_pipes = p;
          g.ist_units = i;
          g.rays = 96;
          g.stack = 16;
          g.fuse = true;
          g.l2_kb = l2;
          g.name = "p" + std::to_string(p) + "i" + std::to_string(i) + (l2 ? "-l2" : "");
          if (seen.insert(g.args()).second) v.push_back(g);
        }
    return v;
  }();
  return all;
}

TpArea fit_tp_area(const std::vector<TpAreaPoint>& pts) {
  if (pts.size() < 3)
    throw std::runtime_error("area model: " + std::to_string(pts.size()) +
                             " synthesised configurations, at least 3 needed (make area-configs)");
  // Normal equations of logic = a + b p + c i.
  double m[3][4] = {};
  for (const auto& q : pts) {
    const double x[3] = {1.0, double(q.pipes), double(q.ist)};
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) m[r][k] += x[r] * x[k];
      m[r][3] += x[r] * q.nand2;
    }
  }
  for (int col = 0; col < 3; ++col) {  // Gauss-Jordan with partial pivoting
    int piv = col;
    for (int r = col + 1; r < 3; ++r)
      if (std::fabs(m[r][col]) > std::fabs(m[piv][col])) piv = r;
    if (std::fabs(m[piv][col]) < 1e-9)
      throw std::runtime_error("area model: the synthesised configurations do not vary trv pipes and ist units "
                               "independently");
    for (int k = 0; k < 4; ++k) std::swap(m[col][k], m[piv][k]);
    for (int r = 0; r < 3; ++r) {
      if (r == col) continue;
      const double f = m[r][col] / m[col][col];
      for (int k = 0; k < 4; ++k) m[r][k] -= f * m[col][k];
    }
  }
  TpArea t;
  t.a = m[0][3] / m[0][0];
  t.b = m[1][3] / m[1][1];
  t.c = m[2][3] / m[2][2];
  t.points = pts;
  for (const auto& q : pts) {
    const double e = t.logic(q.pipes, q.ist) / q.nand2 - 1;
    if (!(std::fabs(e) <= kAreaModelTolerance)) {
      char b[160];
      std::snprintf(b, sizeof b, "area model: %s (%d pipes x %d ist) synthesised %.0f NAND2 eq., modelled %.0f (%+.1f%%, "
                    "over %.0f%%)", q.config.c_str(), q.pipes, q.ist, q.nand2, t.logic(q.pipes, q.ist), 100 * e,
                    100 * kAreaModelTolerance);
      throw std::runtime_error(b);
    }
  }
  return t;
}

TpArea read_tp_area(const std::string& path) {
  std::ifstream is(path);
  if (!is) throw std::runtime_error("cannot read area table '" + path + "' (make area-configs writes it)");
  std::vector<TpAreaPoint> pts;
  std::string line;
  while (std::getline(is, line)) {
    // | config | PIPES | IST | cells | FFs | NAND2 eq. | SRAM bits | yosys s |
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, '|')) {
      const size_t b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
      f.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    if (f.size() < 7 || f[1].empty() || f[1] == "config" || f[1][0] == '-') continue;
    TpAreaPoint q;
    q.config = f[1];
    try {
      q.pipes = std::stoi(f[2]);
      q.ist = std::stoi(f[3]);
      q.nand2 = std::stod(f[6]);
    } catch (const std::exception&) {
      continue;  // a run that did not finish
    }
    if (q.pipes > 0 && q.ist > 0 && q.nand2 > 0) pts.push_back(q);
  }
  try {
    return fit_tp_area(pts);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("'" + path + "': " + e.what());
  }
}

std::string tp_area_markdown(const TpArea& t) {
  std::ostringstream os;
  char b[200];
  std::snprintf(b, sizeof b, "RTU logic model: %.0f + %.0f x trv pipes + %.0f x ist units NAND2 eq. (least squares over "
                "rtu.v synthesised whole, docs/area_configs.md; every configuration within %.0f%%):\n\n",
                t.a, t.b, t.c, 100 * kAreaModelTolerance);
  os << b << "| config | trv x ist | synthesised (NAND2 eq.) | model | error |\n|---|---|---:|---:|---:|\n";
  for (const auto& q : t.points) {
    std::snprintf(b, sizeof b, "| %s | %d x %d | %.0f | %.0f | %+.1f%% |\n", q.config.c_str(), q.pipes, q.ist, q.nand2,
                  t.logic(q.pipes, q.ist), 100 * (t.logic(q.pipes, q.ist) / q.nand2 - 1));
    os << b;
  }
  return os.str();
}

RtuArea rtu_area(const TpConfig& c, const TpArea& a, int rtus, const CacheSizes& k) {
  RtuArea r;
  r.logic = a.logic(c.trv_pipes, c.ist_units);
  auto ported = [](double bits, int ports) { return bits * (1.0 + 0.5 * (ports - 1)); };
  const double node = k.node_kb * 8192, list = k.list_kb * 8192, tri = k.tri_kb * 8192;
  const double slots = c.rays * kSlotBits, stacks = double(c.rays) * c.stack * kEntryBits,
               mailboxes = double(c.rays) * c.mailbox * kMailboxEntryBits;
  const double l2 = double(c.l2_kb) * 8192 / std::max(rtus, 1);
  r.sram_bits = node + list + tri + slots + stacks + mailboxes + l2;
  r.sram_nand2 = kSramBitNand2 * (ported(node, c.trv_pipes) + ported(list, c.trv_pipes) +
                                  ported(tri, c.ist_units) + slots + stacks + mailboxes + l2);
  r.total = r.logic + r.sram_nand2;
  return r;
}

std::vector<TpJob> make_tp_jobs(const TpOptions& o) {
  std::vector<const TpConfig*> cfgs;
  for (const auto& c : tp_configs())
    if (o.configs.empty() || std::find(o.configs.begin(), o.configs.end(), c.name) != o.configs.end())
      cfgs.push_back(&c);
  for (const auto& n : o.configs)
    if (std::none_of(cfgs.begin(), cfgs.end(), [&](const TpConfig* c) { return c->name == n; }))
      throw std::invalid_argument("unknown throughput configuration '" + n + "'");
  if (o.scenes.empty()) throw std::invalid_argument("no scenes");
  std::vector<TpJob> jobs;
  for (const auto& s : o.scenes) {
    const bool paper = s != "corridor" && std::find(paper_scenes().begin(), paper_scenes().end(), s) != paper_scenes().end();
    const bool known = std::find(paper_scenes().begin(), paper_scenes().end(), s) != paper_scenes().end() ||
                       std::find(hard_scenes().begin(), hard_scenes().end(), s) != hard_scenes().end();
    if (!known) throw std::invalid_argument("unknown scene '" + s + "'");
    const std::string arg = paper ? o.scenes_dir + "/" + s + ".glb" : s;
    if (paper && !std::ifstream(arg)) throw std::invalid_argument("scene file '" + arg + "' not found");
    for (const TpConfig* c : cfgs) {
      TpJob j;
      j.scene = s;
      j.scene_arg = arg;
      j.config = c->name;
      j.id = s + "-" + c->name;
      j.json = o.out + "/" + j.id + ".json";
      j.png = o.out + "/" + j.id + ".png";
      j.argv = {o.raycore, "simulate", arg, "--format", "fp24", "--rounding", "rtz", "--vtu", "off",
                "--spawn", "none", "--width", std::to_string(o.width), "--height", std::to_string(o.height),
                "--threads", std::to_string(o.threads), "--quiet", "--no-reference", "--rtus", "6",
                "--mem-latency", "100", "--report", j.json, "--png", j.png};
      for (const auto& x : c->args()) j.argv.push_back(x);
      jobs.push_back(j);
    }
  }
  return jobs;
}

namespace {
const nlohmann::json& key(const nlohmann::json& j, const std::vector<const char*>& path, const TpJob& job) {
  const nlohmann::json* p = &j;
  for (const char* k : path) {
    if (!p->is_object() || !p->contains(k))
      throw std::runtime_error(job.json + ": no key '" + k + "'");
    p = &(*p)[k];
  }
  return *p;
}
}  // namespace

TpRow read_tp_row(const TpJob& j, const nlohmann::json& r, const TpArea& a) {
  TpRow w;
  w.scene = j.scene;
  w.config = j.config;
  const auto& hw = key(r, {"hardware"}, j);
  w.golden_match = key(r, {"golden_match"}, j).get<bool>();
  w.cycles = key(hw, {"cycles"}, j).get<uint64_t>();
  w.rpc_rtu = key(hw, {"rays_per_cycle_per_rtu"}, j).get<double>();
  w.trv_steps = key(hw, {"per_ray", "trv_steps"}, j).get<double>();
  w.tri_tests = key(hw, {"per_ray", "tri_tests"}, j).get<double>();
  w.bytes_per_ray = key(hw, {"per_ray", "bus_bytes"}, j).get<double>();
  w.dram_gb_s = key(hw, {"bus", "bandwidth_gb_s"}, j).get<double>();
  w.trv_busy = key(hw, {"utilisation", "breakdown", "trv", "busy"}, j).get<double>();
  w.trv_stalled = key(hw, {"utilisation", "breakdown", "trv", "stalled"}, j).get<double>();
  w.ist_busy = key(hw, {"utilisation", "breakdown", "ist", "busy"}, j).get<double>();
  w.ist_stalled = key(hw, {"utilisation", "breakdown", "ist", "stalled"}, j).get<double>();
  w.l2_hit = key(hw, {"l2", "hit_rate"}, j).get<double>();
  w.mrays_s = key(hw, {"mrays_per_s"}, j).get<double>();
  w.clock_mhz = key(hw, {"clock", "mhz"}, j).get<double>();
  w.clock_source = key(hw, {"clock", "source"}, j).get<std::string>();
  w.stack_max = key(hw, {"work", "stack_max"}, j).get<uint64_t>();
  const auto it = std::find_if(tp_configs().begin(), tp_configs().end(),
                               [&](const TpConfig& c) { return c.name == j.config; });
  if (it == tp_configs().end()) throw std::runtime_error(j.json + ": unknown configuration " + j.config);
  CacheSizes k;
  k.node_kb = key(r, {"config", "node_cache", "size_kb"}, j).get<double>();
  k.list_kb = key(r, {"config", "list_cache", "size_kb"}, j).get<double>();
  k.tri_kb = key(r, {"config", "tri_cache", "size_kb"}, j).get<double>();
  w.area = rtu_area(*it, a, key(r, {"config", "rtus"}, j).get<int>(), k);
  w.ok = true;
  return w;
}

void mark_tp(std::vector<TpRow>& rows) {
  std::map<std::string, std::vector<size_t>> by_scene;
  for (size_t i = 0; i < rows.size(); ++i)
    if (rows[i].ok && rows[i].golden_match) by_scene[rows[i].scene].push_back(i);
  for (const auto& [scene, idx] : by_scene) {
    std::vector<std::pair<double, double>> p;
    for (size_t i : idx) p.push_back({rows[i].area.total, rows[i].rpc_rtu});
    const auto on = pareto_front(p);
    for (size_t k = 0; k < idx.size(); ++k) {
      TpRow& r = rows[idx[k]];
      r.pareto = on[k];
      r.goal = r.rpc_rtu >= kGoalRpc && r.dram_gb_s <= kGoalGbS;
    }
  }
}

namespace {
std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}
const TpConfig& cfg_of(const std::string& n) {
  for (const auto& c : tp_configs())
    if (c.name == n) return c;
  throw std::runtime_error("unknown configuration " + n);
}
}  // namespace

std::string tp_markdown(const std::vector<TpRow>& rows, const std::vector<std::string>& scenes, const TpArea* area) {
  std::ostringstream os;
  if (area) os << tp_area_markdown(*area) << "\n";
  // The clock of the Mrays/s columns: the reports' (one for every row when they agree).
  std::set<std::string> clocks;
  for (const auto& r : rows)
    if (r.ok) clocks.insert(fmt("%.0f MHz", r.clock_mhz) + " (" + r.clock_source + ")");
  if (!clocks.empty()) {
    os << "Mrays/s: all RTUs at ";
    bool first = true;
    for (const auto& c : clocks) os << (first ? "" : ", ") << c, first = false;
    os << (clocks.size() == 1 ? "" : " (the reports differ)")
       << "; `timing`: docs/timing.json's clock of rtu.v synthesised at the defaults (`make timing`), applied to "
          "every configuration (each is not timed on its own).\n\n";
  }
  // The ladder: one row per lever, one column group per scene.
  os << "| step | lever added | ";
  for (const auto& s : scenes) os << s << " rays/cycle/RTU (steps, tests, B/ray, GB/s) | ";
  os << "RTU logic (NAND2 eq.) | RTU SRAM (kbit) | RTU total (NAND2 eq.) |\n|---|---|";
  for (size_t i = 0; i < scenes.size(); ++i) os << "---|";
  os << "---:|---:|---:|\n";
  for (const auto& c : tp_configs()) {
    if (!c.ladder) continue;
    os << "| " << c.name << " | " << c.lever << " | ";
    const TpRow* any = nullptr;
    for (const auto& s : scenes) {
      const auto it = std::find_if(rows.begin(), rows.end(),
                                   [&](const TpRow& r) { return r.scene == s && r.config == c.name; });
      if (it == rows.end() || !it->ok) {
        os << "- | ";
        continue;
      }
      any = &*it;
      os << (it->goal ? "**" : "") << fmt("%.4f", it->rpc_rtu) << (it->goal ? "**" : "")
         << (it->golden_match ? "" : " (MISMATCH)") << " (" << fmt("%.1f", it->trv_steps) << ", "
         << fmt("%.1f", it->tri_tests) << ", " << fmt("%.1f", it->bytes_per_ray) << ", "
         << fmt("%.2f", it->dram_gb_s) << ") | ";
    }
    if (any)
      os << fmt("%.0f", any->area.logic) << " | " << fmt("%.0f", any->area.sram_bits / 1024) << " | "
         << fmt("%.0f", any->area.total) << " |\n";
    else
      os << "- | - | - |\n";
  }
  // Per scene: every configuration, Pareto front and goal marked.
  for (const auto& s : scenes) {
    os << "\n**" << s << "** (bold: on the Pareto front of RTU area against rays/cycle per RTU; goal: >= "
       << kGoalRpc << " rays/cycle per RTU at <= " << kGoalGbS << " GB/s)\n\n"
       << "| config | trv x ist | rays | L2 KB | rays/cycle/RTU | cycles | trv steps/ray | tests/ray | "
          "trv busy / stalled | ist busy / stalled | DRAM B/ray | DRAM GB/s | L2 hit | stack used | RTU total "
          "(NAND2 eq.) | Mrays/s | goal |\n|---|---|---:|---:|---:|---:|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---|\n";
    const TpRow* least = nullptr;
    for (const auto& r : rows)
      if (r.scene == s && r.goal && (!least || r.area.total < least->area.total)) least = &r;
    for (const auto& r : rows) {
      if (r.scene != s) continue;
      const TpConfig& c = cfg_of(r.config);
      if (!r.ok) {
        os << "| " << r.config << " | (no report) |\n";
        continue;
      }
      const std::string b = r.pareto ? "**" : "";
      os << "| " << b << r.config << b << " | " << c.trv_pipes << " x " << c.ist_units << " | " << c.rays
         << " | " << c.l2_kb << " | " << b << fmt("%.4f", r.rpc_rtu) << b << (r.golden_match ? "" : " MISMATCH")
         << " | " << r.cycles << " | " << fmt("%.1f", r.trv_steps) << " | " << fmt("%.1f", r.tri_tests)
         << " | " << fmt("%.0f%%", 100 * r.trv_busy) << " / " << fmt("%.0f%%", 100 * r.trv_stalled) << " | "
         << fmt("%.0f%%", 100 * r.ist_busy) << " / " << fmt("%.0f%%", 100 * r.ist_stalled) << " | "
         << fmt("%.2f", r.bytes_per_ray) << " | " << fmt("%.2f", r.dram_gb_s) << " | "
         << fmt("%.0f%%", 100 * r.l2_hit) << " | " << r.stack_max << " | " << fmt("%.0f", r.area.total) << " | "
         << fmt("%.1f", r.mrays_s) << " | " << (&r == least ? "**met, least area**" : r.goal ? "met" : "") << " |\n";
    }
  }
  return os.str();
}

std::string tp_plot_data(const std::vector<TpRow>& rows, const std::string& scene) {
  std::ostringstream os;
  os << "# area_nand2 rays_per_cycle_per_rtu pareto goal config least_area_meeting_the_goal mrays_per_s\n";
  std::vector<const TpRow*> v;
  for (const auto& r : rows)
    if (r.scene == scene && r.ok && r.golden_match) v.push_back(&r);
  std::sort(v.begin(), v.end(), [](const TpRow* a, const TpRow* b) { return a->area.total < b->area.total; });
  bool least = true;  // sorted by area: the first row that meets the goal is the least area
  for (const TpRow* r : v) {
    os << fmt("%.0f", r->area.total) << " " << fmt("%.5f", r->rpc_rtu) << " " << int(r->pareto) << " "
       << int(r->goal) << " " << r->config << " " << int(r->goal && least) << " " << fmt("%.3f", r->mrays_s) << "\n";
    if (r->goal) least = false;
  }
  return os.str();
}

std::string tp_csv(const std::vector<TpRow>& rows) {
  std::ostringstream os;
  os << "scene,config,ok,golden_match,cycles,rays_per_cycle_per_rtu,trv_steps_per_ray,tri_tests_per_ray,"
        "dram_bytes_per_ray,dram_gb_s,trv_busy,trv_stalled,ist_busy,ist_stalled,l2_hit,stack_max,"
        "logic_nand2,sram_bits,total_nand2,pareto,goal,mrays_per_s,clock_mhz,clock_source\n";
  for (const auto& r : rows)
    os << r.scene << "," << r.config << "," << r.ok << "," << r.golden_match << "," << r.cycles << ","
       << fmt("%.6f", r.rpc_rtu) << "," << fmt("%.3f", r.trv_steps) << "," << fmt("%.3f", r.tri_tests) << ","
       << fmt("%.3f", r.bytes_per_ray) << "," << fmt("%.4f", r.dram_gb_s) << "," << fmt("%.4f", r.trv_busy)
       << "," << fmt("%.4f", r.trv_stalled) << "," << fmt("%.4f", r.ist_busy) << ","
       << fmt("%.4f", r.ist_stalled) << "," << fmt("%.4f", r.l2_hit) << "," << r.stack_max << ","
       << fmt("%.0f", r.area.logic) << "," << fmt("%.0f", r.area.sram_bits) << ","
       << fmt("%.0f", r.area.total) << "," << r.pareto << "," << r.goal << "," << fmt("%.3f", r.mrays_s) << ","
       << fmt("%.1f", r.clock_mhz) << "," << r.clock_source << "\n";
  return os.str();
}

}  // namespace raycore::sweep
