// The double-precision reference tracer (sim/reference/reference.h, bvh.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "meshes.h"
#include "sim/reference/predicates.h"
#include "sim/reference/reference.h"

namespace raycore::reference {
namespace {

using namespace testing;

// --- Single triangle and single quad: exact expected hits ---------------------------------------

TEST(ReferenceTracer, SingleTriangleExactHit) {
  const Reference ref(make_scene({{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}}}, look_at({0, 0, 5}, {0, 0, 0}),
                                 {0, 0, 10}));
  TriHit h = ref.closest({{0.25, 0.25, 1}, {0, 0, -1}});
  EXPECT_EQ(h.tri, 0);
  EXPECT_EQ(h.t, 1.0);
  EXPECT_EQ(h.b0, 0.5);
  EXPECT_EQ(h.b1, 0.25);
  EXPECT_EQ(h.b2, 0.25);
  // From behind (no culling), a longer non-unit direction: t in units of |dir|.
  h = ref.closest({{0.5, 0.25, -3}, {0, 0, 2}});
  EXPECT_EQ(h.tri, 0);
  EXPECT_EQ(h.t, 1.5);
  const Vec3 p = ref.hit_point(h);
  EXPECT_EQ(p.x, 0.5);
  EXPECT_EQ(p.y, 0.25);
  EXPECT_EQ(p.z, 0.0);
  // Misses: outside, beyond t_max, behind the origin, parallel to the plane.
  EXPECT_EQ(ref.closest({{2, 2, 1}, {0, 0, -1}}).tri, -1);
  EXPECT_EQ(ref.closest({{0.25, 0.25, 1}, {0, 0, -1}}, 0, 1.0).tri, -1);
  EXPECT_EQ(ref.closest({{0.25, 0.25, 1}, {0, 0, 1}}).tri, -1);
  EXPECT_EQ(ref.closest({{-1, 0.25, 0}, {1, 0, 0}}).tri, -1);
  // Exactly on a vertex and on an edge: hits (the test is closed).
  EXPECT_EQ(ref.closest({{1, 0, 1}, {0, 0, -1}}).tri, 0);
  EXPECT_EQ(ref.closest({{0.5, 0.5, 1}, {0, 0, -1}}).tri, 0);
  EXPECT_EQ(ref.closest({{0.5, 0.5 + 0x1p-52, 1}, {0, 0, -1}}).tri, -1);
}

// A ray exactly on an edge whose projected vertices the double shear rounds: origin-far-camera's
// pixel (193, 167) in FP24 (its ray's components are FP24 values), which meets the plane y = 0 at x
// = -100 exactly (z = -1925/59), on the triangle's edge x = -100. The test is closed, so it hits;
// before 2026-12-07 the double sheared coordinates put it outside. Just beside the edge (the
// origin moved by an ulp) the exact side decides either way.
TEST(ReferenceTracer, RayExactlyOnAnEdgeFarFromTheOriginHits) {
  const Vec3 o{30000, 24000, 40000}, d{-0.541961669921875, -0.43212890625, -0.72080230712890625};
  const Reference ref(make_scene({{Vec3{-100, 0, -40}, Vec3{-100, 0, -30}, Vec3{-90, 0, -30}}},
                                 look_at(o, {-100, 0, -32}), {0, 100, 0}));
  const TriHit h = ref.closest({o, d});
  EXPECT_EQ(h.tri, 0);
  EXPECT_NEAR(h.t, 24000 / 0.43212890625, 1e-9);
  // x = -100 - dx 2^-41 t': the ray 2^-41 x 55539 beside the edge, outside (x < -100) or inside.
  EXPECT_EQ(ref.closest({{std::nextafter(30000.0, 0.0), 24000, 40000}, d}).tri, -1);
  EXPECT_EQ(ref.closest({{std::nextafter(30000.0, 1e9), 24000, 40000}, d}).tri, 0);
  // The predicate itself: the edge (-100, 0, -40) -> (-100, 0, -30), sheared as ShearedRay does.
  const ShearedRay sr(Ray{o, d});
  const Vec3 p{-100, 0, -40}, q{-100, 0, -30};
  EXPECT_EQ(sheared_edge_sign(o, d, sr.kx, sr.ky, sr.kz, p, q), 0);
  EXPECT_EQ(sheared_edge_sign(o, d, sr.kx, sr.ky, sr.kz, q, p), 0);
  const Vec3 o2{std::nextafter(30000.0, 0.0), 24000, 40000};
  EXPECT_EQ(sheared_edge_sign(o2, d, sr.kx, sr.ky, sr.kz, p, q), -sheared_edge_sign(o2, d, sr.kx, sr.ky, sr.kz, q, p));
  EXPECT_NE(sheared_edge_sign(o2, d, sr.kx, sr.ky, sr.kz, p, q), 0);
}

TEST(ReferenceTracer, SingleQuadExactHitsAndTies) {
  // Two triangles in z = 5, diagonal (0,0)-(2,2): tri 0 below it, tri 1 above it.
  const Reference ref(make_scene(quad(2, 5.0, 0, 2, 0, 2), look_at({1, 1, 0}, {1, 1, 5}), {1, 1, -5}));
  ASSERT_EQ(ref.bvh().size(), 2u);
  struct Case {
    double x, y;
    int32_t tri;
  } cases[] = {{1.5, 0.5, 0}, {0.5, 1.5, 1}, {1, 1, 0} /* on the diagonal: tie -> lowest index */,
               {2, 2, 0} /* shared corner */, {0, 2, 1}, {2, 0, 0}, {2.5, 1, -1}, {-0x1p-40, 1, -1}};
  for (const Case& c : cases) {
    const TriHit h = ref.closest({{c.x, c.y, 0}, {0, 0, 1}});
    EXPECT_EQ(h.tri, c.tri) << "ray at (" << c.x << ", " << c.y << ")";
    if (c.tri >= 0) {
      EXPECT_EQ(h.t, 5.0) << "ray at (" << c.x << ", " << c.y << ")";
    }
  }
  // The tie goes to the lowest scene index whatever the order: swap the two triangles.
  auto swapped = quad(2, 5.0, 0, 2, 0, 2);
  std::swap(swapped[0], swapped[1]);
  const Reference ref2(make_scene(swapped, look_at({1, 1, 0}, {1, 1, 5}), {1, 1, -5}));
  EXPECT_EQ(ref2.closest({{1, 1, 0}, {0, 0, 1}}).tri, 0);
  EXPECT_EQ(ref2.closest({{1.5, 0.5, 0}, {0, 0, 1}}).tri, 1);
  // Pixel interface: the camera's centre ray (2x2 image: corner pixels) all hit at the expected
  // triangles; the image centre is the shared diagonal.
  const Reference ref3(make_scene(quad(2, 5.0, 0, 2, 0, 2), look_at({1, 1, 0}, {1, 1, 5}, 40.0), {1, 1, -5}));
  const sim::Frame f = ref3.render(2, 2, 1);
  for (const auto& px : f.px) {
    EXPECT_GE(px.tri, 0);
    EXPECT_NEAR(px.hit.z, 5.0, 1e-15);
  }
}

TEST(ReferenceTracer, DegenerateTrianglesAreNeverHit) {
  std::vector<Tri> t = {{Vec3{0, 0, 0}, Vec3{1, 1, 0}, Vec3{2, 2, 0}}, {Vec3{0, 0, 0}, Vec3{0, 0, 0}, Vec3{1, 0, 0}}};
  const Reference ref(make_scene(t, look_at({0, 0, 5}, {0, 0, 0}), {0, 0, 10}));
  EXPECT_EQ(ref.bvh().stats().degenerate, 2u);
  EXPECT_EQ(ref.closest({{1, 1, 1}, {0, 0, -1}}).tri, -1);
  EXPECT_EQ(ref.closest({{0.5, 0, 1}, {0, 0, -1}}).tri, -1);
}

TEST(ReferenceTracer, BadInputIsRejected) {
  scenes::Scene s = make_scene(quad(2, 5.0, 0, 2, 0, 2), look_at({1, 1, 0}, {1, 1, 5}), {1, 1, -5});
  s.light.present = false;
  EXPECT_THROW(Reference{s}, std::runtime_error);
  s.light.present = true;
  s.tris[1][2].y = std::nan("");
  try {
    Reference r(s);
    FAIL() << "a NaN coordinate was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 1"), std::string::npos) << e.what();
  }
  s.tris[1][2].y = 2;
  EXPECT_THROW(Reference(s).render(0, 10), std::runtime_error);
}

