// sim/errors.cpp - see errors.h.
#include "sim/errors.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>

#include "hls/ist.h"
#include "hls/vtu.h"
#include "hls/wald.h"
#include "sim/reference/reference.h"

namespace raycore::sim {

namespace {

// The triangles of `image`'s records (each recovered from its Wald constants taken as exact
// numbers, or a watertight record's vertices as they are), plus `offset` (in long double), into
// s.tris by scene index.
template <class A>
void records_to_tris(scenes::Scene& s, const scenes::Scene& scene, const hls::Image& image, const hls::Vec3& offset) {
  using F = typename A::Fmt;
  if (image.tri_count() != scene.tris.size())
    throw std::invalid_argument("stored_scene: the image has " + std::to_string(image.tri_count()) +
                                " triangle records, the scene " + std::to_string(scene.tris.size()));
  auto ld = [](uint32_t x) { return static_cast<long double>(A::to_double(x)); };
  for (uint32_t i = 0; i < image.tri_count(); ++i) {
    const hls::WaldTri<F> w = image.template wald<F>(i);
    if (w.id >= s.tris.size()) throw std::invalid_argument("stored_scene: record id out of range");
    hls::Tri& t = s.tris[w.id];
    const hls::Vec3 fallback = scene.tris[w.id][0];
    if (w.kind == hls::IstKind::watertight) {
      if (w.degenerate()) {
        t = {fallback, fallback, fallback};
        continue;
      }
      for (int j = 0; j < 3; ++j)
        for (int a = 0; a < 3; ++a)
          t[size_t(j)][a] = double(ld(w.c[hls::WaldTri<F>::VA + 3 * j + a]) + static_cast<long double>(offset[a]));
      continue;
    }
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
      p[k] = double(nd - nu * u - nv * v + static_cast<long double>(offset[k]));
      p[a_u] = double(u + static_cast<long double>(offset[a_u]));
      p[a_v] = double(v + static_cast<long double>(offset[a_v]));
      t[size_t(j)] = p;
    }
  }
}

}  // namespace

scenes::Scene stored_scene(const scenes::Scene& scene, const hls::Image& image, const hls::Vec3& anchor) {
  if (image.vtu_applied()) throw std::invalid_argument("stored_scene: the image is VTU-translated");
  scenes::Scene s = scene;
  hls::visit_format(image.format(), image.rounding(), [&](auto fmt, auto rnd) {
    using A = hls::Arith<decltype(fmt), decltype(rnd)::value>;
    records_to_tris<A>(s, scene, image, anchor);
    for (int i = 0; i < 3; ++i) {
      s.camera.position[i] = anchor[i] + A::to_double(A::from_double(scene.camera.position[i] - anchor[i]));
      s.light.position[i] = anchor[i] + A::to_double(A::from_double(scene.light.position[i] - anchor[i]));
    }
  });
  s.name = scene.name + " (stored)";
  return s;
}

scenes::Scene datapath_scene(const scenes::Scene& scene, const hls::Image& image, const TraceConfig& cfg) {
  if (image.vtu_applied()) throw std::invalid_argument("datapath_scene: the image is VTU-translated already");
  if (!cfg.vtu) return stored_scene(scene, image, cfg.anchor);
  scenes::Scene s = scene;
  hls::visit_format(image.format(), image.rounding(), [&](auto fmt, auto rnd) {
    using F = decltype(fmt);
    constexpr hls::Rounding R = decltype(rnd)::value;
    using A = hls::Arith<F, R>;
    const auto setup = hls::FrameSetup<F, R>::make(scene.camera.position, scene.light.position, true, cfg.anchor);
    const hls::Vec3 offset{setup.offset[0], setup.offset[1], setup.offset[2]};
    records_to_tris<A>(s, scene, hls::transform_image(image, setup.vtu), offset);
    for (int i = 0; i < 3; ++i) {
      s.camera.position[i] = offset[i] + A::to_double(setup.origin[i]);
      s.light.position[i] = offset[i] + A::to_double(setup.light[i]);
    }
  });
  s.name = scene.name + " (datapath)";
  return s;
}

namespace {

using reference::PixelError;

// A shadow ray's filter: skips the triangle the hardware skips (skip-origin and the strategies
// built on it).
class SkipOne final : public reference::HitFilter {
 public:
  explicit SkipOne(int32_t id) : id_(id) {}
  bool skip(int32_t tri) const override { return tri == id_; }

