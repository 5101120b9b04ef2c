// systemc/pins/trv.h - the traversal unit's datapath at pin level: the ports of rtl/units/trv.v
// exactly as a Verilated --sc model has them (toolchain.md pitfall 14: 1 bit bool, 2..32 bits
// uint32_t), its SystemC twin TrvTwin, and bind_trv() (one template for both, so either can be
// bound in the same place).
//
// One ray step per cycle, selected by in_op_i: 0 = split at an inner node (hls::trv_split plus
// systemc/trv.h's child order and interval update), 1 = clip to the scene box (hls::trv_clip_box).
// The twin computes the step at the input through hls/ (the one definition of the arithmetic) and
// carries the result through a ReadyChain of 4 * STAGES registers: the RTL's latency and
// handshake, cycle for cycle. Outputs the RTL leaves don't-care for a clip (visit, below, tsplit,
// node, far_node, far_tfar) are 0 here; compare them only for splits.
#pragma once

#include <systemc>

#include <cstdint>

#include "hls/ray.h"
#include "hls/trv.h"
#include "systemc/pins/chain.h"

namespace raycore::sc::pins {

// One step in (field names = the port names without in_/_i).
struct TrvStepIn {
  uint32_t op = 0, axis = 0, split = 0, node = 0, child = 0;
  uint32_t o[3] = {}, d[3] = {}, inv[3] = {}, tnear = 0, tfar = 0, lo[3] = {}, hi[3] = {};
  uint32_t tag = 0;
};
// Its result (field names = the port names without out_/_o).
struct TrvStepOut {
  uint32_t op = 0, hit = 0, visit = 0, below = 0, tsplit = 0, tnear = 0, tfar = 0, node = 0,
           far_node = 0, far_tfar = 0, tag = 0;
};

struct TrvSignals {
  sc_core::sc_signal<bool> in_valid, in_ready, in_op, out_valid, out_ready, out_op, out_hit,
      out_below;
  sc_core::sc_signal<uint32_t> in_axis, in_split, in_node, in_child, in_o[3], in_d[3], in_inv[3],
      in_tnear, in_tfar, in_lo[3], in_hi[3], in_tag;
  sc_core::sc_signal<uint32_t> out_visit, out_tsplit, out_tnear, out_tfar, out_node, out_far_node,
      out_far_tfar, out_tag;

  void drive(const TrvStepIn& x) {
    in_valid.write(true);
    in_op.write(x.op != 0);
    in_axis.write(x.axis);
    in_split.write(x.split);
    in_node.write(x.node);
    in_child.write(x.child);
    for (int i = 0; i < 3; ++i) {
      in_o[i].write(x.o[i]);
      in_d[i].write(x.d[i]);
      in_inv[i].write(x.inv[i]);
      in_lo[i].write(x.lo[i]);
      in_hi[i].write(x.hi[i]);
    }
    in_tnear.write(x.tnear);
    in_tfar.write(x.tfar);
    in_tag.write(x.tag);
  }
  TrvStepOut out() const {
    TrvStepOut r;
    r.op = out_op.read();
    r.hit = out_hit.read();
    r.visit = out_visit.read();
    r.below = out_below.read();
    r.tsplit = out_tsplit.read();
    r.tnear = out_tnear.read();
    r.tfar = out_tfar.read();
    r.node = out_node.read();
    r.far_node = out_far_node.read();
    r.far_tfar = out_far_tfar.read();
    r.tag = out_tag.read();
    return r;
  }
};

// Binds a trv at pin level (TrvTwin or a Verilated --sc model of rtl/units/trv.v) to the signals.
template <class M>
void bind_trv(M& m, TrvSignals& s, sc_core::sc_signal<bool>& clk, sc_core::sc_signal<bool>& rst_n) {
  m.clk_i(clk);
  m.rst_ni(rst_n);
  m.in_valid_i(s.in_valid);
  m.in_ready_o(s.in_ready);
  m.in_op_i(s.in_op);
  m.in_axis_i(s.in_axis);
  m.in_split_i(s.in_split);
  m.in_node_i(s.in_node);
  m.in_child_i(s.in_child);
  m.in_o_x_i(s.in_o[0]);
  m.in_o_y_i(s.in_o[1]);
  m.in_o_z_i(s.in_o[2]);
  m.in_d_x_i(s.in_d[0]);
  m.in_d_y_i(s.in_d[1]);
  m.in_d_z_i(s.in_d[2]);
  m.in_inv_x_i(s.in_inv[0]);
  m.in_inv_y_i(s.in_inv[1]);
  m.in_inv_z_i(s.in_inv[2]);
  m.in_tnear_i(s.in_tnear);
  m.in_tfar_i(s.in_tfar);
  m.in_lo_x_i(s.in_lo[0]);
  m.in_lo_y_i(s.in_lo[1]);
  m.in_lo_z_i(s.in_lo[2]);
  m.in_hi_x_i(s.in_hi[0]);
  m.in_hi_y_i(s.in_hi[1]);
  m.in_hi_z_i(s.in_hi[2]);
  m.in_tag_i(s.in_tag);
  m.out_valid_o(s.out_valid);
  m.out_ready_i(s.out_ready);
  m.out_op_o(s.out_op);
  m.out_hit_o(s.out_hit);
  m.out_visit_o(s.out_visit);
  m.out_below_o(s.out_below);
  m.out_tsplit_o(s.out_tsplit);
  m.out_tnear_o(s.out_tnear);
  m.out_tfar_o(s.out_tfar);
  m.out_node_o(s.out_node);
  m.out_far_node_o(s.out_far_node);
  m.out_far_tfar_o(s.out_far_tfar);
  m.out_tag_o(s.out_tag);
}

// The SystemC twin of rtl/units/trv.v for the arithmetic A (hls::Arith<F, R>); stages = the RTL's
// STAGES (>= 1), tag_bits = its TAG_BITS.
template <class A>
class TrvTwin : public sc_core::sc_module {
 public:
  sc_core::sc_in<bool> clk_i, rst_ni, in_valid_i;
  sc_core::sc_out<bool> in_ready_o;
  sc_core::sc_in<bool> in_op_i;
  sc_core::sc_in<uint32_t> in_axis_i, in_split_i, in_node_i, in_child_i;
  sc_core::sc_in<uint32_t> in_o_x_i, in_o_y_i, in_o_z_i, in_d_x_i, in_d_y_i, in_d_z_i;
  sc_core::sc_in<uint32_t> in_inv_x_i, in_inv_y_i, in_inv_z_i, in_tnear_i, in_tfar_i;
  sc_core::sc_in<uint32_t> in_lo_x_i, in_lo_y_i, in_lo_z_i, in_hi_x_i, in_hi_y_i, in_hi_z_i;
  sc_core::sc_in<uint32_t> in_tag_i;
  sc_core::sc_out<bool> out_valid_o;
  sc_core::sc_in<bool> out_ready_i;
  sc_core::sc_out<bool> out_op_o, out_hit_o;
  sc_core::sc_out<uint32_t> out_visit_o;
  sc_core::sc_out<bool> out_below_o;
  sc_core::sc_out<uint32_t> out_tsplit_o, out_tnear_o, out_tfar_o, out_node_o, out_far_node_o,
      out_far_tfar_o, out_tag_o;

