// Numerical stability on hard cases (issue 6; findings in docs/robustness.md):
// - ReIntersection: pbrt-style, seeded random triangles at magnitudes 1 .. 10^6, a ray through a
//   random interior point, a shadow ray spawned with each strategy (hls::hit_shadow) and traced
//   against the triangle alone (hls::ist_wald); error_bound must never re-hit, none must.
// - Watertight: rays from inside closed meshes (cube, icosphere, jittered closed room) must hit.
// - FarOffset: one small scene translated by 10^k, k = 0..6, VTU off/on, store world/anchored,
//   errors vs the reference (total) and vs the stored scene (arithmetic, sim/errors.h).
// - Limitations: the paper's two (camera at the origin: VTU = no change; objects at the origin,
//   camera far: VTU gains little).
// - Regression: literal bit patterns of failures found here.
// Every test prints its table (lines prefixed with the test's tag, for tb/robust/plot.sh).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <algorithm>
#include <array>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "hls/fp.h"
#include "hls/hit.h"
#include "hls/image.h"
#include "hls/ist.h"
#include "hls/wald.h"
#include "scenes/generate.h"
#include "scenes/scene.h"
#include "sim/errors.h"
#include "sim/golden/golden.h"
#include "sim/reference/bvh.h"
#include "sim/reference/metrics.h"
#include "sim/reference/reference.h"
#include "sim/run.h"

