// tb/hls/test_vtu.cpp - the VTU transform: against constants computed in double from pre-translated
// vertices (the bound of docs/image.md), nodes, box and light, degenerate records, whole images.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "hls/image.h"
#include "hls/vtu.h"
#include "tb/hls/test_util.h"

namespace raycore::hls {
namespace {

using test::Rng;
using test::uni;

// The nine constants of triangle t translated by -cam, for a given projection axis k, in extended
// precision (long double: the translation and the formulas add errors of about 2^-64 relative,
// far below the bounds checked). An independent transcription of the convention: plane
// n.x = n.A scaled by 1/n_k; barycentrics by Cramer's rule in the (u, v) plane.
void wald_ref(const Tri& t, const double cam[3], int k, double c[9]) {
  using L = long double;
  const int u = (k + 1) % 3, v = (k + 2) % 3;
  L a[3], b[3], cc[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = L(t[0][i]) - L(cam[i]);
    b[i] = L(t[1][i]) - L(cam[i]);
    cc[i] = L(t[2][i]) - L(cam[i]);
  }
  const L e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const L e2[3] = {cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]};
  const L n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                  e1[0] * e2[1] - e1[1] * e2[0]};
  const L det = e1[u] * e2[v] - e1[v] * e2[u];  // = n_k
  c[0] = double(n[u] / det);
  c[1] = double(n[v] / det);
  c[2] = double((n[k] * a[k] + n[u] * a[u] + n[v] * a[v]) / det);
  // beta = ((h_u - A_u) e2_v - (h_v - A_v) e2_u) / det
  c[3] = double(e2[v] / det);
  c[4] = double(-e2[u] / det);
  c[5] = double((a[v] * e2[u] - a[u] * e2[v]) / det);
  // gamma = ((h_v - A_v) e1_u - (h_u - A_u) e1_v) / det
  c[6] = double(-e1[v] / det);
  c[7] = double(e1[u] / det);
  c[8] = double((a[u] * e1[v] - a[v] * e1[u]) / det);
}

double ulp_of(double m, int man_bits) {
  if (m == 0) return 0;
  return std::ldexp(1.0, std::ilogb(m) - man_bits);
}

struct VtuErr {
  double worst_ratio = 0;  // max |error| / bound, over all nine constants
  double worst_ulps = 0;   // max |error| in ulps of the largest term, over all nine
  double worst_d_ratio = 0, worst_d_ulps = 0;  // the same for the translated n_d', b_d', c_d' only
  double worst_pre = 0;    // max |got - pre-translated record| / its bound
  int checked = 0;
};