  SC_HAS_PROCESS(TrvTwin);
  TrvTwin(sc_core::sc_module_name name, unsigned stages, unsigned tag_bits = 16)
      : sc_core::sc_module(name),
        tag_mask_(tag_bits >= 32 ? ~0u : (1u << tag_bits) - 1u),
        chain_(4 * stages) {
    SC_METHOD(seq);
    sensitive << clk_i.pos() << rst_ni.neg();
    dont_initialize();
    SC_METHOD(comb);
    sensitive << out_ready_i << changed_;
  }

  // One step as the RTL computes it (axis 3 is treated as axis 0).
  static TrvStepOut compute(const TrvStepIn& x) {
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
      e.hit = hls::trv_clip_box<A>(x.lo, x.hi, r, e.tnear, e.tfar) ? 1u : 0u;
      return e;
    }
    const hls::SplitStep s = hls::trv_split<A>(x.split, x.axis == 3 ? 0u : x.axis, r, x.tnear,
                                               x.tfar);
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

 private:
  void seq() {
    if (!rst_ni.read()) {
      chain_.reset();
    } else {
      TrvStepOut r;
      const bool valid = in_valid_i.read();
      if (valid) {
        TrvStepIn x;
        x.op = in_op_i.read() ? 1u : 0u;
        x.axis = in_axis_i.read() & 3u;
        x.split = in_split_i.read();
        x.node = in_node_i.read();
        x.child = in_child_i.read();
        x.o[0] = in_o_x_i.read();
        x.o[1] = in_o_y_i.read();
        x.o[2] = in_o_z_i.read();
        x.d[0] = in_d_x_i.read();
        x.d[1] = in_d_y_i.read();
        x.d[2] = in_d_z_i.read();
        x.inv[0] = in_inv_x_i.read();
        x.inv[1] = in_inv_y_i.read();
        x.inv[2] = in_inv_z_i.read();
        x.tnear = in_tnear_i.read();
        x.tfar = in_tfar_i.read();
        x.lo[0] = in_lo_x_i.read();
        x.lo[1] = in_lo_y_i.read();
        x.lo[2] = in_lo_z_i.read();
        x.hi[0] = in_hi_x_i.read();
        x.hi[1] = in_hi_y_i.read();
        x.hi[2] = in_hi_z_i.read();
        x.tag = in_tag_i.read() & tag_mask_;
        r = compute(x);
      }
      chain_.edge(valid, r, out_ready_i.read());
    }
    changed_.write(!changed_.read());
  }
  void comb() {
    in_ready_o.write(chain_.in_ready(out_ready_i.read()));
    out_valid_o.write(chain_.out_valid());
    const TrvStepOut& o = chain_.out();
    out_op_o.write(o.op != 0);
    out_hit_o.write(o.hit != 0);
    out_visit_o.write(o.visit);
    out_below_o.write(o.below != 0);
    out_tsplit_o.write(o.tsplit);
    out_tnear_o.write(o.tnear);
    out_tfar_o.write(o.tfar);
    out_node_o.write(o.node);
    out_far_node_o.write(o.far_node);
    out_far_tfar_o.write(o.far_tfar);
    out_tag_o.write(o.tag);
  }

  uint32_t tag_mask_;
  ReadyChain<TrvStepOut> chain_;
  sc_core::sc_signal<bool> changed_;
};

}  // namespace raycore::sc::pins