namespace {

namespace hls = raycore::hls;
namespace sim = raycore::sim;
namespace scenes = raycore::scenes;
namespace ref = raycore::reference;
using hls::FormatId;
using hls::Rounding;
using hls::Spawn;
using hls::Tri;
using hls::Vec3;

// ---- deterministic random numbers (no std:: distributions: their output is library-specific) --

struct Rng {
  uint64_t s;
  explicit Rng(uint64_t seed) : s(seed * 0x9E3779B97F4A7C15ull + 1) {}
  uint64_t next() {  // splitmix64
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uni() { return double(next() >> 11) * 0x1p-53; }       // [0, 1)
  double sym() { return 2 * uni() - 1; }                         // [-1, 1)
  Vec3 sphere() {                                                // uniform unit vector
    for (;;) {
      const Vec3 v{sym(), sym(), sym()};
      const double l = hls::dot(v, v);
      if (l > 1e-6 && l <= 1) return v * (1 / std::sqrt(l));
    }
  }
};

std::string spawn_name(Spawn s) { return sim::to_string(s); }

std::string fmt_name(FormatId f, Rounding r) {
  return std::string(hls::format_name(f)) + "-" + hls::rounding_name(r);
}

// ---- re-intersection ---------------------------------------------------------------------------

struct ReCase {
  uint64_t tested = 0;  // primary hits with the light in front
  uint64_t rehit = 0;   // shadow ray hit its own triangle
};

// One random triangle, ray and light at magnitude `mag`; returns false if the primary ray missed
// or the hit unit found the light behind (nothing to test). `rehit[s]` per strategy.
template <class A>
bool reintersect_one(Rng& rng, double mag, const std::vector<hls::SpawnParams>& sps, bool* rehit,
                     std::string* detail) {  // detail: per strategy, filled once
  using F = typename A::Fmt;
  const Tri tri = {Vec3{rng.sym(), rng.sym(), rng.sym()} * mag,
                   Vec3{rng.sym(), rng.sym(), rng.sym()} * mag,
                   Vec3{rng.sym(), rng.sym(), rng.sym()} * mag};
  const hls::WaldTri<F> w = hls::make_wald<F, A::rounding>(tri, 7);
  if (w.degenerate()) return false;
  // A random interior point (barycentrics >= 0.05) and a ray through it from a random direction.
  double b1 = 0.05 + 0.9 * rng.uni(), b2 = 0.05 + 0.9 * rng.uni();
  if (b1 + b2 > 0.95) {
    b1 = 1 - b1;
    b2 = 1 - b2;
  }
  const Vec3 p = tri[0] * (1 - b1 - b2) + tri[1] * b1 + tri[2] * b2;
  const Vec3 d = rng.sphere();
  const Vec3 o = p - d * (mag * (0.1 + 1.9 * rng.uni()));
  Vec3 n = hls::normalize(hls::cross(tri[1] - tri[0], tri[2] - tri[0]));
  if (hls::dot(n, o - p) < 0) n = n * -1.0;
  if (hls::dot(n, o - p) < 0.01 * hls::length(o - p)) return false;  // skip near-tangent primaries
  // The light on the primary ray's side, 10^-3 .. 1 mag off the plane (grazing light included),
  // up to mag away along it.
  const Vec3 lat = Vec3{rng.sym(), rng.sym(), rng.sym()} * mag;
  const Vec3 lp = p + (lat - n * hls::dot(lat, n)) + n * (mag * std::pow(10.0, -3 * rng.uni()));
  hls::Ray pr;
  for (int i = 0; i < 3; ++i) {
    pr.o[i] = A::from_double(o[i]);
    pr.d[i] = A::from_double(d[i]);
    pr.inv[i] = A::rcp(pr.d[i]);
  }
  const uint32_t tmin = A::from_double(1.0 / 4096);
  pr.tmin = tmin;
  pr.tmax = F::max_mag;
  const hls::IstOut h = hls::ist_test<A>(w, pr.o, pr.d, pr.tmin, pr.tmax);
  if (h.exit != hls::IstExit::hit) return false;
  const uint32_t light[3] = {A::from_double(lp.x), A::from_double(lp.y), A::from_double(lp.z)};
  const hls::HitTri ht{w.id, w.k, w.c[hls::kNU], w.c[hls::kNV], w.c[hls::kND], h.den};
  for (size_t s = 0; s < sps.size(); ++s) {
    const hls::ShadowSetup ss = hls::hit_shadow<A>(pr, h.t, ht, light, tmin, sps[s]);
    if (!ss.front) return false;  // decided before the spawn: the same for every strategy
    const bool hit = ss.skip_id != w.id &&
                     hls::ist_test<A>(w, ss.ray.o, ss.ray.d, ss.ray.tmin, ss.ray.tmax).exit ==
                         hls::IstExit::hit;
    rehit[s] = hit;
    if (hit && detail && detail[s].empty()) {
      char buf[512];
      std::snprintf(buf, sizeof buf,
                    "k=%u c={%#x,%#x,%#x,%#x,%#x,%#x,%#x,%#x,%#x} o={%#x,%#x,%#x} d={%#x,%#x,%#x} "
                    "light={%#x,%#x,%#x} segment=%d",
                    w.k, w.c[0], w.c[1], w.c[2], w.c[3], w.c[4], w.c[5], w.c[6], w.c[7], w.c[8],
                    pr.o[0], pr.o[1], pr.o[2], pr.d[0], pr.d[1], pr.d[2], light[0], light[1],
                    light[2], int(sps[s].segment));
      detail[s] = buf;
    }
  }
  return true;
}

constexpr int kMagnitudes = 7;  // 10^0 .. 10^6
constexpr int kTrianglesPerMagnitude = 4000;

struct ReTable {
  std::vector<hls::SpawnParams> sps;
  std::vector<std::string> names;
  uint64_t tested[kMagnitudes] = {};
  std::vector<std::vector<uint64_t>> rehit;  // [strategy][magnitude]
  std::vector<std::string> first_failure;  // per strategy: bit patterns of the first re-hit
};

template <class A>
ReTable reintersect_table(FormatId f) {
  ReTable t;
  for (bool seg : {false, true}) {
    for (Spawn s : {Spawn::none, Spawn::skip_origin, Spawn::ulp_offset, Spawn::error_bound, Spawn::skip_offset,
                    Spawn::skip_slab, Spawn::skip_back}) {
      hls::SpawnParams sp;
      sp.spawn = s;
      sp.ulps = sim::default_spawn_ulps(f, s);
      sp.segment = seg;
      t.sps.push_back(sp);
      t.names.push_back(std::string(spawn_name(s)) + (seg ? "/seg" : "/unit"));
    }
  }
  if (t.sps.size() > 16) throw std::logic_error("reintersect_table: more than 16 strategies");
  t.rehit.assign(t.sps.size(), std::vector<uint64_t>(kMagnitudes, 0));
  t.first_failure.assign(t.sps.size(), std::string());
  std::vector<char> rehit(t.sps.size());
  for (int m = 0; m < kMagnitudes; ++m) {
    Rng rng(1000u + uint64_t(m));
    const double mag = std::pow(10.0, m);
    for (int i = 0; i < kTrianglesPerMagnitude; ++i) {
      bool rh[16] = {};
      if (!reintersect_one<A>(rng, mag, t.sps, rh, t.first_failure.data()))
        continue;
      ++t.tested[m];
      for (size_t s = 0; s < t.sps.size(); ++s) t.rehit[s][size_t(m)] += rh[s] ? 1 : 0;
    }
  }
  return t;
}

void print_re_table(const std::string& cfg, const ReTable& t) {
  std::printf("reintersect %s: re-hit rate in %% of tested rays per magnitude 10^0..10^6\n", cfg.c_str());
  std::printf("reintersect %-14s", "tested");
  for (int m = 0; m < kMagnitudes; ++m) std::printf(" %8llu", (unsigned long long)t.tested[m]);
  std::printf("\n");
  for (size_t s = 0; s < t.sps.size(); ++s) {
    std::printf("reintersect %-14s", t.names[s].c_str());
    for (int m = 0; m < kMagnitudes; ++m)
      std::printf(" %8.3f", t.tested[m] ? 100.0 * double(t.rehit[s][size_t(m)]) / double(t.tested[m]) : 0.0);
    std::printf("\n");
  }
  for (size_t s = 0; s < t.sps.size(); ++s)
    if (!t.first_failure[s].empty())
      std::printf("reintersect %s first re-hit: %s\n", t.names[s].c_str(), t.first_failure[s].c_str());
  std::fflush(stdout);
}

template <class A>
void check_reintersection(FormatId f) {
  const ReTable t = reintersect_table<A>(f);
  const std::string cfg = fmt_name(f, A::rounding);
  print_re_table(cfg, t);
  for (int m = 0; m < kMagnitudes; ++m) EXPECT_GT(t.tested[m], uint64_t(kTrianglesPerMagnitude) / 2) << cfg;
  for (size_t s = 0; s < t.sps.size(); ++s) {
    const uint64_t big = t.rehit[s][4] + t.rehit[s][5] + t.rehit[s][6];
    switch (t.sps[s].spawn) {
      case Spawn::error_bound:
      case Spawn::skip_origin:  // the triangle alone: skipping it is trivially exact
      case Spawn::skip_offset:
      case Spawn::skip_slab:
      case Spawn::skip_back:
        for (int m = 0; m < kMagnitudes; ++m)
          EXPECT_EQ(t.rehit[s][size_t(m)], 0u) << cfg << " " << t.names[s] << " at 10^" << m
                                               << "; first: " << t.first_failure[s];
        break;
      case Spawn::none:
        if (t.sps[s].segment) break;  // reported only (see docs/robustness.md)
        // t_min = 2^-12 is a world distance (unit) or a fraction of the light distance (segment):
        // useless once ulps of the hit point exceed it.
        EXPECT_GT(big, uint64_t(t.tested[6]) / 20) << cfg << " " << t.names[s]
                                                   << ": none must re-intersect at 10^4..10^6";
        break;
      case Spawn::ulp_offset:
        break;  // reported only
    }
  }
}

TEST(ReIntersection, Fp24Rtz) { check_reintersection<hls::Arith<hls::FP24, Rounding::rtz>>(FormatId::fp24); }
TEST(ReIntersection, Fp24Rne) { check_reintersection<hls::Arith<hls::FP24, Rounding::rne>>(FormatId::fp24); }
TEST(ReIntersection, Fp32Rtz) { check_reintersection<hls::Arith<hls::FP32, Rounding::rtz>>(FormatId::fp32); }
TEST(ReIntersection, Fp32Rne) { check_reintersection<hls::Arith<hls::FP32, Rounding::rne>>(FormatId::fp32); }

// ---- neighbours: folded triangle pairs ---------------------------------------------------------
//
// What decides the frames (docs/robustness.md, "Beating the paper"): not the own triangle (skipped
// by id) but its neighbours. Per magnitude 10^0..10^6 (distance of the pair from the camera, which
// sits at the origin as with the VTU on): triangles A and B sharing an edge, B folded by phi about
// it; a primary ray from the camera hits A at distance delta from the shared edge (delta = 10^-4 ..
// 10^-1 of the edge length, log-uniform); the shadow ray (hls::hit_shadow) is traced against B
// alone (hls::ist_wald).
// - valley: phi in [30, 180] degrees (180 = coplanar), camera and light inside the wedge (in front
//   of both planes, the light from grazing A to grazing B): the exact segment never crosses B, so
//   a hit on B is a false shadow;
// - wall: phi in [30, 150] degrees, camera in the wedge, light behind B (still in front of A), kept
//   when the exact segment (double, watertight test) crosses B with barycentrics >= 10^-3: a miss
//   is a light leak through a contact occluder.
struct FoldCase {
  Tri a, b;
  Vec3 cam, p, light;
};

// One random folded pair at magnitude `mag`; wall = light behind B. False if rejected.
bool make_fold(Rng& rng, double mag, bool wall, FoldCase& fc) {
  const double deg = M_PI / 180;
  const double phi = wall ? (30 + 120 * rng.uni()) * deg : std::min(180.0, 30 + 160 * rng.uni()) * deg;
  const Vec3 e = rng.sphere();
  const Vec3 a = hls::normalize(hls::cross(e, rng.sphere()));
  const Vec3 c = hls::cross(e, a);  // A's valley-side normal
  const Vec3 b = a * std::cos(phi) + c * std::sin(phi);
  const double len = mag * (0.05 + 0.2 * rng.uni());
  const Vec3 q0 = rng.sphere() * mag;  // the pair, about mag from the camera at the origin
  const Vec3 q1 = q0 + e * len;
  const double w = len * (0.4 + 0.6 * rng.uni());
  fc.a = {q0, q1, q0 + e * (0.5 * len) + a * w};
  fc.b = {q1, q0, q0 + e * (0.5 * len) + b * w};
  const double along = 0.25 + 0.5 * rng.uni();
  const double delta = len * std::pow(10.0, -4 + 3 * rng.uni());
  fc.p = q0 + e * (along * len) + a * delta;
  // Camera in the wedge (angles from a toward b), then translated so it sits at the origin.
  const double th_c = 0.1 + (phi - 0.2) * rng.uni();
  const Vec3 cam = fc.p + (a * std::cos(th_c) + c * std::sin(th_c)) * (mag * (0.5 + rng.uni())) +
                   e * (mag * 0.3 * rng.sym());
  const double th_l = wall ? phi + 0.02 + (M_PI - phi - 0.04) * rng.uni() : 0.01 + (phi - 0.02) * rng.uni();
  const Vec3 light = fc.p + (a * std::cos(th_l) + c * std::sin(th_l)) * (mag * (0.3 + 2 * rng.uni())) +
                     e * (mag * 0.3 * rng.sym());
  for (Vec3* v : {&fc.a[0], &fc.a[1], &fc.a[2], &fc.b[0], &fc.b[1], &fc.b[2], &fc.p})
    *v = *v - cam;
  fc.light = light - cam;
  fc.cam = Vec3{0, 0, 0};
  // Ground truth in double from the exact point: valley never crosses B, wall must (clearly).
  ref::TriHit th;
  const bool crosses =
      ref::intersect_triangle(ref::ShearedRay(ref::Ray{fc.p, fc.light - fc.p}), fc.b, 1e-9, 1.0, &th);
  if (!wall) return !crosses;
  return crosses && std::min({th.b0, th.b1, th.b2}) >= 1e-3 && th.t > 1e-6;
}

enum class FoldOutcome { skipped, ok, error };

// The hardware path for one case and strategy: error = false shadow (valley) / leak (wall).
template <class A>
FoldOutcome fold_outcome(const FoldCase& fc, bool wall, const hls::SpawnParams& sp) {
  using F = typename A::Fmt;
  const hls::WaldTri<F> wa = hls::make_wald<F, A::rounding>(fc.a, 1);
  const hls::WaldTri<F> wb = hls::make_wald<F, A::rounding>(fc.b, 2);
  if (wa.degenerate() || wb.degenerate()) return FoldOutcome::skipped;
  const Vec3 d = hls::normalize(fc.p - fc.cam);
  hls::Ray pr;
  for (int i = 0; i < 3; ++i) {
    pr.o[i] = A::zero;
    pr.d[i] = A::from_double(d[i]);
    pr.inv[i] = A::rcp(pr.d[i]);
  }
  const uint32_t tmin = A::from_double(1.0 / 4096);
  pr.tmin = tmin;
  pr.tmax = F::max_mag;
  const hls::IstOut h = hls::ist_test<A>(wa, pr.o, pr.d, pr.tmin, pr.tmax);
  if (h.exit != hls::IstExit::hit) return FoldOutcome::skipped;
  const hls::IstOut hb = hls::ist_test<A>(wb, pr.o, pr.d, pr.tmin, h.t);
  if (hb.exit == hls::IstExit::hit) return FoldOutcome::skipped;  // the camera would see B there
  const uint32_t light[3] = {A::from_double(fc.light.x), A::from_double(fc.light.y), A::from_double(fc.light.z)};
  const hls::HitTri ht{wa.id, wa.k, wa.c[hls::kNU], wa.c[hls::kNV], wa.c[hls::kND], h.den};
  const hls::ShadowSetup ss = hls::hit_shadow<A>(pr, h.t, ht, light, tmin, sp);
  if (!ss.front) return FoldOutcome::skipped;  // the light-side decision (same for every strategy)
  const bool hit = ss.skip_id != wb.id &&
                   hls::ist_test<A>(wb, ss.ray.o, ss.ray.d, ss.ray.tmin, ss.ray.tmax).exit ==
                       hls::IstExit::hit;
  return (wall ? !hit : hit) ? FoldOutcome::error : FoldOutcome::ok;
}

constexpr int kFoldsPerMagnitude = 3000;

struct FoldTable {
  std::vector<std::string> names;
  std::vector<hls::SpawnParams> sps;
  uint64_t tested[2][kMagnitudes] = {};                 // [wall][magnitude] (cases every strategy ran)
  std::vector<std::array<std::array<uint64_t, kMagnitudes>, 2>> errors;  // [strategy][wall][m]
  uint64_t total(size_t s, int wall) const {
    uint64_t n = 0;
    for (int m = 0; m < kMagnitudes; ++m) n += errors[s][size_t(wall)][size_t(m)];
    return n;
  }
};

hls::SpawnParams spawn(Spawn s, int32_t ulps) {
  hls::SpawnParams sp;
  sp.spawn = s;
  sp.ulps = ulps;
  return sp;
}

template <class A>
FoldTable fold_table(FormatId f) {
  FoldTable t;
  const int32_t off = sim::default_spawn_ulps(f);
  for (auto [s, u] : std::vector<std::pair<Spawn, int32_t>>{{Spawn::none, 0},
                                                             {Spawn::skip_origin, 0},
                                                             {Spawn::ulp_offset, off},
                                                             {Spawn::error_bound, 0},
                                                             {Spawn::skip_offset, off},
                                                             {Spawn::skip_slab, 2},
                                                             {Spawn::skip_slab, 4},
                                                             {Spawn::skip_back, 1}}) {
    t.sps.push_back(spawn(s, u));
    t.names.push_back(spawn_name(s) + (sim::spawn_uses_ulps(s) ? " " + std::to_string(u) : std::string()));
  }
  t.errors.assign(t.sps.size(), {});
  for (int wall = 0; wall < 2; ++wall)
    for (int m = 0; m < kMagnitudes; ++m) {
      Rng rng(5000u + 100u * uint64_t(wall) + uint64_t(m));
      const double mag = std::pow(10.0, m);
      for (int i = 0; i < kFoldsPerMagnitude; ++i) {
        FoldCase fc;
        if (!make_fold(rng, mag, wall != 0, fc)) continue;
        std::vector<FoldOutcome> out;
        for (const auto& sp : t.sps) out.push_back(fold_outcome<A>(fc, wall != 0, sp));
        if (out[0] == FoldOutcome::skipped) continue;  // the same for every strategy
        ++t.tested[wall][m];
        for (size_t s = 0; s < out.size(); ++s)
          t.errors[s][size_t(wall)][size_t(m)] += out[s] == FoldOutcome::error ? 1 : 0;
      }
    }
  return t;
}

template <class A>
FoldTable check_folds(FormatId f) {
  const FoldTable t = fold_table<A>(f);
  const std::string cfg = fmt_name(f, A::rounding);
  for (int wall = 0; wall < 2; ++wall) {
    std::printf("neighbours %s %s: %s in %% of tested rays per magnitude 10^0..10^6\n", cfg.c_str(),
                wall ? "wall" : "valley", wall ? "light leaks" : "false shadows");
    std::printf("neighbours %-14s", "tested");
    for (int m = 0; m < kMagnitudes; ++m) std::printf(" %8llu", (unsigned long long)t.tested[wall][m]);
    std::printf("\n");
    for (size_t s = 0; s < t.sps.size(); ++s) {
      std::printf("neighbours %-14s", t.names[s].c_str());
      for (int m = 0; m < kMagnitudes; ++m)
        std::printf(" %8.3f", t.tested[wall][m] ? 100.0 * double(t.errors[s][size_t(wall)][size_t(m)]) /
                                                      double(t.tested[wall][m])
                                                : 0.0);
      std::printf("\n");
    }
  }
  std::fflush(stdout);
  for (int wall = 0; wall < 2; ++wall)
    for (int m = 0; m < kMagnitudes; ++m) EXPECT_GT(t.tested[wall][m], uint64_t(kFoldsPerMagnitude) / 4) << cfg;
  return t;
}

size_t fold_index(const FoldTable& t, const std::string& name) {
  for (size_t s = 0; s < t.names.size(); ++s)
    if (t.names[s] == name) return s;
  ADD_FAILURE() << "no strategy " << name;
  return 0;
}

double fold_rate(const FoldTable& t, const std::string& name, int wall, int m) {
  const uint64_t n = t.tested[wall][m];
  return n ? 100.0 * double(t.errors[fold_index(t, name)][size_t(wall)][size_t(m)]) / double(n) : 0.0;
}

// Bounds: about 1.3x the worst measured with these seeds (docs/robustness.md).
void check_fold_bounds(const FoldTable& t, FormatId f, const std::string& cfg) {
  const std::string off = f == FormatId::fp24 ? " 2" : " 256";
  for (int m = 0; m < kMagnitudes; ++m) {
    const std::string at = cfg + " at 10^" + std::to_string(m);
    // t_min = 2^-12 world units: at magnitude 1 it swallows the wall for hit points within it of
    // the edge, whatever the strategy (delta reaches 5e-6).
    if (m == 0) {
      EXPECT_GE(fold_rate(t, "skip-origin", 1, m), 5.0) << at;
      continue;
    }
    if (f == FormatId::fp24) {
      // The back-off puts the point in front of both planes of the valley; the slab skips the
      // crossings within it; moving the origin along A's normal by the conservative error bound
      // goes behind B in acute valleys (and past walls).
      EXPECT_LE(fold_rate(t, "skip-back 1", 0, m), 0.05) << at;
      EXPECT_LE(fold_rate(t, "skip-slab 2", 0, m), 0.1) << at;
      EXPECT_GE(fold_rate(t, "error-bound", 0, m), 5.0) << at;
      EXPECT_GE(fold_rate(t, "error-bound", 1, m), 5.0) << at;
      // The slab's price: leaks through walls closer than the slab.
      EXPECT_LE(fold_rate(t, "skip-origin", 1, m), 0.2) << at;
      EXPECT_LE(fold_rate(t, "skip-slab 2", 1, m), 1.0) << at;
      EXPECT_LE(fold_rate(t, "skip-slab 4", 1, m), 4.2) << at;
      EXPECT_LE(fold_rate(t, "skip-back 1", 1, m), 3.5) << at;
    } else {
      for (const char* s : {"none", "skip-origin", "error-bound", "skip-slab 2", "skip-slab 4", "skip-back 1"})
        EXPECT_EQ(fold_rate(t, s, 0, m), 0.0) << at << " " << s;
      EXPECT_LE(fold_rate(t, "ulp-offset" + off, 0, m), 0.6) << at;
      for (const char* s : {"skip-origin", "error-bound", "skip-slab 2", "skip-slab 4", "skip-back 1"})
        EXPECT_LE(fold_rate(t, s, 1, m), 0.15) << at << " " << s;
    }
  }
  EXPECT_LE(t.total(fold_index(t, "skip-slab 2"), 0), t.total(fold_index(t, "skip-origin"), 0)) << cfg;
  EXPECT_LE(t.total(fold_index(t, "skip-back 1"), 0), t.total(fold_index(t, "skip-slab 4"), 0)) << cfg;
}

TEST(Neighbours, Fp24Rtz) {
  check_fold_bounds(check_folds<hls::Arith<hls::FP24, Rounding::rtz>>(FormatId::fp24), FormatId::fp24, "fp24-rtz");
}
TEST(Neighbours, Fp24Rne) {
  check_fold_bounds(check_folds<hls::Arith<hls::FP24, Rounding::rne>>(FormatId::fp24), FormatId::fp24, "fp24-rne");
}
TEST(Neighbours, Fp32Rne) {
  check_fold_bounds(check_folds<hls::Arith<hls::FP32, Rounding::rne>>(FormatId::fp32), FormatId::fp32, "fp32-rne");
}

// ---- closed meshes -----------------------------------------------------------------------------

void add_quad(std::vector<Tri>& out, Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  out.push_back({a, b, c});
  out.push_back({a, c, d});
}

// The box lo..hi, each face an n x n grid; interior grid vertices moved by up to `jitter` along
// the face normal (edge vertices are computed by the same formula on every face: closed).
std::vector<Tri> grid_box(Vec3 lo, Vec3 hi, int n, double jitter, uint64_t seed) {
  Rng rng(seed);
  std::vector<Tri> out;
  auto coord = [&](int axis, int i) { return lo[axis] + (hi[axis] - lo[axis]) * i / n; };
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side) {
      const int u = (k + 1) % 3, v = (k + 2) % 3;
      std::vector<Vec3> g(size_t((n + 1) * (n + 1)));
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
          Vec3 p;
          p[k] = side ? hi[k] : lo[k];
          p[u] = coord(u, i);
          p[v] = coord(v, j);
          if (i > 0 && i < n && j > 0 && j < n) p[k] += jitter * rng.sym();
          g[size_t(i * (n + 1) + j)] = p;
        }
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto at = [&](int a, int b) { return g[size_t(a * (n + 1) + b)]; };
          add_quad(out, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
  return out;
}

std::vector<Tri> icosphere(Vec3 c, double r, int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p = hls::normalize(p);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(hls::normalize(v[size_t(a)] + v[size_t(b)]));
      return mid[key] = int(v.size() - 1);
    };
    std::vector<std::array<int, 3>> nf;
    for (const auto& x : f) {
      const int a = midpoint(x[0], x[1]), b = midpoint(x[1], x[2]), cc = midpoint(x[2], x[0]);
      nf.push_back({x[0], a, cc});
      nf.push_back({x[1], b, a});
      nf.push_back({x[2], cc, b});
      nf.push_back({a, b, cc});
    }
    f = nf;
  }
  std::vector<Tri> out;
  for (const auto& x : f) out.push_back({c + v[size_t(x[0])] * r, c + v[size_t(x[1])] * r, c + v[size_t(x[2])] * r});
  return out;
}