// Compare one VTU-transformed record with constants computed from the vertices translated by the
// VTU's camera. Bounds (u = unit roundoff, 2^-M rtz, 2^-(M+1) rne; the magnitudes
// are of the untranslated double constants and the camera):
//   unchanged constants  u |x|                      (their own rounding)
//   n_d'  u (2|n_d| + 2|c_k| + 4|n_u c_u| + 4|n_v c_v|)
//   b_d'  u (2|b_d| + 3|b_nu c_u| + 3|b_nv c_v|)      c_d' likewise
// times (1 + 8u) for the second-order terms, plus 2^-40 of the terms for the reference's own
// rounding and 8 * 2^emin for flushed products.
// With pre (the record built from the pre-translated vertices, same k), also checks
// |got - pre| <= bound + pre's own rounding.
template <class F, Rounding R>
void compare(const WaldTri<F>& got, const Tri& orig, const double cam[3], VtuErr& e,
             const char* what, const WaldTri<F>* pre = nullptr) {
  const double u = std::ldexp(1.0, R == Rounding::rtz ? -F::man_bits : -F::man_bits - 1);
  const int k = int(got.k), ku = (k + 1) % 3, kv = (k + 2) % 3;
  double c0[9], c1[9];
  const double zero[3] = {0, 0, 0};
  wald_ref(orig, zero, k, c0);
  wald_ref(orig, cam, k, c1);
  const double tiny = 8 * std::ldexp(1.0, F::emin);
  double bound[9], mag[9];
  for (int j = 0; j < 9; ++j) {
    mag[j] = std::fabs(c0[j]);
    bound[j] = u * std::fabs(c0[j]);
  }
  const double nuc = std::fabs(c0[0] * cam[ku]), nvc = std::fabs(c0[1] * cam[kv]);
  // One sop per offset (hls/fp.h): the stored constants' own roundings, the window's
  // 2^(T-3M-5) <= 2^(-3M-3) of the largest term, and the one final rounding of the result.
  const double window = std::ldexp(1.0, -3 * F::man_bits - 3);
  mag[2] = std::max({std::fabs(c0[2]), std::fabs(cam[k]), nuc, nvc});
  bound[2] = u * (std::fabs(c0[2]) + nuc + nvc + std::fabs(c1[2])) + window * mag[2];
  for (int j : {5, 8}) {
    const double p = std::fabs(c0[j - 2] * cam[ku]), q = std::fabs(c0[j - 1] * cam[kv]);
    mag[j] = std::max({std::fabs(c0[j]), p, q});
    bound[j] = u * (std::fabs(c0[j]) + p + q + std::fabs(c1[j])) + window * mag[j];
  }
  // Reference error (extended precision): a tiny multiple of the terms' size.
  double scale = 0;
  for (const Vec3& p : orig)
    for (int i = 0; i < 3; ++i) scale = std::max(scale, std::fabs(p[i]) + std::fabs(cam[i]));
  const double coef = std::max({std::fabs(c0[3]), std::fabs(c0[4]), std::fabs(c0[6]), std::fabs(c0[7]), 1.0});
  for (int j = 0; j < 9; ++j) {
    const double b = bound[j] * (1 + 8 * u) + std::ldexp(coef * scale, -40) + tiny;
    const double err = std::fabs(to_double<F>(got.c[j]) - c1[j]);
    ASSERT_LE(err, b) << what << ": constant " << j << " = " << to_double<F>(got.c[j])
                      << ", from translated vertices " << c1[j] << ", bound " << b;
    e.worst_ratio = std::max(e.worst_ratio, err / b);
    const double ulps = mag[j] > 0 ? err / ulp_of(mag[j], F::man_bits) : 0.0;
    e.worst_ulps = std::max(e.worst_ulps, ulps);
    if (j == 2 || j == 5 || j == 8) {
      e.worst_d_ratio = std::max(e.worst_d_ratio, err / b);
      e.worst_d_ulps = std::max(e.worst_d_ulps, ulps);
    }
    if (pre) {
      const double d = std::fabs(to_double<F>(got.c[j]) - to_double<F>(pre->c[j]));
      const double bp = b + u * std::fabs(c1[j]);
      ASSERT_LE(d, bp) << what << ": constant " << j << " = " << to_double<F>(got.c[j])
                       << ", built from translated vertices " << to_double<F>(pre->c[j]);
      e.worst_pre = std::max(e.worst_pre, d / bp);
    }
  }
  ++e.checked;
}

template <class F, Rounding R>
void vtu_random(const char* name) {
  Rng r(100 + F::man_bits + int(R));
  VtuErr e;
  for (int i = 0; i < 40000; ++i) {
    const double mag = std::pow(10.0, uni(r, 0, 4));
    const Vec3 centre{uni(r, -mag, mag), uni(r, -mag, mag), uni(r, -mag, mag)};
    const Tri t = test::random_tri(r, centre, std::pow(10.0, uni(r, -2, 2)));
    const Vec3 cam{(r() & 1 ? 1 : -1) * std::pow(10.0, uni(r, 0, 4)),
                   (r() & 1 ? 1 : -1) * std::pow(10.0, uni(r, 0, 4)),
                   (r() & 1 ? 1 : -1) * std::pow(10.0, uni(r, 0, 4))};
    const WaldTri<F> w = make_wald<F, R>(t, uint32_t(i));
    if (w.degenerate()) continue;
    const auto vtu = Vtu<F, R>::from_camera(cam);
    const WaldTri<F> got = vtu.tri(w);
    EXPECT_EQ(got.k, w.k);
    EXPECT_EQ(got.id, w.id);
    EXPECT_EQ(got.flags, w.flags);
    const double c[3] = {to_double<F>(vtu.c[0]), to_double<F>(vtu.c[1]), to_double<F>(vtu.c[2])};
    compare<F, R>(got, t, c, e, name);
    if (testing::Test::HasFatalFailure()) return;
  }
  EXPECT_GT(e.checked, 39000);
  std::printf("%s: %d triangles; worst error %.3f of the bound (%.2f ulps of the largest term); "
              "translated n_d', b_d', c_d' alone: %.3f of the bound (%.2f ulps)\n",
              name, e.checked, e.worst_ratio, e.worst_ulps, e.worst_d_ratio, e.worst_d_ulps);
}
TEST(Vtu, TrianglesFp24Rtz) { vtu_random<FP24, Rounding::rtz>("fp24 rtz"); }
TEST(Vtu, TrianglesFp24Rne) { vtu_random<FP24, Rounding::rne>("fp24 rne"); }
TEST(Vtu, TrianglesFp32Rtz) { vtu_random<FP32, Rounding::rtz>("fp32 rtz"); }
TEST(Vtu, TrianglesFp32Rne) { vtu_random<FP32, Rounding::rne>("fp32 rne"); }

