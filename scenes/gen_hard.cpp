// scenes/gen_hard.cpp - small scenes that each stress one numerical weak spot of a 24-bit ray
// tracer. Each has a camera and a point light; sizes stay at 1k-20k triangles.
#include <cmath>
#include <string>

#include "scenes/builder.h"

namespace raycore::scenes::gen {
namespace {

// A bumpy closed blob (a stand-in for a scanned model): radius r0 with smooth lumps.
double blob_radius(Vec3 d, double r0, double phase) {
  double s1, c1, s2, c2, s3, c3;
  sincos(3 * d.x + 2 * d.y + phase, s1, c1);
  sincos(5 * d.z - 2 * d.x, s2, c2);
  sincos(7 * d.y + d.z, s3, c3);
  return r0 * (1 + 0.12 * s1 + 0.08 * c2 + 0.05 * s3 * c1);
}

double tangent(double a) {
  double s, c;
  sincos(a, s, c);
  return s / c;
}

}  // namespace

// far: everything (a bumpy blob, a ground plate, a box, a column, a thin leaning plate) lies
// ~`dist` units from the origin, with the camera right beside it. Stresses: FP24 has 16 fraction
// bits, so at 10^5 a coordinate's ulp is 1 unit while the objects are ~10-100 units big: vertices,
// Wald constants and hit points are coarse, and shadow rays start far off their surfaces. The VTU
// (camera moved to the origin) is meant to fix exactly this.
Scene build_far(double dist) {
  const Vec3 o{std::nearbyint(0.7 * dist), std::nearbyint(0.1 * dist), std::nearbyint(-0.7 * dist)};
  Builder b("far");
  b.part("ground");
  b.grid(o + Vec3{-200, 0, -200}, {0, 0, 400}, {400, 0, 0}, 16, 16);
  b.part("blob");
  b.sphere(Frame(o), {0, 32, 0}, 30, 40, 80, [](Vec3 d) { return blob_radius(d, 28, 0.5); });
  b.part("crate");
  b.box(Frame(o + Vec3{55, 0, -35}, 0.4), {-15, 0, -15}, {15, 40, 15});
  b.part("column");
  b.cylinder(Frame(o), {-50, 0, 30}, 10, 60, 32);
  b.part("plate");
  b.box(Frame(o + Vec3{30, 0, 45}, -0.7), {-20, 0, -1}, {20, 35, 1});
  Scene s = b.finish();
  s.camera = look_at_camera(o + Vec3{95, 48, 120}, o + Vec3{0, 25, 0}, 45);
  s.light = {true, o + Vec3{-70, 160, 90}, 1.0};
  return s;
}

// grazing: a 4000 x 4000 ground, a long wall, a ramp tilted by 0.5 degrees and a platform whose
// plane is slightly off every axis, seen from 4 units above the ground and lit from 25 units above
// it, so that primary and shadow rays meet the large planes at angles well under a degree.
// Stresses: the t of a grazing ray is very sensitive to the plane constant (n_d), so rounding
// moves hit points far along the surface; shadow rays leave almost parallel to the surface and
// re-hit it (self-intersection / acne); long shadows of small casters.
Scene build_grazing() {
  Builder b("grazing");
  b.part("ground");
  b.grid({-2000, 0, -2000}, {0, 0, 4000}, {4000, 0, 0}, 40, 40);
  b.part("wall");
  b.grid({1500, 0, -2000}, {0, 400, 0}, {0, 0, 4000}, 4, 40);
  b.part("ramp");
  {
    const double t = tangent(0.5 * kPi / 180);
    const Vec3 p0{-1200, 0.5, 200};
    b.grid(p0, {0, 1000 * t, 1000}, {1000, 0, 0}, 16, 16);
  }
  b.part("platform");
  {
    const Vec3 n = hls::normalize({0.02, 1, 0.013});
    const Vec3 u = hls::normalize(hls::cross(n, {1, 0, 0}));  // in the plane
    const Vec3 v = hls::cross(u, n);
    const Vec3 c{700, 40, -700};
    b.grid(c - u * 500 - v * 500, u * 1000, v * 1000, 16, 16);
  }
  Rng rng(0x6A2A21A6ull);
  for (int i = 0; i < 10; ++i) {
    b.part("caster_" + std::to_string(i));
    const Vec3 p{rng.range(-1200, 1300), 0, rng.range(-1500, 1500)};
    if (i % 3 == 2) b.cylinder(Frame(), p, rng.range(5, 12), rng.range(20, 60), 24);
    else b.box(Frame(p, rng.range(0, 1.5)), {-10, 0, -10}, {10, rng.range(15, 50), 10});
  }
  Scene s = b.finish();
  s.camera = look_at_camera({1300, 4, -1900}, {700, 0, 1900}, 40);
  s.light = {true, {-1900, 25, 300}, 1.0};
  return s;
}

// slivers: a disc made of a 2048-triangle fan, a ground rectangle cut into 2-unit-wide strips 800
// units long, a column with 1024 sides (its sides are 350 x 0.37 slivers, its caps fans), a wall
// fanned from one corner into 512 needles, and a twisted ribbon of thin triangles along a helix.
// Stresses: watertightness along long shared edges (rays through an edge must hit one of its two
// triangles), precision of the barycentric tests when one edge is tiny, and kd-tree splitting of
// long thin triangles (many leaf references).
Scene build_slivers() {
  Builder b("slivers");
  b.part("fan_disc");
  {
    const int n = 2048;
    const Vec3 c{0, 0, 0};
    for (int i = 0; i < n; ++i) {
      double s0, c0, s1, c1;
      sincos(2 * kPi * i / n, s0, c0);
      sincos(2 * kPi * ((i + 1) % n) / n, s1, c1);
      b.tri(c, c + Vec3{300 * c1, 0, 300 * s1}, c + Vec3{300 * c0, 0, 300 * s0});
    }
  }
  b.part("strips");
  for (int i = 0; i < 400; ++i) {
    const double z0 = -400 + 2.0 * i, z1 = z0 + 2;
    if (i % 2) b.quad({350, 0, z0}, {350, 0, z1}, {1150, 0, z1}, {1150, 0, z0});
    else b.quad({350, 0, z1}, {1150, 0, z1}, {1150, 0, z0}, {350, 0, z0});
  }
  b.part("column");
  b.cylinder(Frame(), {-450, 0, -100}, 60, 350, 1024);
  b.part("needle_wall");
  {
    const Vec3 apex{-600, 0, 450};
    const int n = 512;
    for (int i = 0; i < n; ++i) {
      const Vec3 p0{-600 + 1200.0 * i / n, 300, 450}, p1{-600 + 1200.0 * (i + 1) / n, 300, 450};
      b.tri(apex, p1, p0);
    }
    b.tri(apex, {600, 0, 450}, {600, 300, 450});
  }
  b.part("ribbon");
  {
    const int n = 150;
    auto at = [](int i, double w) {
      double s, c, st, ct;
      sincos(6 * kPi * i / 150, s, c);
      sincos(kPi * i / 150, st, ct);
      const Vec3 centre{-450 + 90 * c, 20 + 1.8 * i, 250 + 90 * s};
      return centre + Vec3{ct * w, st * w, 0};
    };
    for (int i = 0; i < n; ++i) b.quad(at(i, -1.5), at(i + 1, -1.5), at(i + 1, 1.5), at(i, 1.5));
  }
  Scene s = b.finish();
  s.camera = look_at_camera({0, 420, -900}, {0, 60, 100}, 60);
  s.light = {true, {-700, 500, -400}, 1.0};
  return s;
}

// coplanar: a floor with "decals" above it at offsets 1e-1 .. 1e-6 and 0, exactly coplanar
// overlapping quads with different triangulations, cubes stacked and packed face to face, a plate
// crossing the floor at 0.001 rad, and a tilted panel and a wall with decal layers offset along
// their normals. Stresses: which of two (nearly) coincident surfaces a ray hits (z-fighting) and
// whether a shadow ray from the upper layer is blocked by the lower one; offsets below the
// format's resolution (FP24 ulp at 400 is 2^-8; float32 in the file: 2^-16 at 400) collapse.
Scene build_coplanar() {
  Builder b("coplanar");
  b.part("floor");
  b.grid({-400, 0, -400}, {0, 0, 800}, {800, 0, 0}, 24, 24);
  const double offsets[] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 0};
  for (int i = 0; i < 7; ++i) {
    b.part("decal_" + std::to_string(i));
    const double x0 = -330 + 90.0 * i, y = offsets[i];
    b.quad({x0, y, -330}, {x0, y, -250}, {x0 + 80, y, -250}, {x0 + 80, y, -330});  // other diagonal than the floor
    b.part("decal_small_" + std::to_string(i));
    b.quad({x0 + 20, 2 * y, -310}, {x0 + 20, 2 * y, -270}, {x0 + 60, 2 * y, -270}, {x0 + 60, 2 * y, -310});
  }
  b.part("overlap_a");
  b.quad({-330, 0, -200}, {-330, 0, -60}, {-130, 0, -60}, {-130, 0, -200});
  b.part("overlap_b");
  b.quad({-230, 0, -180}, {-30, 0, -180}, {-30, 0, -40}, {-230, 0, -40});
  b.part("overlap_c");
  for (int i = 0; i < 8; ++i) {
    double s0, c0, s1, c1;
    sincos(i * kPi / 16, s0, c0);
    sincos((i + 1) * kPi / 16, s1, c1);
    b.tri({-180, 0, -120}, {-180 + 100 * c0, 0, -120 + 100 * s0}, {-180 + 100 * c1, 0, -120 + 100 * s1});
  }
  b.part("tower");
  for (int i = 0; i < 4; ++i) b.box({40, 40.0 * i, -200}, {80, 40.0 * (i + 1), -160});
  b.part("packed_cubes");
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) b.box({120 + 30.0 * i, 0, -200 + 30.0 * j}, {150 + 30.0 * i, 30, -170 + 30.0 * j});
  b.part("crossing_plate");
  {
    const double t = tangent(1e-3);
    b.grid({50, -100 * t, -100}, {0, 0, 200}, {200, 200 * t, 0}, 4, 4);
  }
  // A tilted panel with layers along its normal.
  {
    const Vec3 n = hls::normalize({0.3, 0.8, 0.52});
    const Vec3 u = hls::normalize(hls::cross(n, {0, 0, 1})), v = hls::cross(n, u);
    const Vec3 c{200, 120, 200};
    b.part("panel");
    b.grid(c - u * 80 - v * 80, u * 160, v * 160, 4, 4);
    for (int i = 0; i < 6; ++i) {
      b.part("panel_decal_" + std::to_string(i));
      const Vec3 o = c + n * offsets[i] + u * (-70 + 25.0 * i) - v * 60;
      b.quad(o, o + u * 20, o + u * 20 + v * 120, o + v * 120);
    }
  }
  b.part("wall");
  b.grid({-400, 0, 390}, {800, 0, 0}, {0, 200, 0}, 8, 2);
  for (int i = 0; i < 7; ++i) {
    b.part("wall_decal_" + std::to_string(i));
    const double x0 = -330 + 90.0 * i, z = 390 - offsets[i];
    b.quad({x0, 40, z}, {x0 + 80, 40, z}, {x0 + 80, 160, z}, {x0, 160, z});
  }
  Scene s = b.finish();
  s.camera = look_at_camera({-60, 330, -720}, {0, 20, 0}, 55);
  s.light = {true, {300, 420, -260}, 1.0};
  return s;
}

