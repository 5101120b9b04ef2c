// tb/robust/pixel_errors.cpp - `robust_pixels`: every shadow error of one golden frame against the
// reference, pixel by pixel, with what explains it (docs/robustness.md, "Beating the paper").
//
//   robust_pixels SCENE [raycore render options] [--literal] [--stored]
//
// --stored: against the reference of the stored scene (sim::stored_scene: the arithmetic error)
// instead of the scene's; occluders are still described with the scene's vertices (which ones
// it shares with the hit triangle).
//
// Per error pixel (classes as in sim/reference/metrics.h):
//   no_ray   the hit unit found the light behind (false_shadow_no_ray): same triangle as the
//            reference?, the light's and the camera's cosines to the plane, dens/den of the unit;
//   false    the shadow ray hit an occluder the reference does not see: the occluder's shared
//            vertices with the hit triangle, its largest vertex distance from the plane, the
//            distance along the ray at which it is hit (double, from the golden hit point);
//   leak     the shadow ray reached the light, the reference found an occluder: its shared
//            vertices, where the golden shadow ray crosses it in double (world distance, smallest
//            barycentric) and what hls::ist_wald says for it (exit phase).
// A summary counts the classes and sub-classes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include <CLI/CLI.hpp>

#include "hls/fp.h"
#include "hls/hit.h"
#include "hls/image.h"
#include "hls/ist.h"
#include "hls/rgu.h"
#include "hls/vtu.h"
#include "hls/wald.h"
#include "sim/cli.h"
#include "sim/errors.h"
#include "sim/golden/golden.h"
#include "sim/reference/bvh.h"
#include "sim/reference/metrics.h"
#include "sim/reference/predicates.h"
#include "sim/reference/reference.h"
#include "sim/run.h"

