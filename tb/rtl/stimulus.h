// tb/rtl/stimulus.h - the random stimulus of the vtu and ist co-simulation tests, shared by the
// Verilator --cc tests against hls/ (test_rtl_vtu, test_rtl_ist) and the lockstep tests of the
// SystemC twins against the Verilated --sc models (tb/systemc/test_pins.cpp).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

#include "hls/fp.h"
#include "hls/geom.h"
#include "hls/image.h"
#include "hls/wald.h"

namespace raycore::rtltest {

using hls::Rounding;

// ---- ist: one test's inputs (Wald's 9 constants, or a watertight record's 12) ----
struct IstIn {
  uint32_t k = 0;
  uint32_t c[12] = {};
  uint32_t o[3] = {}, d[3] = {};
  uint32_t tmin = 0, tmax = 0;
};

// Random test inputs for records of a kind (Wald's by default): mostly a ray aimed at a chosen
// barycentric point of a random triangle.
template <class F, Rounding R>
class Stimulus {
 public:
  explicit Stimulus(uint64_t seed, hls::IstKind kind = hls::IstKind::wald) : rng_(seed), kind_(kind) {}

  IstIn next() {
    IstIn x;
    const uint32_t kind = uint32_t(rng_() % 100);
    if (kind < 10) {  // fully random bit patterns
      x.k = uint32_t(rng_() % 3);
      for (int i = 0; i < hls::tri_const_count(kind_); ++i) x.c[i] = bits();
      for (int i = 0; i < 3; ++i) {
        x.o[i] = bits();
        x.d[i] = bits();
      }
      x.tmin = bits();
      x.tmax = bits();
      return x;
    }
    const double scale = std::ldexp(1.0, int(rng_() % 13) - 6);  // 2^-6 .. 2^6
    hls::Tri tri;
    for (hls::Vec3& p : tri) p = {uni(-scale, scale), uni(-scale, scale), uni(-scale, scale)};
    if (kind < 13) tri[2] = tri[0] + (tri[1] - tri[0]) * uni(-1, 2);  // degenerate (collinear)
    // Watertight records: also a repeated vertex (zero area in double: the all-zero degenerate
    // record, whose edge functions are exactly zero: the det = 0 exit).
    if (kind < 12 && kind_ == hls::IstKind::watertight) tri[2] = tri[1];
    const hls::WaldTri<F> w = hls::make_wald<F, R>(tri, 0, kind_);
    x.k = w.k;
    for (int i = 0; i < w.count(); ++i) x.c[i] = w.c[i];
    // The aimed-at barycentric point: inside, outside, or on an edge.
    double b = uni(0, 1), g = uni(0, 1);
    switch (rng_() % 6) {
      case 0:
      case 1:  // inside
        if (b + g > 1) {
          b = 1 - b;
          g = 1 - g;
        }
        break;
      case 2:  // outside beyond one edge (or two)
        b = uni(-1, 2);
        g = uni(-1, 2);
        break;
      case 3:  // on an edge
        switch (rng_() % 3) {
          case 0: b = 0; break;
          case 1: g = 0; break;
          default: g = 1 - b; break;
        }
        break;
      case 4:  // just outside an edge
        switch (rng_() % 3) {
          case 0: b = -std::ldexp(uni(0, 1), -int(rng_() % 20)); break;
          case 1: g = -std::ldexp(uni(0, 1), -int(rng_() % 20)); break;
          default: g = 1 - b + std::ldexp(uni(0, 1), -int(rng_() % 20)); break;
        }
        break;
      default:  // a vertex
        b = double(rng_() % 2);
        g = b > 0 ? 0 : double(rng_() % 2);
        break;
    }
    const hls::Vec3 p = tri[0] + (tri[1] - tri[0]) * b + (tri[2] - tri[0]) * g;
    const double oscale = scale * std::ldexp(1.0, int(rng_() % 5));
    const hls::Vec3 o = {p.x + uni(-oscale, oscale), p.y + uni(-oscale, oscale),
                         p.z + uni(-oscale, oscale)};
    const double dlen = std::ldexp(uni(0.5, 1), int(rng_() % 9) - 4);  // t_hit ~ 1 / dlen
    const hls::Vec3 d = (p - o) * dlen;
    for (int i = 0; i < 3; ++i) {
      x.o[i] = hls::from_double<F, R>(o[i]);
      x.d[i] = hls::from_double<F, R>(d[i]);
    }
    const double th = 1 / dlen;
    switch (rng_() % 5) {
      case 0:  // wide interval
        x.tmin = 0;
        x.tmax = F::max_mag;
        break;
      case 1:  // the hit lies beyond tmax or before tmin
        x.tmin = hls::from_double<F, R>(th * uni(0.5, 1.5));
        x.tmax = hls::from_double<F, R>(th * uni(0.5, 2));
        break;
      case 2:  // tight around the hit
        x.tmin = hls::from_double<F, R>(th * (1 - std::ldexp(1.0, -int(rng_() % 20))));
        x.tmax = hls::from_double<F, R>(th * (1 + std::ldexp(1.0, -int(rng_() % 20))));
        break;
      default:  // usual: tmin small, tmax above the hit
        x.tmin = hls::from_double<F, R>(std::ldexp(uni(0, 1), -10) * th);
        x.tmax = hls::from_double<F, R>(th * uni(1.01, 4));
        break;
    }
    return x;
  }

