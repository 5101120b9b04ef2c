// sim/reference/predicates.cpp - see predicates.h.
#include "sim/reference/predicates.h"

#include <mpfr.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <initializer_list>
#include <stdexcept>

namespace raycore::reference {
namespace {

constexpr double kEps = DBL_EPSILON / 2;  // unit roundoff of double, 2^-53

// An MPFR number that frees itself. All arithmetic below is done at a precision chosen so that
// every operation is exact; the ternary results are checked, so a wrong choice cannot go unseen.
class Mp {
 public:
  explicit Mp(mpfr_prec_t prec) { mpfr_init2(v_, prec); }
  Mp(const Mp&) = delete;
  Mp& operator=(const Mp&) = delete;
  ~Mp() { mpfr_clear(v_); }
  mpfr_ptr get() { return v_; }

 private:
  mpfr_t v_;
};

void check_exact(int ternary) {
  if (ternary != 0) throw std::logic_error("reference predicates: MPFR evaluation was not exact");
}

// Precision (bits) making sums and differences of the inputs exact, products of `degree` such
// differences, and sums of a few of those products exact.
mpfr_prec_t exact_precision(std::initializer_list<double> xs, int degree) {
  int hi = -100000, lo = 100000;
  for (double x : xs) {
    if (x == 0) continue;
    int e = 0;
    std::frexp(x, &e);      // |x| < 2^e
    hi = std::max(hi, e);
    lo = std::min(lo, e - 53);  // the lowest bit x can carry
  }
  if (hi < lo) return 64;
  const int span = hi - lo + 2;  // a difference of two inputs fits in this many bits
  return mpfr_prec_t(degree * span + 16);
}

// Exact sign of a 3x3 determinant of differences, det[b - a; c - a; p - a].
int orient3d_exact(const hls::Vec3& a, const hls::Vec3& b, const hls::Vec3& c, const hls::Vec3& p) {
  const mpfr_prec_t prec = exact_precision(
      {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, p.x, p.y, p.z}, 3);
  Mp d[3][3] = {{Mp(prec), Mp(prec), Mp(prec)}, {Mp(prec), Mp(prec), Mp(prec)},
                {Mp(prec), Mp(prec), Mp(prec)}};
  const hls::Vec3* rows[3] = {&b, &c, &p};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) {
      check_exact(mpfr_set_d(d[r][k].get(), (*rows[r])[k], MPFR_RNDN));
      check_exact(mpfr_sub_d(d[r][k].get(), d[r][k].get(), a[k], MPFR_RNDN));
    }
  Mp m(prec), t(prec), acc(prec);
  mpfr_set_zero(acc.get(), 1);
  // det = d00 (d11 d22 - d12 d21) - d01 (d10 d22 - d12 d20) + d02 (d10 d21 - d11 d20)
  const int cols[3][2] = {{1, 2}, {0, 2}, {0, 1}};
  for (int k = 0; k < 3; ++k) {
    const int i = cols[k][0], j = cols[k][1];
    check_exact(mpfr_mul(m.get(), d[1][i].get(), d[2][j].get(), MPFR_RNDN));
    check_exact(mpfr_mul(t.get(), d[1][j].get(), d[2][i].get(), MPFR_RNDN));
    check_exact(mpfr_sub(m.get(), m.get(), t.get(), MPFR_RNDN));
    check_exact(mpfr_mul(m.get(), m.get(), d[0][k].get(), MPFR_RNDN));
    if (k == 1)
      check_exact(mpfr_sub(acc.get(), acc.get(), m.get(), MPFR_RNDN));
    else
      check_exact(mpfr_add(acc.get(), acc.get(), m.get(), MPFR_RNDN));
  }
  return mpfr_sgn(acc.get()) > 0 ? 1 : (mpfr_sgn(acc.get()) < 0 ? -1 : 0);
}

// Exact sign of (bx - ax)(cy - ay) - (by - ay)(cx - ax).
int orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy) {
  const mpfr_prec_t prec = exact_precision({ax, ay, bx, by, cx, cy}, 2);
  Mp u(prec), v(prec), w(prec), z(prec);
  check_exact(mpfr_set_d(u.get(), bx, MPFR_RNDN));
  check_exact(mpfr_sub_d(u.get(), u.get(), ax, MPFR_RNDN));
  check_exact(mpfr_set_d(v.get(), cy, MPFR_RNDN));
  check_exact(mpfr_sub_d(v.get(), v.get(), ay, MPFR_RNDN));
  check_exact(mpfr_mul(u.get(), u.get(), v.get(), MPFR_RNDN));
  check_exact(mpfr_set_d(w.get(), by, MPFR_RNDN));
  check_exact(mpfr_sub_d(w.get(), w.get(), ay, MPFR_RNDN));
  check_exact(mpfr_set_d(z.get(), cx, MPFR_RNDN));
  check_exact(mpfr_sub_d(z.get(), z.get(), ax, MPFR_RNDN));
  check_exact(mpfr_mul(w.get(), w.get(), z.get(), MPFR_RNDN));
  check_exact(mpfr_sub(u.get(), u.get(), w.get(), MPFR_RNDN));
  return mpfr_sgn(u.get()) > 0 ? 1 : (mpfr_sgn(u.get()) < 0 ? -1 : 0);
}

