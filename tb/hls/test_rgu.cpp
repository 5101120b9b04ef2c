// tb/hls/test_rgu.cpp - the ray generation unit's datapath and pixel order (hls/rgu.h).
//
//   RguCamera.MatchesPrimaryDirection  the camera registers (FP32, rne) span
//                                      scenes::primary_direction's rays: d00 + x dx + y dy,
//                                      normalised in double, within 2e-6 rad of it
//   RguCoord.Exact                     pixel coordinates convert exactly (FP24: all of 0 .. 2^17)
//   RguPrimary.DirectionError          the in-format direction against the exact one, FP24
//                                      rtz/rne, every pixel of an 800 x 480 frame for random
//                                      cameras: angle and |d| - 1 within a few ulps; prints the
//                                      statistics beside those of the old rounding of the double
//                                      direction (RGUERR lines)
//   RguTiles.Order                     every pixel exactly once over the RTUs, tile i on RTU
//                                      i mod N, tiles in increasing order, row-major inside
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "hls/fp.h"
#include "hls/geom.h"
#include "hls/rgu.h"
#include "scenes/scene.h"

namespace raycore::hls {
namespace {

// A random camera: an orthonormal basis (right, up, -forward right-handed), a field of view.
scenes::Camera random_camera(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Vec3 f;
  do f = {u(rng), u(rng), u(rng)};
  while (length(f) < 0.1);
  f = normalize(f);
  Vec3 a = std::fabs(f.y) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
  if (rng() % 4 == 0) f = Vec3{0, 0, -1};  // the default, axis-aligned (exact zeros)
  const Vec3 r = normalize(cross(f, a));
  scenes::Camera c;
  c.present = true;
  c.forward = f;
  c.right = r;
  c.up = cross(r, f);
  c.yfov = (10.0 + 110.0 * std::uniform_real_distribution<double>(0, 1)(rng)) * M_PI / 180.0;
  return c;
}

double angle(const Vec3& a, const Vec3& b) {
  const Vec3 c = cross(a, b);
  return std::atan2(length(c), dot(a, b));
}

template <class A>
Vec3 to_vec(const uint32_t v[3]) {
  return {A::to_double(v[0]), A::to_double(v[1]), A::to_double(v[2])};
}

TEST(RguCamera, MatchesPrimaryDirection) {
  using A = Arith<FP32, Rounding::rne>;
  std::mt19937_64 rng(11);
  const uint32_t origin[3] = {0, 0, 0};
  for (int k = 0; k < 200; ++k) {
    const scenes::Camera cam = random_camera(rng);
    const int w = 1 + int(rng() % 1200), h = 1 + int(rng() % 900);
    const RguCamera rc = rgu_camera<A>(origin, cam.forward, cam.right, cam.up, cam.yfov, w, h);
    const Vec3 d00 = to_vec<A>(rc.d00), dx = to_vec<A>(rc.dx), dy = to_vec<A>(rc.dy);
    for (int j = 0; j < 50; ++j) {
      const int x = j == 0 ? w - 1 : int(rng() % uint64_t(w)), y = j == 1 ? h - 1 : int(rng() % uint64_t(h));
      const Vec3 d = normalize(d00 + dx * double(x) + dy * double(y));
      ASSERT_LT(angle(d, scenes::primary_direction(cam, x, y, w, h)), 2e-6)
          << "camera " << k << " " << w << "x" << h << " pixel " << x << "," << y;
    }
  }
}

TEST(RguCoord, Exact) {
  using A24 = Arith<FP24, Rounding::rtz>;
  for (uint32_t n = 0; n <= (1u << 17); ++n) ASSERT_EQ(A24::to_double(rgu_coord<A24>(n)), double(n));
  using A32 = Arith<FP32, Rounding::rne>;
  std::mt19937_64 rng(3);
  for (int k = 0; k < 100000; ++k) {
    const uint32_t n = uint32_t(rng() % (1u << 24));
    ASSERT_EQ(A32::to_double(rgu_coord<A32>(n)), double(n));
  }
}

// Over every pixel of an 800 x 480 frame of 6 random cameras: the angle between the unit's
// direction and the exact one, and |d| - 1, in units of 2^-M (M = 16, FP24's mantissa bits).
template <Rounding R>
void direction_error(const char* mode) {
  using A = Arith<FP24, R>;
  constexpr double u = 1.0 / 65536.0;
  std::mt19937_64 rng(5);
  const int w = 800, h = 480;
  const uint32_t origin[3] = {0, 0, 0};
  double max_new = 0, sum_new = 0, max_old = 0, sum_old = 0, max_len = 0, max_len_old = 0;
  uint64_t n = 0;
  for (int k = 0; k < 6; ++k) {
    const scenes::Camera cam = random_camera(rng);
    const RguCamera rc = rgu_camera<A>(origin, cam.forward, cam.right, cam.up, cam.yfov, w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const Vec3 exact = scenes::primary_direction(cam, x, y, w, h);
        const Ray r = rgu_primary<A>(rc, uint32_t(x), uint32_t(y), 0);
        const Vec3 d = to_vec<A>(r.d);
        const uint32_t old[3] = {A::from_double(exact.x), A::from_double(exact.y), A::from_double(exact.z)};
        const Vec3 dold = to_vec<A>(old);
        const double a = angle(d, exact) / u, ao = angle(dold, exact) / u;
        max_new = std::max(max_new, a);
        max_old = std::max(max_old, ao);
        sum_new += a;
        sum_old += ao;
        max_len = std::max(max_len, std::fabs(length(d) - 1) / u);
        max_len_old = std::max(max_len_old, std::fabs(length(dold) - 1) / u);
        for (int i = 0; i < 3; ++i) ASSERT_EQ(r.inv[i], A::rcp(r.d[i]));
        ++n;
      }
  }
  std::printf("RGUERR fp24 %s angle/2^-16: in-format max %.3f mean %.3f, rounded-once max %.3f mean "
              "%.3f; | |d|-1 |/2^-16: in-format max %.3f, rounded-once max %.3f (%llu rays)\n",
              mode, max_new, sum_new / double(n), max_old, sum_old / double(n), max_len, max_len_old,
              (unsigned long long)n);
  EXPECT_LT(max_new, 8.0);
  EXPECT_LT(max_len, 8.0);
}

TEST(RguPrimary, DirectionErrorRtz) { direction_error<Rounding::rtz>("rtz"); }
TEST(RguPrimary, DirectionErrorRne) { direction_error<Rounding::rne>("rne"); }

TEST(RguTiles, Order) {
  std::mt19937_64 rng(7);
  for (int k = 0; k < 300; ++k) {
    int w = 1 + int(rng() % 70), h = 1 + int(rng() % 50);
    if (k == 0) {
      w = 800;
      h = 480;
    }
    const int tile = k % 5 == 0 ? 1 + int(rng() % 9) : 8;
    const int rtus = 1 + int(rng() % 9);
    const int tiles_x = (w + tile - 1) / tile;
    std::vector<int> seen(size_t(w) * size_t(h), 0);
    for (int rtu = 0; rtu < rtus; ++rtu) {
      RguTiles t(w, h, tile, rtu, rtus);
      long last = -1;
      while (!t.done()) {
        const int x = t.x(), y = t.y();
        ASSERT_TRUE(x >= 0 && x < w && y >= 0 && y < h);
        ASSERT_EQ(t.pixel(), uint32_t(y * w + x));
        const int ti = (y / tile) * tiles_x + x / tile;
        ASSERT_EQ(ti % rtus, rtu) << "tile " << ti;
        // Tiles increasing, then row-major inside the tile.
        const long key = (long(ti) * tile + y % tile) * tile + x % tile;
        ASSERT_GT(key, last);
        last = key;
        ++seen[size_t(y) * size_t(w) + size_t(x)];
        t.next();
      }
    }
    for (size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], 1) << "pixel " << i << " of " << w << "x" << h;
  }
}

}  // namespace
}  // namespace raycore::hls