scenes::Camera camera_basis(Vec3 pos, Vec3 fwd, Vec3 up, double yfov, double aspect) {
  scenes::Camera c;
  c.present = true;
  c.position = pos;
  c.forward = hls::normalize(fwd);
  c.right = hls::normalize(hls::cross(c.forward, up));
  c.up = hls::cross(c.right, c.forward);
  c.yfov = yfov;
  c.aspect = aspect;
  return c;
}

scenes::Camera look_at(Vec3 pos, Vec3 target, double yfov, double aspect) {
  return camera_basis(pos, target - pos, Vec3{0, 1, 0}, yfov, aspect);
}

struct ClosedMesh {
  std::string name;
  std::vector<Tri> tris;
  std::vector<Vec3> inside;  // camera positions strictly inside
};

std::vector<ClosedMesh> closed_meshes() {
  std::vector<ClosedMesh> m;
  {
    ClosedMesh c{"cube", grid_box(Vec3{3.7, -1.3, 250.5}, Vec3{5.9, 0.45, 253.1}, 1, 0, 1), {}};
    c.inside = {Vec3{4.8, -0.4, 251.8}, Vec3{3.71, -1.29, 250.51}, Vec3{5.89, 0.44, 253.09}};
    m.push_back(c);
  }
  {
    ClosedMesh c{"icosphere", icosphere(Vec3{123.4, -56.7, 89.1}, 7.3, 3), {}};
    c.inside = {Vec3{123.4, -56.7, 89.1}, Vec3{129.0, -54.0, 91.0}, Vec3{118.0, -59.0, 87.0}};
    m.push_back(c);
  }
  {
    ClosedMesh c{"room", grid_box(Vec3{-20.3, 0.1, -12.7}, Vec3{19.9, 10.2, 12.4}, 8, 0.4, 2), {}};
    c.inside = {Vec3{0.3, 5.1, 0.2}, Vec3{-19.0, 1.0, 11.0}, Vec3{17.5, 9.0, -11.5}};
    m.push_back(c);
  }
  return m;
}

