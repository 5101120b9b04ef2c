// Golden tracer tests: exact hits on a triangle and a quad, a constructed case with a known number
// of self-intersections, thread-count invariance, agreement with the double-precision reference.
#include <gtest/gtest.h>

#include <cfenv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "hls/fp.h"
#include "hls/image.h"
#include "hls/rgu.h"
#include "scenes/generate.h"
#include "scenes/scene.h"
#include "sim/errors.h"
#include "sim/golden/golden.h"
#include "sim/reference/metrics.h"
#include "sim/reference/reference.h"

namespace {

using raycore::hls::FormatId;
using raycore::hls::Rounding;
using raycore::hls::Tri;
using raycore::hls::Vec3;
namespace hls = raycore::hls;
namespace sim = raycore::sim;
namespace scenes = raycore::scenes;

scenes::Scene make_scene(std::vector<Tri> tris, Vec3 cam, Vec3 light) {
  scenes::Scene s;
  s.name = "test";
  s.tris = std::move(tris);
  s.camera.present = true;
  s.camera.position = cam;  // default basis: looks down -Z, +Y up
  s.light.present = true;
  s.light.position = light;
  return s;
}

sim::Frame trace(const scenes::Scene& s, sim::TraceConfig cfg, sim::TraceStats* st = nullptr) {
  const hls::Image img = hls::build_image(s.tris, cfg.format, cfg.rounding);
  return sim::trace_golden(img, s.camera, s.light, cfg, st);
}

sim::TraceConfig config(FormatId f, Rounding r, bool vtu, int w, int h) {
  sim::TraceConfig c;
  c.format = f;
  c.rounding = r;
  c.vtu = vtu;
  c.width = w;
  c.height = h;
  c.threads = 1;
  return c;
}

// A 1x1 image looks exactly down -Z: direction (0, 0, -1), every operation exact.
TEST(Golden, SingleTriangleExactHit) {
  const Tri t = {Vec3{-1, -1, -10}, Vec3{3, -1, -10}, Vec3{-1, 3, -10}};
  for (FormatId f : {FormatId::fp24, FormatId::fp32})
    for (Rounding r : {Rounding::rtz, Rounding::rne})
      for (bool vtu : {false, true})
        for (Vec3 cam : {Vec3{0, 0, 0}, Vec3{0.5, 0.25, 2}}) {
          const auto s = make_scene({t}, cam, Vec3{0, 0, 5});
          const sim::Frame fr = trace(s, config(f, r, vtu, 1, 1));
          ASSERT_EQ(fr.px.size(), 1u);
          const auto& p = fr.px[0];
          EXPECT_EQ(p.tri, 0);
          EXPECT_EQ(p.t, 10.0 + cam.z) << "format " << int(f) << " vtu " << vtu;
          EXPECT_TRUE(p.shadow_ray);
          EXPECT_TRUE(p.lit);
          EXPECT_EQ(p.hit.x, cam.x);
          EXPECT_EQ(p.hit.y, cam.y);
          EXPECT_EQ(p.hit.z, -10.0);
        }
}

// A ray exactly through the shared diagonal of a quad hits one of its two triangles, and a grid
// of rays hits exactly where the double-precision test says (away from the outline).
TEST(Golden, QuadSharedEdgeAndGrid) {
  const Vec3 a{-2, -2, -10}, b{2, -2, -10}, c{2, 2, -10}, d{-2, 2, -10};
  const std::vector<Tri> quad = {{a, b, c}, {a, c, d}};
  for (Rounding r : {Rounding::rtz, Rounding::rne}) {
    // Camera on the diagonal x == y: the centre ray crosses the shared edge a-c.
    const auto s = make_scene(quad, Vec3{0.75, 0.75, 0}, Vec3{0, 0, 5});
    const sim::Frame fr = trace(s, config(FormatId::fp24, r, false, 1, 1));
    EXPECT_TRUE(fr.px[0].tri == 0 || fr.px[0].tri == 1);
    EXPECT_EQ(fr.px[0].t, 10.0);
  }
  const auto s = make_scene(quad, Vec3{0, 0, 0}, Vec3{0, 0, 5});
  const int w = 41, h = 41;
  const sim::Frame fr = trace(s, config(FormatId::fp24, Rounding::rtz, false, w, h));
  int checked = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Vec3 dir = scenes::primary_direction(s.camera, x, y, w, h);
      const double tt = -10.0 / dir.z;
      const double px = dir.x * tt, py = dir.y * tt;
      const double margin = std::min(2 - std::fabs(px), 2 - std::fabs(py));
      if (std::fabs(margin) < 1e-2) continue;  // the outline: decided by rounding
      ++checked;
      EXPECT_EQ(fr.at(x, y).tri >= 0, margin > 0) << "pixel " << x << "," << y;
      if (margin > 0) {
        EXPECT_NEAR(fr.at(x, y).t, tt, tt * 1e-4);
      }
    }
  EXPECT_GT(checked, 1000);
}