// Splits, box and light: one correctly rounded subtraction (bit-exact against rounding the exact
// difference, which double holds exactly for these magnitudes); leaves pass through.
template <class F, Rounding R>
void vtu_nodes_points() {
  Rng r(7);
  using A = Arith<F, R>;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 cam{uni(r, -1e4, 1e4), uni(r, -1e4, 1e4), uni(r, -1e4, 1e4)};
    const auto vtu = Vtu<F, R>::from_camera(cam);
    const uint32_t axis = uint32_t(r() % 3);
    const uint32_t split = A::from_double(uni(r, -1e4, 1e4));
    const uint64_t raw = encode_node(Node{split, uint32_t(r()) & node_index_mask, axis});
    const uint64_t moved = vtu.node(raw);
    const Node m = decode_node(moved);
    ASSERT_EQ(moved >> 32, raw >> 32) << "index/axis changed";
    ASSERT_EQ(m.split_or_count, (from_double<F, R>(to_double<F>(split) - to_double<F>(vtu.c[axis]))));
    const uint64_t leaf = encode_node(Node{uint32_t(r() % 9), uint32_t(r()) & node_index_mask, 3});
    ASSERT_EQ(vtu.node(leaf), leaf);
    uint32_t lo[3], hi[3], lo2[3], hi2[3], p[3];
    for (int a = 0; a < 3; ++a) {
      const double x = uni(r, -1e4, 1e4), y = x + uni(r, 0, 1e3);
      lo[a] = lo2[a] = A::from_double(x);
      hi[a] = hi2[a] = A::from_double(y);
      p[a] = A::from_double(uni(r, -1e4, 1e4));
    }
    uint32_t q[3] = {p[0], p[1], p[2]};
    const uint32_t l0[3] = {lo[0], lo[1], lo[2]}, h0[3] = {hi[0], hi[1], hi[2]};
    vtu.box(lo, hi);
    vtu.box_outward(lo2, hi2);
    vtu.point(q);
    for (int a = 0; a < 3; ++a) {
      const double ca = to_double<F>(vtu.c[a]);
      ASSERT_EQ(lo[a], (from_double<F, R>(to_double<F>(l0[a]) - ca)));
      ASSERT_EQ(hi[a], (from_double<F, R>(to_double<F>(h0[a]) - ca)));
      ASSERT_EQ(q[a], (from_double<F, R>(to_double<F>(p[a]) - ca)));
      ASSERT_LE(to_double<F>(lo2[a]), to_double<F>(l0[a]) - ca);
      ASSERT_GE(to_double<F>(hi2[a]), to_double<F>(h0[a]) - ca);
    }
  }
}
TEST(Vtu, NodesBoxLightFp24Rtz) { vtu_nodes_points<FP24, Rounding::rtz>(); }
TEST(Vtu, NodesBoxLightFp24Rne) { vtu_nodes_points<FP24, Rounding::rne>(); }
TEST(Vtu, NodesBoxLightFp32Rtz) { vtu_nodes_points<FP32, Rounding::rtz>(); }
TEST(Vtu, NodesBoxLightFp32Rne) { vtu_nodes_points<FP32, Rounding::rne>(); }

// A degenerate record stays finite and can never hit, whatever the camera.
template <class F, Rounding R>
void vtu_degenerate() {
  using A = Arith<F, R>;
  using W = WaldTri<F>;
  Rng r(9);
  const Tri pts[] = {Tri{Vec3{1, 2, 3}, Vec3{1, 2, 3}, Vec3{1, 2, 3}},
                     Tri{Vec3{0, 0, 0}, Vec3{1, 2, 3}, Vec3{2, 4, 6}},
                     Tri{Vec3{5e3, 0, 0}, Vec3{5e3 + 1, 0, 0}, Vec3{5e3 + 0.5, 1e-40, 0}}};
  for (const Tri& t : pts) {
    const WaldTri<F> w = make_wald<F, R>(t, 3);
    ASSERT_TRUE(w.degenerate());
    for (int i = 0; i < 2000; ++i) {
      const Vec3 cam{uni(r, -1e4, 1e4), uni(r, -1e4, 1e4), uni(r, -1e4, 1e4)};
      const WaldTri<F> g = Vtu<F, R>::from_camera(cam).tri(w);
      ASSERT_TRUE(g.degenerate());
      ASSERT_EQ(g.c[W::BD], neg<F>(F::one));
      for (uint32_t c : g.c) ASSERT_NE(c & F::max_mag, F::max_mag) << "saturated constant";
      // beta at any hit point is -1: the test's second phase always rejects.
      const uint32_t hu = A::from_double(uni(r, -1e5, 1e5)), hv = A::from_double(uni(r, -1e5, 1e5));
      const uint32_t beta = A::add3(A::mul(g.c[W::BNU], hu), A::mul(g.c[W::BNV], hv), g.c[W::BD]);
      ASSERT_TRUE(A::lt(beta, A::zero));
      ASSERT_EQ(beta, neg<F>(F::one));
    }
  }
}
TEST(Vtu, DegenerateFp24Rtz) { vtu_degenerate<FP24, Rounding::rtz>(); }
TEST(Vtu, DegenerateFp24Rne) { vtu_degenerate<FP24, Rounding::rne>(); }
TEST(Vtu, DegenerateFp32Rtz) { vtu_degenerate<FP32, Rounding::rtz>(); }

