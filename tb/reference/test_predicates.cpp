// Exact-sign predicates of the reference (sim/reference/predicates.h).
#include <gtest/gtest.h>

#include <cmath>

#include "sim/reference/predicates.h"

namespace raycore::reference {
namespace {

TEST(ReferencePredicates, DiffOfProductsExactSignWherePlainDoubleCancels) {
  // (1 + 2^-30)^2 - 1 * (1 + 2^-29) = 2^-60 exactly; the plain double evaluation gives 0.
  const double a = 1.0 + 0x1p-30, d = 1.0 + 0x1p-29;
  const double plain = a * a - 1.0 * d;
  EXPECT_EQ(plain, 0.0);
  EXPECT_EQ(diff_of_products(a, a, 1.0, d), 0x1p-60);
  EXPECT_EQ(edge_function(a, a, 1.0, d), 0x1p-60);
  EXPECT_EQ(edge_function(1.0, d, a, a), -0x1p-60);
  // Equal products give exactly 0.
  EXPECT_EQ(diff_of_products(3.0, 0.1, 0.1, 3.0), 0.0);
  EXPECT_EQ(edge_function(3.0, 0.1, 0.1, 3.0), 0.0);
}

TEST(ReferencePredicates, Orient3dExactOnCoplanarPointsFarFromOrigin) {
  // All four points have z = 0.1 (the same double): exactly coplanar, although the plain
  // evaluation at these magnitudes is dominated by rounding.
  const hls::Vec3 a{1e8 + 0.1, 3e7 + 0.3, 0.1}, b{-2e8 + 0.7, 1e8 + 0.9, 0.1}, c{5e7 + 0.3, -4e8 + 0.1, 0.1};
  const hls::Vec3 p{12345.678, -987.1, 0.1};
  EXPECT_EQ(orient3d(a, b, c, p), 0);
  const int up = orient3d(a, b, c, hls::Vec3{p.x, p.y, std::nextafter(0.1, 1.0)});
  const int down = orient3d(a, b, c, hls::Vec3{p.x, p.y, std::nextafter(0.1, 0.0)});
  EXPECT_NE(up, 0);
  EXPECT_EQ(down, -up);
  // Orientation: a, b, c counter-clockwise seen from +z gives +1 above.
  const hls::Vec3 o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0};
  EXPECT_EQ(orient3d(o, x, y, hls::Vec3{0.2, 0.2, 1e-300}), 1);
  EXPECT_EQ(orient3d(o, y, x, hls::Vec3{0.2, 0.2, 1e-300}), -1);
  EXPECT_EQ(orient3d(o, x, y, hls::Vec3{0.2, 0.2, 0.0}), 0);
}

TEST(ReferencePredicates, DegenerateTriangles) {
  const hls::Vec3 a{0.1, 0.2, 0.3}, b{1.1, 1.2, 1.3};
  EXPECT_TRUE(is_degenerate(a, a, b));
  EXPECT_TRUE(is_degenerate(a, b, b));
  // Exactly collinear (dyadic coordinates), then the last coordinate one ulp off the line.
  EXPECT_TRUE(is_degenerate({1, 2, 3}, {2, 4, 6}, {3.5, 7, 10.5}));
  EXPECT_FALSE(is_degenerate({1, 2, 3}, {2, 4, 6}, {3.5, 7, std::nextafter(10.5, 11.0)}));
  EXPECT_FALSE(is_degenerate({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
}

}  // namespace
}  // namespace raycore::reference
