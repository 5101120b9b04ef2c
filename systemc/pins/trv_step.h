// systemc/pins/trv_step.h - one step of the traversal unit's datapath (rtl/units/trv.v) as plain
// C++: its input and output records and trv_step<A>, what the RTL computes. The one definition
// shared by the SystemC twin (systemc/pins/trv.h) and the RTL tests' reference (tb/rtl/trv_stim.h:
// test_rtl_trv checks the Verilated --cc model against it). No SystemC here.
//
// op 0 = split at an inner node (hls::trv_split plus systemc/trv.h's child order and interval
// update), 1 = clip to the scene box (hls::trv_clip_box). Outputs the RTL leaves don't-care for a
// clip (visit, below, tsplit, node, far_node, far_tfar) are 0 here; compare them only for splits.
// The widening N (hls::Margins::widen_ulps) is a per-frame register of the unit (widen_i), not part
// of an item.
#pragma once

#include <cstdint>

#include "hls/ray.h"
#include "hls/trv.h"

namespace raycore::sc::pins {

// One step in (field names = the port names without in_/_i).
struct TrvStepIn {
  uint32_t op = 0;    // 0 split, 1 clip
  uint32_t axis = 0;  // 0..2 (3 = invalid, the unit treats it as 0)
  uint32_t split = 0, node = 0, child = 0;
  uint32_t o[3] = {}, d[3] = {}, inv[3] = {}, tnear = 0, tfar = 0, lo[3] = {}, hi[3] = {};
  uint32_t tag = 0;
};
// Its result (field names = the port names without out_/_o).
struct TrvStepOut {
  uint32_t op = 0, hit = 0, visit = 0, below = 0, tsplit = 0, tnear = 0, tfar = 0, node = 0,
           far_node = 0, far_tfar = 0, tag = 0;
};

// The widening register's width in rtl/units/trv.v (widen_i: 0..kMaxWidenUlps = 64).
constexpr uint32_t kTrvWidenBits = 7;

// One step as the RTL computes it (axis 3 is treated as axis 0), for the arithmetic A, with the
// interval widening register widen (hls/margins.h: ulps on each side of the compared interval).
template <class A>
TrvStepOut trv_step(const TrvStepIn& x, uint32_t widen = 0) {
  const int32_t w = int32_t(widen & ((1u << kTrvWidenBits) - 1u));
  hls::Ray r;
  for (int i = 0; i < 3; ++i) {
    r.o[i] = x.o[i];
    r.d[i] = x.d[i];
    r.inv[i] = x.inv[i];
  }
  TrvStepOut e;
  e.op = x.op;
  e.tag = x.tag;
  if (x.op != 0) {
    r.tmin = x.tnear;
    r.tmax = x.tfar;
    e.hit = hls::trv_clip_box<A>(x.lo, x.hi, r, e.tnear, e.tfar, w) ? 1u : 0u;
    return e;
  }
  const hls::SplitStep s = hls::trv_split<A>(x.split, x.axis == 3 ? 0u : x.axis, r, x.tnear,
                                             x.tfar, w);
  const uint32_t first = s.below_first ? x.node + 1 : x.child;
  const uint32_t second = s.below_first ? x.child : x.node + 1;
  e.visit = uint32_t(s.visit);
  e.below = s.below_first ? 1u : 0u;
  e.tsplit = s.tsplit;
  e.tnear = x.tnear;
  e.tfar = s.visit == hls::Visit::both ? s.tsplit : x.tfar;
  e.node = s.visit == hls::Visit::second ? second : first;
  e.far_node = second;
  e.far_tfar = x.tfar;
  return e;
}

}  // namespace raycore::sc::pins
