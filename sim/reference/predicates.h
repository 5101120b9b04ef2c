// sim/reference/predicates.h - exact-sign geometric predicates in double precision, for the
// double-precision reference tracer.
//
// Both predicates return the sign of an exactly defined expression of their double inputs (as if
// evaluated in exact arithmetic), not of its rounded value: a fast floating-point evaluation is
// kept when a forward error bound proves its sign, otherwise an exact evaluation decides.
// Assumes finite inputs whose intermediate products neither overflow nor underflow (scene
// coordinates between about 1e-70 and 1e70 in magnitude).
#pragma once

#include "hls/geom.h"

namespace raycore::reference {

// a*b - c*d with a relative error of at most 2 units in the last place (Kahan's algorithm with
// a fused multiply-add; Jeannerod, Louvet, Muller 2013), hence with the exact sign, and exactly 0
// when a*b == c*d.
double diff_of_products(double a, double b, double c, double d);

// The 2D edge function a*b - c*d with its exact sign: the plain double evaluation when its error
// bound proves the sign, else diff_of_products. Used by the watertight ray/triangle test.
double edge_function(double a, double b, double c, double d);

// Sign (-1, 0, +1) of dot(cross(b - a, c - a), p - a) evaluated exactly: +1 when p lies on the
// side of the plane through a, b, c that the normal cross(b - a, c - a) points to, 0 when the
// four points are exactly coplanar (or a, b, c are collinear). Filtered (Shewchuk's orient3d
// error bound), with an exact MPFR fallback.
int orient3d(const hls::Vec3& a, const hls::Vec3& b, const hls::Vec3& c, const hls::Vec3& p);

// Sign (-1, 0, +1) of the watertight test's edge function of vertices p, q for the exact ray o + t d,
// sheared with the axes kx, ky, kz (bvh.cpp's ShearedRay): X_q Y_p - Y_q X_p with X_v = d_kz (v -
// o)_kx - d_kx (v - o)_kz and Y_v likewise with ky (the sheared coordinates scaled by d_kz, whose
// square keeps the sign), evaluated exactly (MPFR): what the double sheared coordinates' rounding
// decides when the ray passes within it of the edge.
int sheared_edge_sign(const hls::Vec3& o, const hls::Vec3& d, int kx, int ky, int kz, const hls::Vec3& p,
                      const hls::Vec3& q);

// True when the three vertices are exactly collinear (or coincident): the triangle has zero area.
bool is_degenerate(const hls::Vec3& a, const hls::Vec3& b, const hls::Vec3& c);

}  // namespace raycore::reference
