// sim/run.h - what every frame command (render, simulate, compare, table3, sweep) shares: the
// scene and configuration options, loading/building the memory image, and the report's parts.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "hls/image.h"
#include "hls/kdtree.h"
#include "scenes/options.h"
#include "scenes/scene.h"
#include "sim/golden/golden.h"

namespace CLI {
class App;
}

namespace raycore::sim {

struct RunOptions {
  std::string scene;  // generator name or .gltf/.glb path
  scenes::SceneOverrides overrides;
  std::string format = "fp24", rounding = "rtz", vtu = "off", spawn = "none";
  int spawn_ulps = 0;  // 0: default_spawn_ulps(format)
  std::string shadow_ray = "unit";  // unit: normalised direction, t_min in world units; segment
  double tmin = 1.0 / 4096;
  double bary_margin = 0;  // --bary-margin: the ist's barycentric margin eps (hls/margins.h)
  int trv_widen = 0;       // --trv-widen: the trv's interval widening in ulps
  std::string ist = "wald";  // --ist: wald or watertight (hls/ist.h)
  int width = 800, height = 480, threads = 0;
  int leaf_size = 8;
  std::string kd = "ours";  // kd-tree cost preset: ours (hls::BuildOptions) or raycore
  double kd_node_cost = 0, kd_tri_cost = 0, kd_split_ratio = 0, kd_empty_bonus = -1;  // 0/-1: preset's
  int kd_max_depth = 0;     // 0: automatic
  std::string store = "world";  // world: the image holds world coordinates; anchored: relative to
                                //   the scene's box centre (TraceConfig::anchor)
  std::string shadow_spawn = "front";  // front: only hits whose light is in front; all: every hit
  std::string shadow_hit = "any";  // any: the walk ends at the first leaf with a hit; closest
  std::string image_in;    // --image: run from a dumped memory image
  std::string dump_image;  // --dump-image
  std::string out_dir = "out";
  std::string png, report;  // default: <out_dir>/<scene>-<config>.png/.json
  std::string error_pixels;  // --error-pixels: the budget's error pixels as CSV (sim/errors.h)
  bool reference = true;
  bool quiet = false;
};

// Adds the scene, format, rounding, VTU, spawn, t_min, size, threads and image options.
void add_run_options(CLI::App& cmd, RunOptions& o);

// Validates the options (clear messages) and makes the tracer configuration.
TraceConfig trace_config(const RunOptions& o);

// The largest coordinate magnitude accepted for a format: squared distances (the hit unit's
// light distance) must stay below the format's largest number, so 2^(emax/2 - 2).
double max_coordinate(hls::FormatId f);

struct Prepared {
  scenes::Scene scene;
  hls::Image image;
  hls::TreeStats tree;
  bool built = false;  // false: loaded with --image
};

// The kd-tree builder's options from --leaf-size and the --kd* options.
hls::BuildOptions build_options(const RunOptions& o);

// Loads or generates the scene, applies overrides, checks camera, light and range, then builds
// the memory image (or loads --image, which must match format and rounding) and dumps it if asked.
// With --store anchored it sets cfg.anchor (the box centre) and stores the scene relative to it.
Prepared prepare(const RunOptions& o, TraceConfig& cfg);

// A short name of the configuration, e.g. "fp24-rtz-vtu-none".
std::string config_tag(const TraceConfig& cfg);
// The margins' part of config_tag: "-m<E>" and "-w<N>" for a nonzero --bary-margin / --trv-widen
// (e.g. "-m0.008-w2"), "" without margins.
std::string margins_tag(const TraceConfig& cfg);

nlohmann::json scene_json(const scenes::Scene& s);
nlohmann::json config_json(const TraceConfig& cfg);
nlohmann::json build_json(const hls::BuildOptions& b);
nlohmann::json tree_json(const hls::TreeStats& t, const hls::Image& img);

}  // namespace raycore::sim