// The VTU-transformed image against an image built from pre-translated geometry: every record
// within the bound above, the box within a few ulps, the node array translated node by node.
template <class F, Rounding R>
void vtu_image(FormatId fid) {
  const auto tris = test::synthetic_scene(8000, 5);
  const Vec3 cam{780.94, 141.63, 73.59};  // the corridor's camera
  const Image img = build_image(tris, fid, R);
  const Image moved = transform_image(img, cam);
  EXPECT_TRUE(moved.vtu_applied());
  EXPECT_NO_THROW(moved.check("transformed"));
  const auto vtu = Vtu<F, R>::from_camera(cam);
  const double c[3] = {to_double<F>(vtu.c[0]), to_double<F>(vtu.c[1]), to_double<F>(vtu.c[2])};
  std::vector<Tri> shifted = tris;
  for (Tri& t : shifted)
    for (Vec3& p : t) p = p - Vec3{c[0], c[1], c[2]};
  const Image pre = build_image(shifted, fid, R);
  VtuErr e;
  int k_diff = 0;
  for (uint32_t i = 0; i < img.tri_count(); ++i) {
    const WaldTri<F> a = moved.wald<F>(i), b = pre.wald<F>(i);
    ASSERT_EQ(a.degenerate(), b.degenerate()) << "triangle " << i;
    if (a.degenerate()) continue;
    if (a.k != b.k) ++k_diff;  // a near tie of |n| components: other constants, compare to double
    compare<F, R>(a, tris[i], c, e, "image", a.k == b.k ? &b : nullptr);
    if (testing::Test::HasFatalFailure()) return;
  }
  EXPECT_LE(k_diff, 10);
  for (uint32_t i = 0; i < img.node_count(); ++i) ASSERT_EQ(moved.node(i), vtu.node(img.node(i)));
  uint32_t lo[3], hi[3], plo[3], phi[3];
  moved.box(lo, hi);
  pre.box(plo, phi);
  for (int a = 0; a < 3; ++a) {
    const double m = std::max({std::fabs(to_double<F>(plo[a])), std::fabs(to_double<F>(phi[a])), std::fabs(c[a])});
    EXPECT_LE(std::fabs(to_double<F>(lo[a]) - to_double<F>(plo[a])), 3 * ulp_of(m, F::man_bits));
    EXPECT_LE(std::fabs(to_double<F>(hi[a]) - to_double<F>(phi[a])), 3 * ulp_of(m, F::man_bits));
  }
  std::printf("image %s: %d records, worst %.3f of the bound (%.2f ulps), against the pre-translated "
              "image %.3f of its bound; k differs in %d\n",
              format_name(fid), e.checked, e.worst_ratio, e.worst_ulps, e.worst_pre, k_diff);
}
TEST(Vtu, ImageFp24Rtz) { vtu_image<FP24, Rounding::rtz>(FormatId::fp24); }
TEST(Vtu, ImageFp32Rne) { vtu_image<FP32, Rounding::rne>(FormatId::fp32); }

TEST(Vtu, ImageFormatMismatch) {
  const Image img = build_image(test::random_scene(3, 50), FormatId::fp24, Rounding::rtz);
  EXPECT_THROW(transform_image(img, Vtu<FP32, Rounding::rtz>{}), std::invalid_argument);
  EXPECT_THROW(transform_image(img, Vtu<FP24, Rounding::rne>{}), std::invalid_argument);
}

}  // namespace
}  // namespace raycore::hls
