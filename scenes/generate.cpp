// scenes/generate.cpp - the generator registry.
#include "scenes/generate.h"

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "scenes/gltf.h"

namespace raycore::scenes {
namespace gen {
Scene build_corridor();
Scene build_far(double dist);
Scene build_grazing();
Scene build_slivers();
Scene build_coplanar();
Scene build_origin_far_camera();
}  // namespace gen

namespace {

struct Entry {
  const char* name;
  const char* description;
};

const Entry kEntries[] = {
    {"corridor",
     "stand-in for the paper's 'Spatial Partitioning II': six furnished rooms (one sunken, reached by "
     "stairs) joined by a long passage; closed walls; camera at (780.94, 141.63, 73.59) looking down the passage"},
    {"far", "a blob, a ground plate and small objects 10^5 units from the origin, camera beside them: "
            "coarse FP24 coordinates (ulp 1 at 10^5); what the VTU fixes"},
    {"grazing", "large planes (ground, wall, 0.5-degree ramp, off-axis platform) seen from 4 units and lit from 25 "
                "units above the ground: grazing primary and shadow rays, acne, long shadows"},
    {"slivers", "long thin triangles: a 2048-triangle fan disc, 800 x 2 strips, a 1024-sided column, a needle fan "
                "wall, a helix ribbon: watertightness along shared edges, barycentric precision"},
    {"coplanar", "decal layers 1e-1 .. 1e-6 above a floor, wall and tilted panel, exactly coplanar overlaps, "
                 "cubes face to face, a plate crossing the floor at 0.001 rad: z-fighting, shadow leaks"},
    {"origin-far-camera", "small objects at the origin seen from 5.5 * 10^4 units through a 0.145-degree field "
                          "of view: the paper's stated limitation (the VTU moves everything far from the origin)"},
};

bool parse_far(const std::string& name, double& dist) {
  if (name == "far") {
    dist = 1e5;
    return true;
  }
  if (name.rfind("far:", 0) != 0) return false;
  const char* b = name.c_str() + 4;
  char* e = nullptr;
  dist = std::strtod(b, &e);
  if (e == b || *e != '\0' || !std::isfinite(dist) || dist < 0 || dist > 1e9)
    throw SceneError("generator 'far:<distance>': '" + name.substr(4) + "' is not a distance in [0, 1e9]");
  return true;
}

}  // namespace

std::vector<std::string> generator_names() {
  std::vector<std::string> v;
  for (const Entry& e : kEntries) v.push_back(e.name);
  return v;
}

bool is_generator(const std::string& name) {
  for (const Entry& e : kEntries)
    if (name == e.name) return true;
  return name.rfind("far:", 0) == 0;
}

std::string generator_description(const std::string& name) {
  double d;
  if (name != "far" && parse_far(name, d)) return std::string(kEntries[1].description) + " (distance " + name.substr(4) + ")";
  for (const Entry& e : kEntries)
    if (name == e.name) return e.description;
  return "";
}

Scene build_scene(const std::string& name) {
  Scene s;
  double dist = 0;
  nlohmann::ordered_json params = nlohmann::ordered_json::object();
  if (name == "corridor") s = gen::build_corridor();
  else if (parse_far(name, dist)) {
    s = gen::build_far(dist);
    params["distance"] = dist;
  } else if (name == "grazing") s = gen::build_grazing();
  else if (name == "slivers") s = gen::build_slivers();
  else if (name == "coplanar") s = gen::build_coplanar();
  else if (name == "origin-far-camera") s = gen::build_origin_far_camera();
  else {
    std::string list;
    for (const Entry& e : kEntries) list += (list.empty() ? "" : ", ") + std::string(e.name);
    throw SceneError("unknown scene generator '" + name + "' (known: " + list + ", far:<distance>)");
  }
  s.name = name;
  s.source = "generated";
  nlohmann::ordered_json ex = {{"generator", "raycore scene gen " + name},
                               {"description", generator_description(name)}};
  if (!params.empty()) ex["parameters"] = params;
  s.extras = ex.dump();
  s.stats.degenerate_triangles = count_degenerate(s.tris);
  return s;
}

std::vector<uint8_t> generate_glb(const std::string& name) { return encode_glb(build_scene(name)); }

Scene generate(const std::string& name) {
  const std::vector<uint8_t> glb = generate_glb(name);
  Scene s = load_gltf_memory(glb.data(), glb.size(), name + ".glb", "", false);
  s.name = name;
  s.source = "generated";
  return s;
}

}  // namespace raycore::scenes
