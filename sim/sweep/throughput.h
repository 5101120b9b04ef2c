// sim/sweep/throughput.h - the throughput-against-area study (`raycore throughput`, issue 14): a
// ladder of the levers (each step adds one to the one before, so each is measured on its own) and
// a grid of trv pipes x ist units x L2 for the Pareto front, each configuration one `raycore
// simulate` job per scene; the reports collected into rays/cycle per RTU, work per ray, unit
// utilisation, DRAM traffic and the RTU area the configuration costs.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace raycore::sweep {

// One configuration of the cycle model: a name and its `raycore simulate` options (every lever
// given explicitly, so the study does not depend on the simulator's defaults).
struct TpConfig {
  std::string name;
  std::string lever;  // what this ladder step adds ("" in the grid)
  bool ladder = false;
  int trv_pipes = 1, ist_units = 1, rays = 64, stack = 64, l2_kb = 0, mailbox = 0, node_kb = 16;
  bool fuse = false, any_hit = true;
  std::vector<std::string> args() const;
};
const std::vector<TpConfig>& tp_configs();  // the ladder, then the grid

// Area of one RTU under the configuration. Logic: rtl/units/rtu.v synthesised whole at several
// trv pipes x ist units (docs/area_configs.md, `make area-configs`), fitted as a + b x pipes +
// c x ist units by least squares; read_tp_area refuses a table the model misses by more than
// kAreaModelTolerance at any synthesised configuration (the check of `make throughput`). Rays in
// flight, stack depth, mailboxes and the node cache's size are counted in SRAM only (the slot and
// stack arrays, the cache's data), so the logic does not follow them (the mailbox has no RTL: its
// logic is not counted; the 32 KB node cache's per-set state adds logic that the fit does not see). SRAM bits: the
// three caches' data arrays, the ray slots (kSlotBits each), the stacks (rays x depth x
// kEntryBits), the mailboxes (rays x entries x 24-bit triangle index) and the RTU's share of the
// L2. A p-port SRAM bit costs (1 + (p - 1) / 2) single-port bits (node and list caches have one
// port per trv pipe, the triangle cache one per ist unit); one single-port bit is kSramBitNand2
// NAND2 eq. (assumptions, stated in docs/results.md).
constexpr double kSlotBits = 840, kEntryBits = 72, kMailboxEntryBits = 24, kSramBitNand2 = 0.5;
constexpr double kAreaModelTolerance = 0.10;
struct TpAreaPoint {
  std::string config;
  int pipes = 0, ist = 0;
  double nand2 = 0;  // rtu.v whole's logic, synthesised (its SRAM bits are counted by rtu_area)
};
struct TpArea {
  double a = 0, b = 0, c = 0;  // logic = a + b x trv pipes + c x ist units (NAND2 eq.)
  std::vector<TpAreaPoint> points;  // what it was fitted to
  double logic(int pipes, int ist) const { return a + b * pipes + c * ist; }
};
// Least squares over >= 3 points with independent pipes and ist units; throws std::runtime_error
// if it cannot fit or misses a point by more than kAreaModelTolerance.
TpArea fit_tp_area(const std::vector<TpAreaPoint>& points);
TpArea read_tp_area(const std::string& area_configs_md);  // throws std::runtime_error
std::string tp_area_markdown(const TpArea& a);  // the model against each synthesised configuration
struct RtuArea {
  double logic = 0, sram_bits = 0, sram_nand2 = 0, total = 0;  // NAND2 eq. / bits
};
struct CacheSizes {
  double node_kb = 16, list_kb = 8, tri_kb = 32;
};
RtuArea rtu_area(const TpConfig& c, const TpArea& a, int rtus, const CacheSizes& caches = {});

struct TpJob {
  std::string id, scene, scene_arg, config;
  std::string json, png;
  std::vector<std::string> argv;
};
struct TpOptions {
  std::vector<std::string> scenes{"sponza-paper", "sibenik-paper", "corridor"};
  std::vector<std::string> configs;  // default: all
  int width = 800, height = 480, threads = 1;
  std::string scenes_dir = "../shared/scenes";
  std::string out = "out/throughput";
  std::string raycore;  // the binary in the job lines
};
std::vector<TpJob> make_tp_jobs(const TpOptions& o);  // throws std::invalid_argument

struct TpRow {
  std::string scene, config;
  bool ok = false, golden_match = false, pareto = false, goal = false;
  double rpc_rtu = 0, trv_steps = 0, tri_tests = 0, bytes_per_ray = 0, dram_gb_s = 0;
  double trv_busy = 0, trv_stalled = 0, ist_busy = 0, ist_stalled = 0, l2_hit = 0;
  uint64_t cycles = 0, stack_max = 0;
  double mrays_s = 0, clock_mhz = 0;  // at the report's clock (hardware.clock: timed or given)
  std::string clock_source;
  RtuArea area;
};
// The goal (issue 14): >= 0.08 rays/cycle per RTU at <= 1.1 GB/s, golden match.
constexpr double kGoalRpc = 0.08, kGoalGbS = 1.1;
TpRow read_tp_row(const TpJob& j, const nlohmann::json& report, const TpArea& a);
void mark_tp(std::vector<TpRow>& rows);  // Pareto front (area vs rays/cycle/RTU) and goal, per scene
// With area: the area model's check table first.
std::string tp_markdown(const std::vector<TpRow>& rows, const std::vector<std::string>& scenes,
                        const TpArea* area = nullptr);
std::string tp_plot_data(const std::vector<TpRow>& rows, const std::string& scene);
std::string tp_csv(const std::vector<TpRow>& rows);

}  // namespace raycore::sweep
