// sim/reference/embree_check.cpp - see embree_check.h.
#include "sim/reference/embree_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sim/reference/reference.h"

#if RAYCORE_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

namespace raycore::reference {
namespace {

// min(b0, b1, b2) of the ray against the triangle's plane, with the same sheared edge functions
// as the watertight test but without rejecting: > 0 inside, < 0 outside (by that barycentric
// margin), 0 on an edge; -inf if the ray is parallel to the plane.
double edge_margin(const Ray& ray, const Tri& tri) {
  const ShearedRay s(ray);
  const Vec3 a = tri[0] - s.org, b = tri[1] - s.org, c = tri[2] - s.org;
  const double ax = a[s.kx] - s.sx * a[s.kz], ay = a[s.ky] - s.sy * a[s.kz];
  const double bx = b[s.kx] - s.sx * b[s.kz], by = b[s.ky] - s.sy * b[s.kz];
  const double cx = c[s.kx] - s.sx * c[s.kz], cy = c[s.ky] - s.sy * c[s.kz];
  const double u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
  const double det = u + v + w;
  if (det == 0) return -std::numeric_limits<double>::infinity();
  return std::min({u / det, v / det, w / det});
}

Vec3 to_float(const Vec3& v) { return {double(float(v.x)), double(float(v.y)), double(float(v.z))}; }

// Does the exact (double, watertight) test on float-rounded inputs decide between the reference's
// triangle and Embree's as Embree did?
bool explained_by_float_inputs(const Ray& ray, const std::vector<Tri>& tris, int32_t ref_tri, int32_t emb_tri) {
  const Ray fr{to_float(ray.org), to_float(ray.dir)};
  const ShearedRay s(fr);
  auto test = [&](int32_t id, TriHit* h) {
    if (id < 0) return false;
    const Tri& t = tris[size_t(id)];
    const Tri ft = {to_float(t[0]), to_float(t[1]), to_float(t[2])};
    return intersect_triangle(s, ft, 0.0, HUGE_VAL, h);
  };
  TriHit hr, he;
  const bool r = test(ref_tri, &hr), e = test(emb_tri, &he);
  if (emb_tri < 0) return !r;  // Embree missed the reference's triangle
  if (ref_tri < 0) return e;   // Embree hit a triangle the reference's ray misses
  return e && (!r || he.t < hr.t);
}

#if RAYCORE_HAVE_EMBREE
// Owns an Embree device and a committed scene of the triangles (converted to float).
class EmbreeScene {
 public:
  EmbreeScene(const std::vector<Tri>& tris, int threads) {
    const std::string cfg = "threads=" + std::to_string(std::max(1, threads));
    device_ = rtcNewDevice(cfg.c_str());
    if (!device_) throw std::runtime_error("embree: rtcNewDevice failed");
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), 3 * tris.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), tris.size()));
    if (!vb || !ib) {
      rtcReleaseGeometry(g);
      throw std::runtime_error("embree: cannot allocate geometry buffers");
    }
    for (size_t i = 0; i < tris.size(); ++i)
      for (size_t k = 0; k < 3; ++k) {
        for (int c = 0; c < 3; ++c) vb[9 * i + 3 * k + size_t(c)] = float(tris[i][k][c]);
        ib[3 * i + k] = unsigned(3 * i + k);
      }
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw std::runtime_error("embree: scene build failed");
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  ~EmbreeScene() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
  }
  // Closest hit of a float ray: primitive id (-1 = miss) and t.
  int32_t intersect(const Vec3& org, const Vec3& dir, float* t) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    rh.ray.org_x = float(org.x);
    rh.ray.org_y = float(org.y);
    rh.ray.org_z = float(org.z);
    rh.ray.dir_x = float(dir.x);
    rh.ray.dir_y = float(dir.y);
    rh.ray.dir_z = float(dir.z);
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return -1;
    *t = rh.ray.tfar;
    return int32_t(rh.hit.primID);
  }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};
#endif

}  // namespace

bool embree_available() { return RAYCORE_HAVE_EMBREE != 0; }

EmbreeAgreement embree_check(const scenes::Scene& scene, int width, int height, const EmbreeCheckOptions& opt) {
  const Reference ref(scene);
  return embree_check(scene, ref.render(width, height, opt.threads, /*shadows=*/false), opt);
}