// Round to 17 significant bits, to nearest even, in double (FP24's significand; no range issues
// for these values). Independent of hls/fp.h.
double rne17(double x) {
  int e;
  std::frexp(x, &e);  // x = m 2^e, 0.5 <= |m| < 1
  const double scaled = std::ldexp(x, 17 - e);
  return std::ldexp(std::nearbyint(scaled), e - 17);
}

// The plane z = -10 seen from the origin (FP24 rne, VTU off, t_min = 0, no offset): the hit point
// is h_z = rne(t d_z), t = rne(-10 rne(1 / d_z)) (d_z: the rgu's direction, hls::rgu_primary, the
// one number taken from hls/ here), and the shadow ray to a light above the plane
// hits its own triangle exactly when h_z < -10 (its distance numerator -10 - h_z is then exact
// and positive). The expected count is computed here with double arithmetic and explicit
// rounding; with rtz the hit point never passes the plane (|t d_z| <= 10), so the count is 0.
TEST(Golden, KnownSelfIntersectionCount) {
  ASSERT_EQ(std::fegetround(), FE_TONEAREST);
  const Tri big = {Vec3{-1000, -1000, -10}, Vec3{3000, -1000, -10}, Vec3{-1000, 3000, -10}};
  const auto s = make_scene({big}, Vec3{0, 0, 0}, Vec3{3, 2, 0});
  const int w = 64, h = 48;
  for (Rounding r : {Rounding::rne, Rounding::rtz}) {
    auto cfg = config(FormatId::fp24, r, false, w, h);
    cfg.tmin = 0;
    const sim::Frame fr = trace(s, cfg);
    using A = hls::Arith<hls::FP24, Rounding::rne>;
    const uint32_t origin[3] = {0, 0, 0};
    const hls::RguCamera rc = hls::rgu_camera<A>(origin, s.camera.forward, s.camera.right,
                                                 s.camera.up, s.camera.yfov, w, h);
    uint64_t expected = 0, got = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double dz = A::to_double(hls::rgu_primary<A>(rc, uint32_t(x), uint32_t(y), 0).d[2]);
        const double t = rne17(-10.0 * rne17(1.0 / dz));
        const double hz = rne17(t * dz);
        if (r == Rounding::rne && hz < -10) ++expected;
        const auto& p = fr.at(x, y);
        ASSERT_EQ(p.tri, 0);
        ASSERT_TRUE(p.shadow_ray);
        if (p.shadow_tri == p.tri) ++got;
      }
    EXPECT_EQ(got, expected) << (r == Rounding::rne ? "rne" : "rtz");
    if (r == Rounding::rne) {
      EXPECT_GT(expected, 100u) << "the case must exercise self-intersections";
    }
  }
}

TEST(Golden, ThreadCountInvariance) {
  const scenes::Scene s = scenes::generate("corridor");
  for (bool vtu : {false, true}) {
    auto cfg = config(FormatId::fp24, Rounding::rtz, vtu, 96, 60);
    cfg.spawn.spawn = hls::Spawn::error_bound;
    const hls::Image img = hls::build_image(s.tris, cfg.format, cfg.rounding);
    cfg.threads = 1;
    const sim::Frame a = sim::trace_golden(img, s.camera, s.light, cfg);
    cfg.threads = 3;
    const sim::Frame b = sim::trace_golden(img, s.camera, s.light, cfg);
    ASSERT_EQ(a.px.size(), b.px.size());
    for (size_t i = 0; i < a.px.size(); ++i) {
      ASSERT_EQ(a.px[i].tri, b.px[i].tri) << i;
      ASSERT_EQ(a.px[i].t_bits, b.px[i].t_bits) << i;
      ASSERT_EQ(a.px[i].lit, b.px[i].lit) << i;
      ASSERT_EQ(a.px[i].shadow_tri, b.px[i].shadow_tri) << i;
      ASSERT_EQ(a.px[i].shade, b.px[i].shade) << i;
    }
  }
}