 private:
  int32_t id_;
};

// The exact trace of a primary ray over (tmin, tmax) against `ref`'s scene, the exact shadow test
// from its hit point (as Reference::trace, with the ray's interval).
PixelResult exact_pixel(const reference::Reference& ref, const reference::Ray& ray, double tmin, double tmax) {
  PixelResult px;
  const reference::TriHit h = ref.closest(ray, tmin, tmax);
  if (h.tri < 0) return px;
  px.tri = h.tri;
  px.t = h.t;
  px.hit = ref.hit_point(h);
  const reference::ShadowResult s = ref.shadow(ray.org, h);
  px.front = px.shadow_ray = s.shadow_ray;
  px.lit = s.lit;
  px.shadow_tri = s.shadow_tri;
  return px;
}

// Where `ray` meets the plane of triangle `tri` (exact inputs, long double: ~2^-64 relative), as
// barycentrics of that triangle (outside [0, 1] when the point is off it). False if the plane is
// degenerate or the ray parallel to it.
bool plane_hit(const reference::Reference& ref, const reference::Ray& ray, int32_t tri, reference::TriHit* h) {
  using LD = long double;
  const hls::Tri& t = ref.bvh().triangle(tri);
  LD v0[3], e1[3], e2[3], o[3], d[3];
  for (int i = 0; i < 3; ++i) {
    v0[i] = t[0][i];
    e1[i] = LD(t[1][i]) - v0[i];
    e2[i] = LD(t[2][i]) - v0[i];
    o[i] = ray.org[i];
    d[i] = ray.dir[i];
  }
  const LD n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const LD den = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
  if (den == 0) return false;
  const LD tt = (n[0] * (v0[0] - o[0]) + n[1] * (v0[1] - o[1]) + n[2] * (v0[2] - o[2])) / den;
  int k = 0;
  if (std::fabs(n[1]) > std::fabs(n[k])) k = 1;
  if (std::fabs(n[2]) > std::fabs(n[k])) k = 2;
  const int u = (k + 1) % 3, v = (k + 2) % 3;
  const LD pu = o[u] + tt * d[u] - v0[u], pv = o[v] + tt * d[v] - v0[v];
  const LD det = e1[u] * e2[v] - e1[v] * e2[u];
  if (det == 0 || !std::isfinite(double(tt))) return false;
  const LD b1 = (pu * e2[v] - pv * e2[u]) / det, b2 = (e1[u] * pv - e1[v] * pu) / det;
  h->tri = tri;
  h->t = double(tt);
  h->b1 = double(b1);
  h->b2 = double(b2);
  h->b0 = double(1 - b1 - b2);
  return true;
}

}  // namespace