EmbreeAgreement embree_check(const scenes::Scene& scene, const sim::Frame& ref, const EmbreeCheckOptions& opt) {
#if !RAYCORE_HAVE_EMBREE
  (void)scene;
  (void)ref;
  (void)opt;
  throw std::runtime_error("embree_check: this build has no Embree (libembree-dev, embree 3)");
#else
  const int w = ref.width, h = ref.height;
  if (w <= 0 || h <= 0 || ref.px.size() != size_t(w) * size_t(h))
    throw std::invalid_argument("embree_check: reference frame is empty or inconsistent");
  const EmbreeScene es(scene.tris, opt.threads);
  const size_t n = ref.px.size();
  std::vector<int32_t> e_tri(n, -1);
  std::vector<float> e_t(n, 0.0f);
  parallel_rows(h, opt.threads, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      const Vec3 dir = scenes::primary_direction(scene.camera, x, y, w, h);
      e_tri[i] = es.intersect(scene.camera.position, dir, &e_t[i]);
    }
  });

  EmbreeAgreement a;
  a.pixels = n;
  for (size_t i = 0; i < n; ++i) {
    const sim::PixelResult& r = ref.px[i];
    const int32_t et = e_tri[i];
    if (r.tri >= 0 && size_t(r.tri) >= scene.tris.size())
      throw std::invalid_argument("embree_check: reference frame indexes a triangle the scene lacks");
    if (r.tri < 0 && et < 0) {
      ++a.agree_both_miss;
      continue;
    }
    if (r.tri >= 0 && r.tri == et) {
      ++a.agree_same_tri;
      continue;
    }
    if (r.tri >= 0 && et >= 0 && std::fabs(double(e_t[i]) - r.t) <= opt.rel_tol * r.t) {
      ++a.agree_tie;
      continue;
    }
    EmbreeDisagreement d;
    d.x = int(i % size_t(w));
    d.y = int(i / size_t(w));
    d.ref_tri = r.tri;
    d.ref_t = r.t;
    d.embree_tri = et;
    d.embree_t = et >= 0 ? double(e_t[i]) : 0.0;
    const Ray ray{scene.camera.position, scenes::primary_direction(scene.camera, d.x, d.y, w, h)};
    d.ref_edge_margin = r.tri >= 0 ? edge_margin(ray, scene.tris[size_t(r.tri)]) : 0.0;
    d.embree_edge_margin = et >= 0 ? edge_margin(ray, scene.tris[size_t(et)]) : 0.0;
    const bool ref_edge = r.tri >= 0 && std::fabs(d.ref_edge_margin) < opt.edge_tol;
    const bool emb_edge = et >= 0 && std::fabs(d.embree_edge_margin) < opt.edge_tol;
    d.near_edge = ref_edge || emb_edge;
    d.float_inputs = explained_by_float_inputs(ray, scene.tris, r.tri, et);
    if (d.float_inputs) ++a.disagree_float_inputs;
    if (et < 0) {
      d.cause = "embree_miss";
      ++a.embree_miss;
    } else if (r.tri < 0) {
      d.cause = "embree_extra_hit";
      ++a.embree_extra_hit;
    } else {
      d.cause = "different_surface";
      ++a.different_surface;
    }
    if (d.near_edge) ++a.disagree_near_edge;
    if (a.examples.size() < opt.max_examples) a.examples.push_back(d);
  }
  a.agree = a.agree_both_miss + a.agree_same_tri + a.agree_tie;
  a.disagree = a.pixels - a.agree;
  a.agreement_pct = a.pixels ? 100.0 * double(a.agree) / double(a.pixels) : 0.0;
  return a;
#endif
}

nlohmann::json to_json(const EmbreeAgreement& a) {
  nlohmann::json ex = nlohmann::json::array();
  for (const auto& d : a.examples)
    ex.push_back({{"x", d.x}, {"y", d.y}, {"cause", d.cause}, {"near_edge", d.near_edge}, {"float_inputs", d.float_inputs},
                  {"ref_tri", d.ref_tri}, {"ref_t", d.ref_t}, {"ref_edge_margin", d.ref_edge_margin},
                  {"embree_tri", d.embree_tri}, {"embree_t", d.embree_t},
                  {"embree_edge_margin", d.embree_edge_margin}});
  return {{"pixels", a.pixels},
          {"agree", a.agree},
          {"agree_both_miss", a.agree_both_miss},
          {"agree_same_tri", a.agree_same_tri},
          {"agree_tie", a.agree_tie},
          {"disagree", a.disagree},
          {"embree_miss", a.embree_miss},
          {"embree_extra_hit", a.embree_extra_hit},
          {"different_surface", a.different_surface},
          {"disagree_near_edge", a.disagree_near_edge},
          {"disagree_float_inputs", a.disagree_float_inputs},
          {"agreement_pct", a.agreement_pct},
          {"examples", ex}};
}

}  // namespace raycore::reference