struct Escape {
  uint64_t rays = 0, escaped = 0;
};

// All directions: six 90-degree views of a random orthonormal basis per camera position.
Escape escapes(const ClosedMesh& mesh, const sim::TraceConfig& base, uint64_t seed) {
  const hls::Image img = hls::build_image(mesh.tris, base.format, base.rounding);
  Rng rng(seed);
  Escape e;
  scenes::Light light;
  light.present = true;
  for (const Vec3& pos : mesh.inside) {
    light.position = pos;
    const Vec3 a = rng.sphere();
    const Vec3 b = hls::normalize(hls::cross(a, rng.sphere()));
    const Vec3 c = hls::cross(a, b);
    const Vec3 dirs[6] = {a, a * -1.0, b, b * -1.0, c, c * -1.0};
    const Vec3 ups[6] = {b, b, c, c, a, a};
    for (int i = 0; i < 6; ++i) {
      const scenes::Camera cam = camera_basis(pos, dirs[i], ups[i], M_PI / 2, 1.0);
      const sim::Frame fr = sim::trace_golden(img, cam, light, base);
      for (const auto& p : fr.px) {
        ++e.rays;
        if (p.tri < 0) ++e.escaped;
      }
    }
  }
  return e;
}

TEST(Watertight, EscapeRatePerConfiguration) {
  const auto meshes = closed_meshes();
  std::printf("watertight: escaped rays (of rays) from inside closed meshes, 6 x 40x40 per camera\n");
  std::vector<double> pcts;
  std::printf("watertight %-10s %-5s", "config", "vtu");
  for (const auto& m : meshes) std::printf(" %22s", m.name.c_str());
  std::printf("\n");
  for (FormatId f : {FormatId::fp24, FormatId::fp32})
    for (Rounding r : {Rounding::rtz, Rounding::rne})
      for (bool vtu : {false, true}) {
        sim::TraceConfig cfg;
        cfg.format = f;
        cfg.rounding = r;
        cfg.vtu = vtu;
        cfg.width = cfg.height = 40;
        cfg.threads = 0;
        std::printf("watertight %-10s %-5s", fmt_name(f, r).c_str(), vtu ? "on" : "off");
        for (const auto& m : meshes) {
          const Escape e = escapes(m, cfg, 77);
          const double pct = 100.0 * double(e.escaped) / double(e.rays);
          std::printf(" %6llu/%7llu %6.3f%%", (unsigned long long)e.escaped, (unsigned long long)e.rays, pct);
          pcts.push_back(pct);
        }
        std::printf("\n");
        std::fflush(stdout);
        // Bounds from measurements with these seeds (docs/robustness.md), about 1.3x the worst
        // seen: Wald's test is not watertight (adjacent triangles' rounded edge constants
        // disagree); the cube has a camera 0.01 (5 FP24 ulps) from a corner, where most rays
        // cross edges close to the origin.
        for (size_t i = 0; i < meshes.size(); ++i)
          EXPECT_LE(pcts[i], f == FormatId::fp32 ? 0.02 : i == 0 ? 1.6 : 0.2)
              << meshes[i].name << " " << fmt_name(f, r) << " vtu " << vtu;
        pcts.clear();
      }
  std::fflush(stdout);
}