// FP32 with the VTU on a furnished scene agrees with the double-precision reference almost
// everywhere; FP24 stays within a few percent.
TEST(Golden, AgreesWithReference) {
  const scenes::Scene s = scenes::generate("corridor");
  const int w = 120, h = 72;
  const sim::Frame ref = raycore::reference::render(s, w, h, 2);
  struct Case {
    FormatId f;
    Rounding r;
    double max_primary_pct, max_shadow_pct;
  };
  for (const Case& c : {Case{FormatId::fp32, Rounding::rne, 0.2, 0.5},
                        Case{FormatId::fp24, Rounding::rtz, 2.0, 5.0}}) {
    auto cfg = config(c.f, c.r, true, w, h);
    cfg.spawn.spawn = hls::Spawn::error_bound;
    const sim::Frame fr = trace(s, cfg);
    const auto m = raycore::reference::compute_errors(fr, ref, s.tris);
    EXPECT_LE(100.0 * double(m.primary_errors) / double(m.pixels), c.max_primary_pct);
    EXPECT_LE(100.0 * double(m.shadow_errors) / double(m.pixels), c.max_shadow_pct);
    EXPECT_EQ(m.self_intersections, 0u);
    EXPECT_GT(m.shadow_rays, uint64_t(w * h / 4));
  }
}

// --shadow-spawn all: one shadow ray per primary hit, the same image and lit decisions as front;
// the self-intersections with the light in front are front's.
TEST(Golden, ShadowSpawnAllSameImage) {
  const scenes::Scene s = scenes::generate("corridor");
  const int w = 96, h = 60;
  const sim::Frame ref = raycore::reference::render(s, w, h, 2);
  for (bool seg : {false, true}) {
    auto cfg = config(FormatId::fp24, Rounding::rtz, false, w, h);
    cfg.spawn.segment = seg;
    sim::TraceStats sf, sa;
    const sim::Frame ff = trace(s, cfg, &sf);
    cfg.spawn.spawn_all = true;
    const sim::Frame fa = trace(s, cfg, &sa);
    EXPECT_EQ(sa.shadow_rays, sa.primary_hits);
    EXPECT_LT(sf.shadow_rays, sa.shadow_rays);
    for (size_t i = 0; i < ff.px.size(); ++i) {
      ASSERT_EQ(ff.px[i].shade, fa.px[i].shade) << i;
      ASSERT_EQ(ff.px[i].lit, fa.px[i].lit) << i;
      ASSERT_EQ(ff.px[i].front, fa.px[i].front) << i;
      ASSERT_EQ(ff.px[i].shadow_ray, ff.px[i].front) << i;
    }
    const auto mf = raycore::reference::compute_errors(ff, ref, s.tris);
    const auto ma = raycore::reference::compute_errors(fa, ref, s.tris);
    EXPECT_EQ(mf.self_intersections, mf.self_intersections_front);
    EXPECT_EQ(ma.self_intersections_front, mf.self_intersections);
    EXPECT_GT(ma.self_intersections, ma.self_intersections_front);  // rtz: the light-behind rays
    EXPECT_EQ(ma.shadow_errors, mf.shadow_errors);
    EXPECT_EQ(ma.primary_errors, mf.primary_errors);
  }
}

// Watertightness margins (--bary-margin, --trv-widen; hls/margins.h): margins set to zero give the
// frame traced with the defaults bit for bit; margins keep every primary hit of the frame without
// them (a margin only adds hits of a triangle test, a widening only adds cells) and add some.
TEST(Golden, MarginsZeroIsDefaultAndOnlyAddHits) {
  const scenes::Scene s = scenes::generate("corridor");
  struct Case {
    Rounding r;
    bool vtu;
    hls::Spawn sp;
  };
  uint64_t added = 0;
  for (const Case& k : {Case{Rounding::rtz, false, hls::Spawn::none},
                        Case{Rounding::rne, true, hls::Spawn::skip_back}}) {
    auto cfg = config(FormatId::fp24, k.r, k.vtu, 96, 60);
    cfg.spawn.spawn = k.sp;
    cfg.spawn.ulps = sim::default_spawn_ulps(cfg.format, k.sp);
    const hls::Image img = hls::build_image(s.tris, cfg.format, cfg.rounding);
    const sim::Frame def = sim::trace_golden(img, s.camera, s.light, cfg);
    auto zero = cfg;
    zero.bary_margin = 0.0;
    zero.trv_widen = 0;
    const sim::Frame z = sim::trace_golden(img, s.camera, s.light, zero);
    for (size_t i = 0; i < def.px.size(); ++i) {
      ASSERT_EQ(def.px[i].tri, z.px[i].tri) << i;
      ASSERT_EQ(def.px[i].t_bits, z.px[i].t_bits) << i;
      ASSERT_EQ(def.px[i].lit, z.px[i].lit) << i;
      ASSERT_EQ(def.px[i].shadow_tri, z.px[i].shadow_tri) << i;
      ASSERT_EQ(def.px[i].shade, z.px[i].shade) << i;
    }
    for (const auto& [eps, widen] : {std::pair{0.008, 0}, std::pair{0.0, 4}, std::pair{0.008, 2}}) {
      auto m = cfg;
      m.bary_margin = eps;
      m.trv_widen = widen;
      const sim::Frame f = sim::trace_golden(img, s.camera, s.light, m);
      for (size_t i = 0; i < def.px.size(); ++i) {
        if (def.px[i].tri >= 0) {
          ASSERT_GE(f.px[i].tri, 0) << i << ": margins lost a primary hit";
        }
        if (def.px[i].tri < 0 && f.px[i].tri >= 0) ++added;
        const bool same_hit = def.px[i].tri == f.px[i].tri && def.px[i].t_bits == f.px[i].t_bits;
        if (same_hit && def.px[i].shadow_ray && def.px[i].shadow_tri >= 0) {
          ASSERT_GE(f.px[i].shadow_tri, 0) << i << ": margins lost an occluder";
        }
      }
    }
  }
  std::printf("MARGINS golden corridor: primary hits added by margins %llu\n", (unsigned long long)added);
}

