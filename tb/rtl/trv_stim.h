// tb/rtl/trv_stim.h - stimulus and reference for rtl/units/trv.v (the traversal datapath), shared
// by tb/rtl/test_rtl_trv.cpp (Verilated --cc model vs hls/) and tb/rtl/test_lockstep_trv.cpp
// (Verilated --sc model vs the SystemC twin systemc/pins/trv.h).
//
// TrvIn is one item at the unit's input (op 0: hls::trv_split at an inner node, op 1:
// hls::trv_clip_box), TrvOut the unit's outputs; trv_expect<A> computes them (trv_step, the
// definition the SystemC twin uses too). same() compares what is defined for the item's op (the
// split fields are don't-care for a clip). TrvStim draws random and directed items: random rays,
// planes and boxes, and the edge cases (d = +-0 on the axis, the origin on the plane, the plane
// exactly at tnear or tfar or one ulp beside, -0 for every interval end, saturated reciprocals, the
// origin on a box face, empty and inverted boxes), plus fully random bit patterns.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>

#include "hls/fp.h"
#include "systemc/pins/trv_step.h"
#include "tb/fp/fp_check.h"

namespace raycore::rtltest {

// The unit's input and outputs are the twin's records (systemc/pins/trv_step.h); the tag is the
// harness's.
using TrvIn = sc::pins::TrvStepIn;
using TrvOut = sc::pins::TrvStepOut;

// Equal in every field defined for the op (clip: hit, tnear, tfar).
inline bool same(const TrvOut& a, const TrvOut& b) {
  if (a.op != b.op || a.hit != b.hit || a.tnear != b.tnear || a.tfar != b.tfar) return false;
  if (a.op == 1) return true;
  return a.visit == b.visit && a.below == b.below && a.tsplit == b.tsplit && a.node == b.node &&
         a.far_node == b.far_node && a.far_tfar == b.far_tfar;
}

// What the unit puts out for x: trv_step, the one definition (hls/ plus systemc/trv.h's rules).
template <class A>
TrvOut trv_expect(const TrvIn& x, uint32_t widen) {
  return sc::pins::trv_step<A>(x, widen);
}

template <class F>
std::string describe(const TrvIn& x) {
  using fptest::show;
  std::ostringstream s;
  auto v3 = [&](const char* n, const uint32_t* a) {
    s << " " << n << "=[" << show<F>(a[0]) << " " << show<F>(a[1]) << " " << show<F>(a[2]) << "]";
  };
  if (x.op == 0)
    s << "split axis=" << x.axis << " split=" << show<F>(x.split) << " node=" << x.node
      << " child=" << x.child;
  else
    s << "clip";
  v3("o", x.o);
  v3("d", x.d);
  v3("inv", x.inv);
  s << " tnear=" << show<F>(x.tnear) << " tfar=" << show<F>(x.tfar);
  if (x.op == 1) {
    v3("lo", x.lo);
    v3("hi", x.hi);
  }
  return s.str();
}

template <class F>
std::string describe(const TrvOut& r) {
  using fptest::show;
  std::ostringstream s;
  s << "op=" << r.op << " hit=" << r.hit << " tnear=" << show<F>(r.tnear)
    << " tfar=" << show<F>(r.tfar);
  if (r.op == 0)
    s << " visit=" << r.visit << " below=" << r.below << " tsplit=" << show<F>(r.tsplit)
      << " node=" << r.node << " far_node=" << r.far_node << " far_tfar=" << show<F>(r.far_tfar);
  return s.str();
}

// Random and directed trv items.
template <class F, hls::Rounding R>
class TrvStim {
  using A = hls::Arith<F, R>;

 public:
  explicit TrvStim(uint64_t seed) : rng_(seed) {}

  // Directed item k (k < directed_count()): every combination of the edge cases, deterministic.
  static constexpr uint64_t directed_count() { return 2 * 3 * 6 * 8 * 8; }
  TrvIn directed(uint64_t k) {
    TrvIn x = base_ray();
    const uint32_t op = uint32_t(k % 2);
    k /= 2;
    const uint32_t axis = uint32_t(k % 3);
    k /= 3;
    const uint32_t dcase = uint32_t(k % 6);  // d on the axis: +0, -0, +, -, tiny, huge
    k /= 6;
    const uint32_t pcase = uint32_t(k % 8);  // where the plane / box face lies
    k /= 8;
    const uint32_t icase = uint32_t(k % 8);  // the interval
    x.op = op;
    x.axis = axis;
    const uint32_t dd[6] = {0u, F::sign_mask, F::one, F::sign_mask | F::one, F::min_mag,
                            F::max_mag};
    x.d[axis] = dd[dcase];
    if (rng_() & 1u) x.d[axis] ^= F::sign_mask * (dcase >= 2 ? 1u : 0u);
    x.inv[axis] = A::rcp(x.d[axis]);
    // Plane (split) or both box faces on this axis.
    const uint32_t oa = x.o[axis];
    uint32_t p = 0;
    switch (pcase) {
      case 0: p = oa; break;                        // the origin on the plane / face
      case 1: p = A::next_up(oa); break;            // one ulp above
      case 2: p = A::next_down(oa); break;          // one ulp below
      case 3: p = 0; break;                         // +0
      case 4: p = F::sign_mask; break;              // -0
      case 5: p = A::add(oa, num(-8, 8)); break;    // somewhere
      case 6: p = F::max_mag | (rng_() & 1u ? F::sign_mask : 0u); break;  // far away
      default: p = bits(); break;
    }
    x.split = p;
    if (op == 1) {
      x.lo[axis] = p;
      x.hi[axis] = (icase & 1u) ? oa : A::add(p, num(-4, 4));  // sometimes inverted or empty
    }
    // The interval: around tsplit (computed as the unit does), exact, one ulp off, -0, ...
    const uint32_t ts = A::mul(A::sub(p, oa), x.inv[axis]);
    switch (icase) {
      case 0: x.tnear = 0; x.tfar = F::max_mag; break;
      case 1: x.tnear = ts; x.tfar = A::add(ts, F::one); break;       // plane at tnear
      case 2: x.tnear = A::sub(ts, F::one); x.tfar = ts; break;       // plane at tfar
      case 3: x.tnear = A::next_up(ts); x.tfar = A::next_up(A::next_up(ts)); break;
      case 4: x.tnear = A::next_down(A::next_down(ts)); x.tfar = A::next_down(ts); break;
      case 5: x.tnear = F::sign_mask; x.tfar = F::sign_mask; break;   // -0, -0
      case 6: x.tnear = F::sign_mask; x.tfar = ts; break;
      default: x.tnear = ts; x.tfar = ts; break;                      // a point interval
    }
    return x;
  }