// The watertightness margins (--bary-margin, --trv-widen; hls/margins.h) on the same closed meshes:
// a margin only adds hits, so no mesh escapes more rays with it; printed per margin (docs/robustness.md).
TEST(Watertight, MarginsOnlyCloseCracks) {
  const auto meshes = closed_meshes();
  struct M {
    double eps;
    int32_t widen;
  };
  for (Rounding r : {Rounding::rtz, Rounding::rne}) {
    sim::TraceConfig cfg;
    cfg.format = FormatId::fp24;
    cfg.rounding = r;
    cfg.width = cfg.height = 40;
    cfg.threads = 0;
    std::vector<uint64_t> base;
    for (const M& m : {M{0, 0}, M{0, 4}, M{std::ldexp(1.0, -14), 0}, M{std::ldexp(1.0, -12), 2},
                       M{0.008, 2}}) {
      cfg.bary_margin = m.eps;
      cfg.trv_widen = m.widen;
      std::printf("watertight-margins %-10s E %-9g N %d", fmt_name(FormatId::fp24, r).c_str(), m.eps,
                  m.widen);
      for (size_t i = 0; i < meshes.size(); ++i) {
        const Escape e = escapes(meshes[i], cfg, 77);
        std::printf(" %s %llu/%llu", meshes[i].name.c_str(), (unsigned long long)e.escaped,
                    (unsigned long long)e.rays);
        if (base.size() < meshes.size())
          base.push_back(e.escaped);
        else
          EXPECT_LE(e.escaped, base[i]) << meshes[i].name << " E " << m.eps << " N " << m.widen;
      }
      std::printf("\n");
      std::fflush(stdout);
    }
  }
}

// ---- far-offset invariance ---------------------------------------------------------------------

// A small scene (ground grid, icosphere, box, a thin leaning plate), camera, light; all translated
// by `off`.
scenes::Scene small_scene(Vec3 off) {
  scenes::Scene s;
  s.name = "small";
  s.source = "generated";
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) {
      const double x0 = -10 + 2.5 * i, z0 = -10 + 2.5 * j;
      add_quad(s.tris, Vec3{x0, 0, z0}, Vec3{x0, 0, z0 + 2.5}, Vec3{x0 + 2.5, 0, z0 + 2.5}, Vec3{x0 + 2.5, 0, z0});
    }
  for (const Tri& t : icosphere(Vec3{-2.5, 3.1, -1.0}, 3.0, 2)) s.tris.push_back(t);
  for (const Tri& t : grid_box(Vec3{3.0, 0.0, -4.0}, Vec3{5.5, 4.5, -1.5}, 2, 0, 3)) s.tris.push_back(t);
  add_quad(s.tris, Vec3{-8, 0, 4}, Vec3{-3, 0, 6}, Vec3{-3, 5, 5.2}, Vec3{-8, 5, 3.2});
  for (Tri& t : s.tris)
    for (Vec3& v : t) v = v + off;
  s.camera = look_at(Vec3{1.5, 7.0, 17.0} + off, Vec3{0, 1.5, 0} + off, 0.8726646259971648, 800.0 / 480.0);
  s.light.present = true;
  s.light.position = Vec3{8.0, 18.0, 9.0} + off;
  return s;
}

struct Errors {
  ref::ErrorMetrics m;
  uint64_t total() const { return m.self_intersections + m.shadow_errors + m.primary_errors; }
};

Errors frame_errors(const scenes::Scene& s, const sim::TraceConfig& cfg, const sim::Frame& reference) {
  const hls::Image img = hls::build_image(s.tris, cfg.format, cfg.rounding);
  const sim::Frame fr = sim::trace_golden(img, s.camera, s.light, cfg);
  return {ref::compute_errors(fr, reference, s.tris)};
}

constexpr int kFarW = 160, kFarH = 96;

// One far-offset curve point: total (vs the scene) and arithmetic (vs the stored scene) errors.
struct FarPoint {
  Errors total, arith;
};

// The scene stored as `store` says (world: as given; anchored: relative to its box centre, the
// camera and light registers relative to it), traced VTU off and on; both judged against the
// scene's reference and against the stored scene's.
std::array<FarPoint, 2> far_points(const scenes::Scene& s, FormatId f, Rounding r, bool anchored,
                                   const sim::Frame& reference) {
  sim::TraceConfig cfg;
  cfg.format = f;
  cfg.rounding = r;
  cfg.width = kFarW;
  cfg.height = kFarH;
  cfg.anchored = anchored;
  cfg.anchor = anchored ? hls::store_anchor(s.tris) : Vec3{};
  const hls::Image img = hls::build_image(anchored ? hls::relative_to(s.tris, cfg.anchor) : s.tris, f, r);
  const scenes::Scene st = sim::stored_scene(s, img, cfg.anchor);
  const sim::Frame ref_st = ref::render(st, kFarW, kFarH, 0);
  std::array<FarPoint, 2> p;
  for (bool vtu : {false, true}) {
    cfg.vtu = vtu;
    const sim::Frame fr = sim::trace_golden(img, s.camera, s.light, cfg);
    p[vtu] = {{ref::compute_errors(fr, reference, s.tris)}, {ref::compute_errors(fr, ref_st, st.tris)}};
  }
  return p;
}