StageBudget stage_budget(const Frame& f, const scenes::Scene& scene, const hls::Image& image,
                         const TraceConfig& cfg, const Frame& ref, const Frame& ref_stored,
                         const reference::Reference& stored, const reference::Reference* datapath) {
  const auto t0 = std::chrono::steady_clock::now();
  const size_t n = size_t(f.width) * size_t(f.height);
  if (ref.width != f.width || ref.height != f.height || ref_stored.width != f.width ||
      ref_stored.height != f.height || f.px.size() != n || ref.px.size() != n || ref_stored.px.size() != n)
    throw std::invalid_argument("stage_budget: the frames differ in size");
  if (cfg.width != f.width || cfg.height != f.height)
    throw std::invalid_argument("stage_budget: the frame is not of the configuration's size");
  StageBudget b;
  b.pixel.assign(n, Stage::none);
  std::vector<size_t> err;
  for (size_t i = 0; i < n; ++i)
    if (reference::classify_pixel(f.px[i], ref.px[i]) != PixelError::none) err.push_back(i);
  const HardwareRays rays(image, scene.camera, scene.light, cfg);
  auto departs = [&](const PixelResult& p, size_t i) {
    return reference::classify_pixel(p, ref.px[i]) != PixelError::none;
  };
  // One error pixel: the first partial pipeline that is an error against P0 (and, for
  // traversal_intersection with the VTU on, whether the exact trace of the same ray against the
  // datapath's geometry already departs: vtu set).
  // What the primary hit got wrong (TraversalKind), for a pixel charged at P3. Distances in world
  // units against the format's ulp at the magnitude of o + t d in the hardware's frame (the largest
  // coordinate of the hit point and of the ray's origin: the camera at the origin with the VTU on,
  // the world's without).
  const int man_bits = cfg.format == hls::FormatId::fp24 ? 16 : 23;
  auto tolerance = [&](const reference::Ray& ray, double t) {
    double m = 0;  // the largest of the point's and the ray origin's coordinates (o + t d)
    for (int k = 0; k < 3; ++k) {
      const double p = ray.org[k] + t * ray.dir[k];
      m = std::max(m, cfg.vtu ? std::fabs(p - ray.org[k]) : std::max(std::fabs(p), std::fabs(ray.org[k])));
    }
    return kEdgeUlps * std::ldexp(1.0, std::ilogb(std::max(m, 1e-300)) - man_bits);
  };
  // The signed distance of the exact hit h on triangle tri to its nearest edge (negative: outside),
  // and that edge (the index of the vertex opposite it).
  auto edge_distance = [&](int32_t tri, const reference::TriHit& h, int* edge = nullptr) {
    const hls::Tri& v = stored.bvh().triangle(tri);
    double e[3][3], len[3];
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) e[i][k] = double(v[(i + 2) % 3][k]) - double(v[(i + 1) % 3][k]);
      len[i] = std::sqrt(e[i][0] * e[i][0] + e[i][1] * e[i][1] + e[i][2] * e[i][2]);
    }
    const double cx = e[1][1] * e[2][2] - e[1][2] * e[2][1], cy = e[1][2] * e[2][0] - e[1][0] * e[2][2],
                 cz = e[1][0] * e[2][1] - e[1][1] * e[2][0];
    const double twice_area = std::sqrt(cx * cx + cy * cy + cz * cz);
    const double w[3] = {h.b0, h.b1, h.b2};  // w_i: the weight of vertex i, 0 on the edge opposite it
    double d = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i)
      if (len[i] > 0 && w[i] * twice_area / len[i] < d) {
        d = w[i] * twice_area / len[i];
        if (edge) *edge = i;
      }
    return d;
  };
  // The scene's edges (its own vertices, as the glTF shares them): the triangles on each.
  struct EdgeKey {
    std::array<double, 6> p;
    bool operator==(const EdgeKey& o) const { return p == o.p; }
  };
  struct EdgeHash {
    size_t operator()(const EdgeKey& k) const {
      size_t h = 0;
      for (double x : k.p) h = h * 1000003u ^ std::hash<double>()(x);
      return h;
    }
  };
  auto edge_key = [&](int32_t tri, int opposite) {
    const hls::Tri& t = scene.tris[size_t(tri)];
    const hls::Vec3 &a = t[size_t((opposite + 1) % 3)], &c = t[size_t((opposite + 2) % 3)];
    const bool swap = std::make_tuple(c[0], c[1], c[2]) < std::make_tuple(a[0], a[1], a[2]);
    const hls::Vec3 &lo = swap ? c : a, &hi = swap ? a : c;
    return EdgeKey{{lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]}};
  };
  std::unordered_map<EdgeKey, std::vector<int32_t>, EdgeHash> edges;
  std::once_flag edges_built;
  auto neighbours = [&](int32_t tri, int opposite) -> const std::vector<int32_t>& {
    std::call_once(edges_built, [&] {
      for (size_t i = 0; i < scene.tris.size(); ++i)
        for (int j = 0; j < 3; ++j) edges[edge_key(int32_t(i), j)].push_back(int32_t(i));
    });
    return edges.at(edge_key(tri, opposite));
  };
  auto kind_of = [&](const PixelResult& hw, const PixelResult& p2, const reference::Ray& ray, ErrorPixel& ep) {
    reference::TriHit ha_hit, hb_hit;
    const bool ha = p2.tri >= 0 && plane_hit(stored, ray, p2.tri, &ha_hit);
    const bool hb = hw.tri >= 0 && plane_hit(stored, ray, hw.tri, &hb_hit);
    int edge = 0;
    const double da = ha ? edge_distance(p2.tri, ha_hit, &edge) : std::nan("");
    if (ha) ep.edge_a = da, ep.tol = tolerance(ray, ha_hit.t);
    if (hb) {
      ep.t_b_exact = hb_hit.t;
      ep.edge_b = edge_distance(hw.tri, hb_hit);
      if (!ha) ep.tol = tolerance(ray, hb_hit.t);
    }
    if (hw.tri == p2.tri) return TraversalKind::same;
    if (p2.tri >= 0) {  // the hardware's own test of A for this ray
      const IstVerdict va = rays.test(ep.x, ep.y, p2.tri);
      if (va.hit) {
        ep.t_a_hw = va.t;
        // It hits A too: A's leaf was never tested (the traversal), or B came first by the
        // hardware's t. That is an order of two hits where the exact ray meets B as well (inside
        // or on its edges); where it passes outside B, B's outline was decided wrong: a silhouette.
        if (hw.tri < 0 || va.t < hw.t) return TraversalKind::deep;
        return hb && ep.edge_b >= 0 ? TraversalKind::order : TraversalKind::silhouette;
      }
    }
    if (ha && da <= tolerance(ray, ha_hit.t)) {  // A missed near an edge
      // A seam only where a neighbour continues the surface across the edge as the ray sees it:
      // the ray meets its plane just outside it (by at most tol) or on its edge, the mirror of A's
      // just inside. A neighbour on A's side of the edge (a fold seen nearly edge-on: the ray meets
      // it inside too) leaves an outline there, which the ray's side of the edge decides: a
      // silhouette.
      bool seam = false, hit_other = false;
      for (int32_t nb : neighbours(p2.tri, edge))
        if (nb != p2.tri) {
          reference::TriHit hn;
          if (plane_hit(stored, ray, nb, &hn)) {
            const double dn = edge_distance(nb, hn);
            seam |= dn <= 0 && dn >= -tolerance(ray, hn.t);
          }
          hit_other |= nb == hw.tri;
        }
      return seam && !hit_other ? TraversalKind::crack : TraversalKind::silhouette;
    }
    if (hb) {
      const double d = ep.edge_b;
      if (d <= 0 && d >= -tolerance(ray, hb_hit.t)) return TraversalKind::silhouette;  // B just outside, or on its edge
    }
    return TraversalKind::deep;
  };
  // Charges pixel i and fills its record (ep: x, y and the hardware's hit set by the caller).
  auto charge = [&](size_t i, bool& vtu, ErrorPixel& ep) -> Stage {
    const PixelResult& hw = f.px[i];
    if (departs(ref_stored.px[i], i)) return Stage::storage;  // P1
    const int x = int(i % size_t(f.width)), y = int(i / size_t(f.width));
    const PixelRays r = rays.pixel(x, y, hw);
    const reference::Ray primary{r.org, r.dir};
    const PixelResult p2 = exact_pixel(stored, primary, r.tmin, r.tmax);  // P2
    ep.tri_a = p2.tri;
    if (p2.tri >= 0) ep.t_a = p2.t;
    if (departs(p2, i)) return Stage::ray_generation;
    PixelResult p3;  // P3: the hardware's hit, the exact shadow from its exact point
    if (hw.tri >= 0) {
      p3 = p2;
      p3.tri = hw.tri;
      p3.t = hw.t;
      if (p2.tri != hw.tri) {
        p3.front = p3.shadow_ray = p3.lit = false;
        p3.shadow_tri = -1;
        reference::TriHit h;
        if (plane_hit(stored, primary, hw.tri, &h)) {
          const reference::ShadowResult s = stored.shadow(primary.org, h);
          p3.front = p3.shadow_ray = s.shadow_ray;
          p3.lit = s.lit;
          p3.shadow_tri = s.shadow_tri;
        }
      }
    }
    if (departs(p3, i)) {
      vtu = datapath && departs(exact_pixel(*datapath, primary, r.tmin, r.tmax), i);
      ep.kind = kind_of(hw, p2, primary, ep);
      return Stage::traversal_primary;
    }
    // P4: the hardware's shadow ray traced exactly.
    auto shadow_traced = [&](const reference::Reference& scene_ref) {
      PixelResult p4 = hw;
      p4.lit = false;
      p4.shadow_tri = -1;
      if (r.shadow) {
        const SkipOne skip(r.shadow_skip);
        const reference::TriHit occ = scene_ref.closest(reference::Ray{r.shadow_org, r.shadow_dir}, r.shadow_tmin,
                                                        r.shadow_tmax, r.shadow_skip >= 0 ? &skip : nullptr);
        p4.lit = r.front && occ.tri < 0;
        p4.shadow_tri = occ.tri;
      }
      return p4;
    };
    if (departs(shadow_traced(stored), i)) return Stage::spawn;
    vtu = datapath && departs(shadow_traced(*datapath), i);
    return Stage::traversal_shadow;  // P5: the hardware frame, an error
  };
  std::vector<ErrorPixel>& eps = b.error_pixels;
  eps.assign(err.size(), ErrorPixel{});
  constexpr int kChunk = 64;
  const int chunks = int((err.size() + kChunk - 1) / kChunk);
  if (chunks > 0)
    reference::parallel_rows(chunks, cfg.threads, [&](int c) {
      for (size_t j = size_t(c) * kChunk; j < std::min(err.size(), size_t(c + 1) * kChunk); ++j) {
        const size_t i = err[j];
        ErrorPixel& ep = eps[j];
        ep.x = int(i % size_t(f.width));
        ep.y = int(i / size_t(f.width));
        ep.primary = reference::is_primary_error(reference::classify_pixel(f.px[i], ref.px[i]));
        ep.tri_b = f.px[i].tri;
        if (f.px[i].tri >= 0) ep.t_b = f.px[i].t;
        bool vtu = false;
        ep.stage = charge(i, vtu, ep);
        ep.vtu = vtu;
      }
    });
  for (size_t j = 0; j < err.size(); ++j) {
    const size_t i = err[j];
    const Stage stage = eps[j].stage;
    b.pixel[i] = stage;
    const bool primary = eps[j].primary;
    (primary ? b.primary_errors : b.shadow_errors)++;
    StageCount* c = nullptr;
    switch (stage) {
      case Stage::storage: c = &b.storage; break;
      case Stage::ray_generation: c = &b.ray_generation; break;
      case Stage::traversal_primary:
        c = &b.traversal_intersection;
        if (!primary) ++b.traversal_shadow_by_primary_ray;
        ++b.traversal_kind[size_t(eps[j].kind)];
        break;
      case Stage::spawn: c = &b.spawn; break;
      case Stage::traversal_shadow:
        c = &b.traversal_intersection;
        ++b.traversal_shadow_by_shadow_ray;
        break;
      case Stage::none: throw std::logic_error("stage_budget: an error pixel without a stage");
    }
    (primary ? c->primary : c->shadow)++;
    if (eps[j].vtu) (primary ? b.traversal_vtu_primary : b.traversal_vtu_shadow)++;
  }
  b.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return b;
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