// origin-far-camera: a small scene around the origin (ground, blob, boxes, an arch, a column),
// watched through a narrow field of view from ~5.5 * 10^4 units away, light close to the objects.
// Stresses the geometry-transition paper's stated limitation: without the VTU the geometry and
// the shadow rays live at small coordinates (accurate); with it everything is translated by
// -camera, to ~5.5 * 10^4, where the FP24 ulp is 0.5 to 1 unit, so the VTU makes things worse.
Scene build_origin_far_camera() {
  Builder b("origin-far-camera");
  b.part("ground");
  b.grid({-100, 0, -100}, {0, 0, 200}, {200, 0, 0}, 20, 20);
  b.part("blob");
  b.sphere(Frame(), {0, 22, 0}, 20, 30, 60, [](Vec3 d) { return blob_radius(d, 19, 1.7); });
  b.part("boxes");
  b.box(Frame({45, 0, -30}, 0.3), {-10, 0, -10}, {10, 25, 10});
  b.box(Frame({-40, 0, 40}, -0.5), {-12, 0, -6}, {12, 14, 6});
  b.part("arch");
  b.box({-70, 0, -60}, {-62, 40, -52});
  b.box({-30, 0, -60}, {-22, 40, -52});
  b.box({-72, 40, -62}, {-20, 48, -50});
  b.part("column");
  b.cylinder(Frame(), {50, 0, 50}, 6, 45, 32);
  Scene s = b.finish();
  const Vec3 eye{30000, 24000, 40000};
  const double x = 70 / hls::length(eye);  // atan(x) for small x, by its series
  const double fov = 2 * (x - x * x * x / 3 + x * x * x * x * x / 5) * 180 / kPi;
  s.camera = look_at_camera(eye, {0, 18, 0}, fov);
  s.light = {true, {60, 150, 80}, 1.0};
  return s;
}

}  // namespace raycore::scenes::gen