TEST(FarOffset, VtuKeepsErrorFlat) {
  std::printf("far_offset: # small scene (%d x %d) translated by 10^k (1,1,1); errors = self + shadow + primary,\n"
              "far_offset: # total (vs the scene) and arithmetic (vs the stored scene)\n",
              kFarW, kFarH);
  std::printf("far_offset: # k config vtu store self shadow primary total a_self a_shadow a_primary a_total\n");
  for (FormatId f : {FormatId::fp24, FormatId::fp32})
    for (Rounding r : {Rounding::rtz, Rounding::rne}) {
      // [store][vtu][k]: total and arithmetic
      uint64_t tot[2][2][7] = {}, ar[2][2][7] = {};
      for (int k = 0; k <= 6; ++k) {
        const double d = std::pow(10.0, k);
        const scenes::Scene s = small_scene(Vec3{d, d, d});
        ASSERT_LE(s.bounds().hi.x, sim::max_coordinate(f));
        ASSERT_LE(s.light.position.y, sim::max_coordinate(f));
        const sim::Frame reference = ref::render(s, kFarW, kFarH, 0);
        for (int anchored = 0; anchored < 2; ++anchored) {
          const auto p = far_points(s, f, r, anchored, reference);
          for (int vtu = 0; vtu < 2; ++vtu) {
            const FarPoint& e = p[size_t(vtu)];
            tot[anchored][vtu][k] = e.total.total();
            ar[anchored][vtu][k] = e.arith.total();
            std::printf("far_offset: %d %s %s %s %llu %llu %llu %llu %llu %llu %llu %llu\n", k, fmt_name(f, r).c_str(),
                        vtu ? "on" : "off", anchored ? "anchored" : "world",
                        (unsigned long long)e.total.m.self_intersections, (unsigned long long)e.total.m.shadow_errors,
                        (unsigned long long)e.total.m.primary_errors, (unsigned long long)e.total.total(),
                        (unsigned long long)e.arith.m.self_intersections, (unsigned long long)e.arith.m.shadow_errors,
                        (unsigned long long)e.arith.m.primary_errors, (unsigned long long)e.arith.total());
          }
        }
      }
      std::fflush(stdout);
      const uint64_t(&on)[7] = tot[0][1];
      const uint64_t(&off)[7] = tot[0][0];
      // The VTU keeps the error flat only while the image's own constants (rounded at the
      // scene's magnitude before the VTU translates them) resolve the scene: FP24 up to 10^3,
      // FP32 up to 10^4 for this 20-unit scene (docs/robustness.md). rtz only for the "off is
      // worse" claim: with rne, spawn none self-intersects at every offset, VTU or not.
      const std::string cfg = fmt_name(f, r);
      const int kmax = f == FormatId::fp24 ? 3 : 4;
      for (int k = 1; k <= kmax; ++k) EXPECT_LE(on[k], 3 * on[0] + 20) << cfg << " k=" << k;
      if (r == Rounding::rtz) {
        EXPECT_GT(off[kmax], 5 * on[kmax] + 50) << cfg << " k=" << kmax;
      }
      // Beyond: both degrade (FP24 k = 6: thousands of primary errors of 15360 pixels).
      EXPECT_GT(on[6], on[0]) << cfg;
      // Store anchored: the image holds the scene relative to its box centre, the registers the
      // camera and light relative to it, so every k stores the same numbers: errors flat to k = 6,
      // VTU on or off (measured: equal for k >= 1, within 2 of k = 0), and no storage error
      // (total = arithmetic within 1).
      for (int vtu = 0; vtu < 2; ++vtu)
        for (int k = 0; k <= 6; ++k) {
          const int64_t t = int64_t(tot[1][vtu][k]);
          EXPECT_LE(std::llabs(t - int64_t(tot[1][vtu][0])), 10) << cfg << " anchored vtu " << vtu << " k=" << k;
          EXPECT_LE(std::llabs(t - int64_t(ar[1][vtu][k])), 5) << cfg << " anchored vtu " << vtu << " k=" << k;
        }
      // World, VTU on, at k = 6 anchored is far better, and most of world's error is storage in
      // FP24 (the vertices rounded at 10^6: ulp 8 in FP24; measured rtz 8796 total, 1126 arithmetic).
      EXPECT_LT(tot[1][1][6], tot[0][1][6]) << cfg;
      if (f == FormatId::fp24) {
        EXPECT_GT(tot[0][1][6], ar[0][1][6] + 1000) << cfg;
      }
      // The arithmetic error of world VTU on is flat as far as the total is (<= k = 3 / 4) and grows
      // beyond it too (the VTU translates constants of magnitude 10^k: FP24 rtz 634 at k = 4).
      for (int k = 1; k <= kmax; ++k) EXPECT_LE(ar[0][1][k], 3 * ar[0][1][0] + 20) << cfg << " k=" << k;
    }
}

// The same scene with the strategies that beat skip-origin on the paper's scenes (docs/robustness.md):
// fp24 rtz skip-slab 2 and fp24 rne skip-back 1: no self-intersection at any k, VTU on or off;
// errors flat to k = 2, then the primary errors of the image's constants (rounded at 10^k before
// the VTU) take over; VTU off is no longer worse than on.
TEST(FarOffset, NewStrategies) {
  struct Cfg {
    Rounding r;
    Spawn s;
    int32_t ulps;
  };
  std::printf("far_offset_new: # k config spawn vtu self shadow primary total\n");
  for (const Cfg& c : {Cfg{Rounding::rtz, Spawn::skip_slab, 2}, Cfg{Rounding::rne, Spawn::skip_back, 1}}) {
    uint64_t on[7] = {}, off[7] = {};
    const std::string name = fmt_name(FormatId::fp24, c.r) + " " + spawn_name(c.s) + " " + std::to_string(c.ulps);
    for (int k = 0; k <= 6; ++k) {
      const double d = std::pow(10.0, k);
      const scenes::Scene s = small_scene(Vec3{d, d, d});
      const sim::Frame reference = ref::render(s, kFarW, kFarH, 0);
      for (bool vtu : {false, true}) {
        sim::TraceConfig cfg;
        cfg.rounding = c.r;
        cfg.vtu = vtu;
        cfg.spawn = spawn(c.s, c.ulps);
        cfg.width = kFarW;
        cfg.height = kFarH;
        const Errors e = frame_errors(s, cfg, reference);
        (vtu ? on : off)[k] = e.total();
        std::printf("far_offset_new: %d %s %s %llu %llu %llu %llu\n", k, name.c_str(), vtu ? "on" : "off",
                    (unsigned long long)e.m.self_intersections, (unsigned long long)e.m.shadow_errors,
                    (unsigned long long)e.m.primary_errors, (unsigned long long)e.total());
        EXPECT_EQ(e.m.self_intersections, 0u) << name << " k=" << k << " vtu " << vtu;
      }
    }
    std::fflush(stdout);
    // Flat to k = 2; at k = 3 the primary errors of the constants rounded at 10^3 start (about 30).
    for (int k = 1; k <= 2; ++k) EXPECT_LE(on[k], on[0] + 10) << name << " k=" << k;
    EXPECT_LE(on[3], 60u) << name;
    // The VTU's gain was the self-intersections: with these strategies VTU off is no worse than on
    // (measured: off <= on + 15 up to k = 4).
    for (int k = 0; k <= 4; ++k) EXPECT_LE(off[k], 2 * on[k] + 20) << name << " k=" << k;
    EXPECT_GT(on[6], on[0]) << name;
  }
}

// ---- the paper's two limitations ---------------------------------------------------------------

TEST(Limitations, CameraAtOriginVtuGainsNothing) {
  std::printf("limitation_a: # camera at / near the origin: VTU off vs on, %d x %d\n", kFarW, kFarH);
  for (Vec3 cam_at : {Vec3{0, 0, 0}, Vec3{0.37, 0.21, -0.13}}) {
    scenes::Scene s = small_scene(Vec3{0, 0, 0});
    const Vec3 shift = cam_at - s.camera.position;  // move everything so the camera sits at cam_at
    for (Tri& t : s.tris)
      for (Vec3& v : t) v = v + shift;
    s.camera.position = cam_at;
    s.light.position = s.light.position + shift;
    const sim::Frame reference = ref::render(s, kFarW, kFarH, 0);
    for (Rounding r : {Rounding::rtz, Rounding::rne}) {
      sim::TraceConfig cfg;
      cfg.rounding = r;
      cfg.width = kFarW;
      cfg.height = kFarH;
      Errors e[2];
      for (int vtu = 0; vtu < 2; ++vtu) {
        cfg.vtu = vtu != 0;
        e[vtu] = frame_errors(s, cfg, reference);
        std::printf("limitation_a: camera (%g,%g,%g) fp24-%s vtu %s: self %llu shadow %llu primary %llu\n",
                    cam_at.x, cam_at.y, cam_at.z, hls::rounding_name(r), vtu ? "on" : "off",
                    (unsigned long long)e[vtu].m.self_intersections, (unsigned long long)e[vtu].m.shadow_errors,
                    (unsigned long long)e[vtu].m.primary_errors);
      }
      if (cam_at.x == 0 && cam_at.y == 0 && cam_at.z == 0) {
        // Translation by an exact zero is the identity: the same frame.
        EXPECT_EQ(e[0].m.self_intersections, e[1].m.self_intersections);
        EXPECT_EQ(e[0].m.shadow_errors, e[1].m.shadow_errors);
        EXPECT_EQ(e[0].m.primary_errors, e[1].m.primary_errors);
      } else {
        // No real gain (here rtz even gets worse with the VTU: its translated plane constants
        // are truncated once more).
        EXPECT_GE(2 * e[1].total() + 10, e[0].total()) << "VTU gains nothing near the origin";
      }
    }
  }
  std::fflush(stdout);
}