  uint64_t raw() { return rng_(); }

 private:
  double uni(double a, double b) { return a + (b - a) * (double(rng_() >> 11) * 0x1p-53); }
  uint32_t bits() { return uint32_t(rng_()) & F::mask; }
  std::mt19937_64 rng_;
  hls::IstKind kind_;
};

// ---- vtu: one record (node or triangle) with the camera and enable it is sent with ----
template <class F>
struct Record {
  bool tri = false;
  uint64_t node = 0;
  hls::WaldTri<F> t;
  uint32_t cam[3] = {0, 0, 0};
  bool on = true;
};

template <class F, Rounding R>
class Gen {
 public:
  explicit Gen(uint64_t seed) : rng_(seed) {}
  // A format value: magnitude 1e-3..1e4 (log-uniform), random sign; 1/32 a signed zero, 1/64 a
  // raw bit pattern of the format (any exponent, incl. the zero field with a nonzero mantissa).
  uint32_t value() {
    const uint32_t sel = uint32_t(rng_() & 63u);
    if (sel == 0) return uint32_t(rng_()) & F::mask;
    if (sel <= 2) return (rng_() & 1u) ? F::sign_mask : 0u;
    const double mag = std::pow(10.0, std::uniform_real_distribution<double>(-3.0, 4.0)(rng_));
    return hls::Arith<F, R>::from_double((rng_() & 1u) ? -mag : mag);
  }
  uint32_t cam_coord() { return (rng_() & 15u) == 0 ? 0u : value(); }
  Record<F> next() {
    if ((rng_() & 7u) == 0)
      for (uint32_t& c : cam_) c = cam_coord();
    if ((rng_() & 255u) == 0) on_ = !on_;
    if (!on_ && (rng_() & 7u) != 0) on_ = true;  // off for short stretches
    Record<F> r;
    for (int i = 0; i < 3; ++i) r.cam[i] = cam_[i];
    r.on = on_;
    r.tri = (rng_() & 1u) != 0;
    if (r.tri) {
      r.t.k = uint32_t(rng_() % 3u);
      r.t.flags = uint32_t(rng_() & 0xFFu);
      r.t.id = uint32_t(rng_());
      for (int i = 0; i < r.t.count(); ++i) r.t.c[i] = value();  // Wald's 9 (vtu.v's record)
    } else {
      const uint64_t axis = rng_() & 3u;
      uint64_t hi = (uint64_t(rng_()) << 32) & ~(uint64_t(3) << 56);
      hi |= axis << 56;
      // Leaves: any count; inner nodes: a split in the format (bits above its width zero).
      const uint32_t lo = axis == hls::node_leaf_axis ? uint32_t(rng_()) : value();
      r.node = hi | lo;
    }
    return r;
  }
  std::mt19937_64& rng() { return rng_; }

 private:
  std::mt19937_64 rng_;
  uint32_t cam_[3] = {0, 0, 0};
  bool on_ = true;
};

}  // namespace raycore::rtltest
