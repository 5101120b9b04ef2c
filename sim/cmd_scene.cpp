// `raycore scene`: generate the procedural scenes, show what a scene file holds.
//   raycore scene gen NAME [-o FILE]     NAME: a generator or `all` (default output scenes/NAME.glb)
//   raycore scene info FILE|NAME [--json] [--camera ... --light ... --scale ...]
//   raycore scene list                   the generators and what each stresses
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "scenes/generate.h"
#include "scenes/gltf.h"
#include "scenes/options.h"
#include "sim/cli.h"

namespace raycore::cli {
namespace {

using scenes::Scene;
using scenes::SceneError;
using scenes::Vec3;

struct GenArgs {
  std::string name;
  std::string out;
};

struct InfoArgs {
  std::string what;
  bool json = false;
  scenes::SceneOverrides overrides;
};

std::string fmt3(Vec3 v) {
  char b[128];
  std::snprintf(b, sizeof b, "(%.9g, %.9g, %.9g)", v.x, v.y, v.z);
  return b;
}

void gen_one(const std::string& name, const std::string& path) {
  const Scene s = scenes::build_scene(name);
  scenes::write_gltf(s, path);
  const hls::Box b = s.bounds();
  std::printf("wrote %s: %zu triangles, bounds %s .. %s\n", path.c_str(), s.tris.size(), fmt3(b.lo).c_str(),
              fmt3(b.hi).c_str());
}

void run_gen(const GenArgs& a) {
  if (a.name == "all") {
    const std::string dir = a.out.empty() ? "scenes" : a.out;
    for (const std::string& n : scenes::generator_names()) gen_one(n, dir + "/" + n + ".glb");
    return;
  }
  if (!scenes::is_generator(a.name)) {
    std::string list;
    for (const std::string& n : scenes::generator_names()) list += " " + n;
    throw UserError("unknown scene generator '" + a.name + "' (known:" + list + ", far:<distance>, all)");
  }
  gen_one(a.name, a.out.empty() ? "scenes/" + a.name + ".glb" : a.out);
}

void run_info(const InfoArgs& a) {
  const Scene s = scenes::load_scene(a.what, a.overrides);
  const hls::Box b = s.bounds();
  const double deg = 180.0 / 3.14159265358979323846;
  std::string description;
  if (!s.extras.empty()) {
    const auto ex = nlohmann::json::parse(s.extras, nullptr, false);
    if (ex.is_object() && ex.contains("description") && ex["description"].is_string())
      description = ex["description"].get<std::string>();
  }
  if (a.json) {
    auto v3 = [](Vec3 v) { return nlohmann::ordered_json::array({v.x, v.y, v.z}); };
    nlohmann::ordered_json j;
    j["scene"] = s.name;
    j["source"] = s.source;
    j["triangles"] = s.tris.size();
    j["meshes"] = s.meshes.size();
    j["degenerate_triangles"] = s.stats.degenerate_triangles;
    j["skipped_primitives"] = s.stats.skipped_primitives;
    j["bounds"] = {{"lo", v3(b.lo)}, {"hi", v3(b.hi)}};
    if (s.camera.present)
      j["camera"] = {{"position", v3(s.camera.position)}, {"forward", v3(s.camera.forward)},
                     {"up", v3(s.camera.up)},             {"right", v3(s.camera.right)},
                     {"yfov_deg", s.camera.yfov * deg},   {"aspect", s.camera.aspect}};
    else
      j["camera"] = nullptr;
    if (s.light.present)
      j["light"] = {{"position", v3(s.light.position)}, {"intensity", s.light.intensity}};
    else
      j["light"] = nullptr;
    j["warnings"] = s.stats.warnings;
    if (!description.empty()) j["description"] = description;
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  std::printf("scene       %s (%s)\n", s.name.c_str(), s.source.c_str());
  if (!description.empty()) std::printf("about       %s\n", description.c_str());
  std::printf("triangles   %zu in %zu meshes; %" PRIu64 " degenerate (zero area); %" PRIu64
              " non-triangle primitives skipped\n",
              s.tris.size(), s.meshes.size(), s.stats.degenerate_triangles, s.stats.skipped_primitives);
  std::printf("bounds      %s .. %s\n", fmt3(b.lo).c_str(), fmt3(b.hi).c_str());
  if (s.camera.present)
    std::printf("camera      position %s forward %s up %s yfov %.6g deg aspect %.6g\n",
                fmt3(s.camera.position).c_str(), fmt3(s.camera.forward).c_str(), fmt3(s.camera.up).c_str(),
                s.camera.yfov * deg, s.camera.aspect);
  else
    std::printf("camera      none (give --camera X,Y,Z and --look-at X,Y,Z)\n");
  if (s.light.present)
    std::printf("light       point at %s intensity %.6g\n", fmt3(s.light.position).c_str(), s.light.intensity);
  else
    std::printf("light       none (give --light X,Y,Z)\n");
}

void register_scene(CLI::App& app) {
  auto* c = app.add_subcommand("scene", "Procedural scenes and scene file information");
  c->require_subcommand(1);

  auto gen = std::make_shared<GenArgs>();
  auto* g = c->add_subcommand("gen", "Generate a procedural scene as .glb (deterministic)");
  g->add_option("name", gen->name, "Generator name, far:<distance>, or 'all'")->required();
  g->add_option("-o,--output", gen->out, "Output file (default scenes/NAME.glb; for 'all': a directory)");
  g->callback([gen] {
    try {
      run_gen(*gen);
    } catch (const SceneError& e) {
      throw UserError(e.what());
    }
  });

  auto info = std::make_shared<InfoArgs>();
  auto* i = c->add_subcommand("info", "Triangles, bounds, camera, light and degenerate count of a scene");
  i->add_option("scene", info->what, "A .gltf / .glb file or a generator name")->required();
  i->add_flag("--json", info->json, "Print JSON");
  scenes::add_scene_options(*i, info->overrides);
  i->callback([info] {
    try {
      run_info(*info);
    } catch (const SceneError& e) {
      throw UserError(e.what());
    }
  });

  auto* l = c->add_subcommand("list", "List the scene generators and what each stresses");
  l->callback([] {
    for (const std::string& n : scenes::generator_names())
      std::printf("%-18s %s\n", n.c_str(), scenes::generator_description(n).c_str());
  });
}

}  // namespace
RAYCORE_COMMAND(register_scene);
}  // namespace raycore::cli
