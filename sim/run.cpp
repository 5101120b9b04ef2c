// sim/run.cpp - shared options and preparation of frame commands (see run.h).
#include "sim/run.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "scenes/gltf.h"
#include "sim/cli.h"

namespace raycore::sim {

void add_run_options(CLI::App& c, RunOptions& o) {
  c.add_option("scene", o.scene,
               "scene: a built-in generator name (corridor, far, grazing, slivers, coplanar, "
               "origin-far-camera) or a .gltf/.glb file");
  scenes::add_scene_options(c, o.overrides);
  c.add_option("--format", o.format, "number format: fp24 or fp32")
      ->check(CLI::IsMember({"fp24", "fp32"}))
      ->capture_default_str();
  c.add_option("--rounding", o.rounding,
               "rounding: rtz (toward zero, correctly rounded), rne, or raycore (RayCore's own FP24 "
               "arithmetic: truncating, 1-guard-bit add, 2-guard-bit add3, table reciprocal; "
               "fp24 only)")
      ->check(CLI::IsMember({"rtz", "rne", "raycore"}))
      ->capture_default_str();
  c.add_option("--vtu", o.vtu, "viewport transfer unit: on or off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  c.add_option("--spawn", o.spawn,
               "shadow-ray spawn: none (t_min only, the paper's), skip-origin (skip the hit "
               "triangle by id), ulp-offset (origin moved along the normal by --spawn-ulps ulps), "
               "error-bound (origin moved past a conservative error bound), skip-offset "
               "(skip-origin + ulp-offset), skip-slab (skip-origin + t_min raised to clear a slab "
               "of --spawn-ulps ulps of the hit point above the plane), skip-back (skip-slab with "
               "a 4-ulp slab + the hit point backed off along the primary ray by --spawn-ulps "
               "ulps of t; for rne)")
      ->check(CLI::IsMember({"none", "skip-origin", "ulp-offset", "error-bound", "skip-offset", "skip-slab", "skip-back"}))
      ->capture_default_str();
  c.add_option("--spawn-ulps", o.spawn_ulps,
               "ulp-offset, skip-offset: ulps for a unit normal component (0: 2 for fp24, 256 for "
               "fp32); skip-slab: slab height in ulps of the hit point's largest coordinate (0: 4); "
               "skip-back: back-off in ulps of t (0: 1)")
      ->check(CLI::Range(0, 1 << 20));
  c.add_option("--shadow-ray", o.shadow_ray,
               "shadow-ray direction: unit (normalised; t_min in world units) or segment "
               "(light - hit; t_min a fraction of the light distance)")
      ->check(CLI::IsMember({"unit", "segment"}))
      ->capture_default_str();
  c.add_option("--shadow-spawn", o.shadow_spawn,
               "which primary hits spawn a shadow ray: front (the light on the side the ray came "
               "from; the others are shadowed without a ray) or all (every hit, as the paper counts; "
               "the image is the same, the extra rays cost cycles and can self-intersect)")
      ->check(CLI::IsMember({"front", "all"}))
      ->capture_default_str();
  c.add_option("--store", o.store,
               "how the memory image holds the scene: world (coordinates as given) or anchored "
               "(relative to the scene's box centre, chosen on the host in double; the camera and "
               "light registers relative to it, so the VTU translates by camera - anchor)")
      ->check(CLI::IsMember({"world", "anchored"}))
      ->capture_default_str();
  c.add_option("--tmin", o.tmin, "ray t_min (default 2^-12, RayCore's)")
      ->check(CLI::Range(0.0, 1e6));
  c.add_option("--bary-margin", o.bary_margin,
               "watertightness margin of the ist (hls/margins.h): a hit needs beta, gamma >= -E and "
               "beta + gamma <= 1 + E (E a number >= 0 and <= 1, rounded to the format; RayCore's "
               "emulator uses 0.008; default 0: none)");
  c.add_option("--trv-widen", o.trv_widen,
               "watertightness margin of the trv: its interval comparisons see [tnear, tfar] widened "
               "by N ulps on each side (0..64; default 0: none)");
  c.add_option("--ist", o.ist,
               "intersection test and triangle record: wald (Wald's projection test on 9 constants, "
               "RayCore's; 32-byte fp24 records) or watertight (Woop, Benthin and Wald's test on "
               "the plane and the three vertices: no ray passes between triangles that share an "
               "edge; 48-byte fp24 records; no --bary-margin)")
      ->check(CLI::IsMember({"wald", "watertight"}))
      ->capture_default_str();
  c.add_option("--width", o.width, "image width")->check(CLI::Range(1, 16384))->capture_default_str();
  c.add_option("--height", o.height, "image height")->check(CLI::Range(1, 16384))->capture_default_str();
  c.add_option("--threads", o.threads, "host threads (0: all cores)")->check(CLI::Range(0, 1024));
  c.add_option("--leaf-size", o.leaf_size, "kd-tree leaf size")->check(CLI::Range(1, 255))
      ->capture_default_str();
  c.add_option("--kd", o.kd,
               "kd-tree builder costs: ours (node 1, triangle 1.5, split below the leaf cost) or "
               "raycore (RayCore's driver: node 1.7072, triangle 3.4623, split below 0.8 x the leaf cost)")
      ->check(CLI::IsMember({"ours", "raycore"}))
      ->capture_default_str();
  c.add_option("--kd-node-cost", o.kd_node_cost, "SAH cost of a traversal step (0: the preset's)")
      ->check(CLI::Range(0.0, 1e6));
  c.add_option("--kd-tri-cost", o.kd_tri_cost, "SAH cost of a triangle test (0: the preset's)")
      ->check(CLI::Range(0.0, 1e6));
  c.add_option("--kd-split-ratio", o.kd_split_ratio,
               "split only below this fraction of the leaf's cost (0: the preset's)")
      ->check(CLI::Range(0.0, 10.0));
  c.add_option("--kd-empty-bonus", o.kd_empty_bonus, "SAH bonus for a split with an empty side (0..1)")
      ->check(CLI::Range(0.0, 1.0));
  c.add_option("--kd-max-depth", o.kd_max_depth, "kd-tree depth limit (0: round(8 + 1.3 log2 N))")
      ->check(CLI::Range(0, hls::max_tree_depth));
  c.add_option("--shadow-hit", o.shadow_hit,
               "shadow-ray traversal: any (ends at the first leaf with a hit, as hardware does; the "
               "occluder reported is that leaf's closest) or closest (the nearest occluder, needed "
               "for the paper's self-intersection count); lit/shadowed is the same in both")
      ->check(CLI::IsMember({"any", "closest"}))
      ->capture_default_str();
  c.add_option("--image", o.image_in, "run from a dumped memory image (camera/light from the scene or options)");
  c.add_option("--dump-image", o.dump_image, "write the memory image to this file");
  c.add_option("--out-dir", o.out_dir, "directory for the image and report")->capture_default_str();
  c.add_option("--png", o.png, "PNG path (default <out-dir>/<scene>-<config>.png)");
  c.add_option("--report", o.report, "JSON report path (default <out-dir>/<scene>-<config>.json)");
  c.add_flag("!--no-reference", o.reference, "skip the double-precision reference and error metrics");
  c.add_option("--error-pixels", o.error_pixels,
               "write every error pixel of the budget by stage as CSV: where, the stage charged, the "
               "exact and the hardware's primary hits (sim/errors.h ErrorPixel)");
  c.add_flag("-q,--quiet", o.quiet, "print nothing but errors");
}

TraceConfig trace_config(const RunOptions& o) {
  TraceConfig c;
  c.format = hls::format_from_string(o.format);
  c.rounding = hls::rounding_from_string(o.rounding);
  if (c.format == hls::FormatId::fp32 && c.rounding == hls::Rounding::raycore)
    throw cli::UserError("--rounding raycore is RayCore's FP24 arithmetic: it needs --format fp24 "
                         "(fp32 takes rtz or rne)");
  c.vtu = o.vtu == "on";
  c.spawn.spawn = spawn_from_string(o.spawn);
  c.spawn.ulps = o.spawn_ulps > 0 ? o.spawn_ulps : default_spawn_ulps(c.format, c.spawn.spawn);
  c.spawn.segment = o.shadow_ray == "segment";
  c.spawn.any_hit = o.shadow_hit == "any";
  c.spawn.spawn_all = o.shadow_spawn == "all";
  c.anchored = o.store == "anchored";
  if (!o.error_pixels.empty() && !o.reference)
    throw cli::UserError("--error-pixels needs the reference's error budget: drop --no-reference");
  if (c.anchored && (!o.image_in.empty() || !o.dump_image.empty()))
    throw cli::UserError("--store anchored builds its image from the scene: it cannot be combined with "
                         "--image or --dump-image (a dumped image does not record its anchor)");
  if (!std::isfinite(o.tmin) || o.tmin < 0) throw cli::UserError("--tmin must be a finite number >= 0");
  c.tmin = o.tmin;
  if (!std::isfinite(o.bary_margin) || o.bary_margin < 0 || o.bary_margin > 1)
    throw cli::UserError("--bary-margin must be a finite number in [0, 1] (e.g. 0.008), not " +
                         std::to_string(o.bary_margin));
  if (o.trv_widen < 0 || o.trv_widen > hls::kMaxWidenUlps)
    throw cli::UserError("--trv-widen must be 0.." + std::to_string(hls::kMaxWidenUlps) +
                         " ulps, not " + std::to_string(o.trv_widen));
  c.bary_margin = o.bary_margin;
  c.trv_widen = o.trv_widen;
  c.ist = hls::ist_kind_from_string(o.ist);
  if (c.ist == hls::IstKind::watertight && c.bary_margin != 0)
    throw cli::UserError("--bary-margin is Wald's test's margin: --ist watertight has none (give "
                         "--bary-margin 0 or --ist wald)");
  c.width = o.width;
  c.height = o.height;
  c.threads = o.threads;
  return c;
}

double max_coordinate(hls::FormatId f) {
  const int emax = f == hls::FormatId::fp24 ? hls::FP24::emax : hls::FP32::emax;
  return std::ldexp(1.0, emax / 2 - 2);
}

hls::BuildOptions build_options(const RunOptions& o) {
  hls::BuildOptions bo = o.kd == "raycore" ? hls::raycore_build_options() : hls::BuildOptions{};
  bo.leaf_size = o.leaf_size;
  if (o.kd_node_cost > 0) bo.cost_traversal = o.kd_node_cost;
  if (o.kd_tri_cost > 0) bo.cost_intersect = o.kd_tri_cost;
  if (o.kd_split_ratio > 0) bo.split_ratio = o.kd_split_ratio;
  if (o.kd_empty_bonus >= 0) bo.empty_bonus = o.kd_empty_bonus;
  bo.max_depth = o.kd_max_depth;
  return bo;
}

Prepared prepare(const RunOptions& o, TraceConfig& cfg) {
  Prepared p;
  if (o.scene.empty()) {
    if (o.image_in.empty()) throw cli::UserError("no scene given (a generator name or a .gltf/.glb file)");
    // From a dumped image alone: camera and light come from the options.
    p.scene.name = "image";
    p.scene.source = o.image_in;
    scenes::apply_overrides(p.scene, o.overrides);
  } else {
    p.scene = scenes::load_scene(o.scene, o.overrides);
  }
  scenes::require_camera_and_light(p.scene);
  scenes::check_range(p.scene, max_coordinate(cfg.format), hls::format_name(cfg.format));
  if (!o.image_in.empty()) {
    p.image = hls::Image::load(o.image_in);
    if (p.image.format() != cfg.format || p.image.rounding() != cfg.rounding)
      throw cli::UserError("image '" + o.image_in + "' is " + hls::format_name(p.image.format()) +
                           "/" + hls::rounding_name(p.image.rounding()) + ", the run asks for " +
                           hls::format_name(cfg.format) + "/" + hls::rounding_name(cfg.rounding));
    if (p.image.ist_kind() != cfg.ist)
      throw cli::UserError("image '" + o.image_in + "' holds " + hls::ist_kind_name(p.image.ist_kind()) +
                           " triangle records, the run asks for --ist " + hls::ist_kind_name(cfg.ist));
    if (p.image.vtu_applied())
      throw cli::UserError("image '" + o.image_in + "' is already VTU-translated; dump images with the VTU off");
    p.tree = hls::analyze_image(p.image);
    if (!p.scene.tris.empty() && p.scene.tris.size() != p.image.tri_count())
      throw cli::UserError("image '" + o.image_in + "' has " + std::to_string(p.image.tri_count()) +
                           " triangles, the scene " + std::to_string(p.scene.tris.size()));
  } else {
    hls::BuildOptions bo = build_options(o);
    bo.ist = cfg.ist;
    cfg.anchor = {};
    if (cfg.anchored) {
      cfg.anchor = hls::store_anchor(p.scene.tris);
      p.image = hls::build_image(hls::relative_to(p.scene.tris, cfg.anchor), cfg.format, cfg.rounding, bo, &p.tree);
    } else {
      p.image = hls::build_image(p.scene.tris, cfg.format, cfg.rounding, bo, &p.tree);
    }
    p.built = true;
  }
  if (!o.dump_image.empty()) p.image.save(o.dump_image);
  return p;
}

std::string config_tag(const TraceConfig& c) {
  return std::string(hls::format_name(c.format)) + "-" + hls::rounding_name(c.rounding) +
         (c.vtu ? "-vtu-" : "-novtu-") + to_string(c.spawn.spawn) + (c.spawn.spawn_all ? "-all" : "") +
         (c.anchored ? "-anchored" : "") + (c.ist == hls::IstKind::watertight ? "-watertight" : "") +
         margins_tag(c);
}

std::string margins_tag(const TraceConfig& c) {
  std::string s;
  if (c.bary_margin != 0) {
    char b[32];
    std::snprintf(b, sizeof b, "-m%g", c.bary_margin);
    s += b;
  }
  if (c.trv_widen != 0) s += "-w" + std::to_string(c.trv_widen);
  return s;
}

static nlohmann::json vec(const hls::Vec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json scene_json(const scenes::Scene& s) {
  const hls::Box b = s.bounds();
  nlohmann::json j = {{"name", s.name},
                      {"source", s.source},
                      {"triangles", s.tris.size()},
                      {"degenerate", s.stats.degenerate_triangles},
                      {"skipped_primitives", s.stats.skipped_primitives},
                      {"camera", {{"position", vec(s.camera.position)},
                                  {"forward", vec(s.camera.forward)},
                                  {"yfov_deg", s.camera.yfov * 180.0 / M_PI}}},
                      {"light", vec(s.light.position)}};
  if (!s.tris.empty()) j["bounds"] = {vec(b.lo), vec(b.hi)};
  return j;
}

nlohmann::json config_json(const TraceConfig& c) {
  nlohmann::json j = {{"format", hls::format_name(c.format)},
                      {"rounding", hls::rounding_name(c.rounding)},
                      {"vtu", c.vtu},
                      {"spawn", to_string(c.spawn.spawn)},
                      {"t_min", c.tmin},
                      {"shadow_ray", c.spawn.segment ? "segment" : "unit"},
                      {"shadow_hit", c.spawn.any_hit ? "any" : "closest"},
                      {"shadow_spawn", c.spawn.spawn_all ? "all" : "front"},
                      {"store", c.anchored ? "anchored" : "world"},
                      {"anchor", vec(c.anchor)},
                      {"bary_margin", c.bary_margin},
                      {"trv_widen", c.trv_widen},
                      {"ist", hls::ist_kind_name(c.ist)},
                      {"width", c.width},
                      {"height", c.height}};
  if (spawn_uses_ulps(c.spawn.spawn)) j["spawn_ulps"] = c.spawn.ulps;
  return j;
}

nlohmann::json build_json(const hls::BuildOptions& b) {
  return {{"leaf_size", b.leaf_size},       {"node_cost", b.cost_traversal},
          {"tri_cost", b.cost_intersect},   {"split_ratio", b.split_ratio},
          {"empty_bonus", b.empty_bonus},   {"max_depth", b.max_depth}};
}

nlohmann::json tree_json(const hls::TreeStats& t, const hls::Image& img) {
  return {{"image_bytes", img.bytes.size()},
          {"nodes", t.nodes},
          {"inner", t.inner},
          {"leaves", t.leaves},
          {"empty_leaves", t.empty_leaves},
          {"max_depth", t.max_depth},
          {"refs", t.refs},
          {"refs_per_tri", t.refs_per_tri},
          {"sah_cost", t.sah_cost},
          {"build_seconds", t.build_seconds},
          {"degenerate", t.degenerate},
          {"saturated_constants", t.saturated_constants},
          {"flushed_constants", t.flushed_constants}};
}

}  // namespace raycore::sim