namespace {

namespace hls = raycore::hls;
namespace sim = raycore::sim;
namespace ref = raycore::reference;
using hls::Tri;
using hls::Vec3;

int shared_vertices(const Tri& a, const Tri& b) {
  int n = 0;
  for (const Vec3& p : a)
    for (const Vec3& q : b)
      if (p.x == q.x && p.y == q.y && p.z == q.z) ++n;
  return n;
}

// Largest distance of b's vertices from a's plane.
double plane_distance(const Tri& a, const Tri& b) {
  const Vec3 n = hls::normalize(hls::cross(a[1] - a[0], a[2] - a[0]));
  double m = 0;
  for (const Vec3& p : b) m = std::max(m, std::fabs(hls::dot(n, p - a[0])));
  return m;
}

bool exactly_coplanar(const Tri& a, const Tri& b) {
  for (const Vec3& p : b)
    if (ref::orient3d(a[0], a[1], a[2], p) != 0) return false;
  return true;
}

const char* exit_name(hls::IstExit e) {
  switch (e) {
    case hls::IstExit::hit: return "hit";
    case hls::IstExit::distance: return "distance";
    case hls::IstExit::beta: return "beta";
    case hls::IstExit::gamma: return "gamma";
    case hls::IstExit::sum: return "sum";
  }
  return "?";
}

template <class A>
void analyse(const sim::RunOptions& o, bool literal, bool stored, const std::vector<int>& pick_in) {
  const int pick[2] = {pick_in.size() == 2 ? pick_in[0] : -1, pick_in.size() == 2 ? pick_in[1] : -1};
  using F = typename A::Fmt;
  sim::TraceConfig cfg = sim::trace_config(o);
  const sim::Prepared p = sim::prepare(o, cfg);
  const auto& sc = p.scene;
  const sim::Frame g = sim::trace_golden(p.image, sc.camera, sc.light, cfg);
  const ref::Reference reference(stored ? sim::stored_scene(sc, p.image, cfg.anchor) : sc);
  const sim::Frame r = reference.render(cfg.width, cfg.height, cfg.threads);
  const ref::ErrorMetrics m = ref::compute_errors(g, r, sc.tris);
  std::printf("# %s %s: self %llu shadow %llu (false %llu: self %llu no_ray %llu; leak %llu) primary %llu\n",
              sc.name.c_str(), sim::config_tag(cfg).c_str(), (unsigned long long)m.self_intersections,
              (unsigned long long)m.shadow_errors, (unsigned long long)m.false_shadow,
              (unsigned long long)m.false_shadow_self, (unsigned long long)m.false_shadow_no_ray,
              (unsigned long long)m.light_leak, (unsigned long long)m.primary_errors);

  // The datapath's view: frame set-up, (translated) triangles by scene index.
  const auto setup = hls::FrameSetup<F, A::rounding>::make(sc.camera.position, sc.light.position, cfg.vtu, cfg.anchor);
  const hls::Image img = cfg.vtu ? hls::transform_image(p.image, setup.vtu) : p.image;
  std::unordered_map<uint32_t, hls::WaldTri<F>> wt;
  for (uint32_t i = 0; i < img.tri_count(); ++i) {
    const auto t = img.template wald<F>(i);
    wt[t.id] = t;
  }
  const uint32_t tmin = A::from_double(cfg.tmin);
  const hls::SpawnParams sp = sim::resolved_spawn(cfg);
  const hls::RguCamera rgu_cam = hls::rgu_camera<A>(setup.origin, sc.camera.forward, sc.camera.right,
                                                    sc.camera.up, sc.camera.yfov, cfg.width, cfg.height);
  const Vec3 L = sc.light.position, C = sc.camera.position;
  std::map<std::string, int> summary, kinds, floor_by_rel;

  for (int y = 0; y < cfg.height; ++y)
    for (int x = 0; x < cfg.width; ++x) {
      const auto& a = g.at(x, y);
      const auto& b = r.at(x, y);
      if (a.tri < 0 || b.tri < 0 || !(std::fabs(a.t - b.t) <= ref::kPrimaryDistanceTolerance * b.t)) continue;
      const bool la = a.shadow_ray && a.lit, lr = b.shadow_ray && b.lit;
      const bool picked = pick[0] == x && pick[1] == y;
      if (pick[0] >= 0 && !picked) continue;
      if (la == lr && !picked) continue;
      const Tri& T = sc.tris[size_t(a.tri)];
      const Vec3 n = hls::normalize(hls::cross(T[1] - T[0], T[2] - T[0]));
      const Vec3 P = a.hit;
      const double side = hls::dot(n, C - P) < 0 ? -1.0 : 1.0;
      const double cosl = side * hls::dot(n, L - P) / hls::length(L - P);
      const double cosc = side * hls::dot(n, C - P) / hls::length(C - P);
      // The unit's shadow set-up for this pixel (the golden tracer's operations).
      const hls::Ray pr = hls::rgu_primary<A>(rgu_cam, uint32_t(x), uint32_t(y), tmin);
      const auto wi = wt.find(uint32_t(a.tri));
      if (wi == wt.end()) continue;  // not in the image (degenerate): cannot have been hit
      const auto& w = wi->second;
      const hls::HitTri ht{w.id, w.k, w.c[hls::kNU], w.c[hls::kNV], w.c[hls::kND],
                           hls::ist_test<A>(w, pr.o, pr.d, pr.tmin, pr.tmax).den};
      const hls::ShadowSetup ss = hls::hit_shadow<A>(pr, a.t_bits, ht, setup.light, tmin, sp);
      std::string cls;
      char buf[768];
      // "near": the shadow ray crosses the occluder within 64 ulps (of the hit point's largest
      // coordinate, datapath frame) of the plane: where spawn strategies act. Others: boundaries.
      uint32_t hmax = 0;
      for (int i = 0; i < 3; ++i) hmax = std::max(hmax, A::abs(ss.h[i]));
      const double near_dist = 64 * A::to_double(hls::ulp<F>(hmax));
      bool near = false;
      if (!la && !a.shadow_ray) {
        cls = a.tri == b.tri ? "no_ray same-tri" : "no_ray other-tri";
        if (a.tri != b.tri) {
          const Tri& U = sc.tris[size_t(b.tri)];
          cls += " shared=" + std::to_string(shared_vertices(T, U));
        }
        std::snprintf(buf, sizeof buf, "cosL %+.3e cosC %+.3e dens %+.3e den %+.3e exact_light_side %d",
                      cosl, cosc, A::to_double(ss.dens), A::to_double(ht.den),
                      ref::orient3d(T[0], T[1], T[2], L) * ref::orient3d(T[0], T[1], T[2], C));
      } else if (!la) {
        const Tri& O = sc.tris[size_t(a.shadow_tri)];
        const int sh = shared_vertices(T, O);
        const bool cop = exactly_coplanar(T, O);
        ref::TriHit th;
        const Vec3 wdir = L - P;
        const bool hitd = ref::intersect_triangle(ref::ShearedRay(ref::Ray{P, wdir}), O, -1.0, 2.0, &th);
        const double dist = hitd ? th.t * hls::length(wdir) : NAN;
        // Where the unit's own shadow ray met the occluder (world units).
        double tw = NAN;
        const auto woi = wt.find(uint32_t(a.shadow_tri));
        if (woi != wt.end()) {
          const auto& wo = woi->second;
          const hls::IstOut io = hls::ist_test<A>(wo, ss.ray.o, ss.ray.d, ss.ray.tmin, ss.ray.tmax);
          tw = A::to_double(io.t) * (sp.segment ? hls::length(wdir) : 1.0);
        }
        near = tw * std::fabs(cosl) < near_dist;  // crossed within 64 ulps of the plane
        cls = a.shadow_tri == a.tri ? "false self" : cop ? "false coplanar" : sh ? "false neighbour" : "false other";
        std::snprintf(buf, sizeof buf,
                      "occ %d shared %d coplanar %d plane_dist %.3e hit_dist %.3e unit_t %.3e cosL %+.3e",
                      a.shadow_tri, sh, int(cop), plane_distance(T, O), dist, tw, cosl);
      } else {
        // Leak: the reference's occluder.
        const Tri& O = sc.tris[size_t(b.shadow_tri)];
        const int sh = shared_vertices(T, O);
        ref::TriHit th;
        const Vec3 wdir = L - P;
        const bool hitd = ref::intersect_triangle(ref::ShearedRay(ref::Ray{P, wdir}), O, -1.0, 2.0, &th);
        const double dist = hitd ? th.t * hls::length(wdir) : NAN;
        const double bmin = hitd ? std::min({th.b0, th.b1, th.b2}) : NAN;
        const auto woi = wt.find(uint32_t(b.shadow_tri));
        hls::IstOut io{hls::IstExit::distance, 0, 0, 0}, io0 = io;
        if (woi != wt.end()) {
          const auto& wo = woi->second;
          io = hls::ist_test<A>(wo, ss.ray.o, ss.ray.d, ss.ray.tmin, ss.ray.tmax);
          io0 = hls::ist_test<A>(wo, ss.ray.o, ss.ray.d, 0, ss.ray.tmax);
        }
        if (woi == wt.end())
          cls = "leak occluder-not-in-image";
        else if (!hitd)
          cls = "leak missed-in-double";
        else if (io0.exit == hls::IstExit::hit)
          cls = "leak below-tmin";
        else if (io.exit == hls::IstExit::distance)
          cls = "leak distance";
        else
          cls = "leak edge";
        cls += sh ? " neighbour" : " apart";
        near = hitd && dist * std::fabs(cosl) < near_dist;
        std::snprintf(buf, sizeof buf,
                      "occ %d shared %d plane_dist %.3e hit_dist %.3e bmin %.3e ist %s (tmin 0: %s t %.3e) cosL %+.3e",
                      b.shadow_tri, sh, plane_distance(T, O), dist, bmin, exit_name(io.exit),
                      exit_name(io0.exit), A::to_double(io0.t), cosl);
      }
      // The primary hit against the reference's: same triangle, the same plane (a coplanar
      // neighbour: the same surface), or another surface (a silhouette or a crease seen
      // differently by the format's primary ray: no spawn strategy can change that).
      std::string rel = "same-tri";
      if (a.tri != b.tri) {
        const Tri& U = sc.tris[size_t(b.tri)];
        const double pd = plane_distance(T, U);
        rel = exactly_coplanar(T, U) || pd < 1e-6 * (1 + hls::length(P)) ? "same-plane" : "other-surface";
      }
      const std::string kind = !a.shadow_ray ? "no_ray" : near ? "near" : "far";
      if (picked) {
        const int32_t occ = a.shadow_tri >= 0 ? a.shadow_tri : b.shadow_tri;
        std::printf("pixel %d %d: golden tri %d lit %d shadow_tri %d; reference tri %d lit %d shadow_tri %d\n", x, y,
                    a.tri, int(la), a.shadow_tri, b.tri, int(lr), b.shadow_tri);
        const auto oi = occ >= 0 ? wt.find(uint32_t(occ)) : wt.end();
        auto c9 = [](const hls::WaldTri<F>& q) {
          std::string out = std::to_string(q.k) + ", {";
          for (int i = 0; i < 9; ++i) {
            char h[16];
            std::snprintf(h, sizeof h, "%s%#x", i ? ", " : "", q.c[i]);
            out += h;
          }
          return out + "}";
        };
        std::printf("literal %d %d: tri {%s} occ {%s} d {%#x, %#x, %#x} light {%#x, %#x, %#x}\n", x, y,
                    c9(w).c_str(), oi != wt.end() ? c9(oi->second).c_str() : "none", pr.d[0], pr.d[1],
                    pr.d[2], setup.light[0], setup.light[1], setup.light[2]);
        if (la == lr) continue;
      } else if (literal && a.shadow_ray) {
        // The bit patterns of this pixel, for a literal regression test (tb/robust): primary ray,
        // hit triangle, the occluder (the unit's for a false shadow, the reference's for a leak),
        // the light in the datapath's frame.
        const int32_t occ = la ? b.shadow_tri : a.shadow_tri;
        const auto oi = occ >= 0 ? wt.find(uint32_t(occ)) : wt.end();
        if (oi != wt.end()) {
          auto c9 = [](const hls::WaldTri<F>& q) {
            std::string out = std::to_string(q.k) + ", {";
            for (int i = 0; i < 9; ++i) {
              char h[16];
              std::snprintf(h, sizeof h, "%s%#x", i ? ", " : "", q.c[i]);
              out += h;
            }
            return out + "}";
          };
          std::printf("literal %d %d: tri {%s} occ {%s} d {%#x, %#x, %#x} light {%#x, %#x, %#x}\n", x, y,
                      c9(w).c_str(), c9(oi->second).c_str(), pr.d[0], pr.d[1], pr.d[2], setup.light[0],
                      setup.light[1], setup.light[2]);
        }
      }
      ++summary[rel + ": " + cls];
      ++kinds[kind];
      if (kind != "near") ++floor_by_rel[rel];
      std::printf("%4d %4d tri %6d ref %6d %-13s %-26s dP %.2e %s\n", x, y, a.tri, b.tri, rel.c_str(),
                  cls.c_str(), hls::length(a.hit - b.hit), buf);
    }
  std::printf("# summary\n");
  int other = 0;
  for (const auto& [k, v] : summary) {
    std::printf("# %-44s %d\n", k.c_str(), v);
    if (k.rfind("other-surface", 0) == 0) other += v;
  }
  std::printf("# primary hit on another surface than the reference's: %d of %llu shadow errors\n", other,
              (unsigned long long)m.shadow_errors);
  std::printf("# near (occluder within 64 ulps: spawn-dependent) %d, far (shadow boundary) %d, no_ray %d\n",
              kinds["near"], kinds["far"], kinds["no_ray"]);
  std::printf("# floor (far + no_ray): same-tri %d same-plane %d other-surface %d total %d\n",
              floor_by_rel["same-tri"], floor_by_rel["same-plane"], floor_by_rel["other-surface"],
              kinds["far"] + kinds["no_ray"]);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"robust_pixels: every shadow error of a golden frame, explained pixel by pixel"};
  sim::RunOptions o;
  sim::add_run_options(app, o);
  bool literal = false;
  app.add_flag("--literal", literal, "also print each error pixel's bit patterns (VTU on: origin 0)");
  bool stored = false;
  app.add_flag("--stored", stored, "against the stored scene's reference (arithmetic error)");
  std::vector<int> pick;
  app.add_option("--pixel", pick, "only this pixel (x y), with its bit patterns, error or not")->expected(2);
  try {
    app.parse(argc, argv);
    const sim::TraceConfig cfg = sim::trace_config(o);
    hls::visit_format(cfg.format, cfg.rounding, [&](auto f, auto rr) {
      analyse<hls::Arith<decltype(f), decltype(rr)::value>>(o, literal, stored, pick);
    });
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "robust_pixels: %s\n", e.what());
    return 1;
  }
  return 0;
}