// Shewchuk's orient2d filter (error bound for rounded differences and products), then exact.
int orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  const double l = (bx - ax) * (cy - ay);
  const double r = (by - ay) * (cx - ax);
  const double det = l - r;
  const double bound = (3.0 + 16.0 * kEps) * kEps * (std::fabs(l) + std::fabs(r));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return orient2d_exact(ax, ay, bx, by, cx, cy);
}

}  // namespace

int sheared_edge_sign(const hls::Vec3& o, const hls::Vec3& d, int kx, int ky, int kz, const hls::Vec3& p,
                      const hls::Vec3& q) {
  // X_v = d_kz (v - o)_kx - d_kx (v - o)_kz: products of two differences of inputs (d_k is one),
  // the edge function a sum of products of two of those: degree 4.
  const mpfr_prec_t prec = exact_precision({o.x, o.y, o.z, d.x, d.y, d.z, p.x, p.y, p.z, q.x, q.y, q.z}, 4);
  Mp x[2] = {Mp(prec), Mp(prec)}, y[2] = {Mp(prec), Mp(prec)};
  Mp a(prec), b(prec);
  const hls::Vec3* v[2] = {&p, &q};
  for (int i = 0; i < 2; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const int k = axis == 0 ? kx : ky;
      Mp& out = axis == 0 ? x[i] : y[i];
      check_exact(mpfr_set_d(a.get(), (*v[i])[k], MPFR_RNDN));  // d_kz (v - o)_k
      check_exact(mpfr_sub_d(a.get(), a.get(), o[k], MPFR_RNDN));
      check_exact(mpfr_mul_d(a.get(), a.get(), d[kz], MPFR_RNDN));
      check_exact(mpfr_set_d(b.get(), (*v[i])[kz], MPFR_RNDN));  // d_k (v - o)_kz
      check_exact(mpfr_sub_d(b.get(), b.get(), o[kz], MPFR_RNDN));
      check_exact(mpfr_mul_d(b.get(), b.get(), d[k], MPFR_RNDN));
      check_exact(mpfr_sub(out.get(), a.get(), b.get(), MPFR_RNDN));
    }
  }
  check_exact(mpfr_mul(a.get(), x[1].get(), y[0].get(), MPFR_RNDN));  // X_q Y_p - Y_q X_p
  check_exact(mpfr_mul(b.get(), y[1].get(), x[0].get(), MPFR_RNDN));
  check_exact(mpfr_sub(a.get(), a.get(), b.get(), MPFR_RNDN));
  return mpfr_sgn(a.get()) > 0 ? 1 : (mpfr_sgn(a.get()) < 0 ? -1 : 0);
}

double diff_of_products(double a, double b, double c, double d) {
  const double cd = c * d;
  const double err = std::fma(-c, d, cd);  // cd - c*d, exact
  const double dop = std::fma(a, b, -cd);  // a*b - cd, rounded once
  return dop + err;
}

double edge_function(double a, double b, double c, double d) {
  const double p = a * b, q = c * d;
  const double e = p - q;
  // |e - (ab - cd)| <= u|p| + u|q| + u|e| <= 3u (|p| + |q|): beyond that the sign is proven.
  if (std::fabs(e) > 3.0 * kEps * (std::fabs(p) + std::fabs(q))) return e;
  return diff_of_products(a, b, c, d);
}

int orient3d(const hls::Vec3& a, const hls::Vec3& b, const hls::Vec3& c, const hls::Vec3& p) {
  // Shewchuk's orient3d with the rows (b - a, c - a, p - a); o3derrboundA covers the rounded
  // differences, products and sums.
  const double bax = b.x - a.x, bay = b.y - a.y, baz = b.z - a.z;
  const double cax = c.x - a.x, cay = c.y - a.y, caz = c.z - a.z;
  const double pax = p.x - a.x, pay = p.y - a.y, paz = p.z - a.z;
  const double m0l = cay * paz, m0r = caz * pay;
  const double m1l = cax * paz, m1r = caz * pax;
  const double m2l = cax * pay, m2r = cay * pax;
  const double det = bax * (m0l - m0r) - bay * (m1l - m1r) + baz * (m2l - m2r);
  const double permanent = (std::fabs(m0l) + std::fabs(m0r)) * std::fabs(bax) +
                           (std::fabs(m1l) + std::fabs(m1r)) * std::fabs(bay) +
                           (std::fabs(m2l) + std::fabs(m2r)) * std::fabs(baz);
  const double bound = (7.0 + 56.0 * kEps) * kEps * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return orient3d_exact(a, b, c, p);
}

bool is_degenerate(const hls::Vec3& a, const hls::Vec3& b, const hls::Vec3& c) {
  const bool ab = a.x == b.x && a.y == b.y && a.z == b.z;
  const bool ac = a.x == c.x && a.y == c.y && a.z == c.z;
  const bool bc = b.x == c.x && b.y == c.y && b.z == c.z;
  if (ab || ac || bc) return true;
  // Collinear in 3D iff collinear in all three coordinate-plane projections.
  return orient2d(a.x, a.y, b.x, b.y, c.x, c.y) == 0 && orient2d(a.y, a.z, b.y, b.z, c.y, c.z) == 0 &&
         orient2d(a.z, a.x, b.z, b.x, c.z, c.x) == 0;
}

}  // namespace raycore::reference
