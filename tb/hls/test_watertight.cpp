// tb/hls/test_watertight.cpp - the watertight test (hls::ist_watertight, --ist watertight) and its
// record (hls/wald.h), in every format and rounding:
//   - no leak: rays aimed at random points of an edge two triangles share (a quad split along its
//     diagonal, near the origin and 10^4 away, from origins near and far), and at a vertex that a
//     fan of triangles shares, always hit one of them; Wald's test on the same rays does leak (the
//     harness can fail);
//   - against double precision: rays through a triangle's inside hit it with t within a few ulps
//     of the exact t; rays clearly outside miss; den is Wald's den bit for bit;
//   - the edge function is antisymmetric: E(Q, P) is E(P, Q) negated, bit for bit;
//   - an outline edge is decided as the exact shear decides it, for rays farther than 2^-20 of the
//     sheared coordinates' magnitude (the shear in FP32's 8/23);
//   - the VTU translates a watertight record's vertices by the camera (one shift each) and its
//     plane through the shifted vertex A, so the translated records of two triangles still share
//     their vertices.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "hls/fp.h"
#include "hls/ist.h"
#include "hls/vtu.h"
#include "hls/wald.h"
#include "tb/hls/test_util.h"

namespace raycore::hls {
namespace {

using test::Rng;
using test::uni;

// o rounded to the format, as the ray's origin register holds it.
template <class A>
Vec3 stored(const Vec3& p) {
  return Vec3{A::to_double(A::from_double(p.x)), A::to_double(A::from_double(p.y)), A::to_double(A::from_double(p.z))};
}

template <class A>
Ray make_ray(const Vec3& o, const Vec3& d) {
  Ray r;
  for (int i = 0; i < 3; ++i) {
    r.o[i] = A::from_double(o[i]);
    r.d[i] = A::from_double(d[i]);
  }
  r.tmin = A::from_double(1.0 / 4096);
  r.tmax = A::from_double(1e9);
  return r;
}

Vec3 unit(const Vec3& v) {
  const double n = std::sqrt(dot(v, v));
  return {v.x / n, v.y / n, v.z / n};
}

Vec3 random_dir(Rng& r) {
  for (;;) {
    const Vec3 v{uni(r, -1, 1), uni(r, -1, 1), uni(r, -1, 1)};
    const double n = dot(v, v);
    if (n > 0.01 && n <= 1) return unit(v);
  }
}

template <class A>
bool hits(const WaldTri<typename A::Fmt>& w, const Ray& r) {
  return ist_test<A>(w, r.o, r.d, r.tmin, r.tmax).exit == IstExit::hit;
}

// Rays at random points of the diagonal of random quads (two triangles sharing B, C), from origins
// at 1..50 quad sizes; counts the rays that hit neither triangle, for the given record kind.
template <class F, Rounding R>
int edge_leaks(IstKind kind, uint64_t seed, double offset, int n) {
  using A = Arith<F, R>;
  Rng rng(seed);
  int leaks = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 c{offset + uni(rng, -3, 3), uni(rng, -3, 3), offset * 0.5 + uni(rng, -3, 3)};
    // At least 2^7 ulps of the coordinates: the stored quad keeps its shape.
    const double s = std::max(0.125, std::ldexp(offset, 7 - F::man_bits)) * std::ldexp(1.0, int(rng() % 8));
    const Vec3 nrm = random_dir(rng);
    Vec3 e1 = random_dir(rng);
    e1 = unit(cross(nrm, e1));
    const Vec3 e2 = cross(nrm, e1);
    auto at = [&](double a, double b) { return c + e1 * (a * s) + e2 * (b * s); };
    const Vec3 A0 = at(uni(rng, -1.2, -0.6), uni(rng, -1.2, -0.6));
    const Vec3 B = at(uni(rng, 0.6, 1.2), uni(rng, -1.2, -0.6));
    const Vec3 C = at(uni(rng, -1.2, -0.6), uni(rng, 0.6, 1.2));
    const Vec3 D = at(uni(rng, 0.6, 1.2), uni(rng, 0.6, 1.2)) + nrm * (s * uni(rng, -0.2, 0.2));
    const WaldTri<F> t1 = make_wald<F, R>(Tri{A0, B, C}, 1, kind);
    const WaldTri<F> t2 = make_wald<F, R>(Tri{C, B, D}, 2, kind);
    if (t1.degenerate() || t2.degenerate()) continue;
    // The rounded vertices of the shared edge, so the aim point lies on the stored edge, and the
    // rounded origin, so the ray (its direction rounded once) passes within 2^-M |p - o| of it.
    const Vec3 b = stored<A>(B), cc = stored<A>(C);
    for (int j = 0; j < 8; ++j) {
      const double u = uni(rng, 0.1, 0.9);
      const Vec3 p = b + (cc - b) * u;
      Vec3 dir = random_dir(rng);
      if (dot(dir, nrm) > 0) dir = dir * -1.0;
      if (std::fabs(dot(dir, nrm)) < 0.3) continue;  // not grazing: the quad's outline is far
      const Vec3 o = stored<A>(p - dir * (s * uni(rng, 1, 50)));
      const Ray r = make_ray<A>(o, (p - o) * (1.0 / (s * 8)));
      if (!hits<A>(t1, r) && !hits<A>(t2, r)) ++leaks;
    }
  }
  return leaks;
}

template <class F, Rounding R>
void no_edge_leak(uint64_t seed) {
  for (double offset : {0.0, 1e4}) {
    EXPECT_EQ((edge_leaks<F, R>(IstKind::watertight, seed, offset, 4000)), 0) << "offset " << offset;
  }
}
TEST(Watertight, NoEdgeLeakFp24Rtz) { no_edge_leak<FP24, Rounding::rtz>(1); }
TEST(Watertight, NoEdgeLeakFp24Rne) { no_edge_leak<FP24, Rounding::rne>(2); }
TEST(Watertight, NoEdgeLeakFp24Raycore) { no_edge_leak<FP24, Rounding::raycore>(3); }
TEST(Watertight, NoEdgeLeakFp32Rne) { no_edge_leak<FP32, Rounding::rne>(4); }
// The harness can fail: Wald's test, on the same rays, lets some through.
TEST(Watertight, WaldLeaksOnTheSameRays) {
  EXPECT_GT((edge_leaks<FP24, Rounding::rtz>(IstKind::wald, 1, 1e4, 4000)), 0);
}

// A fan of triangles around a shared vertex V; rays aimed exactly at V's stored position.
template <class F, Rounding R>
void no_vertex_leak(uint64_t seed) {
  using A = Arith<F, R>;
  Rng rng(seed);
  int leaks = 0, rays = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 nrm = random_dir(rng);
    const Vec3 e1 = unit(cross(nrm, random_dir(rng))), e2 = cross(nrm, e1);
    const double s = std::ldexp(1.0, int(rng() % 6) - 2);
    const Vec3 v{uni(rng, -5, 5), uni(rng, -5, 5), uni(rng, -5, 5)};
    const Vec3 vs = stored<A>(v);
    const int m = 4 + int(rng() % 5);  // gaps below pi: the fan covers a disc around V
    std::vector<Vec3> ring;
    double a = uni(rng, 0, 1);
    for (int j = 0; j < m; ++j) {
      const double ang = 2 * M_PI * (j + 0.2 + 0.6 * uni(rng, 0, 1)) / m + a;
      ring.push_back(v + e1 * (s * std::cos(ang)) + e2 * (s * std::sin(ang)) +
                     nrm * (s * uni(rng, -0.1, 0.1)));
    }
    std::vector<WaldTri<F>> fan;
    for (int j = 0; j < m; ++j)
      fan.push_back(make_wald<F, R>(Tri{v, ring[size_t(j)], ring[size_t((j + 1) % m)]}, uint32_t(j),
                                    IstKind::watertight));
    for (int k = 0; k < 4; ++k) {
      Vec3 dir = random_dir(rng);
      if (dot(dir, nrm) > 0) dir = dir * -1.0;
      if (std::fabs(dot(dir, nrm)) < 0.4) continue;
      const Vec3 o = stored<A>(vs - dir * (s * uni(rng, 1, 30)));
      const Ray r = make_ray<A>(o, vs - o);
      bool any = false;
      for (const auto& w : fan) any |= hits<A>(w, r);
      leaks += !any;
      ++rays;
    }
  }
  EXPECT_GT(rays, 3000);
  EXPECT_EQ(leaks, 0);
}
TEST(Watertight, NoVertexLeakFp24Rtz) { no_vertex_leak<FP24, Rounding::rtz>(11); }
TEST(Watertight, NoVertexLeakFp24Rne) { no_vertex_leak<FP24, Rounding::rne>(12); }

