// hls/hit.h - the hit unit's datapath: the hit point, the light test, and the shadow ray with the
// configured spawn strategy.
#pragma once

#include <cstdint>

#include "hls/fp.h"
#include "hls/ist.h"
#include "hls/ray.h"

namespace raycore::hls {

// How a shadow ray leaves its hit point (the issue's --spawn):
//   none         t_min only (the paper's baseline)
//   skip_origin  t_min, and the origin triangle is skipped by its id (RayCore's emulator)
//   ulp_offset   origin moved along the normal by an integer number of ulps of each coordinate
//                (Waechter & Binder 2019, adapted to the format; fixed offset near zero)
//   error_bound  origin moved along the normal just past a conservative bound of the hit point's
//                distance from the plane, derived from the operations and the rounding mode used
//   skip_offset  skip_origin and ulp_offset together (the own triangle by id; neighbours and
//                coplanar triangles by the small offset)
//   skip_slab    skip_origin, and t_min raised so the ray starts `ulps` ulps of the hit point's
//                largest coordinate above the plane (detail::slab_tmin): occluders crossed within
//                that slab (the neighbours and coplanar triangles the rounded hit point lies
//                behind) are not hit; the origin stays where it is
//   skip_back    skip_slab with a slab of kBackSlabUlps, and the hit point computed at t backed
//                off by `ulps` ulps of t (on the bit pattern): a point on the primary ray just
//                before the surface, on the side the ray came from (the light's side whenever a
//                shadow ray is spawned), in front of the neighbours the camera sees around it.
//                Meant for rne, whose hit points lie on either side of the plane.
enum class Spawn : uint8_t { none, skip_origin, ulp_offset, error_bound, skip_offset, skip_slab, skip_back };

struct SpawnParams {
  Spawn spawn = Spawn::none;
  int32_t ulps = 0;  // ulp_offset, skip_offset: offset in ulps of the format for a unit normal
                     // component; skip_slab: slab height in ulps of max |h_i|; skip_back: back-off
                     // in ulps of t
  bool segment = false;  // shadow ray as the segment h + t (light - h), t < 1; else unit direction
  // Traversal of the shadow ray: any-hit (true) ends it after the first leaf with a hit (the
  // occluder reported is that leaf's closest; lit/shadowed is the same as closest-hit's), as
  // ray-tracing hardware does; closest-hit (false) walks on to the nearest occluder, which the
  // self-intersection metric needs.
  bool any_hit = false;
  // Which primary hits spawn a shadow ray (--shadow-spawn): front (false) only those whose light is
  // on the side the primary ray came from (the others are shadowed without a ray); all (true)
  // every primary hit, as the paper counts (384,000 shadow rays at 800 x 480). The pixel is lit
  // only if the light is in front and the ray reaches it, so the image is the same either way; the
  // extra rays cost cycles and can self-intersect (the paper's Table 3 counts them).
  bool spawn_all = false;
};

// What the hit unit needs of the winning triangle.
struct HitTri {
  uint32_t id;
  uint32_t k;
  uint32_t n_u, n_v, n_d;  // plane: x_k + n_u x_u + n_v x_v = n_d
  uint32_t den;            // n . d of the primary ray (from the ist)
};

struct ShadowSetup {
  uint32_t h[3];     // hit point
  bool front;        // the light is on the side the primary ray came from (else: shadowed)
  bool spawn;        // a shadow ray is spawned: front, or every hit with SpawnParams::spawn_all
  uint32_t dens;     // n . (direction to the light)
  Ray ray;           // the shadow ray (see SpawnParams::segment)
  uint32_t skip_id;  // triangle id the shadow ray skips (skip_origin), else ~0u
};

namespace detail {

// The plane normal (1 at k, n_u at u, n_v at v) as a per-axis array.
inline void plane_normal(const HitTri& tri, uint32_t one, uint32_t n[3]) {
  n[tri.k] = one;
  n[axis_u(tri.k)] = tri.n_u;
  n[axis_v(tri.k)] = tri.n_v;
}

// skip_slab's t_min: the shadow ray (direction d, dens = n . d) is at height t |dens| / |n| above
// the plane, |n| = |(1, n_u, n_v)| in [1, sqrt 3]; so t_min' = 2 slab / max(|dens|, 1/16), slab =
// ulps ulps of max_i |h_i|, clears a slab of at least that height (the neighbours and coplanar
// triangles the rounded hit point lies behind), for the unit direction and the segment alike.
// |dens| is floored at 1/16 (a grazing light would otherwise skip a long stretch of the ray:
// measured, that leaks light through real occluders). Hardware: a max of three exponents, a max, one
// reciprocal, two multiplies, a comparison (returns the larger of t_min and t_min').
// scale2 = 2 ulps as a number of the format (HitRegs::slab_scale, a per-frame register).
template <class A>
inline uint32_t slab_tmin_scaled(const uint32_t h[3], uint32_t dens, uint32_t scale2, uint32_t tmin) {
  using F = typename A::Fmt;
  const uint32_t hmax = A::max(A::max(A::abs(h[0]), A::abs(h[1])), A::abs(h[2]));
  const uint32_t slab = A::mul(scale2, ulp<F>(hmax));
  const uint32_t t0 = A::mul(slab, A::rcp(A::max(A::abs(dens), A::from_double(1.0 / 16))));
  return A::lt(tmin, t0) ? t0 : tmin;
}
template <class A>
inline uint32_t slab_tmin(const uint32_t h[3], uint32_t dens, int32_t ulps, uint32_t tmin) {
  return slab_tmin_scaled<A>(h, dens, A::from_double(2.0 * double(ulps)), tmin);
}

}  // namespace detail

// skip_back's slab (skip_slab's default): the back-off alone leaves the grazing-light neighbours.
constexpr int32_t kBackSlabUlps = 4;

// The unit roundoff of the rounding policy as a number of the format: 2^-M (rtz), 2^-(M+1) (rne),
// 2^(1-M) (raycore: not correctly rounded; the operations the bound below counts err by at most
// 1.5 * 2^-M times the magnitudes it charges: add3 1.5, rcp 1.19, add, mul below 1; hls/fp.h).
template <class A>
constexpr uint32_t unit_roundoff() {
  using F = typename A::Fmt;
  constexpr int e = (A::rounding == Rounding::rtz       ? -F::man_bits
                     : A::rounding == Rounding::raycore ? 1 - F::man_bits
                                                        : -F::man_bits - 1) +
                    F::bias;
  return uint32_t(e) << F::man_bits;
}

// The hit unit's per-frame registers that depend on the spawn parameters (computed once by the
// host, in the format; rtl/units/hit.v takes them as static inputs): the one definition of these
// constants, used by hit_shadow below.
struct HitRegs {
  uint32_t scale = 0;       // ulp_offset, skip_offset: ulps as a number
  uint32_t fixed = 0;       //   and ulps * ulp(2^-5) (the fixed offset near zero)
  uint32_t slab_scale = 0;  // skip_slab: 2 ulps; skip_back: 2 kBackSlabUlps (as numbers)
  int32_t back = 0;         // skip_back: the hit point's t moved by this many ulps (-ulps)
};
template <class A>
inline HitRegs hit_regs(const SpawnParams& sp) {
  using F = typename A::Fmt;
  HitRegs g;
  g.scale = A::from_double(double(sp.ulps));
  g.fixed = A::mul(g.scale, ulp<F>(uint32_t(F::bias - 5) << F::man_bits));  // ulp(2^-5)
  g.slab_scale = A::from_double(
      2.0 * double(sp.spawn == Spawn::skip_back ? kBackSlabUlps : sp.ulps));
  g.back = -sp.ulps;
  return g;
}

// The unit with its registers given (sp.ulps is not read: g holds what depends on it); the pin-level
// twin calls this with the register values on its pins.
template <class A>
inline ShadowSetup hit_shadow_regs(const Ray& pr, uint32_t t, const HitTri& tri,
                                   const uint32_t light[3], uint32_t tmin, const SpawnParams& sp,
                                   const HitRegs& g) {
  using F = typename A::Fmt;
  ShadowSetup s{};
  // Hit point (skip_back: at t - ulps ulps of t, on the bit pattern).
  const uint32_t th = sp.spawn == Spawn::skip_back ? add_ulps<F>(t, g.back) : t;
  for (int i = 0; i < 3; ++i) s.h[i] = A::add(pr.o[i], A::mul(th, pr.d[i]));
  // Direction to the light. unit (default): normalised, t in (tmin, distance to the light), so
  // t_min is in world units; segment: light - h unnormalised, t in (tmin, 1), so t_min is a
  // fraction of the distance to the light and no square root is needed.
  Ray& r = s.ray;
  uint32_t ld[3];
  for (int i = 0; i < 3; ++i) ld[i] = A::sub(light[i], s.h[i]);
  if (sp.segment) {
    for (int i = 0; i < 3; ++i) r.d[i] = ld[i];
    r.tmax = A::one;
  } else {
    const uint32_t len =
        A::sqrt(A::add3(A::mul(ld[0], ld[0]), A::mul(ld[1], ld[1]), A::mul(ld[2], ld[2])));
    const uint32_t rl = A::rcp(len);
    for (int i = 0; i < 3; ++i) r.d[i] = A::mul(ld[i], rl);
    r.tmax = len;
  }
  for (int i = 0; i < 3; ++i) r.inv[i] = A::rcp(r.d[i]);
  r.tmin = tmin;
  s.skip_id = ~0u;
  const int u = axis_u(tri.k), v = axis_v(tri.k);
  // Light in front: the shadow direction and the primary ray leave/arrive on opposite sides, i.e.
  // n . d_shadow and n . d_primary have opposite signs (the same operations as the ist's den, so the
  // shadow ray's own test sees the same sign).
  s.dens = A::add3(r.d[tri.k], A::mul(tri.n_u, r.d[u]), A::mul(tri.n_v, r.d[v]));
  s.front = !A::is_zero(s.dens) && !A::is_zero(tri.den) && A::sign(s.dens) != A::sign(tri.den);
  for (int i = 0; i < 3; ++i) r.o[i] = s.h[i];
  s.spawn = s.front || sp.spawn_all;
  if (!s.spawn) return s;

  uint32_t n[3];
  detail::plane_normal(tri, A::one, n);
  const bool side_neg = A::sign(s.dens);  // offset toward the light's side: along sign(dens) * n
  switch (sp.spawn) {
    case Spawn::none:
      break;
    case Spawn::skip_origin:
      s.skip_id = tri.id;
      break;
    case Spawn::skip_slab:
      s.skip_id = tri.id;
      r.tmin = detail::slab_tmin_scaled<A>(s.h, s.dens, g.slab_scale, r.tmin);
      break;
    case Spawn::skip_back:  // the back-off is in the hit point above; slab_scale = 2 kBackSlabUlps
      s.skip_id = tri.id;
      r.tmin = detail::slab_tmin_scaled<A>(s.h, s.dens, g.slab_scale, r.tmin);
      break;
    case Spawn::skip_offset:
      s.skip_id = tri.id;
      [[fallthrough]];
    case Spawn::ulp_offset: {
      // Waechter & Binder: of_i = int(ulps * n_i) ulps of p_i; near zero (|p_i| < 2^-5) a fixed
      // offset of ulps * n_i * ulp(2^-5) instead.
      const uint32_t scale = g.scale, fixed = g.fixed;
      const uint32_t origin = uint32_t(F::bias - 5) << F::man_bits;  // 2^-5
      for (int i = 0; i < 3; ++i) {
        const uint32_t ni = side_neg ? A::neg(n[i]) : n[i];
        if (A::lt(A::abs(s.h[i]), origin))
          r.o[i] = A::add(s.h[i], A::mul(fixed, ni));
        else
          r.o[i] = add_ulps<F>(s.h[i], to_int_rtz<F>(A::mul(scale, ni)));
      }
      break;
    }
    case Spawn::error_bound: {
      // Bound B on |f(h)| + the shadow test's own numerator error, where f(p) = p_k + n_u p_u +
      // n_v p_v - n_d (|n| >= 1 since n_k = 1):
      //   primary numerator   5u (|n_d| + |o_k| + |n_u o_u| + |n_v o_v|)
      //   primary denominator 3u |t| (|d_k| + |n_u d_u| + |n_v d_v|)
      //   t = num * rcp(den)  2u |t den|
      //   hit point           2u sum_i |n_i| (|t d_i| + |h_i|)
      //   shadow numerator    5u (|n_d| + |h_k| + |n_u h_u| + |n_v h_v|)
      //   moving the origin   u sum_i |n_i| |h_i| (plus the offset itself, covered by the factor)
      // The origin moves by 2B along n: f changes by 2B |n|^2 >= 2B; the factor 2 also covers the
      // rounding of this computation itself (about 30 operations, each within 1 + u).
      const uint32_t uu = unit_roundoff<A>();
      auto ab = [](uint32_t x) { return A::abs(x); };
      const uint32_t nu_ou = ab(A::mul(tri.n_u, pr.o[u])), nv_ov = ab(A::mul(tri.n_v, pr.o[v]));
      const uint32_t e_num = A::add3(A::add(ab(tri.n_d), ab(pr.o[tri.k])), nu_ou, nv_ov);
      const uint32_t e_den = A::add3(ab(pr.d[tri.k]), ab(A::mul(tri.n_u, pr.d[u])),
                                     ab(A::mul(tri.n_v, pr.d[v])));
      const uint32_t at = ab(t);
      uint32_t e_hit = A::zero, e_move = A::zero;
      for (int i = 0; i < 3; ++i) {
        const uint32_t ani = ab(n[i]), ahi = ab(s.h[i]);
        e_hit = A::add(e_hit, A::mul(ani, A::add(ab(A::mul(t, pr.d[i])), ahi)));
        e_move = A::add(e_move, A::mul(ani, ahi));
      }
      const uint32_t e_snum =
          A::add3(A::add(ab(tri.n_d), ab(s.h[tri.k])), ab(A::mul(tri.n_u, s.h[u])),
                  ab(A::mul(tri.n_v, s.h[v])));
      const uint32_t c5 = A::from_double(5.0), c3 = A::from_double(3.0), c2 = A::from_double(2.0);
      uint32_t b = A::add3(A::mul(c5, e_num), A::mul(c3, A::mul(at, e_den)),
                           A::mul(c2, ab(A::mul(t, tri.den))));
      b = A::add3(b, A::mul(c2, e_hit), A::add(A::mul(c5, e_snum), e_move));
      const uint32_t delta = A::mul(c2, A::mul(uu, b));
      for (int i = 0; i < 3; ++i) {
        const uint32_t step = A::mul(delta, n[i]);
        r.o[i] = side_neg ? A::sub(s.h[i], step) : A::add(s.h[i], step);
      }
      break;
    }
  }
  return s;
}

template <class A>
inline ShadowSetup hit_shadow(const Ray& pr, uint32_t t, const HitTri& tri, const uint32_t light[3],
                              uint32_t tmin, const SpawnParams& sp) {
  return hit_shadow_regs<A>(pr, t, tri, light, tmin, sp, hit_regs<A>(sp));
}

}  // namespace raycore::hls