  TrvIn random() {
    const uint32_t kind = uint32_t(rng_() % 100);
    TrvIn x;
    if (kind < 10) {  // random bit patterns everywhere
      x.op = uint32_t(rng_() & 1u);
      x.axis = uint32_t(rng_() % 4);  // incl. the invalid 3
      x.split = bits();
      for (int i = 0; i < 3; ++i) {
        x.o[i] = bits();
        x.d[i] = bits();
        x.inv[i] = (rng_() & 1u) ? bits() : A::rcp(x.d[i]);
        x.lo[i] = bits();
        x.hi[i] = bits();
      }
      x.tnear = bits();
      x.tfar = bits();
      x.node = uint32_t(rng_());
      x.child = uint32_t(rng_());
      return x;
    }
    x = base_ray();
    x.op = (kind < 45) ? 1u : 0u;
    x.axis = uint32_t(rng_() % 3);
    if (rng_() % 16 == 0) {  // a zero direction component
      const int a = int(rng_() % 3);
      x.d[a] = (rng_() & 1u) ? F::sign_mask : 0u;
      x.inv[a] = A::rcp(x.d[a]);
    }
    const double sc = std::ldexp(1.0, int(rng_() % 9) - 2);
    for (int i = 0; i < 3; ++i) {
      const double a = uni(-sc, sc), b = uni(-sc, sc);
      x.lo[i] = A::from_double(std::min(a, b));
      x.hi[i] = A::from_double(std::max(a, b));
      if (rng_() % 32 == 0) x.lo[i] = x.o[i];  // origin on a face
    }
    x.split = (rng_() % 8 == 0) ? x.o[x.axis] : A::from_double(uni(-sc, sc));
    const uint32_t ts = A::mul(A::sub(x.split, x.o[x.axis]), x.inv[x.axis]);
    switch (rng_() % 7) {
      case 0: x.tnear = 0; x.tfar = F::max_mag; break;
      case 6: x.tnear = A::add(ts, A::from_double(uni(-1, 2))); x.tfar = A::add(x.tnear, F::one); break;
      case 1: x.tnear = ts; x.tfar = A::add(ts, A::from_double(uni(0, 4))); break;
      case 2: x.tnear = A::sub(ts, A::from_double(uni(0, 4))); x.tfar = ts; break;
      default: {
        const double a = uni(-2, 2 * sc), b = uni(-2, 2 * sc);
        x.tnear = A::from_double(std::min(a, b));
        x.tfar = A::from_double(std::max(a, b));
        break;
      }
    }
    if (x.op == 1 && (rng_() & 1u)) {  // a box around the origin, a ray starting near it
      for (int i = 0; i < 3; ++i) {
        x.lo[i] = A::sub(x.o[i], A::from_double(uni(0, sc)));
        x.hi[i] = A::add(x.o[i], A::from_double(uni(0, sc)));
      }
      x.tnear = A::from_double(uni(-1, 1) * 0.25);
      x.tfar = A::from_double(uni(0, 4 * sc));
    }
    if (rng_() % 16 == 0) x.tnear = F::sign_mask;  // -0
    x.node = uint32_t(rng_() % (1u << 24));
    x.child = uint32_t(rng_() % (1u << 24));
    return x;
  }

  uint64_t raw() { return rng_(); }

 private:
  TrvIn base_ray() {
    TrvIn x;
    for (int i = 0; i < 3; ++i) {
      x.o[i] = A::from_double(uni(-4, 4));
      double d = uni(-1, 1);
      if (std::fabs(d) < 1e-3) d = 0.5;
      x.d[i] = A::from_double(d);
      x.inv[i] = A::rcp(x.d[i]);
      x.lo[i] = A::from_double(uni(-6, -0.5));
      x.hi[i] = A::from_double(uni(0.5, 6));
    }
    x.node = uint32_t(rng_() % (1u << 24));
    x.child = uint32_t(rng_() % (1u << 24));
    return x;
  }
  uint32_t num(double a, double b) { return A::from_double(uni(a, b)); }
  double uni(double a, double b) { return a + (b - a) * (double(rng_() >> 11) * 0x1p-53); }
  uint32_t bits() { return uint32_t(rng_()) & F::mask; }
  std::mt19937_64 rng_;
};

}  // namespace raycore::rtltest