// Inside hits with t near the exact one, outside misses; den = d_k + n_u d_u + n_v d_v rounded
// once (one sop), within an ulp of the exact sum; t is the key's top bits, and the key (t from the
// sheared vertices in the shear format G) lies within a few ulps of G of the exact t of the ray the
// format holds against the stored vertices.
template <class F, Rounding R>
void agrees_with_double(uint64_t seed) {
  using A = Arith<F, R>;
  using K = KeyFormat<F>;
  Rng rng(seed);
  int inside = 0, outside = 0;
  double worst = 0;  // the key's error in units of the bound below
  for (int i = 0; i < 20000; ++i) {
    const Tri tri = test::random_tri(rng, Vec3{uni(rng, -50, 50), uni(rng, -50, 50), uni(rng, -50, 50)}, 4);
    const WaldTri<F> w = make_wald<F, R>(tri, 0, IstKind::watertight);
    if (w.degenerate()) continue;
    const Vec3 n = unit(cross(tri[1] - tri[0], tri[2] - tri[0]));
    // Barycentrics well inside (>= 0.05) or clearly outside (one <= -0.05).
    double b = uni(rng, -0.5, 1), g = uni(rng, -0.5, 1);
    const bool in = b >= 0.05 && g >= 0.05 && b + g <= 0.95;
    const bool out = b <= -0.05 || g <= -0.05 || b + g >= 1.05;
    if (!in && !out) continue;
    const Vec3 p = tri[0] + (tri[1] - tri[0]) * b + (tri[2] - tri[0]) * g;
    Vec3 dir = random_dir(rng);
    if (std::fabs(dot(dir, n)) < 0.2) continue;
    const double dist = uni(rng, 1, 100);
    const Vec3 o = p - dir * dist;
    const Ray r = make_ray<A>(o, dir);
    const IstOut x = ist_test<A>(w, r.o, r.d, r.tmin, r.tmax);
    EXPECT_EQ(x.t, key_t<F>(x.tk));
    // The exact t of the held ray on the stored vertices' plane (long double: 64-bit products of
    // the format's values, a few roundings of 2^-64).
    auto ld = [](uint32_t v) { return static_cast<long double>(A::to_double(v)); };
    long double vx[3][3], ro[3], rd[3];
    for (int j = 0; j < 3; ++j)
      for (int a = 0; a < 3; ++a) vx[j][a] = ld(w.c[3 + 3 * j + a]);
    for (int a = 0; a < 3; ++a) {
      ro[a] = ld(r.o[a]);
      rd[a] = ld(r.d[a]);
    }
    long double e1[3], e2[3], nn[3];
    for (int a = 0; a < 3; ++a) {
      e1[a] = vx[1][a] - vx[0][a];
      e2[a] = vx[2][a] - vx[0][a];
    }
    for (int a = 0; a < 3; ++a) nn[a] = e1[(a + 1) % 3] * e2[(a + 2) % 3] - e1[(a + 2) % 3] * e2[(a + 1) % 3];
    long double num = 0, dn = 0;
    for (int a = 0; a < 3; ++a) {
      num += nn[a] * (vx[0][a] - ro[a]);
      dn += nn[a] * rd[a];
    }
    const int ku = axis_u(w.k), kv = axis_v(w.k);
    const long double exact_den = ld(r.d[w.k]) + ld(w.c[kNU]) * ld(r.d[ku]) + ld(w.c[kNV]) * ld(r.d[kv]);
    const double den = A::to_double(x.den);
    if (den != 0) {
      EXPECT_LE(std::fabs(double(ld(x.den) - exact_den)), std::ldexp(1.0, std::ilogb(den) - F::man_bits)) << i;
    }
    if (in) {
      ++inside;
      ASSERT_EQ(x.exit, IstExit::hit) << i;
      // The key against the exact t: the shear's roundings of 2^-23 of the sheared magnitudes
      // (the coordinates and the distance), over |d . n| >= 0.2 (bound: 2^(3 - 23) of them; an F-wide t errs 2^7 times more).
      const long double te = num / dn;
      const double mag0 = std::max({std::fabs(o.x), std::fabs(o.y), std::fabs(o.z), std::fabs(p.x),
                                    std::fabs(p.y), std::fabs(p.z)});
      const double bound = (mag0 + dist) * std::ldexp(1.0, 3 - K::man_bits);
      const double err = std::fabs(double(static_cast<long double>(to_double<K>(x.tk)) - te));
      worst = std::max(worst, err / bound);
      EXPECT_LE(err, bound) << i;
      // o and d rounded: t errs by a few ulps of the coordinates over |d| = 1.
      const double mag = std::max({std::fabs(o.x), std::fabs(o.y), std::fabs(o.z), std::fabs(p.x), std::fabs(p.y),
                                   std::fabs(p.z)});
      EXPECT_NEAR(A::to_double(x.t), dist, (mag + dist) * std::ldexp(1.0, 4 - F::man_bits)) << i;
    } else {
      ++outside;
      ASSERT_NE(x.exit, IstExit::hit) << i;
    }
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
  ::testing::Test::RecordProperty("worst_key_error_over_bound", std::to_string(worst));
  std::printf("worst key error / bound: %.4f\n", worst);
}
TEST(Watertight, AgreesWithDoubleFp24Rtz) { agrees_with_double<FP24, Rounding::rtz>(21); }
TEST(Watertight, AgreesWithDoubleFp24Rne) { agrees_with_double<FP24, Rounding::rne>(22); }
TEST(Watertight, AgreesWithDoubleFp24Raycore) { agrees_with_double<FP24, Rounding::raycore>(23); }
TEST(Watertight, AgreesWithDoubleFp32Rtz) { agrees_with_double<FP32, Rounding::rtz>(24); }

// An outline edge decided at the shear's precision: rays (their origin and direction as the format
// holds them) aimed near an edge of a lone triangle; the inside test's answer equals the exact one
// (the shear and edge functions on the same bits in 113-bit arithmetic) whenever every exact edge
// function exceeds 2^-20 of the product of its two vertices' sheared magnitudes (what bounds the
// shear's rounding error). The shear runs in FP32's 8/23 for FP24 (hls::ShearFormat), 2^-23 of
// each magnitude at worst; an FP24 shear's 2^-16 reaches into the band 2^-20 .. 2^-14, and the
// test counts that the band is populated.
template <class F, Rounding R>
void outline_at_shear_precision(uint64_t seed) {
  using A = Arith<F, R>;
  __extension__ typedef __float128 Q;
  auto q = [](uint32_t x) { return Q(A::to_double(x)); };
  auto qabs = [](Q x) { return x < 0 ? -x : x; };
  Rng rng(seed);
  int decided = 0, band = 0;
  for (int i = 0; i < 20000; ++i) {
    const Tri tri = test::random_tri(rng, Vec3{uni(rng, -50, 50), uni(rng, -50, 50), uni(rng, -50, 50)}, 4);
    const WaldTri<F> w = make_wald<F, R>(tri, 0, IstKind::watertight);
    if (w.degenerate()) continue;
    Vec3 P[3];
    for (int j = 0; j < 3; ++j)
      for (int a = 0; a < 3; ++a) P[j][a] = A::to_double(w.c[WaldTri<F>::VA + 3 * j + a]);
    // A point near edge (e, e + 1), a small step toward or away from the third vertex.
    const int e = int(rng() % 3);
    const Vec3 &p0 = P[e], &p1 = P[(e + 1) % 3], &p2 = P[(e + 2) % 3];
    const Vec3 base = p0 + (p1 - p0) * uni(rng, 0.1, 0.9);
    const Vec3 p = base + (p2 - base) * uni(rng, -1e-3, 1e-3);
    const Vec3 n = unit(cross(p1 - p0, p2 - p0));
    const Vec3 dir = random_dir(rng);
    if (std::fabs(dot(dir, n)) < 0.2) continue;
    const Ray r = make_ray<A>(p - dir * uni(rng, 1, 100), dir);
    const IstOut x = ist_test<A>(w, r.o, r.d, r.tmin, r.tmax);
    if (x.exit == IstExit::distance || x.exit == IstExit::sum) continue;
    // The exact shear of the same bits (kz as the hardware picks it: the largest |d|, ties low).
    int kz = 0;
    if (A::lt(A::abs(r.d[0]), A::abs(r.d[1]))) kz = 1;
    if (A::lt(A::abs(r.d[kz]), A::abs(r.d[2]))) kz = 2;
    const int kx = (kz + 1) % 3, ky = (kz + 2) % 3;
    // px, py exact, and each one's error bound's scale: the shear rounds ox (oy) and then px (py),
    // each to 2^-23 of its magnitude or better (rtz, FP32's 23 bits).
    const Q ox = q(r.d[kz]) * q(r.o[kx]) - q(r.d[kx]) * q(r.o[kz]);
    const Q oy = q(r.d[kz]) * q(r.o[ky]) - q(r.d[ky]) * q(r.o[kz]);
    Q px[3], py[3], m[3];
    for (int j = 0; j < 3; ++j) {
      const uint32_t* c = w.c + WaldTri<F>::VA + 3 * j;
      px[j] = q(r.d[kz]) * q(c[kx]) - q(r.d[kx]) * q(c[kz]) - ox;
      py[j] = q(r.d[kz]) * q(c[ky]) - q(r.d[ky]) * q(c[kz]) - oy;
      m[j] = std::max(qabs(px[j]), qabs(py[j])) + std::max(qabs(ox), qabs(oy));
    }
    bool neg = false, pos = false, undecidable = false, near = false;
    for (int j = 0; j < 3; ++j) {
      const int a = (j + 1) % 3, b = (j + 2) % 3;  // E(a, b) = bx ay - by ax
      const Q E = px[b] * py[a] - py[b] * px[a];
      // The shear's roundings move E by at most about 2 * 2^-23 * m_a m_b * 2: undecidable below
      // 2^-20 m_a m_b; an FP24 shear's (2^-16 of each) reach 2^-14 m_a m_b.
      undecidable |= qabs(E) <= m[a] * m[b] * Q(std::ldexp(1.0, -20));
      near |= qabs(E) <= m[a] * m[b] * Q(std::ldexp(1.0, -14));
      neg |= E < 0;
      pos |= E > 0;
    }
    if (undecidable) continue;
    ++decided;
    band += near;
    ASSERT_EQ(x.exit == IstExit::hit, !(neg && pos)) << i;
  }
  EXPECT_GT(decided, 10000);
  EXPECT_GT(band, 200);  // rays an FP24 shear could put on the wrong side
}
TEST(Watertight, OutlineAtShearPrecisionFp24Rtz) { outline_at_shear_precision<FP24, Rounding::rtz>(51); }
TEST(Watertight, OutlineAtShearPrecisionFp24Rne) { outline_at_shear_precision<FP24, Rounding::rne>(52); }
TEST(Watertight, OutlineAtShearPrecisionFp24Raycore) { outline_at_shear_precision<FP24, Rounding::raycore>(53); }

// The edge function's two orders: exact negations, bit for bit (what makes a shared edge one).
template <class F, Rounding R>
void edge_antisymmetric(uint64_t seed) {
  using A = Arith<F, R>;
  constexpr uint32_t absent = F::sign_mask;
  Rng rng(seed);
  for (int i = 0; i < 100000; ++i) {
    uint32_t v[4];
    for (uint32_t& x : v) {
      x = A::from_double(std::ldexp(uni(rng, -1, 1), int(rng() % 40) - 20));
      if (rng() % 8 == 0) x = 0;
    }
    if (rng() % 4 == 0) v[2] = v[0];  // equal coordinates: exact cancellation
    const uint32_t pq = A::sop(absent, absent, v[2], v[1], A::neg(v[3]), v[0]);
    const uint32_t qp = A::sop(absent, absent, v[0], v[3], A::neg(v[1]), v[2]);
    if (A::is_zero(pq)) {
      ASSERT_TRUE(A::is_zero(qp)) << i;
    } else {
      ASSERT_EQ(qp, A::neg(pq)) << i;
    }
  }
}
TEST(Watertight, EdgeAntisymmetricFp24Rtz) { edge_antisymmetric<FP24, Rounding::rtz>(31); }
TEST(Watertight, EdgeAntisymmetricFp24Rne) { edge_antisymmetric<FP24, Rounding::rne>(32); }
TEST(Watertight, EdgeAntisymmetricFp24Raycore) { edge_antisymmetric<FP24, Rounding::raycore>(33); }
TEST(Watertight, EdgeAntisymmetricFp32Rne) { edge_antisymmetric<FP32, Rounding::rne>(34); }

// The VTU on a watertight record: each vertex coordinate shifted once, the plane through the
// shifted vertex A (watertight_nd), n_u and n_v unchanged.
TEST(Watertight, VtuShiftsVertices) {
  using A = Arith<FP24, Rounding::rtz>;
  using W = WaldTri<FP24>;
  const Vtu<FP24, Rounding::rtz> vtu = Vtu<FP24, Rounding::rtz>::from_camera(Vec3{1234.5, -17.25, 99.125});
  Rng rng(41);
  for (int i = 0; i < 2000; ++i) {
    const Tri tri = test::random_tri(rng, Vec3{uni(rng, -2e3, 2e3), uni(rng, -2e3, 2e3), uni(rng, -2e3, 2e3)}, 20);
    const W w = make_wald<FP24, Rounding::rtz>(tri, 5, IstKind::watertight);
    const W o = vtu.tri(w);
    for (int j = 0; j < 2; ++j) EXPECT_EQ(o.c[j], w.c[j]) << i;
    for (int j = W::VA; j < W::VA + 9; ++j) EXPECT_EQ(o.c[j], A::sub(w.c[j], vtu.c[j % 3])) << i;
    EXPECT_EQ(o.c[W::ND], (watertight_nd<FP24, Rounding::rtz>(o))) << i;
    uint8_t rec[48];
    encode_tri<FP24>(w, rec);
    vtu.tri_record(rec, IstKind::watertight);
    EXPECT_TRUE(decode_tri<FP24>(rec, IstKind::watertight) == o);
  }
}

}  // namespace
}  // namespace raycore::hls
