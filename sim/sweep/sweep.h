// sim/sweep/sweep.h - the speed-against-error sweep (`raycore sweep`, issue 6): the job list
// (scenes x format x VTU x spawn, each job one `raycore simulate` process writing one JSON report,
// plus `raycore errormap` jobs for the worst-pixel images), and the collection of the reports into
// CSV, JSON, markdown and plot data with the added hardware and the Pareto front marked.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace raycore::sweep {

// The scenes the sweep knows: the paper's (corridor, and the two *-paper.glb files of the shared
// scenes folder) and the hard cases that `raycore scene gen` ships.
const std::vector<std::string>& paper_scenes();
const std::vector<std::string>& hard_scenes();
// A format of the sweep: fp24-rtz, fp24-rne, fp32 (= fp32 rne, IEEE), fp32-rtz, or fp24-raycore
// (FP24 with the rounding `raycore`; accepted here and passed to the job as --rounding raycore:
// the job fails at run time where the tracer does not know that rounding; never a default).
struct FormatSpec {
  std::string name, format, rounding;
};
FormatSpec format_spec(const std::string& name);  // throws std::invalid_argument
// The sweep's default spawn list: every strategy of `raycore render --spawn` (sim::spawn_choices),
// skip-slab with a 2-ulp slab (its best in FP24 rtz, docs/robustness.md).
const std::vector<std::string>& spawn_names();
// A spawn of the sweep: "<strategy>" or "<strategy>:<ulps>" (--spawn-ulps; only for the strategies
// that read it: ulp-offset, skip-offset, skip-slab, skip-back), optionally followed by the
// watertightness margins "+m<E>" (--bary-margin) and "+w<N>" (--trv-widen), e.g.
// "skip-back+m0.008+w2" or "none+w4".
struct SpawnSpec {
  std::string strategy;  // a --spawn value
  int ulps = 0;          // 0: the strategy's default
  std::string margin;    // --bary-margin as written ("" = 0)
  int widen = 0;         // --trv-widen
};
SpawnSpec spawn_spec(const std::string& s);  // throws std::invalid_argument naming the spec

// The stores of the sweep (--store of `raycore render`): world, anchored.
const std::vector<std::string>& store_names();
// The default stores of a scene: world for the paper's scenes and the hard cases whose coordinates
// are small; world and anchored for the two whose scene is far from the origin (far,
// origin-far-camera), where storing relative to the box centre changes the stored geometry.
std::vector<std::string> default_stores(const std::string& scene);

struct Options {
  std::vector<std::string> scenes;   // default: paper + hard
  std::vector<std::string> formats;  // default: fp24-rtz, fp24-rne, fp32
  std::vector<std::string> vtu;      // default: off, on
  std::vector<std::string> spawns;   // default: all four
  std::vector<std::string> stores;   // default: default_stores(scene), per scene; given: every scene
  std::string shadow_spawn = "front";  // --shadow-spawn of every job: front or all
  int width = 800, height = 480;           // paper scenes
  int hard_width = 400, hard_height = 240;  // hard cases
  std::string scenes_dir = "../shared/scenes";
  std::string out = "out/sweep";
  std::string raycore;  // the binary in the job lines (default: this executable)
  int threads = 1;      // host threads per job (the jobs run side by side)
  bool keep_paths = false;  // paths as given (relative ones stay relative), for --transferfile
  // Error maps (raycore errormap): these scenes x these configurations ("fp24-rtz:on:none").
  std::vector<std::string> map_scenes;  // default: sponza-paper, sibenik-paper (if swept)
  std::vector<std::string> map_configs;
};

struct Job {
  std::string kind;  // "simulate" or "errormap"
  std::string id;    // <scene>-<format>-vtu<on|off>-<spawn>[-anchored] (world: no suffix)
  std::string scene, scene_arg;  // name; generator name or .glb path
  std::string format_name, format, rounding, spawn;  // spawn: the spec ("skip-slab:2")
  std::string store = "world";         // --store
  std::string shadow_spawn = "front";  // --shadow-spawn
  bool vtu = false;
  int width = 0, height = 0;
  std::string json, png;      // outputs (errormap: png is the map)
  std::vector<std::string> argv;  // argv[0] = the raycore binary
};

// Validates the options (unknown scene, format, spawn, VTU value, missing scene file, an empty
// list: std::invalid_argument naming the item) and makes the jobs in a fixed order.
std::vector<Job> make_jobs(const Options& o);
// One line of /bin/sh, every argument quoted when needed.
std::string command_line(const Job& j);
std::string shell_quote(const std::string& s);

nlohmann::json manifest_json(const Options& o, const std::vector<Job>& jobs);
std::vector<Job> jobs_from_manifest(const nlohmann::json& m);  // throws std::runtime_error

// Added hardware per RTU in yosys generic cells, from `scripts/sweep_area.sh` (TSV lines
// "module<TAB>format<TAB>rounding<TAB>cells"; modules ist, trv, vtu, spawn-<strategy>).
struct Area {
  std::map<std::string, double> cells;  // key "module/format/rounding"
  bool empty() const { return cells.empty(); }
  // -1 when a needed row is missing.
  double get(const std::string& module, const std::string& format, const std::string& rounding) const;
};
Area read_area(const std::string& path);  // throws std::runtime_error naming the file/line