FrameErrors measure_errors(const Frame& f, const scenes::Scene& scene, const hls::Image& image,
                           const TraceConfig& cfg) {
  const auto t0 = std::chrono::steady_clock::now();
  FrameErrors e;
  const Frame ref = reference::render(scene, f.width, f.height, cfg.threads);
  e.total = reference::compute_errors(f, ref, scene.tris);
  const scenes::Scene st = stored_scene(scene, image, cfg.anchor);
  const reference::Reference stored(st);
  const Frame ref_st = stored.render(f.width, f.height, cfg.threads);
  e.stored = reference::compute_errors(f, ref_st, st.tris);
  try {
    const auto t1 = std::chrono::steady_clock::now();
    std::unique_ptr<reference::Reference> datapath;
    if (cfg.vtu) datapath = std::make_unique<reference::Reference>(datapath_scene(scene, image, cfg));
    e.stages = stage_budget(f, scene, image, cfg, ref, ref_st, stored, datapath.get());
    e.stages.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();  // with datapath's BVH
    e.has_stages = true;
  } catch (const std::runtime_error& x) {  // a frame that is not the golden tracer's (simulate reports it)
    e.stages_note = x.what();
  }
  if (e.has_stages &&
      (e.stages.primary_errors != e.total.primary_errors || e.stages.shadow_errors != e.total.shadow_errors))
    throw std::logic_error("stage_budget: the stages do not add up to the totals");
  e.reference_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return e;
}