TEST(Limitations, OriginObjectsFarCameraVtuGainsLittle) {
  const scenes::Scene s = scenes::generate("origin-far-camera");
  const int w = 200, h = 120;
  const sim::Frame reference = ref::render(s, w, h, 0);
  for (Rounding r : {Rounding::rtz, Rounding::rne}) {
    sim::TraceConfig cfg;
    cfg.rounding = r;
    cfg.width = w;
    cfg.height = h;
    Errors e[2];
    for (int vtu = 0; vtu < 2; ++vtu) {
      cfg.vtu = vtu != 0;
      e[vtu] = frame_errors(s, cfg, reference);
      std::printf("limitation_b: origin-far-camera %dx%d fp24-%s vtu %s: self %llu shadow %llu primary %llu total %llu\n",
                  w, h, hls::rounding_name(r), vtu ? "on" : "off", (unsigned long long)e[vtu].m.self_intersections,
                  (unsigned long long)e[vtu].m.shadow_errors, (unsigned long long)e[vtu].m.primary_errors,
                  (unsigned long long)e[vtu].total());
    }
    // Little gain or worse: VTU on removes at most half of VTU off's errors.
    EXPECT_GE(2 * e[1].total() + 10, e[0].total()) << hls::rounding_name(r);
  }
  std::fflush(stdout);
}

// Both limitations with the new strategies: (a) camera at the origin: VTU on = off, frame for
// frame; (b) origin-far-camera: the VTU still removes at most half the errors.
TEST(Limitations, NewStrategies) {
  scenes::Scene a = small_scene(Vec3{0, 0, 0});
  const Vec3 shift = Vec3{0, 0, 0} - a.camera.position;
  for (Tri& t : a.tris)
    for (Vec3& v : t) v = v + shift;
  a.camera.position = Vec3{0, 0, 0};
  a.light.position = a.light.position + shift;
  const scenes::Scene b = scenes::generate("origin-far-camera");
  const sim::Frame ref_b = ref::render(b, 200, 120, 0);
  for (auto [r, sp] : {std::pair<Rounding, hls::SpawnParams>{Rounding::rtz, spawn(Spawn::skip_slab, 2)},
                       std::pair<Rounding, hls::SpawnParams>{Rounding::rne, spawn(Spawn::skip_back, 1)}}) {
    sim::TraceConfig cfg;
    cfg.rounding = r;
    cfg.spawn = sp;
    cfg.width = kFarW;
    cfg.height = kFarH;
    const hls::Image img = hls::build_image(a.tris, cfg.format, cfg.rounding);
    cfg.vtu = false;
    const sim::Frame off = sim::trace_golden(img, a.camera, a.light, cfg);
    cfg.vtu = true;
    const sim::Frame on = sim::trace_golden(img, a.camera, a.light, cfg);
    int differ = 0;
    for (size_t i = 0; i < on.px.size(); ++i)
      differ += on.px[i].tri != off.px[i].tri || on.px[i].t_bits != off.px[i].t_bits ||
                on.px[i].lit != off.px[i].lit || on.px[i].shadow_ray != off.px[i].shadow_ray;
    EXPECT_EQ(differ, 0) << hls::rounding_name(r) << " " << spawn_name(sp.spawn);
    cfg.width = 200;
    cfg.height = 120;
    Errors e[2];
    for (int vtu = 0; vtu < 2; ++vtu) {
      cfg.vtu = vtu != 0;
      e[vtu] = frame_errors(b, cfg, ref_b);
      std::printf("limitation_new: origin-far-camera fp24-%s %s vtu %s: self %llu shadow %llu primary %llu total %llu\n",
                  hls::rounding_name(r), spawn_name(sp.spawn).c_str(), vtu ? "on" : "off",
                  (unsigned long long)e[vtu].m.self_intersections, (unsigned long long)e[vtu].m.shadow_errors,
                  (unsigned long long)e[vtu].m.primary_errors, (unsigned long long)e[vtu].total());
    }
    EXPECT_GE(2 * e[1].total() + 10, e[0].total()) << hls::rounding_name(r);
  }
  std::fflush(stdout);
}

// ---- literal regressions (bit patterns printed by the ReIntersection tables) -----------------

struct LiteralCase {
  uint32_t k, c[9], o[3], d[3], light[3];
};

// Primary ray -> hit -> shadow ray with `sp`, traced against the triangle alone: re-hit?
template <class A>
bool literal_rehit(const LiteralCase& lc, const hls::SpawnParams& sp) {
  hls::Ray pr;
  for (int i = 0; i < 3; ++i) {
    pr.o[i] = lc.o[i];
    pr.d[i] = lc.d[i];
    pr.inv[i] = A::rcp(pr.d[i]);
  }
  const uint32_t tmin = A::from_double(1.0 / 4096);
  pr.tmin = tmin;
  pr.tmax = A::Fmt::max_mag;
  const hls::IstOut h = hls::ist_wald<A>(lc.k, lc.c, pr.o, pr.d, pr.tmin, pr.tmax);
  EXPECT_EQ(h.exit, hls::IstExit::hit);
  const hls::HitTri ht{7, lc.k, lc.c[hls::kNU], lc.c[hls::kNV], lc.c[hls::kND], h.den};
  const hls::ShadowSetup ss = hls::hit_shadow<A>(pr, h.t, ht, lc.light, tmin, sp);
  EXPECT_TRUE(ss.front);
  return hls::ist_wald<A>(lc.k, lc.c, ss.ray.o, ss.ray.d, ss.ray.tmin, ss.ray.tmax).exit == hls::IstExit::hit;
}

// FP24 rne, magnitude 1: the default 2-ulp offset (Waechter & Binder's 256 FP32 ulps scaled) is
// not enough for a hit point 3 ulps off its plane; error_bound is.
TEST(Regression, Fp24RneUlpOffsetTwoUlpsReHits) {
  using A = hls::Arith<hls::FP24, Rounding::rne>;
  const LiteralCase lc{2,
                       {0x3d6128, 0xbcc59e, 0x3b3629, 0xbf03e6, 0xbfd1fd, 0xbd8a8c, 0x3dea5f, 0xbde72b, 0x3d6b9a},
                       {0xbef39c, 0xbe35de, 0x3f8be8},
                       {0x3dc689, 0x3c8908, 0xbec027},
                       {0x3e41f7, 0x3dc4fe, 0xba43a5}};
  EXPECT_TRUE(literal_rehit<A>(lc, spawn(Spawn::none, 0)));
  EXPECT_TRUE(literal_rehit<A>(lc, spawn(Spawn::ulp_offset, 2)));
  EXPECT_FALSE(literal_rehit<A>(lc, spawn(Spawn::error_bound, 0)));
}

// FP32 rne, magnitude 10^6 (a triangle with tiny n_u, n_v): WB's 256 FP32 ulps re-hit; the error
// bound does not.
TEST(Regression, Fp32RneUlpOffset256ReHitsFar) {
  using A = hls::Arith<hls::FP32, Rounding::rne>;
  const LiteralCase lc{1,
                       {0xbd8b20a6, 0xbd1227b7, 0xc707941d, 0xb5330360, 0xb4de6f80, 0x3eedbc2e, 0xb56722e4,
                        0x35ed7368, 0x3ebdee35},
                       {0xc90d5d2f, 0xc9cf654b, 0x49317f13},
                       {0x3ee264ba, 0x3f5ee85b, 0xbe5c5a0d},
                       {0xc726517d, 0xc6f7c199, 0x4823f5c7}};
  EXPECT_TRUE(literal_rehit<A>(lc, spawn(Spawn::ulp_offset, 256)));
  EXPECT_FALSE(literal_rehit<A>(lc, spawn(Spawn::error_bound, 0)));
}

