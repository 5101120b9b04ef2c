// tb/sweep/test_sweep.cpp - the sweep (sim/sweep/, sim/cmd_sweep.cpp, scripts/sweep.sh).
//   Pareto.*, Area.*, Jobs.*: the library on hand-made input.
//   Target.*:                 the issue-6 and issue-15 targets (arithmetic shadow errors, speed
//                             against spawn none) on hand-made rows.
//   Collect.*:                `raycore sweep --collect` on fixture reports (errors, errors_stored):
//                             the arithmetic and storage columns of the CSV/JSON/markdown.
//   Cli.*:                    bad options give a clear message and a non-zero exit.
//   Pipeline.*:               scripts/sweep.sh end to end on 4 tiny jobs (2 scenes x 2 spawns)
//                             and 1 error map; the CSV/JSON hold real numbers; collect refuses a
//                             sweep with a missing result.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/sweep/sweep.h"
#include "sim/sweep/throughput.h"

namespace fs = std::filesystem;
using raycore::sweep::Row;

namespace {

struct Result {
  int status;
  std::string out;
};

// Runs a shell command, stdout and stderr together.
Result run(const std::string& cmd) {
  Result r{-1, ""};
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::string read_file(const fs::path& p) {
  std::ifstream is(p);
  std::stringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

std::vector<std::vector<std::string>> read_csv(const fs::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream is(read_file(p));
  std::string line;
  while (std::getline(is, line)) {
    std::vector<std::string> f;
    std::string cell;
    std::istringstream ls(line);
    while (std::getline(ls, cell, ',')) f.push_back(cell);
    if (!line.empty() && line.back() == ',') f.push_back("");
    rows.push_back(f);
  }
  return rows;
}

Row row(const std::string& scene, double err, double rpc) {
  Row r;
  r.ok = true;
  r.job.scene = scene;
  r.error_pct = err;
  r.rays_per_cycle = rpc;
  return r;
}

}  // namespace

TEST(Pareto, HandMadeFront) {
  // (error, rays/cycle): a dominates c (less error, more speed); b and a trade off; d ties a
  // exactly (both stay); e is worse than b in both.
  const std::vector<std::pair<double, double>> p = {
      {1.0, 0.10}, {0.5, 0.09}, {2.0, 0.08}, {1.0, 0.10}, {0.6, 0.085}, {0.0, 0.05}};
  const auto on = raycore::sweep::pareto_front(p);
  const std::vector<bool> want = {true, true, false, true, false, true};
  for (size_t i = 0; i < p.size(); ++i)
    EXPECT_EQ(on[i], want[i]) << "point " << i << " (" << p[i].first << ", " << p[i].second << ")";
}

TEST(Pareto, EqualErrorFasterWins) {
  const auto on = raycore::sweep::pareto_front({{0.0, 0.120}, {0.0, 0.119}, {0.0, 0.121}});
  EXPECT_EQ(on, (std::vector<bool>{false, false, true}));
  EXPECT_EQ(raycore::sweep::pareto_front({{3.0, 1.0}}), std::vector<bool>{true});
  EXPECT_TRUE(raycore::sweep::pareto_front({}).empty());
}

TEST(Pareto, MarkedPerScene) {
  // The same numbers in two scenes: each scene's front is its own.
  std::vector<Row> rows = {row("a", 1.0, 0.1), row("a", 2.0, 0.2), row("a", 3.0, 0.15),
                           row("b", 3.0, 0.15), row("b", 4.0, 0.1)};
  raycore::sweep::mark_pareto(rows);
  EXPECT_TRUE(rows[0].pareto);
  EXPECT_TRUE(rows[1].pareto);
  EXPECT_FALSE(rows[2].pareto) << "dominated by (2.0, 0.2) in scene a";
  EXPECT_TRUE(rows[3].pareto) << "scene b's best; scene a's rows must not dominate it";
  EXPECT_FALSE(rows[4].pareto);
  // The plot data lists Pareto points first, by error, one block per scene.
  std::vector<std::string> order;
  const std::string d = raycore::sweep::plot_data(rows, &order);
  EXPECT_EQ(order, (std::vector<std::string>{"a", "b"}));
  EXPECT_NE(d.find("1.000000 0.100000 1"), std::string::npos) << d;
  EXPECT_LT(d.find("1.000000 0.100000 1"), d.find("2.000000 0.200000 1")) << d;
  EXPECT_LT(d.find("2.000000 0.200000 1"), d.find("3.000000 0.150000 0")) << d;
}

TEST(Target, MetOnlyWithinEveryBound) {
  // Scene "a", 10000 pixels: the base (fp24-rtz, VTU on, none) and four candidates.
  auto cfg = [](const std::string& fmt, const std::string& spawn, uint64_t self, uint64_t shadow, double rpc) {
    Row r = row("a", 0, rpc);
    r.job.format_name = fmt;
    r.job.format = fmt.substr(0, 4);
    r.job.vtu = true;
    r.job.spawn = spawn;
    r.pixels = 10000;
    r.self_intersections = self;
    r.shadow_errors = shadow;
    return r;
  };
  const std::vector<Row> rows = {cfg("fp24-rtz", "none", 50, 60, 0.100),
                                 cfg("fp24-rtz", "good", 0, 1, 0.096),      // 0.01%, -4%: met
                                 cfg("fp24-rtz", "slow", 0, 0, 0.094),      // -6%
                                 cfg("fp24-rne", "leaky", 0, 2, 0.100),     // 0.02%
                                 cfg("fp24-rne", "acne", 1, 0, 0.100),      // a self-intersection
                                 cfg("fp32", "exact", 0, 0, 0.100)};        // not FP24: not listed
  const std::string t = raycore::sweep::target_markdown(rows, {"a", "absent"});
  auto line = [&](const std::string& spawn) {
    const size_t b = t.find("| " + spawn + " |");
    return b == std::string::npos ? std::string("(no row)") : t.substr(b, t.find('\n', b) - b);
  };
  EXPECT_NE(line("good").find("| a |"), std::string::npos) << t;
  EXPECT_NE(line("good").find("-4.00%"), std::string::npos) << t;
  for (const char* s : {"none", "slow", "leaky", "acne"}) EXPECT_NE(line(s).find("| - |"), std::string::npos) << s << "\n" << t;
  EXPECT_EQ(t.find("exact"), std::string::npos) << "FP32 rows are not candidates";
  EXPECT_EQ(t.find("absent"), std::string::npos) << "scenes without rows get no column";
}

TEST(Target, Issue15ArithmeticShadowAndSpeedAgainstNone) {
  // Scene "a", 384000 pixels (800 x 480): 0.01% = 38 pixels. Totals are high (storage error), the
  // arithmetic counts decide issue 15; its speed is against the same configuration with spawn none.
  auto cfg = [](const std::string& fmt, bool vtu, const std::string& spawn, const std::string& store, uint64_t self,
                uint64_t shadow, uint64_t shadow_arith, double rpc) {
    Row r = row("a", 0, rpc);
    r.job.format_name = fmt;
    r.job.format = fmt.substr(0, 4);
    r.job.vtu = vtu;
    r.job.spawn = spawn;
    r.job.store = store;
    r.pixels = 384000;
    r.self_intersections = self;
    r.shadow_errors = shadow;
    r.has_stored = true;
    r.stored.self_intersections = self;
    r.stored.shadow_errors = shadow_arith;
    return r;
  };
  const std::vector<Row> rows = {
      cfg("fp24-rtz", true, "none", "world", 50, 900, 100, 0.100),      // the issue-6 base
      cfg("fp24-rtz", true, "good", "world", 0, 900, 38, 0.096),        // 38 = 0.0099%: 15 met, 6 not
      cfg("fp24-rtz", true, "over", "world", 0, 38, 39, 0.100),         // 39 arithmetic: not met
      cfg("fp24-rtz", false, "none", "world", 10, 900, 500, 0.120),     // VTU off's own spawn none
      cfg("fp24-rtz", false, "fast", "world", 0, 30, 2, 0.110),         // -8.3% vs its none: 15 not met;
                                                                        //  +10% vs the base: 6 met
      cfg("fp24-rtz", true, "none", "anchored", 20, 40, 40, 0.050),
      cfg("fp24-rtz", true, "good", "anchored", 0, 5, 5, 0.048),        // -4% vs anchored none: met
  };
  namespace sw = raycore::sweep;
  auto check = [&](size_t i) { return sw::check_target(rows, rows[i]); };
  EXPECT_FALSE(check(1).met6);
  EXPECT_TRUE(check(1).met15);
  EXPECT_NEAR(check(1).arith_shadow_pct, 100.0 * 38 / 384000, 1e-12);
  EXPECT_NEAR(check(1).speed_none, 0.96, 1e-12);
  EXPECT_TRUE(check(2).met6) << "38 total = 0.0099%";
  EXPECT_FALSE(check(2).met15) << "39 > 38 arithmetic";
  EXPECT_TRUE(check(4).met6);
  EXPECT_FALSE(check(4).met15) << "more than 5% slower than its own spawn none";
  EXPECT_NEAR(check(4).speed_none, 0.110 / 0.120, 1e-12);
  EXPECT_TRUE(check(6).met15) << "the anchored row's none is the anchored none";
  EXPECT_NEAR(check(6).speed, 0.48, 1e-12) << "issue 6's base stays world";
  EXPECT_FALSE(check(6).met6);
  Row old = rows[1];
  old.has_stored = false;
  EXPECT_FALSE(sw::check_target(rows, old).have15) << "a report without errors_stored: no issue-15 verdict";

  const std::string t = sw::target_markdown(rows, {"a"});
  auto line = [&](const std::string& spawn, const std::string& store) {
    const size_t b = t.find("| " + spawn + " | " + store + " |");
    return b == std::string::npos ? std::string("(no row)") : t.substr(b, t.find('\n', b) - b);
  };
  EXPECT_NE(line("good", "world").find("/ 0.2344 / -4.00% / **0.0099** / -4.00% | - | a |"), std::string::npos) << t;
  EXPECT_NE(line("fast", "world").find("**0.0078** / +10.00% / 0.0005 / -8.33% | a | - |"), std::string::npos) << t;
  EXPECT_NE(line("good", "anchored").find("| - | a |"), std::string::npos) << t;
  EXPECT_NE(t.find("issue 15 met on"), std::string::npos) << t;
}

TEST(Area, AddedCellsAgainstThePaperBaseline) {
  const fs::path f = fs::temp_directory_path() / "raycore_test_sweep_area.tsv";
  {
    std::ofstream os(f);
    os << "# module format rounding cells\n"
          "ist\tfp24\trtz\t1000\nist\tfp24\trne\t1100\nist\tfp32\trne\t1700\n"
          "trv\tfp24\trtz\t400\ntrv\tfp24\trne\t430\ntrv\tfp32\trne\t650\n"
          "vtu\tfp24\trtz\t500\nvtu\tfp24\trne\t550\nvtu\tfp32\trne\t800\n"
          "spawn-skip-origin\tfp24\trtz\t10\nspawn-error-bound\tfp32\trne\t3000\n"
          "spawn-skip-slab\tfp24\trtz\t20\n";
  }
  const auto a = raycore::sweep::read_area(f.string());
  auto c = raycore::sweep::added_cells(a, "fp24", "rtz", false, "none");
  EXPECT_EQ(c.total, 0) << "the paper's baseline adds nothing";
  c = raycore::sweep::added_cells(a, "fp24", "rtz", true, "skip-origin");
  EXPECT_EQ(c.format, 0);
  EXPECT_EQ(c.vtu, 500);
  EXPECT_EQ(c.spawn, 10);
  EXPECT_EQ(c.total, 510);
  c = raycore::sweep::added_cells(a, "fp24", "rtz", false, "skip-slab:2");
  EXPECT_EQ(c.spawn, 20) << "a spec with ulps: the strategy's row";
  c = raycore::sweep::added_cells(a, "fp32", "rne", true, "error-bound");
  EXPECT_EQ(c.format, 700 + 250) << "the ist's and the trv's deltas";
  EXPECT_EQ(c.total, 950 + 800 + 3000);
  c = raycore::sweep::added_cells(a, "fp24", "rne", false, "ulp-offset");
  EXPECT_EQ(c.format, 100 + 30);
  EXPECT_LT(c.spawn, 0) << "a missing row is unknown, not zero";
  EXPECT_LT(c.total, 0);
  {
    std::ofstream os(f);
    os << "ist\tfp24\trtz\t1000\nist\tfp32\trne\t1700\ntrv\tfp24\trtz\t400\n";
  }
  c = raycore::sweep::added_cells(raycore::sweep::read_area(f.string()), "fp32", "rne", false, "none");
  EXPECT_LT(c.format, 0) << "without the trv's row the format delta is unknown";
  {
    std::ofstream os(f);
    os << "ist fp24 rtz\n";
  }
  EXPECT_THROW(raycore::sweep::read_area(f.string()), std::runtime_error);
  EXPECT_THROW(raycore::sweep::read_area((f.string() + ".absent")), std::runtime_error);
  fs::remove(f);
}

TEST(Jobs, ListValidatesAndCounts) {
  raycore::sweep::Options o;
  o.scenes = {"corridor", "grazing"};
  o.raycore = "rc";
  o.map_scenes = {"none"};
  const auto jobs = raycore::sweep::make_jobs(o);
  EXPECT_EQ(jobs.size(), 2u * 3u * 2u * 7u) << "scenes x formats x vtu x spawns";
  EXPECT_EQ(jobs[0].width, 800);
  EXPECT_EQ(jobs.back().width, 400) << "hard cases use --hard-width";
  EXPECT_EQ(raycore::sweep::command_line(jobs[0]).rfind("rc simulate corridor --format fp24 --rounding rtz", 0), 0u)
      << raycore::sweep::command_line(jobs[0]);
  o.scenes = {"nope"};
  EXPECT_THROW(raycore::sweep::make_jobs(o), std::invalid_argument);
  o.scenes = {"corridor"};
  o.formats = {"fp16"};
  EXPECT_THROW(raycore::sweep::make_jobs(o), std::invalid_argument);
  o.formats = {"fp24-rtz"};
  o.spawns = {"magic"};
  EXPECT_THROW(raycore::sweep::make_jobs(o), std::invalid_argument);
  o.spawns = {"none", "none"};
  EXPECT_THROW(raycore::sweep::make_jobs(o), std::invalid_argument);
  for (const char* bad : {"none:2", "skip-slab:", "skip-slab:0", "skip-slab:2x", "skip-slab:-1", ":2"}) {
    o.spawns = {bad};
    EXPECT_THROW(raycore::sweep::make_jobs(o), std::invalid_argument) << bad;
  }
  o.spawns = {"skip-slab:2", "skip-slab"};
  o.vtu = {"on"};
  const auto slab = raycore::sweep::make_jobs(o);
  ASSERT_EQ(slab.size(), 2u);
  EXPECT_NE(slab[0].id, slab[1].id);
  EXPECT_NE(raycore::sweep::command_line(slab[0]).find("--spawn skip-slab --width"), std::string::npos);
  EXPECT_NE(raycore::sweep::command_line(slab[0]).find("--spawn-ulps 2"), std::string::npos)
      << raycore::sweep::command_line(slab[0]);
  EXPECT_EQ(raycore::sweep::command_line(slab[1]).find("--spawn-ulps"), std::string::npos)
      << "the default ulps: no option";
  // Watertightness margins as a suffix of the spawn: own job ids and the options.
  o.spawns = {"skip-back", "skip-back+m0.008+w2", "none+w4"};
  const auto marg = raycore::sweep::make_jobs(o);
  ASSERT_EQ(marg.size(), 3u);
  EXPECT_NE(marg[0].id, marg[1].id);
  EXPECT_NE(marg[1].id.find("-m0.008-w2"), std::string::npos) << marg[1].id;
  EXPECT_NE(raycore::sweep::command_line(marg[1]).find("--spawn skip-back "), std::string::npos);
  EXPECT_NE(raycore::sweep::command_line(marg[1]).find("--bary-margin 0.008 --trv-widen 2"),
            std::string::npos)
      << raycore::sweep::command_line(marg[1]);
  EXPECT_EQ(raycore::sweep::command_line(marg[2]).find("--bary-margin"), std::string::npos);
  EXPECT_NE(raycore::sweep::command_line(marg[2]).find("--trv-widen 4"), std::string::npos);
  EXPECT_EQ(raycore::sweep::command_line(marg[0]).find("--trv-widen"), std::string::npos);
  for (const char* bad : {"none+", "none+m", "none+m-1", "none+m2", "none+w65", "none+wx", "none+q1"}) {
    o.spawns = {bad};
    EXPECT_THROW(raycore::sweep::make_jobs(o), std::invalid_argument) << bad;
  }
  o.spawns = {"none"};
  o.scenes = {"sponza-paper"};
  o.scenes_dir = "/nonexistent-scenes";
  EXPECT_THROW(raycore::sweep::make_jobs(o), std::invalid_argument);
  EXPECT_EQ(raycore::sweep::shell_quote("a b'c"), "'a b'\\''c'");
}

TEST(Jobs, StoresShadowSpawnAndRaycoreRounding) {
  namespace sw = raycore::sweep;
  sw::Options o;
  o.scenes = {"corridor", "far", "grazing", "origin-far-camera"};
  o.formats = {"fp24-rtz"};
  o.vtu = {"on"};
  o.spawns = {"none"};
  o.raycore = "rc";
  o.map_scenes = {"none"};
  auto ids = [](const std::vector<sw::Job>& jobs) {
    std::vector<std::string> v;
    for (const auto& j : jobs) v.push_back(j.id);
    return v;
  };
  auto has = [](const sw::Job& j, const std::string& opt, const std::string& val) {
    for (size_t i = 0; i + 1 < j.argv.size(); ++i)
      if (j.argv[i] == opt && j.argv[i + 1] == val) return true;
    return false;
  };
  // Default: world everywhere (ids as before --store), anchored too for far and origin-far-camera.
  auto jobs = sw::make_jobs(o);
  EXPECT_EQ(ids(jobs), (std::vector<std::string>{"corridor-fp24-rtz-vtuon-none", "far-fp24-rtz-vtuon-none",
                                                 "far-fp24-rtz-vtuon-none-anchored", "grazing-fp24-rtz-vtuon-none",
                                                 "origin-far-camera-fp24-rtz-vtuon-none",
                                                 "origin-far-camera-fp24-rtz-vtuon-none-anchored"}));
  for (const auto& j : jobs) {
    EXPECT_TRUE(has(j, "--store", j.store)) << sw::command_line(j);
    EXPECT_TRUE(has(j, "--shadow-spawn", "front")) << sw::command_line(j);
    EXPECT_EQ(j.store == "anchored", j.id.size() > 9 && j.id.substr(j.id.size() - 9) == "-anchored") << j.id;
  }
  EXPECT_EQ(jobs[2].store, "anchored");
  EXPECT_EQ(sw::default_stores("sponza-paper"), std::vector<std::string>{"world"});
  // Given: every scene gets them; spawn all is passed to every job and recorded, ids unchanged.
  o.stores = {"anchored", "world"};
  o.shadow_spawn = "all";
  o.scenes = {"corridor"};
  jobs = sw::make_jobs(o);
  EXPECT_EQ(ids(jobs), (std::vector<std::string>{"corridor-fp24-rtz-vtuon-none-anchored", "corridor-fp24-rtz-vtuon-none"}));
  for (const auto& j : jobs) EXPECT_TRUE(has(j, "--shadow-spawn", "all")) << sw::command_line(j);
  // The manifest keeps both; a manifest from before them reads as world / front.
  auto m = sw::manifest_json(o, jobs);
  EXPECT_EQ(m["shadow_spawn"], "all");
  auto back = sw::jobs_from_manifest(m);
  EXPECT_EQ(back[0].store, "anchored");
  EXPECT_EQ(back[0].shadow_spawn, "all");
  m["jobs"][0].erase("store");
  m["jobs"][0].erase("shadow_spawn");
  back = sw::jobs_from_manifest(m);
  EXPECT_EQ(back[0].store, "world");
  EXPECT_EQ(back[0].shadow_spawn, "front");
  // Error maps are world jobs with the sweep's shadow spawn.
  o.map_scenes = {"corridor"};
  o.map_configs = {"fp24-rtz:on:skip-slab:2"};
  jobs = sw::make_jobs(o);
  ASSERT_EQ(jobs.back().kind, "errormap");
  EXPECT_TRUE(has(jobs.back(), "--store", "world"));
  EXPECT_TRUE(has(jobs.back(), "--shadow-spawn", "all"));
  o.map_scenes = {"none"};
  for (const auto& bad : std::vector<std::vector<std::string>>{{"moon"}, {"world", "world"}}) {
    o.stores = bad;
    EXPECT_THROW(sw::make_jobs(o), std::invalid_argument) << bad[0];
  }
  o.stores = {};
  o.shadow_spawn = "sometimes";
  EXPECT_THROW(sw::make_jobs(o), std::invalid_argument);
  o.shadow_spawn = "front";
  // fp24-raycore: accepted as FP24 with the rounding raycore (the job decides whether it runs);
  // never a default.
  const auto f = sw::format_spec("fp24-raycore");
  EXPECT_EQ(f.format, "fp24");
  EXPECT_EQ(f.rounding, "raycore");
  o.formats = {"fp24-raycore"};
  jobs = sw::make_jobs(o);
  ASSERT_EQ(jobs.size(), 1u);
  EXPECT_EQ(jobs[0].id, "corridor-fp24-raycore-vtuon-none");
  EXPECT_TRUE(has(jobs[0], "--rounding", "raycore")) << sw::command_line(jobs[0]);
  o.formats = {};
  for (const auto& j : sw::make_jobs(o)) EXPECT_NE(j.rounding, "raycore") << j.id;
  EXPECT_THROW(sw::format_spec("fp32-raycore"), std::invalid_argument);
}

// Fixture reports (the keys `raycore simulate` writes, small made-up numbers) collected by the
// binary: the arithmetic and storage columns carry the reports' values.
TEST(Collect, ArithmeticAndStorageColumnsFromFixtureReports) {
  const fs::path out = fs::temp_directory_path() / ("raycore_test_sweep_collect_" + std::to_string(::getpid()));
  fs::remove_all(out);
  fs::create_directories(out / "jobs");
  namespace sw = raycore::sweep;
  sw::Options o;
  o.scenes = {"far"};
  o.formats = {"fp24-rtz"};
  o.vtu = {"off"};
  o.spawns = {"none", "skip-slab:2"};
  o.out = out.string();
  o.raycore = "rc";
  const auto jobs = sw::make_jobs(o);
  ASSERT_EQ(jobs.size(), 4u);  // far: world and anchored
  {
    std::ofstream os(out / "manifest.json");
    os << sw::manifest_json(o, jobs).dump(1);
  }
  // per job: self, shadow, primary (total); self, shadow, primary (arithmetic); rays/cycle
  const uint64_t v[4][6] = {{1071, 3395, 7074, 1071, 20, 7}, {0, 1512, 7074, 0, 30, 7},
                            {15, 188, 15, 15, 190, 15}, {0, 3, 15, 0, 5, 16}};
  for (size_t i = 0; i < jobs.size(); ++i) {
    auto e = [&](uint64_t self, uint64_t shadow, uint64_t prim) {
      return nlohmann::json{{"pixels", 96000}, {"primary_rays", 96000}, {"shadow_rays", 50000},
                            {"self_intersections", self}, {"self_intersections_front", self},
                            {"shadow_errors", shadow}, {"false_shadow", shadow}, {"false_shadow_self", self},
                            {"false_shadow_no_ray", 0}, {"light_leak", 0}, {"primary_errors", prim}};
    };
    nlohmann::json r = {{"errors", e(v[i][0], v[i][1], v[i][2])},
                        {"hardware", {{"cycles", 1000000}, {"rays_per_cycle", 0.12 + 0.01 * double(i)},
                                      {"mrays_per_s", 100.0}}},
                        {"golden_match", true}};
    if (i != 1) r["errors_stored"] = e(v[i][3], v[i][4], v[i][5]);  // job 1: a report from before issue 15
    if (i == 0)  // job 0 with the budget by stage (issue 27): 7074 primary, 3395 shadow errors
      r["errors_by_stage"] = {{"storage", {{"primary", 7000}, {"shadow", 3000}}},
                              {"ray_generation", {{"primary", 0}, {"shadow", 5}}},
                              {"traversal_intersection", {{"primary", 74}, {"shadow", 300}, {"vtu_primary", 4},
                                                          {"vtu_shadow", 6}}},
                              {"spawn", {{"primary", 0}, {"shadow", 90}}}};
    std::ofstream os(jobs[i].json);
    os << r.dump(1);
  }
  const Result c = run(std::string(RAYCORE_BIN) + " sweep --collect " + out.string());
  ASSERT_EQ(c.status, 0) << c.out;
  const auto csv = read_csv(out / "sweep.csv");
  ASSERT_EQ(csv.size(), 5u);
  const auto& h = csv[0];
  auto col = [&](const std::string& name) {
    for (size_t i = 0; i < h.size(); ++i)
      if (h[i] == name) return i;
    ADD_FAILURE() << "no column " << name;
    return size_t(0);
  };
  for (size_t i = 0; i < 4; ++i) {
    const auto& f = csv[i + 1];
    ASSERT_EQ(f.size(), h.size()) << "row " << i;
    EXPECT_EQ(f[col("store")], i < 2 ? "world" : "anchored");
    EXPECT_EQ(f[col("shadow_spawn")], "front");
    EXPECT_EQ(f[col("shadow_errors")], std::to_string(v[i][1]));
    if (i == 1) {
      for (const char* k : {"shadow_errors_stored", "error_pixels_stored", "shadow_errors_storage"})
        EXPECT_EQ(f[col(k)], "") << k << ": no errors_stored in the report";
      continue;
    }
    EXPECT_EQ(f[col("self_intersections_stored")], std::to_string(v[i][3]));
    EXPECT_EQ(f[col("shadow_errors_stored")], std::to_string(v[i][4]));
    EXPECT_EQ(f[col("primary_errors_stored")], std::to_string(v[i][5]));
    EXPECT_EQ(f[col("error_pixels_stored")], std::to_string(v[i][4] + v[i][5]));
    EXPECT_EQ(f[col("shadow_errors_storage")], std::to_string(int64_t(v[i][1]) - int64_t(v[i][4])));
    EXPECT_EQ(f[col("primary_errors_storage")], std::to_string(int64_t(v[i][2]) - int64_t(v[i][5])));
    EXPECT_EQ(f[col("error_pixels_storage")],
              std::to_string(int64_t(v[i][1] + v[i][2]) - int64_t(v[i][4] + v[i][5])));
    EXPECT_EQ(f[col("self_intersections_storage")], "0");
  }
  EXPECT_EQ(csv[4][col("shadow_errors_storage")], "-2") << "storage can be negative";
  EXPECT_EQ(csv[1][col("storage_primary")], "7000");
  EXPECT_EQ(csv[1][col("ray_generation_shadow")], "5");
  EXPECT_EQ(csv[1][col("traversal_intersection_shadow")], "300");
  EXPECT_EQ(csv[1][col("traversal_intersection_vtu")], "10");
  EXPECT_EQ(csv[1][col("spawn_shadow")], "90");
  EXPECT_EQ(csv[2][col("spawn_shadow")], "") << "no errors_by_stage in the report";
  const auto j = nlohmann::json::parse(read_file(out / "sweep.json"));
  EXPECT_EQ(j["shadow_spawn"], "front");
  EXPECT_EQ(j["rows"][2]["config"]["store"], "anchored");
  EXPECT_EQ(j["rows"][0]["errors_stored"]["shadow_errors"], 20);
  EXPECT_EQ(j["rows"][0]["errors_storage"]["shadow_errors"], 3375);
  EXPECT_TRUE(j["rows"][1]["errors_stored"].is_null());
  EXPECT_EQ(j["rows"][0]["errors_by_stage"]["storage"]["total"], 10000);
  EXPECT_TRUE(j["rows"][1]["errors_by_stage"].is_null());
  const std::string md = read_file(out / "sweep.md");
  EXPECT_NE(md.find("| fp24-rtz | off | none | world | 1071 | 3395 (3395 / 1071 / 0 / 0) | 20 | 7074 (7) | "
                    "10469 (27) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| fp24-rtz | off | skip-slab:2 | anchored | 0 | 3 (3 / 0 / 0 / 0) | 5 | 15 (16) | 18 (21) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| ? (? + ? + ?) |  | 10000 / 5 / 374 (10) / 90 |"), std::string::npos) << md;
  const std::string hard = read_file(out / "sweep-hard.md");
  EXPECT_NE(hard.find("| fp24-rtz | off | none | anchored | ? | 15 / 188 (190) / 203 (205) / 0.1400 |"),
            std::string::npos)
      << hard;
  const std::string target = read_file(out / "sweep-target.md");
  // skip-slab:2 anchored: 5 arithmetic shadow errors of 96000 (<= 9), 0 self, +7.1% vs its none;
  // no issue-6 base (fp24-rtz VTU on) in this sweep.
  EXPECT_NE(target.find("| fp24-rtz | off | skip-slab:2 | anchored | 0 / - / - / **0.0052** / +7.14% | - | far |"),
            std::string::npos)
      << target;
  fs::remove_all(out);
}

TEST(Cli, BadOptionsFailClearly) {
  const std::string rc = RAYCORE_BIN;
  struct Case {
    std::string args, want;
  } cases[] = {
      {"sweep --list --scenes bogus", "unknown scene 'bogus'"},
      {"sweep --list --formats fp16", "unknown format 'fp16'"},
      {"sweep --list --spawns magic", "unknown spawn strategy 'magic'"},
      {"sweep --list --spawns ,", "empty list"},
      {"sweep --list --vtu maybe", "unknown VTU value"},
      {"sweep --list --stores moon", "unknown store 'moon'"},
      {"sweep --list --shadow-spawn sometimes", "--shadow-spawn"},
      {"sweep --collect /nonexistent-sweep-dir", "manifest.json"},
      {"sweep", "exactly one of --list, --run, --collect"},
  };
  for (const auto& c : cases) {
    const Result r = run(rc + " " + c.args);
    EXPECT_NE(r.status, 0) << c.args << ":\n" << r.out;
    EXPECT_NE(r.out.find(c.want), std::string::npos) << c.args << ": expected '" << c.want << "' in:\n" << r.out;
  }
}

// --ist: a bad name, Wald's margin with the watertight test, a unit view without a watertight
// datapath, and a dumped image whose records are not the kind asked for.
TEST(Cli, IstOptionsFailClearly) {
  const std::string rc = RAYCORE_BIN;
  const fs::path img = fs::temp_directory_path() / ("raycore_test_ist_" + std::to_string(::getpid()) + ".img");
  const Result dump = run(rc + " render corridor --ist watertight --width 8 --height 8 -q --no-reference --out-dir " +
                          fs::temp_directory_path().string() + " --dump-image " + img.string());
  ASSERT_EQ(dump.status, 0) << dump.out;
  struct Case {
    std::string args, want;
  } cases[] = {
      {"render corridor --ist magic", "--ist"},
      {"render corridor --ist watertight --bary-margin 0.01", "--bary-margin is Wald's test's margin"},
      {"simulate corridor --width 8 --height 8 --ist watertight --pins vtu", "vtu has no pin-level twin"},
      {"render corridor --width 8 --height 8 --image " + img.string(),
       "holds watertight triangle records, the run asks for --ist wald"},
  };
  for (const auto& c : cases) {
    const Result r = run(rc + " " + c.args);
    EXPECT_NE(r.status, 0) << c.args << ":\n" << r.out;
    EXPECT_NE(r.out.find(c.want), std::string::npos) << c.args << ": expected '" << c.want << "' in:\n" << r.out;
  }
  fs::remove(img);
}

TEST(Pipeline, TinySweepEndToEnd) {
  if (run("command -v parallel").status != 0) GTEST_SKIP() << "GNU parallel is not installed (make deps)";
  const fs::path out = fs::temp_directory_path() / ("raycore_test_sweep_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const fs::path build = fs::path(RAYCORE_BIN).parent_path().parent_path();
  const std::string cmd = "cd " + std::string(RAYCORE_SOURCE_DIR) + " && SWEEP_OUT=" + out.string() +
                          " SWEEP_DOC= SWEEP_AREA=0 SWEEP_FAR_OFFSET=0 SWEEP_JOBS=2 ./scripts/sweep.sh " +
                          build.string() +
                          " --scenes corridor,grazing --formats fp24-rtz --vtu on --spawns none,skip-slab:2"
                          " --stores world,anchored"
                          " --width 40 --height 24 --hard-width 32 --hard-height 20"
                          " --map-scenes corridor --map-configs fp24-rtz:on:none";
  const Result r = run(cmd);
  ASSERT_EQ(r.status, 0) << cmd << "\n" << r.out;

  const auto csv = read_csv(out / "sweep.csv");
  ASSERT_EQ(csv.size(), 9u) << read_file(out / "sweep.csv");
  const auto& h = csv[0];
  auto col = [&](const std::string& name) {
    for (size_t i = 0; i < h.size(); ++i)
      if (h[i] == name) return i;
    ADD_FAILURE() << "no column " << name;
    return size_t(0);
  };
  for (size_t i = 1; i < csv.size(); ++i) {
    const auto& f = csv[i];
    ASSERT_EQ(f.size(), h.size()) << "row " << i;
    const bool corridor = f[col("scene")] == "corridor";
    EXPECT_EQ(std::stoull(f[col("pixels")]), corridor ? 40u * 24u : 32u * 20u) << "row " << i;
    EXPECT_GT(std::stoull(f[col("shadow_rays")]), 0u) << "row " << i;
    EXPECT_GT(std::stoull(f[col("cycles")]), 1000u) << "row " << i;
    const double rpc = std::stod(f[col("rays_per_cycle")]);
    EXPECT_GT(rpc, 0.0) << "row " << i;
    EXPECT_LT(rpc, 6.0) << "row " << i << ": at most one ray per cycle per RTU";
    EXPECT_EQ(f[col("golden_match")], "true") << "row " << i;
    EXPECT_EQ(f[col("error_pixels")],
              std::to_string(std::stoull(f[col("shadow_errors")]) + std::stoull(f[col("primary_errors")])));
    EXPECT_TRUE(f[col("pareto")] == "0" || f[col("pareto")] == "1");
    if (f[col("spawn")] == "skip-slab:2") {
      EXPECT_EQ(f[col("self_intersections")], "0") << "row " << i;
    }
    // Arithmetic beside the total, storage the difference, as the job's own report has them.
    const std::string id = f[col("scene")] + "-fp24-rtz-vtuon-" + (f[col("spawn")] == "none" ? "none" : "skip-slab2") +
                           (f[col("store")] == "anchored" ? "-anchored" : "");
    const auto rep = nlohmann::json::parse(read_file(out / "jobs" / (id + ".json")));
    EXPECT_EQ(rep["config"]["store"], f[col("store")]) << id;
    for (const char* k : {"self_intersections", "shadow_errors", "primary_errors"}) {
      EXPECT_EQ(f[col(std::string(k) + "_stored")], std::to_string(rep["errors_stored"][k].get<uint64_t>())) << id << " " << k;
      EXPECT_EQ(std::stoll(f[col(std::string(k) + "_storage")]),
                std::stoll(f[col(k)]) - std::stoll(f[col(std::string(k) + "_stored")])) << id << " " << k;
    }
  }
  // At least one Pareto point per scene.
  for (const char* s : {"corridor", "grazing"}) {
    int n = 0;
    for (size_t i = 1; i < csv.size(); ++i) n += csv[i][col("scene")] == s && csv[i][col("pareto")] == "1";
    EXPECT_GE(n, 1) << s;
  }
  const auto j = nlohmann::json::parse(read_file(out / "sweep.json"));
  ASSERT_EQ(j["rows"].size(), 8u);
  EXPECT_TRUE(j["rows"][0]["hardware"]["rays_per_cycle"].get<double>() > 0);
  ASSERT_EQ(j["error_maps"].size(), 1u);
  EXPECT_TRUE(fs::file_size(out / "sweep.png") > 1000) << "the plot";
  EXPECT_TRUE(fs::file_size(out / "maps-corridor.png") > 1000) << "the error-map montage";
  EXPECT_NE(read_file(out / "sweep.md").find("| fp24-rtz | on | skip-slab:2 | anchored |"), std::string::npos);

  // A missing result: collect names it and fails.
  fs::remove(out / "jobs" / "grazing-fp24-rtz-vtuon-none.json");
  const Result c = run(std::string(RAYCORE_BIN) + " sweep --collect " + out.string());
  EXPECT_NE(c.status, 0) << c.out;
  EXPECT_NE(c.out.find("grazing-fp24-rtz-vtuon-none.json"), std::string::npos) << c.out;
  fs::remove_all(out);
}

// ---- raycore throughput (sim/sweep/throughput.h) ------------------------------------------------
namespace {
namespace sw = raycore::sweep;

TEST(Throughput, AreaModelFitsTheSynthesisedRtu) {
  // The shipped table: rtu.v synthesised whole at >= 3 configurations, the model within 10% of each.
  const sw::TpArea a = sw::read_tp_area(std::string(RAYCORE_SOURCE_DIR) + "/docs/area_configs.md");
  ASSERT_GE(a.points.size(), 3u);
  EXPECT_GT(a.b, 0);  // a trv pipe costs logic (its pass, two cache ports)
  EXPECT_GT(a.c, 0);  // so does an ist unit
  for (const auto& q : a.points) EXPECT_NEAR(a.logic(q.pipes, q.ist) / q.nand2, 1.0, sw::kAreaModelTolerance) << q.config;
  EXPECT_NE(sw::tp_area_markdown(a).find("| p4i2 | 4 x 2 |"), std::string::npos);
  // A plane is fitted exactly; a point off it by more than 10% is refused, as are too few points or
  // points that do not vary pipes and ist units independently.
  std::vector<sw::TpAreaPoint> p = {{"a", 1, 1, 1.6e6}, {"b", 2, 1, 1.8e6}, {"c", 1, 2, 1.7e6}};
  const sw::TpArea f = sw::fit_tp_area(p);
  EXPECT_NEAR(f.a, 1.3e6, 1);
  EXPECT_NEAR(f.b, 0.2e6, 1);
  EXPECT_NEAR(f.c, 0.1e6, 1);
  // The plane says 2.5 M at 4 x 4; at 6 M least squares leaves a (the residuals are 3.5 M / 44 x
  // (5, -3, -3, 1)) 25% off; at 3 M, 3.5% (within the tolerance: no throw).
  p.push_back({"d", 4, 4, 3.0e6});
  EXPECT_NO_THROW(sw::fit_tp_area(p));
  p.back().nand2 = 6.0e6;
  EXPECT_THROW(sw::fit_tp_area(p), std::runtime_error);
  EXPECT_THROW(sw::fit_tp_area({{"a", 1, 1, 1e6}, {"b", 2, 2, 2e6}}), std::runtime_error);
  EXPECT_THROW(sw::fit_tp_area({{"a", 1, 1, 1e6}, {"b", 2, 2, 2e6}, {"c", 3, 3, 3e6}}), std::runtime_error);
  EXPECT_THROW(sw::read_tp_area("/nonexistent/area_configs.md"), std::runtime_error);

  sw::TpConfig c;
  c.trv_pipes = 2;
  c.ist_units = 1;
  c.rays = 10;
  c.stack = 4;
  c.l2_kb = 12;
  const sw::RtuArea r = sw::rtu_area(c, f, 3, {1, 2, 4});
  EXPECT_DOUBLE_EQ(r.logic, 1.8e6);
  const double node = 8192, list = 16384, tri = 32768, slots = 10 * sw::kSlotBits,
               stacks = 10 * 4 * sw::kEntryBits, l2 = 12 * 8192 / 3.0;
  EXPECT_DOUBLE_EQ(r.sram_bits, node + list + tri + slots + stacks + l2);
  // Node and list caches have 2 ports (2 trv pipes): 1.5 single-port bits each.
  EXPECT_DOUBLE_EQ(r.sram_nand2, sw::kSramBitNand2 * (1.5 * node + 1.5 * list + tri + slots + stacks + l2));
  EXPECT_DOUBLE_EQ(r.total, r.logic + r.sram_nand2);
}

TEST(Throughput, JobsLadderAndGrid) {
  sw::TpOptions o;
  o.scenes = {"corridor"};
  o.raycore = "raycore";
  const auto jobs = sw::make_tp_jobs(o);
  EXPECT_EQ(jobs.size(), sw::tp_configs().size());
  size_t ladder = 0;
  for (const auto& c : sw::tp_configs()) ladder += c.ladder;
  EXPECT_EQ(ladder, 14u);
  // Every lever is on the command line (the study does not depend on the defaults).
  for (const char* opt : {"--trv-pipes", "--ist-units", "--rays-in-flight", "--stack-depth", "--trv-fuse",
                          "--l2-kb", "--mailbox", "--shadow-hit", "--node-cache-kb"})
    EXPECT_NE(std::find(jobs[0].argv.begin(), jobs[0].argv.end(), opt), jobs[0].argv.end()) << opt;
  o.configs = {"nonesuch"};
  EXPECT_THROW(sw::make_tp_jobs(o), std::invalid_argument);
  o.configs = {};
  o.scenes = {"bogus"};
  EXPECT_THROW(sw::make_tp_jobs(o), std::invalid_argument);
}

TEST(Throughput, ParetoGoalAndLeastArea) {
  sw::TpArea a;
  a.a = 270000;
  a.b = 50000;
  a.c = 100000;
  std::vector<sw::TpRow> rows;
  auto row = [&](const char* cfg, double rpc, double gbs) {
    sw::TpRow r;
    r.scene = "s";
    r.config = cfg;
    r.ok = r.golden_match = true;
    r.rpc_rtu = rpc;
    r.dram_gb_s = gbs;
    for (const auto& c : sw::tp_configs())
      if (c.name == cfg) r.area = sw::rtu_area(c, a, 6);
    rows.push_back(r);
  };
  row("base", 0.02, 0.8);
  row("p2i1", 0.04, 0.9);
  row("p4i2", 0.085, 2.0);     // fast but over the bandwidth
  row("stack16", 0.09, 0.7);   // meets the goal (5 x 4, 96 rays, L2)
  row("mailbox8", 0.095, 0.7);  // meets it too, larger (stack16 and the mailboxes' SRAM)
  sw::mark_tp(rows);
  EXPECT_FALSE(rows[2].goal);
  EXPECT_TRUE(rows[3].goal);
  EXPECT_TRUE(rows[4].goal);
  EXPECT_TRUE(rows[0].pareto);
  const std::string md = sw::tp_markdown(rows, {"s"});
  EXPECT_NE(md.find("| **stack16** |"), std::string::npos) << md;
  EXPECT_NE(md.find("**met, least area**"), std::string::npos) << md;
  const std::string dat = sw::tp_plot_data(rows, "s");
  EXPECT_NE(dat.find(" 0.09000 1 1 stack16 1"), std::string::npos) << dat;  // least area meeting it
  EXPECT_NE(dat.find(" 0.09500 1 1 mailbox8 0"), std::string::npos) << dat;
}

TEST(Throughput, CliRefusesBadInput) {
  const std::string rc = RAYCORE_BIN;
  for (const auto& [args, want] : std::vector<std::pair<std::string, std::string>>{
           {"throughput", "exactly one of --list and --collect"},
           {"throughput --list --scenes bogus", "unknown scene 'bogus'"},
           {"throughput --list --scenes corridor --configs nope", "unknown throughput configuration 'nope'"},
           {"throughput --collect /nonexistent-tp-dir", "manifest.json"}}) {
    const Result r = run(rc + " " + args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_NE(r.out.find(want), std::string::npos) << args << ": " << r.out;
  }
}

}  // namespace