struct AddedCells {
  double format = 0, vtu = 0, spawn = 0, total = 0;  // -1: unknown
};
// Against the paper's baseline (FP24 rtz, VTU off, spawn none): the ist's and the trv datapath's
// deltas for format and rounding (both rows needed), the vtu unit's cells when on, the spawn strategy's cells.
AddedCells added_cells(const Area& a, const std::string& format, const std::string& rounding, bool vtu,
                       const std::string& spawn);

// Pareto front of (cost, benefit) points: lower cost and higher benefit are better. A point is on
// the front unless another point is at least as good in both and strictly better in one.
std::vector<bool> pareto_front(const std::vector<std::pair<double, double>>& cost_benefit);

// The main error counts measured twice (sim/errors.h): against the scene (total) and against the
// stored scene (arithmetic: the datapath's own error); storage = total - arithmetic (per count; can
// be negative: errors are not additive).
struct ErrorCounts {
  uint64_t self_intersections = 0, shadow_errors = 0, primary_errors = 0, error_pixels = 0;
  double error_pct = 0;
};
struct StorageCounts {
  int64_t self_intersections = 0, shadow_errors = 0, primary_errors = 0, error_pixels = 0;
};

// The error pixels by stage (sim/errors.h, the report's errors_by_stage): primary + shadow per
// stage; the four stages sum to the total's primary_errors and shadow_errors.
struct StageErrors {
  uint64_t primary = 0, shadow = 0;
};
struct StageBudgetCounts {
  StageErrors storage, ray_generation, traversal_intersection, spawn;
  uint64_t traversal_vtu = 0;  // of traversal_intersection (primary + shadow): the VTU's geometry
};

struct Row {
  Job job;
  bool ok = false;  // the report was there and complete
  uint64_t pixels = 0, shadow_rays = 0, self_intersections = 0, shadow_errors = 0, false_shadow = 0,
           false_shadow_self = 0, false_shadow_no_ray = 0, light_leak = 0, primary_errors = 0,
           error_pixels = 0;
  uint64_t self_intersections_front = 0;
  double error_pct = 0;
  // errors_stored of the report (has_stored false: a report from before issue 15; the columns
  // are then empty).
  bool has_stored = false;
  ErrorCounts stored;
  StorageCounts storage;  // total - stored
  // errors_by_stage of the report (has_stages false: a report from before issue 27; the columns
  // are then empty).
  bool has_stages = false;
  StageBudgetCounts stages;
  uint64_t cycles = 0;
  double rays_per_cycle = 0, mrays_per_s = 0, sim_seconds = 0;
  bool golden_match = false;
  AddedCells cells;
  bool pareto = false;  // on its scene's (error_pct, rays_per_cycle) front
};

// Reads one simulate report (throws std::runtime_error naming the file and the missing key).
Row read_row(const Job& j, const nlohmann::json& report);
// Marks each scene's Pareto front (error_pct against rays_per_cycle).
void mark_pareto(std::vector<Row>& rows);

std::string csv(const std::vector<Row>& rows);
nlohmann::json rows_json(const std::vector<Row>& rows);
// Markdown: one table per scene (all columns), and a compact table with one row per
// configuration and one column group per scene in `scenes`.
std::string markdown(const std::vector<Row>& rows);
std::string compact_markdown(const std::vector<Row>& rows, const std::vector<std::string>& scenes);
// The targets (beating the paper):
// - issue 6: 0 self-intersections, shadow errors (total) <= max_shadow_pct of the pixels, rays per
//   cycle at most max_slowdown below the paper's VTU configuration (the base: fp24-rtz, VTU on,
//   spawn none, store world);
// - issue 15: 0 self-intersections, arithmetic shadow errors (against the stored scene) <=
//   max_shadow_pct of the pixels (38 at 800 x 480), rays per cycle at most max_slowdown below the
//   same configuration (format, VTU, store) with spawn none.
struct TargetSpec {
  std::string format = "fp24";  // the rows considered
  std::string base_format = "fp24-rtz", base_spawn = "none", base_store = "world";
  bool base_vtu = true;
  double max_shadow_pct = 0.01, max_slowdown = 0.05;
};
struct TargetCheck {
  bool have = false;                   // the row and its bases are there
  double shadow_pct = 0, speed = 0;    // issue 6: total shadow errors %, rays/cycle / base's
  bool met6 = false;
  bool have15 = false;                 // arithmetic counts and the spawn-none row are there
  double arith_shadow_pct = 0, speed_none = 0;  // issue 15: arithmetic shadow %, rays/cycle / spawn none's
  bool met15 = false;
};
// The targets for one row (`rows` holds its bases).
TargetCheck check_target(const std::vector<Row>& rows, const Row& r, const TargetSpec& t = TargetSpec());
// One row per configuration of t.format: per scene self-intersections / shadow errors in % /
// speed against the base / arithmetic shadow errors in % / speed against spawn none (bold: meets
// issue 6's target there on the shadow %, issue 15's on the arithmetic %), and the scenes where
// each target is met.
std::string target_markdown(const std::vector<Row>& rows, const std::vector<std::string>& scenes,
                            const TargetSpec& t = TargetSpec());
// The scenes of `want` that have rows, in want's order.
std::vector<std::string> scenes_present(const std::vector<Row>& rows, const std::vector<std::string>& want);
// Plot data, one block per scene (gnuplot index), columns: error_pct rays_per_cycle pareto format vtu
// spawn label store.
std::string plot_data(const std::vector<Row>& rows, std::vector<std::string>* scene_order);

}  // namespace raycore::sweep
