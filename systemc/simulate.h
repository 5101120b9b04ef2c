// systemc/simulate.h - run the cycle model of RayCore (top: N RTUs sharing membus) on one frame.
//
// simulate() elaborates the SystemC hierarchy (top, membus, rtu<i>: rgu, trv, ist, hit,
// node_cache, list_cache, tri_cache, vtu) and runs it to the end of the frame. SystemC allows one
// elaboration per process: call it once per process (tests: one per TEST, gtest_discover_tests).
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "hls/frame.h"
#include "hls/image.h"
#include "hls/trace.h"
#include "scenes/scene.h"
#include "systemc/config.h"
#include "systemc/membus.h"

namespace raycore::sc {

struct SimResult {
  hls::Frame frame;
  uint64_t cycles = 0;  // to the last pixel write
  std::vector<RtuStats> rtus;
  MembusStats bus;
  uint64_t primary_rays = 0, shadow_rays = 0, issued = 0, retired = 0;
  std::vector<uint8_t> primary_retired, shadow_retired;  // per pixel: times retired
  double wall_seconds = 0, user_seconds = 0;
  uint32_t tri_line_bytes = 0;
  uint64_t pin_edges = 0;  // clock edges given to pin-level units (--pins / --rtl)
};

SimResult simulate(const hls::Image& image, const scenes::Camera& cam, const scenes::Light& light,
                   const hls::TraceConfig& tc, const SimConfig& cfg);

// Pixels where two frames differ in tri, t_bits, shadow_ray, lit, shadow_tri or shade.
struct PixelDiff {
  int x, y;
  hls::PixelResult a, b;
};
std::vector<PixelDiff> diff_frames(const hls::Frame& a, const hls::Frame& b, size_t max_list,
                                   uint64_t* count);

// The report's "hardware" and "sim" objects, and the model's parameters ("config" additions).
nlohmann::json hardware_json(const SimResult& r, const SimConfig& cfg);
nlohmann::json sim_json(const SimResult& r);
nlohmann::json config_json(const SimConfig& cfg);
// Reads the keys of config_json (all optional); throws std::runtime_error naming a bad key.
void config_from_json(const nlohmann::json& j, SimConfig& cfg);

}  // namespace raycore::sc