// Literal cases from 800x480 frames (VTU on: the primary ray starts at 0; bit patterns printed by
// `robust_pixels SCENE --vtu on ... --pixel X Y`): primary ray -> hit on `tri` -> shadow ray with
// a strategy -> traced against `occ` (a neighbour) alone. Returns whether occ is hit.
struct FrameCase {
  uint32_t tri_k, tri[9], occ_k, occ[9], d[3], light[3];
};

template <class A>
bool frame_case_occluded(const FrameCase& fc, const hls::SpawnParams& sp) {
  hls::Ray pr;
  for (int i = 0; i < 3; ++i) {
    pr.o[i] = A::zero;
    pr.d[i] = fc.d[i];
    pr.inv[i] = A::rcp(pr.d[i]);
  }
  const uint32_t tmin = A::from_double(1.0 / 4096);
  pr.tmin = tmin;
  pr.tmax = A::Fmt::max_mag;
  const hls::IstOut h = hls::ist_wald<A>(fc.tri_k, fc.tri, pr.o, pr.d, pr.tmin, pr.tmax);
  EXPECT_EQ(h.exit, hls::IstExit::hit);
  const hls::HitTri ht{1, fc.tri_k, fc.tri[hls::kNU], fc.tri[hls::kNV], fc.tri[hls::kND], h.den};
  const hls::ShadowSetup ss = hls::hit_shadow<A>(pr, h.t, ht, fc.light, tmin, sp);
  EXPECT_TRUE(ss.front);
  return hls::ist_wald<A>(fc.occ_k, fc.occ, ss.ray.o, ss.ray.d, ss.ray.tmin, ss.ray.tmax).exit == hls::IstExit::hit;
}

// sponza-paper fp24 rtz, pixel (288, 147): the hit point lies behind the plane of a neighbour
// (sharing an edge, 7e-5 out of plane) and the shadow ray crosses it 0.016 from the hit point:
// a false shadow with skip-origin (and none); skip-slab 2 clears it.
TEST(Regression, SponzaRtzNeighbourFalseShadowSkipSlabClears) {
  using A = hls::Arith<hls::FP24, Rounding::rtz>;
  const FrameCase fc{0, {0x3df8fa, 0xbe49d0, 0x4a103f, 0xbab9ab, 0xbd5b10, 0xc5f072, 0x3ab9ab, 0xb8876a, 0xc2c11c},
                     0, {0x3df8fb, 0xbe49cc, 0x4a103e, 0x3ab51c, 0x3d577b, 0x45eb52, 0xbab51c, 0x38fa15, 0x43050f},
                     {0x3ef287, 0x3b7864, 0xbcab14}, {0x4928ec, 0x482bcf, 0xc62b25}};
  EXPECT_TRUE(frame_case_occluded<A>(fc, spawn(Spawn::none, 0)));
  EXPECT_TRUE(frame_case_occluded<A>(fc, spawn(Spawn::skip_origin, 0)));
  EXPECT_FALSE(frame_case_occluded<A>(fc, spawn(Spawn::skip_slab, 2)));
}

// corridor fp24 rne, pixel (492, 136): light grazing the floor (cos 0.005), a neighbour sharing a
// vertex crossed 1.94 along the shadow ray from a hit point rounded below the floor: a false
// shadow with skip-origin and skip-slab 4 (the |dens| floor of 1/16 caps its t_min); skip-back 1
// (hit point backed off 1 ulp of t toward the camera) clears it.
TEST(Regression, CorridorRneGrazingNeighbourSkipBackClears) {
  using A = hls::Arith<hls::FP24, Rounding::rne>;
  const FrameCase fc{0, {0, 0xbd36a1, 0xc812d2, 0x3716e0, 0xbda3e5, 0xc4385c, 0x800000, 0x3da3e5, 0x443cc6},
                     0, {0, 0xbb936a, 0xc81c75, 0x3716e0, 0xbd93c2, 0xc4247e, 0x800000, 0x3d93c2, 0x4428e8},
                     {0xbef1c4, 0x3c5c26, 0xbc49d5}, {0xc80e78, 0x44d2f4, 0x43a690}};
  EXPECT_TRUE(frame_case_occluded<A>(fc, spawn(Spawn::skip_origin, 0)));
  EXPECT_TRUE(frame_case_occluded<A>(fc, spawn(Spawn::skip_slab, 4)));
  EXPECT_FALSE(frame_case_occluded<A>(fc, spawn(Spawn::skip_back, 1)));
}

// sponza-paper fp24 rne, pixel (266, 130): the slab's price. Light at cos 0.043 to the floor, a
// neighbour (sharing a vertex) really in the way 1.28 along the ray (the reference: shadowed);
// skip-slab 4's t_min (2 x 4 ulps / max(|dens|, 1/16)) passes it: a light leak; skip-origin and
// skip-slab 1 see the occluder.
TEST(Regression, SponzaRneSkipSlabFourLeaksNearOccluder) {
  using A = hls::Arith<hls::FP24, Rounding::rne>;
  const FrameCase fc{0, {0x3ec102, 0, 0x49b50a, 0xbb4fe1, 0x38f07c, 0x43674e, 0x800000, 0xb8f07c, 0xc1858c},
                     1, {0, 0x3ec103, 0x498acc, 0x38f07c, 0x3b4fe1, 0xc5e7a4, 0xb8f07c, 0, 0xc1858c},
                     {0x3eec59, 0x3bf288, 0xbcf7a2}, {0x4928ec, 0x482bcf, 0xc62b25}};
  EXPECT_TRUE(frame_case_occluded<A>(fc, spawn(Spawn::skip_origin, 0)));
  EXPECT_TRUE(frame_case_occluded<A>(fc, spawn(Spawn::skip_slab, 1)));
  EXPECT_FALSE(frame_case_occluded<A>(fc, spawn(Spawn::skip_slab, 4)));
}

// Known limitation (not fixed: Wald's test is not watertight): a ray exactly through the edge
// where two faces of a cube meet, from a camera 0.01 from both faces, escapes in FP32 rne while
// the watertight reference hits. Pinned so a change in the ist shows up here.
TEST(Regression, Fp32CubeEdgeEscapes) {
  const auto m = closed_meshes()[0];
  sim::TraceConfig cfg;
  cfg.format = FormatId::fp32;
  cfg.rounding = Rounding::rne;
  cfg.width = cfg.height = 40;
  const hls::Image img = hls::build_image(m.tris, cfg.format, cfg.rounding);
  scenes::Scene s;
  s.tris = m.tris;
  s.light.present = true;
  s.light.position = Vec3{5.89, 0.44, 253.09};
  s.camera = camera_basis(s.light.position, Vec3{0, 0, -1}, Vec3{0, 1, 0}, M_PI / 2, 1.0);
  const sim::Frame fr = sim::trace_golden(img, s.camera, s.light, cfg);
  const sim::Frame rf = ref::render(s, 40, 40, 1);
  int escaped = 0, diagonal = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) {
      EXPECT_GE(rf.at(x, y).tri, 0);
      if (fr.at(x, y).tri < 0) {
        ++escaped;
        diagonal += x + y == 39;  // the pixels whose ray has d_x == d_y: exactly through the edge
      }
    }
  std::printf("regression: cube edge fp32-rne: %d escaped of 1600, %d on the diagonal\n", escaped, diagonal);
  EXPECT_EQ(escaped, 20);
  EXPECT_EQ(diagonal, 20);
}

}  // namespace