// --- The BVH finds exactly what a brute-force loop over all triangles finds --------------------

TEST(ReferenceTracer, BvhMatchesBruteForce) {
  // Large random triangles (split into many references by the builder) among small ones, far
  // from the origin, and random rays and segments through the scene.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 c{3000.5, -1200.25, 700.125};
  std::vector<Tri> tris;
  auto rnd = [&](double s) { return c + Vec3{u(rng), u(rng), u(rng)} * s; };
  for (int i = 0; i < 60; ++i) tris.push_back({rnd(100), rnd(100), rnd(100)});
  for (int i = 0; i < 3000; ++i) {
    const Vec3 p = rnd(100);
    tris.push_back({p, p + Vec3{u(rng), u(rng), u(rng)} * 3.0, p + Vec3{u(rng), u(rng), u(rng)} * 3.0});
  }
  append(tris, quad(1, c.y - 50, c.z - 150, c.z + 150, c.x - 150, c.x + 150));  // a big floor
  const Reference ref(make_scene(tris, look_at(c + Vec3{0, 0, 300}, c), c + Vec3{0, 500, 0}));
  EXPECT_GT(ref.bvh().stats().references, tris.size() + 100) << "large triangles should be split";
  int mismatches = 0, hits = 0;
  for (int i = 0; i < 4000; ++i) {
    const bool segment = i % 2 == 1;
    const Ray ray{rnd(150), Vec3{u(rng), u(rng), u(rng)} * (segment ? 200.0 : 1.0)};
    const double t_min = segment ? 1e-3 : 0.0, t_max = segment ? 1.0 : HUGE_VAL;
    const ShearedRay s(ray);
    TriHit best;
    best.t = t_max;
    for (size_t k = 0; k < tris.size(); ++k) {
      TriHit h;
      if (is_degenerate(tris[k][0], tris[k][1], tris[k][2])) continue;
      if (!intersect_triangle(s, tris[k], t_min, t_max, &h)) continue;
      if (best.tri < 0 || h.t < best.t) {
        h.tri = int32_t(k);
        best = h;
      }
    }
    const TriHit b = ref.closest(ray, t_min, t_max);
    hits += b.tri >= 0;
    if ((b.tri != best.tri || (b.tri >= 0 && b.t != best.t)) && ++mismatches <= 5)
      ADD_FAILURE() << "ray " << i << ": BVH tri " << b.tri << " t " << b.t << ", brute force tri " << best.tri
                    << " t " << best.t;
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(hits, 1000);
}

// --- Watertightness ------------------------------------------------------------------------------

// Rays from `origin` (inside the closed mesh) through every vertex, through points exactly on
// every edge, and in random directions: none may escape.
void expect_no_escapes(const std::vector<Tri>& mesh, const std::vector<Vec3>& origins, int random_rays,
                       const char* what) {
  const Reference ref(make_scene(mesh, look_at({0, 0, 5}, {0, 0, 0}), {0, 0, 10}));
  std::mt19937_64 rng(12345);
  std::normal_distribution<double> g;
  uint64_t rays = 0, escapes = 0;
  auto shoot = [&](const Vec3& o, const Vec3& d) {
    ++rays;
    if (ref.closest({o, d}).tri < 0) {
      if (++escapes <= 5)
        ADD_FAILURE() << what << ": ray escapes: origin (" << o.x << ", " << o.y << ", " << o.z << ") dir ("
                      << d.x << ", " << d.y << ", " << d.z << ")";
    }
  };
  for (const Vec3& o : origins) {
    for (const Tri& t : mesh)
      for (int a = 0; a < 3; ++a) {
        const Vec3 va = t[size_t(a)], vb = t[size_t((a + 1) % 3)];
        for (double f : {0.0, 0.125, 0.5, 0.875}) shoot(o, (va + (vb - va) * f) - o);
      }
    for (int i = 0; i < random_rays; ++i) {
      const Vec3 d{g(rng), g(rng), g(rng)};
      if (hls::dot(d, d) > 0) shoot(o, d);
    }
  }
  EXPECT_EQ(escapes, 0u) << what << ": " << escapes << " of " << rays << " rays escaped";
  EXPECT_GT(rays, 1000u);
}

TEST(ReferenceTracer, WatertightCubeEdgesAndCorners) {
  expect_no_escapes(cube(1.0), {{0, 0, 0}, {0.1, -0.2, 0.3}, {-0.37, 0.11, 0.5}, {0.9, 0.9, 0.9}}, 20000,
                    "cube");
}

TEST(ReferenceTracer, WatertightIcosphere) {
  const Vec3 c{1000.3, -20.7, 5.1};  // away from the origin: coordinates carry rounding
  expect_no_escapes(icosphere(3, 3.0, c), {c, c + Vec3{0.5, -1.1, 0.7}, c + Vec3{-2.2, 0.3, 1.4}}, 30000,
                    "icosphere");
}

// --- Shadows ---------------------------------------------------------------------------------------

// Floor y = 0 over [-10, 10]^2 (tris 0, 1; its diagonal passes through the origin), camera above
// looking at the origin.
scenes::Scene shadow_scene(Vec3 light, const std::vector<double>& occluder_heights) {
  std::vector<Tri> t = quad(1, 0.0, -10, 10, -10, 10);
  for (double hgt : occluder_heights) append(t, quad(1, hgt, -1, 1, -1, 1));
  return make_scene(t, look_at({0, 5, 10}, {0, 0, 0}), light);
}

sim::PixelResult trace_to_origin(const Reference& ref) {
  const Vec3 eye = ref.camera().position;
  return ref.trace({eye, hls::normalize(Vec3{0, 0, 0} - eye)});
}

TEST(ReferenceTracer, ShadowOccluderBetweenHitAndLight) {
  const Reference ref(shadow_scene({0, 10, 0}, {5.0}));
  const sim::PixelResult px = trace_to_origin(ref);
  EXPECT_TRUE(px.tri == 0 || px.tri == 1) << px.tri;  // on or next to the floor's diagonal
  EXPECT_TRUE(px.shadow_ray);
  EXPECT_FALSE(px.lit);
  EXPECT_TRUE(px.shadow_tri == 2 || px.shadow_tri == 3) << px.shadow_tri;
  EXPECT_EQ(px.shade, 40);
}

TEST(ReferenceTracer, ShadowNearestOfSeveralOccluders) {
  const Reference ref(shadow_scene({0, 10, 0}, {6.0, 3.0, 8.0}));  // tris 2-3 at 6, 4-5 at 3
  const sim::PixelResult px = trace_to_origin(ref);
  EXPECT_FALSE(px.lit);
  EXPECT_TRUE(px.shadow_tri == 4 || px.shadow_tri == 5) << px.shadow_tri;
}

TEST(ReferenceTracer, ShadowNoOccluderIsLit) {
  const Reference ref(shadow_scene({0, 10, 0}, {}));
  const sim::PixelResult px = trace_to_origin(ref);
  EXPECT_TRUE(px.shadow_ray);
  EXPECT_TRUE(px.lit);
  EXPECT_EQ(px.shadow_tri, -1);
  EXPECT_EQ(px.shade, 255);  // light straight above: cos = 1
  // An occluder beyond the light does not count.
  const Reference beyond(shadow_scene({0, 10, 0}, {12.0}));
  EXPECT_TRUE(trace_to_origin(beyond).lit);
}

TEST(ReferenceTracer, ShadowLightBehindOrInPlaneSpawnsNoRay) {
  for (const Vec3& light : {Vec3{0, -10, 0}, Vec3{5, 0, 5}, Vec3{50, 0, -3}}) {
    const Reference ref(shadow_scene(light, {5.0}));
    const sim::PixelResult px = trace_to_origin(ref);
    EXPECT_GE(px.tri, 0);
    EXPECT_FALSE(px.shadow_ray) << "light at " << light.y;
    EXPECT_FALSE(px.lit);
    EXPECT_EQ(px.shadow_tri, -1);
  }
}

TEST(ReferenceTracer, ShadowOccluderVeryCloseToTheHitPointIsFound) {
  // A wall 1e-6 beside the hit point, unseen by the camera (which looks from the other side) but
  // crossing the shadow ray at a distance of 1.4e-6: far beyond the hit point's error bound.
  for (const Vec3& o : {Vec3{0, 0, 0}, Vec3{1000.5, -2000.25, 3000.125}}) {
    std::vector<Tri> t = quad(1, o.y, o.z - 10, o.z + 10, o.x - 10, o.x + 10);  // floor y = o.y
    append(t, quad(0, o.x + 1e-6, o.y, o.y + 1, o.z - 1, o.z + 1));            // wall x = o.x + 1e-6
    const Reference ref(make_scene(t, look_at(o + Vec3{-5, 5, 0.25}, o), o + Vec3{10, 10, 0}));
    const Vec3 eye = ref.camera().position;
    const sim::PixelResult px = ref.trace({eye, hls::normalize(o - eye)});
    ASSERT_TRUE(px.tri == 0 || px.tri == 1) << px.tri;
    EXPECT_LT(px.hit.x, o.x + 1e-6);
    EXPECT_TRUE(px.shadow_ray);
    EXPECT_FALSE(px.lit) << "origin " << o.x;
    EXPECT_TRUE(px.shadow_tri == 2 || px.shadow_tri == 3) << px.shadow_tri;
    const ShadowResult s = ref.shadow(eye, ref.closest({eye, hls::normalize(o - eye)}));
    EXPECT_LT(s.t_lo, 1e-9);
  }
}

TEST(ReferenceTracer, GrazingLightOverTessellatedFloorFarFromOriginIsLitEverywhere) {
  // A tilted floor far from the origin, 16 x 16 cells, vertex heights computed in double (so
  // neighbours are only nearly coplanar); the light 2 degrees above the floor's plane, far away.
  const Vec3 o{5000.3, 1200.7, -7000.1};
  auto height = [](double x, double z) { return 0.1 * x + 0.05 * z; };
  std::vector<Tri> t;
  const int n = 16;
  const double cell = 1.37;
  auto vtx = [&](int i, int j) {
    const double x = i * cell, z = j * cell;
    return o + Vec3{x, height(x, z), z};
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      t.push_back({vtx(i, j), vtx(i + 1, j), vtx(i + 1, j + 1)});
      t.push_back({vtx(i, j), vtx(i + 1, j + 1), vtx(i, j + 1)});
    }
  const Vec3 centre = vtx(n / 2, n / 2);
  // Floor normal ~ (-0.1, 1, -0.05); light direction tilted 2 degrees up from an in-plane vector.
  const Vec3 nrm = hls::normalize({-0.1, 1.0, -0.05});
  const Vec3 along = hls::normalize(hls::cross(nrm, {0, 0, 1}));
  const double a = 2.0 * M_PI / 180.0;
  const Vec3 light = centre + (along * std::cos(a) + nrm * std::sin(a)) * 500.0;
  const Reference ref(make_scene(t, look_at(centre + Vec3{3, 15, 25}, centre), light));
  const sim::Frame f = ref.render(80, 60, 2);
  uint64_t hits = 0, shadow_rays = 0, lit = 0, self = 0;
  for (const auto& px : f.px) {
    if (px.tri < 0) continue;
    ++hits;
    shadow_rays += px.shadow_ray;
    lit += px.shadow_ray && px.lit;
    self += px.shadow_ray && px.shadow_tri == px.tri;
  }
  // And rays aimed exactly at every vertex and at points on every edge: hit points on shared
  // edges, where the neighbours (nearly coplanar) touch the shadow ray's origin.
  const Vec3 eye = ref.camera().position;
  for (const Tri& tri : t)
    for (int k = 0; k < 3; ++k)
      for (double along_edge : {0.0, 0.25, 0.5}) {
        const Vec3 target = tri[size_t(k)] + (tri[size_t((k + 1) % 3)] - tri[size_t(k)]) * along_edge;
        const sim::PixelResult px = ref.trace({eye, target - eye});
        if (px.tri < 0) continue;
        ++hits;
        shadow_rays += px.shadow_ray;
        lit += px.shadow_ray && px.lit;
        self += px.shadow_ray && px.shadow_tri == px.tri;
      }
  EXPECT_GT(hits, 5000u);
  EXPECT_EQ(shadow_rays, hits);
  EXPECT_EQ(lit, hits);
  EXPECT_EQ(self, 0u);
}

// --- Thread-count invariance -------------------------------------------------------------------------

bool same_bits(const sim::PixelResult& a, const sim::PixelResult& b) {
  auto eq = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  return a.tri == b.tri && a.t_bits == b.t_bits && eq(a.t, b.t) && eq(a.hit.x, b.hit.x) && eq(a.hit.y, b.hit.y) &&
         eq(a.hit.z, b.hit.z) && a.shadow_ray == b.shadow_ray && a.lit == b.lit && a.shadow_tri == b.shadow_tri &&
         a.shade == b.shade;
}

TEST(ReferenceTracer, ThreadCountInvariance) {
  const Reference ref(test_world());
  const sim::Frame f1 = ref.render(96, 64, 1);
  uint64_t hits = 0, lit = 0, shadowed = 0;
  for (const auto& px : f1.px) {
    hits += px.tri >= 0;
    lit += px.lit;
    shadowed += px.tri >= 0 && !px.lit;
  }
  // The frame is not trivial: hits, lit and shadowed pixels.
  EXPECT_GT(hits, 3000u);
  EXPECT_GT(lit, 1000u);
  EXPECT_GT(shadowed, 100u);
  for (int threads : {2, 3}) {
    const sim::Frame fn = ref.render(96, 64, threads);
    ASSERT_EQ(fn.px.size(), f1.px.size());
    size_t diffs = 0;
    for (size_t i = 0; i < f1.px.size(); ++i)
      if (!same_bits(f1.px[i], fn.px[i]) && ++diffs <= 3)
        ADD_FAILURE() << threads << " threads: pixel " << i << " differs";
    EXPECT_EQ(diffs, 0u) << threads << " threads";
  }
}

}  // namespace
}  // namespace raycore::reference
