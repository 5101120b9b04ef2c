// systemc/rtl_fields.h - the records that several Verilated units' ports share, packed and unpacked
// once for every binding (systemc/{trv,ist,hit,rgu}_rtl.cpp).
#pragma once

#include <cstdint>

#include "hls/ray.h"
#include "systemc/slot.h"
#include "systemc/vl_bits.h"

namespace raycore::sc::vl {

// A hit record {found, t, den, pos, id, k, nu, nv, nd}, nd lowest, 67 + 4W + (W + tx) bits from bit
// lo: trv_unit's res_rec_i (found = 1 for every result) and best_o, ist_unit's res_rec_o, the best
// record in hit_unit's rd_i. The record's t is the closest-hit key (hls::KeyFormat) with tx
// extension bits below F's t: the model's key (Best::t) shifted right by `drop` bits (the key's
// extension bits less tx; a unit with tx 0 holds the key's top bits, F's t: exact for a Wald
// frame's keys, the hit unit's t for any).
template <class T>
void set_best(T& port, unsigned lo, unsigned w, const Best& b, unsigned tx = 0, unsigned drop = 0) {
  set_bits(port, lo, w, b.nd);
  set_bits(port, lo + w, w, b.nv);
  set_bits(port, lo + 2 * w, w, b.nu);
  set_bits(port, lo + 3 * w, 2, b.k);
  set_bits(port, lo + 3 * w + 2, 32, b.id);
  set_bits(port, lo + 3 * w + 34, 32, b.pos);
  set_bits(port, lo + 3 * w + 66, w, b.den);
  set_bits(port, lo + 4 * w + 66, w + tx, b.t >> drop);
  set_bits(port, lo + 5 * w + tx + 66, 1, b.found);
}
template <class T>
Best get_best(const T& port, unsigned lo, unsigned w, unsigned tx = 0, unsigned drop = 0) {
  Best b;
  b.nd = get_bits(port, lo, w);
  b.nv = get_bits(port, lo + w, w);
  b.nu = get_bits(port, lo + 2 * w, w);
  b.k = get_bits(port, lo + 3 * w, 2);
  b.id = get_bits(port, lo + 3 * w + 2, 32);
  b.pos = get_bits(port, lo + 3 * w + 34, 32);
  b.den = get_bits(port, lo + 3 * w + 66, w);
  b.t = get_bits(port, lo + 4 * w + 66, w + tx) << drop;
  b.found = get_bits(port, lo + 5 * w + tx + 66, 1) != 0;
  return b;
}

// A ray {o xyz, d xyz, inv xyz, tmin, tmax}, tmax lowest, 11W bits from bit lo: trv_unit's
// in_ray_i, hit_unit's and rgu_unit's out_ray_o.
template <class T>
void set_ray(T& port, unsigned lo, unsigned w, const hls::Ray& r) {
  set_bits(port, lo, w, r.tmax);
  set_bits(port, lo + w, w, r.tmin);
  for (unsigned i = 0; i < 3; ++i) {
    set_bits(port, lo + (4 - i) * w, w, r.inv[i]);
    set_bits(port, lo + (7 - i) * w, w, r.d[i]);
    set_bits(port, lo + (10 - i) * w, w, r.o[i]);
  }
}
template <class T>
hls::Ray get_ray(const T& port, unsigned lo, unsigned w) {
  hls::Ray r{};
  r.tmax = get_bits(port, lo, w);
  r.tmin = get_bits(port, lo + w, w);
  for (unsigned i = 0; i < 3; ++i) {
    r.inv[i] = get_bits(port, lo + (4 - i) * w, w);
    r.d[i] = get_bits(port, lo + (7 - i) * w, w);
    r.o[i] = get_bits(port, lo + (10 - i) * w, w);
  }
  return r;
}

}  // namespace raycore::sc::vl
