// sim/errors.cpp - see errors.h.
#include "sim/errors.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "hls/ist.h"
#include "hls/wald.h"
#include "sim/reference/reference.h"

namespace raycore::sim {

scenes::Scene stored_scene(const scenes::Scene& scene, const hls::Image& image, const hls::Vec3& anchor) {
  if (image.vtu_applied()) throw std::invalid_argument("stored_scene: the image is VTU-translated");
  if (image.tri_count() != scene.tris.size())
    throw std::invalid_argument("stored_scene: the image has " + std::to_string(image.tri_count()) +
                                " triangle records, the scene " + std::to_string(scene.tris.size()));
  scenes::Scene s = scene;
  hls::visit_format(image.format(), image.rounding(), [&](auto fmt, auto rnd) {
    using F = decltype(fmt);
    using A = hls::Arith<F, decltype(rnd)::value>;
    auto ld = [](uint32_t x) { return static_cast<long double>(A::to_double(x)); };
    for (uint32_t i = 0; i < image.tri_count(); ++i) {
      const hls::WaldTri<F> w = hls::decode_tri<F>(image.tri(i));
      if (w.id >= s.tris.size()) throw std::invalid_argument("stored_scene: record id out of range");
      hls::Tri& t = s.tris[w.id];
      const hls::Vec3 fallback = scene.tris[w.id][0];
      const long double nu = ld(w.c[hls::kNU]), nv = ld(w.c[hls::kNV]), nd = ld(w.c[hls::kND]);
      const long double bu = ld(w.c[hls::kBNU]), bv = ld(w.c[hls::kBNV]), bd = ld(w.c[hls::kBD]);
      const long double cu = ld(w.c[hls::kCNU]), cv = ld(w.c[hls::kCNV]), cd = ld(w.c[hls::kCD]);
      const long double det = bu * cv - bv * cu;
      if (w.degenerate() || det == 0 || !std::isfinite(double(det))) {
        t = {fallback, fallback, fallback};
        continue;
      }
      const int k = int(w.k), a_u = (k + 1) % 3, a_v = (k + 2) % 3;
      // beta = bu u + bv v + bd, gamma = cu u + cv v + cd: vertex A at (0, 0), B at (1, 0), C at (0, 1).
      const long double bg[3][2] = {{0, 0}, {1, 0}, {0, 1}};
      for (int j = 0; j < 3; ++j) {
        const long double rb = bg[j][0] - bd, rg = bg[j][1] - cd;
        const long double u = (rb * cv - bv * rg) / det, v = (bu * rg - rb * cu) / det;
        hls::Vec3 p;
        p[k] = double(nd - nu * u - nv * v + static_cast<long double>(anchor[k]));
        p[a_u] = double(u + static_cast<long double>(anchor[a_u]));
        p[a_v] = double(v + static_cast<long double>(anchor[a_v]));
        t[size_t(j)] = p;
      }
    }
    for (int i = 0; i < 3; ++i) {
      s.camera.position[i] = anchor[i] + A::to_double(A::from_double(scene.camera.position[i] - anchor[i]));
      s.light.position[i] = anchor[i] + A::to_double(A::from_double(scene.light.position[i] - anchor[i]));
    }
  });
  s.name = scene.name + " (stored)";
  return s;
}

FrameErrors measure_errors(const Frame& f, const scenes::Scene& scene, const hls::Image& image,
                           const hls::Vec3& anchor, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  FrameErrors e;
  const Frame ref = reference::render(scene, f.width, f.height, threads);
  e.total = reference::compute_errors(f, ref, scene.tris);
  const scenes::Scene st = stored_scene(scene, image, anchor);
  const Frame ref_st = reference::render(st, f.width, f.height, threads);
  e.stored = reference::compute_errors(f, ref_st, st.tris);
  e.reference_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return e;
}

void add_errors_json(nlohmann::json& j, const FrameErrors& e, bool any_hit) {
  j["errors"] = reference::to_json(e.total);
  j["errors_stored"] = reference::to_json(e.stored);
  nlohmann::json d = nlohmann::json::object();
  for (auto it = j["errors"].begin(); it != j["errors"].end(); ++it) {
    if (!it->is_number_unsigned() || it.key() == "pixels" || it.key() == "primary_rays") continue;
    d[it.key()] = int64_t(it->get<uint64_t>()) - int64_t(j["errors_stored"][it.key()].get<uint64_t>());
  }
  j["errors_storage"] = d;
  for (const char* k : {"errors", "errors_stored"})
    j[k]["shadow_hit"] = any_hit ? "any" : "closest";  // what shadow_tri means
  j["reference"] = {{"wall_seconds", e.reference_seconds}};
}

void print_errors(const FrameErrors& e, bool any_hit) {
  auto line = [&](const char* what, const reference::ErrorMetrics& m) {
    std::printf("%s self-intersections %llu (%.3f%%, %llu light in front; %s-hit shadow rays), shadow "
                "errors %llu (false shadow %llu, light leak %llu), primary errors %llu\n",
                what, (unsigned long long)m.self_intersections, m.self_intersection_pct,
                (unsigned long long)m.self_intersections_front, any_hit ? "any" : "closest",
                (unsigned long long)m.shadow_errors, (unsigned long long)m.false_shadow,
                (unsigned long long)m.light_leak, (unsigned long long)m.primary_errors);
  };
  line("errors    total (vs the scene):      ", e.total);
  line("          arithmetic (vs the stored):", e.stored);
}

}  // namespace raycore::sim