nlohmann::json stages_json(const StageBudget& b) {
  auto c = [](const StageCount& s) {
    return nlohmann::json{{"primary", s.primary}, {"shadow", s.shadow}, {"total", s.total()}};
  };
  nlohmann::json j;
  j["order"] = {"storage", "ray_generation", "traversal_intersection", "spawn"};
  j["storage"] = c(b.storage);
  j["ray_generation"] = c(b.ray_generation);
  j["traversal_intersection"] = c(b.traversal_intersection);
  j["traversal_intersection"]["shadow_by_primary_ray"] = b.traversal_shadow_by_primary_ray;
  j["traversal_intersection"]["shadow_by_shadow_ray"] = b.traversal_shadow_by_shadow_ray;
  j["traversal_intersection"]["vtu_primary"] = b.traversal_vtu_primary;
  j["traversal_intersection"]["vtu_shadow"] = b.traversal_vtu_shadow;
  j["traversal_intersection"]["by_primary_ray"] = {
      {"crack", b.traversal_kind[0]}, {"silhouette", b.traversal_kind[1]}, {"order", b.traversal_kind[2]},
      {"deep", b.traversal_kind[3]}, {"same", b.traversal_kind[4]}};
  j["spawn"] = c(b.spawn);
  j["primary_errors"] = b.primary_errors;
  j["shadow_errors"] = b.shadow_errors;
  j["error_pixels"] = b.primary_errors + b.shadow_errors;
  j["wall_seconds"] = b.seconds;
  return j;
}