// The stored scene: vertices recovered from the records' Wald constants. Exact where the
// constants are (small integers, n_k a power of two), within the format's rounding elsewhere;
// degenerate records become zero-area triangles; the camera and light are rounded.
TEST(Golden, StoredSceneRecoversTheRecords) {
  const Tri exact = {Vec3{-1, -1, -10}, Vec3{3, -1, -10}, Vec3{-1, 3, -10}};  // n_k = 16
  const Tri sliver = {Vec3{0, 0, -5}, Vec3{1, 1, -5}, Vec3{2, 2, -5}};      // zero area
  const Tri tilted = {Vec3{0.1, 0.2, -7.3}, Vec3{2.7, -0.4, -6.1}, Vec3{-1.3, 1.9, -8.2}};
  auto s = make_scene({exact, sliver, tilted}, Vec3{0.1, 0.2, 0.3}, Vec3{0.3, 0.3, 5.1});
  for (FormatId f : {FormatId::fp24, FormatId::fp32}) {
    const Rounding r = f == FormatId::fp24 ? Rounding::rtz : Rounding::rne;
    const hls::Image img = hls::build_image(s.tris, f, r);
    const scenes::Scene st = sim::stored_scene(s, img);
    ASSERT_EQ(st.tris.size(), 3u);
    for (int j = 0; j < 3; ++j)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(st.tris[0][size_t(j)][c], exact[size_t(j)][c]);
    EXPECT_EQ(st.tris[1][0][0], st.tris[1][1][0]);  // collapsed
    EXPECT_EQ(st.tris[1][1][2], st.tris[1][2][2]);
    const double tol = f == FormatId::fp24 ? 1e-3 : 1e-5;
    for (int j = 0; j < 3; ++j)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(st.tris[2][size_t(j)][c], tilted[size_t(j)][c], tol);
    EXPECT_NE(st.camera.position.x, s.camera.position.x);  // 0.1 is not a binary fraction
    EXPECT_NEAR(st.camera.position.x, 0.1, tol);
    EXPECT_NEAR(st.light.position.z, 5.1, tol * 8);
  }
  // A VTU-translated image or one of another scene is refused.
  const hls::Image img = hls::build_image(s.tris, FormatId::fp24, Rounding::rtz);
  EXPECT_THROW(sim::stored_scene(make_scene({exact}, Vec3{}, Vec3{0, 0, 5}), img), std::invalid_argument);
}

TEST(Golden, RejectsMismatchedImage) {
  const Tri t = {Vec3{-1, -1, -10}, Vec3{3, -1, -10}, Vec3{-1, 3, -10}};
  const auto s = make_scene({t}, Vec3{0, 0, 0}, Vec3{0, 0, 5});
  const hls::Image img = hls::build_image(s.tris, FormatId::fp24, Rounding::rtz);
  EXPECT_THROW(sim::trace_golden(img, s.camera, s.light, config(FormatId::fp32, Rounding::rtz, false, 4, 4)),
               std::invalid_argument);
  EXPECT_THROW(sim::trace_golden(img, s.camera, s.light, config(FormatId::fp24, Rounding::rtz, false, 0, 4)),
               std::invalid_argument);
}

}  // namespace
