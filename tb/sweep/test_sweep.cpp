// tb/sweep/test_sweep.cpp - the sweep (sim/sweep/, sim/cmd_sweep.cpp, scripts/sweep.sh).
//   Pareto.*, Area.*, Jobs.*: the library on hand-made input.
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
      {"sweep --collect /nonexistent-sweep-dir", "manifest.json"},
      {"sweep", "exactly one of --list, --run, --collect"},
  };
  for (const auto& c : cases) {
    const Result r = run(rc + " " + c.args);
    EXPECT_NE(r.status, 0) << c.args << ":\n" << r.out;
    EXPECT_NE(r.out.find(c.want), std::string::npos) << c.args << ": expected '" << c.want << "' in:\n" << r.out;
  }
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
                          " --width 40 --height 24 --hard-width 32 --hard-height 20"
                          " --map-scenes corridor --map-configs fp24-rtz:on:none";
  const Result r = run(cmd);
  ASSERT_EQ(r.status, 0) << cmd << "\n" << r.out;

  const auto csv = read_csv(out / "sweep.csv");
  ASSERT_EQ(csv.size(), 5u) << read_file(out / "sweep.csv");
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
  }
  // At least one Pareto point per scene.
  for (const char* s : {"corridor", "grazing"}) {
    int n = 0;
    for (size_t i = 1; i < csv.size(); ++i) n += csv[i][col("scene")] == s && csv[i][col("pareto")] == "1";
    EXPECT_GE(n, 1) << s;
  }
  const auto j = nlohmann::json::parse(read_file(out / "sweep.json"));
  ASSERT_EQ(j["rows"].size(), 4u);
  EXPECT_TRUE(j["rows"][0]["hardware"]["rays_per_cycle"].get<double>() > 0);
  ASSERT_EQ(j["error_maps"].size(), 1u);
  EXPECT_TRUE(fs::file_size(out / "sweep.png") > 1000) << "the plot";
  EXPECT_TRUE(fs::file_size(out / "maps-corridor.png") > 1000) << "the error-map montage";
  EXPECT_NE(read_file(out / "sweep.md").find("| fp24-rtz | on | skip-slab:2 |"), std::string::npos);

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

TEST(Throughput, AreaTableAndRtuArea) {
  const sw::TpArea a = sw::read_tp_area(std::string(RAYCORE_SOURCE_DIR) + "/docs/area.md");
  EXPECT_GT(a.trv, 10000);
  EXPECT_GT(a.ist, a.trv);  // the Wald test is the bigger datapath
  EXPECT_GT(a.ascache, 0);
  sw::TpConfig c;
  c.trv_pipes = 2;
  c.ist_units = 1;
  c.rays = 10;
  c.stack = 4;
  c.l2_kb = 12;
  const sw::RtuArea r = sw::rtu_area(c, a, 3, {1, 2, 4});
  EXPECT_DOUBLE_EQ(r.logic, 2 * a.trv + a.ist + 3 * a.ascache);
  const double node = 8192, list = 16384, tri = 32768, slots = 10 * sw::kSlotBits,
               stacks = 10 * 4 * sw::kEntryBits, l2 = 12 * 8192 / 3.0;
  EXPECT_DOUBLE_EQ(r.sram_bits, node + list + tri + slots + stacks + l2);
  // Node and list caches have 2 ports (2 trv pipes): 1.5 single-port bits each.
  EXPECT_DOUBLE_EQ(r.sram_nand2, sw::kSramBitNand2 * (1.5 * node + 1.5 * list + tri + slots + stacks + l2));
  EXPECT_DOUBLE_EQ(r.total, r.logic + r.sram_nand2);
  EXPECT_THROW(sw::read_tp_area("/nonexistent/area.md"), std::runtime_error);
}

TEST(Throughput, JobsLadderAndGrid) {
  sw::TpOptions o;
  o.scenes = {"corridor"};
  o.raycore = "raycore";
  const auto jobs = sw::make_tp_jobs(o);
  EXPECT_EQ(jobs.size(), sw::tp_configs().size());
  size_t ladder = 0;
  for (const auto& c : sw::tp_configs()) ladder += c.ladder;
  EXPECT_EQ(ladder, 10u);
  // Every lever is on the command line (the study does not depend on the defaults).
  for (const char* opt : {"--trv-pipes", "--ist-units", "--rays-in-flight", "--stack-depth", "--trv-fuse",
                          "--l2-kb", "--mailbox", "--shadow-hit"})
    EXPECT_NE(std::find(jobs[0].argv.begin(), jobs[0].argv.end(), opt), jobs[0].argv.end()) << opt;
  o.configs = {"nonesuch"};
  EXPECT_THROW(sw::make_tp_jobs(o), std::invalid_argument);
  o.configs = {};
  o.scenes = {"bogus"};
  EXPECT_THROW(sw::make_tp_jobs(o), std::invalid_argument);
}

TEST(Throughput, ParetoGoalAndLeastArea) {
  sw::TpArea a{50000, 100000, 90000};
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
  row("stack16", 0.09, 0.7);   // meets the goal (4 x 2, 96 rays, L2)
  row("p6i3-l2", 0.095, 0.7);  // meets it too, larger
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
  EXPECT_NE(dat.find(" 0.09500 1 1 p6i3-l2 0"), std::string::npos) << dat;
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