void write_error_pixels(const StageBudget& b, const std::string& path) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> out(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!out) throw std::runtime_error("--error-pixels: cannot write " + path);
  static const char* const stages[] = {"none", "storage", "ray_generation", "traversal_intersection", "spawn",
                                       "traversal_intersection"};
  static const char* const kinds[] = {"crack", "silhouette", "order", "deep", "same"};
  auto num = [](double v) {
    if (std::isnan(v)) return std::string();
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  std::fprintf(out.get(), "x,y,error,stage,ray,kind,vtu,tri_a,t_a,t_a_hw,tri_b,t_b,t_b_exact,edge_a,edge_b,tol\n");
  for (const ErrorPixel& p : b.error_pixels) {
    const bool trv = p.stage == Stage::traversal_primary || p.stage == Stage::traversal_shadow;
    const char* ray = p.stage == Stage::traversal_primary ? "primary" : p.stage == Stage::traversal_shadow ? "shadow" : "";
    std::fprintf(out.get(), "%d,%d,%s,%s,%s,%s,%s,%d,%s,%s,%d,%s,%s,%s,%s,%s\n", p.x, p.y,
                 p.primary ? "primary" : "shadow", stages[size_t(p.stage)], ray,
                 p.stage == Stage::traversal_primary ? kinds[size_t(p.kind)] : "", trv ? (p.vtu ? "1" : "0") : "",
                 p.tri_a, num(p.t_a).c_str(), num(p.t_a_hw).c_str(), p.tri_b, num(p.t_b).c_str(), num(p.t_b_exact).c_str(),
                 num(p.edge_a).c_str(), num(p.edge_b).c_str(), num(p.tol).c_str());
  }
  if (std::fflush(out.get()) != 0 || std::ferror(out.get()))
    throw std::runtime_error("--error-pixels: cannot write " + path);
}

void write_error_pixels(const FrameErrors& e, bool have_reference, const std::string& path) {
  if (!have_reference) throw std::runtime_error("--error-pixels: no error budget (the scene has no triangles)");
  if (!e.has_stages) throw std::runtime_error("--error-pixels: no error budget (" + e.stages_note + ")");
  write_error_pixels(e.stages, path);
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
  if (e.has_stages) j["errors_by_stage"] = stages_json(e.stages);
  if (!e.stages_note.empty()) j["errors_by_stage"] = {{"error", e.stages_note}};
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
  if (!e.stages_note.empty()) std::printf("          by stage: not measured (%s)\n", e.stages_note.c_str());
  if (!e.has_stages) return;
  const StageBudget& b = e.stages;
  auto two = [](const StageCount& c) {
    return std::to_string(c.primary) + " + " + std::to_string(c.shadow);
  };
  std::printf("          by stage (primary + shadow):  storage %s, ray generation %s, traversal/intersection "
              "%s (shadow: %llu by the primary ray's hit, %llu by the shadow ray's; the VTU's geometry "
              "%llu + %llu; the primary ray's: crack %llu, silhouette %llu, order %llu, deep %llu, same "
              "triangle %llu), spawn %s\n",
              two(b.storage).c_str(), two(b.ray_generation).c_str(), two(b.traversal_intersection).c_str(),
              (unsigned long long)b.traversal_shadow_by_primary_ray,
              (unsigned long long)b.traversal_shadow_by_shadow_ray, (unsigned long long)b.traversal_vtu_primary,
              (unsigned long long)b.traversal_vtu_shadow, (unsigned long long)b.traversal_kind[0],
              (unsigned long long)b.traversal_kind[1], (unsigned long long)b.traversal_kind[2],
              (unsigned long long)b.traversal_kind[3], (unsigned long long)b.traversal_kind[4],
              two(b.spawn).c_str());
}

}  // namespace raycore::sim
