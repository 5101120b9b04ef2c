// systemc/pins/vtu.h - the VTU at pin level: the ports of rtl/units/vtu.v exactly as a Verilated
// --sc model has them (names, and types per toolchain.md pitfall 14: 1 bit bool, 2..32 bits
// uint32_t, 33..64 bits uint64_t), the SystemC twin behind those ports, and VtuPort: the
// cycle-level view the cycle model's vtu unit uses, with either the twin or the Verilated model
// bound in the same place (bind() is one template for both, so a port whose name or type differed
// would not compile).
//
// The twin computes each record at the input through hls::Vtu (the one definition of the
// transform) and carries it through a ReadyChain of 3 * STAGES registers: the RTL's latency and
// handshake, cycle for cycle (tb/systemc/test_pins.cpp runs both side by side).
#pragma once

#include <systemc>

#include <cstdint>
#include <memory>

#include "hls/image.h"
#include "hls/vtu.h"
#include "hls/wald.h"
#include "systemc/pins/chain.h"

namespace raycore::sc::pins {

// One record on either side of the unit (node: kind 0, node; triangle: kind 1, the rest).
struct VtuRec {
  bool kind = false;
  uint64_t node = 0;
  uint32_t k = 0, flags = 0, c[9] = {}, id = 0, tag = 0;
};

#define RAYCORE_VTU_C(X) X(0) X(1) X(2) X(3) X(4) X(5) X(6) X(7) X(8)

// The wires between the cycle model and a unit with vtu.v's ports.
struct VtuSignals {
  sc_core::sc_signal<bool> vtu_on, in_valid, in_ready, in_kind, out_valid, out_ready, out_kind;
  sc_core::sc_signal<uint32_t> cam_x, cam_y, cam_z, in_k, in_flags, in_id, in_tag;
  sc_core::sc_signal<uint32_t> out_k, out_flags, out_id, out_tag;
  sc_core::sc_signal<uint64_t> in_node, out_node;
  sc_core::sc_signal<uint32_t> in_c[9], out_c[9];
};

// Binds every port of M (the twin or a Verilated vtu) to s, clock and reset.
template <class M>
void bind_vtu(M& m, VtuSignals& s, sc_core::sc_signal<bool>& clk, sc_core::sc_signal<bool>& rst_n) {
  m.clk_i(clk);
  m.rst_ni(rst_n);
  m.vtu_on_i(s.vtu_on);
  m.cam_x_i(s.cam_x);
  m.cam_y_i(s.cam_y);
  m.cam_z_i(s.cam_z);
  m.in_valid_i(s.in_valid);
  m.in_ready_o(s.in_ready);
  m.in_kind_i(s.in_kind);
  m.in_node_i(s.in_node);
  m.in_k_i(s.in_k);
  m.in_flags_i(s.in_flags);
#define RAYCORE_BIND_IN_C(i) m.in_c##i##_i(s.in_c[i]);
  RAYCORE_VTU_C(RAYCORE_BIND_IN_C)
#undef RAYCORE_BIND_IN_C
  m.in_id_i(s.in_id);
  m.in_tag_i(s.in_tag);
  m.out_valid_o(s.out_valid);
  m.out_ready_i(s.out_ready);
  m.out_kind_o(s.out_kind);
  m.out_node_o(s.out_node);
  m.out_k_o(s.out_k);
  m.out_flags_o(s.out_flags);
#define RAYCORE_BIND_OUT_C(i) m.out_c##i##_o(s.out_c[i]);
  RAYCORE_VTU_C(RAYCORE_BIND_OUT_C)
#undef RAYCORE_BIND_OUT_C
  m.out_id_o(s.out_id);
  m.out_tag_o(s.out_tag);
}

// The SystemC twin of rtl/units/vtu.v (format F, rounding R, STAGES registers per operator level).
template <class F, hls::Rounding R>
class VtuTwin : public sc_core::sc_module {
 public:
  sc_core::sc_in<bool> clk_i, rst_ni, vtu_on_i;
  sc_core::sc_in<uint32_t> cam_x_i, cam_y_i, cam_z_i;
  sc_core::sc_in<bool> in_valid_i;
  sc_core::sc_out<bool> in_ready_o;
  sc_core::sc_in<bool> in_kind_i;
  sc_core::sc_in<uint64_t> in_node_i;
  sc_core::sc_in<uint32_t> in_k_i, in_flags_i;
  sc_core::sc_in<uint32_t> in_c0_i, in_c1_i, in_c2_i, in_c3_i, in_c4_i, in_c5_i, in_c6_i, in_c7_i,
      in_c8_i;
  sc_core::sc_in<uint32_t> in_id_i, in_tag_i;
  sc_core::sc_out<bool> out_valid_o;
  sc_core::sc_in<bool> out_ready_i;
  sc_core::sc_out<bool> out_kind_o;
  sc_core::sc_out<uint64_t> out_node_o;
  sc_core::sc_out<uint32_t> out_k_o, out_flags_o;
  sc_core::sc_out<uint32_t> out_c0_o, out_c1_o, out_c2_o, out_c3_o, out_c4_o, out_c5_o, out_c6_o,
      out_c7_o, out_c8_o;
  sc_core::sc_out<uint32_t> out_id_o, out_tag_o;

  SC_HAS_PROCESS(VtuTwin);
  VtuTwin(sc_core::sc_module_name name, unsigned stages)
      : sc_core::sc_module(name), chain_(3 * stages) {
    SC_METHOD(seq);
    sensitive << clk_i.pos() << rst_ni.neg();
    dont_initialize();
    SC_METHOD(comb);
    sensitive << out_ready_i << changed_;
  }

  // The transform of one record, as the RTL computes it (k = 3 is treated as k = 0).
  static VtuRec compute(const VtuRec& in, bool on, const uint32_t cam[3]) {
    if (!on) return in;
    hls::Vtu<F, R> v;
    for (int i = 0; i < 3; ++i) v.c[i] = cam[i];
    VtuRec o = in;
    if (!in.kind) {
      o.node = v.node(in.node);
      return o;
    }
    hls::WaldTri<F> t;
    t.k = in.k == 3 ? 0 : in.k;
    t.flags = in.flags;
    for (int i = 0; i < 9; ++i) t.c[i] = in.c[i];
    t.id = in.id;
    const hls::WaldTri<F> r = v.tri(t);
    for (int i = 0; i < 9; ++i) o.c[i] = r.c[i];
    return o;
  }

 private:
  void seq() {
    if (!rst_ni.read()) {
      chain_.reset();
    } else {
      VtuRec in;
      const bool valid = in_valid_i.read();
      if (valid) {
        in.kind = in_kind_i.read();
        in.node = in_node_i.read();
        in.k = in_k_i.read();
        in.flags = in_flags_i.read();
        const uint32_t c[9] = {in_c0_i.read(), in_c1_i.read(), in_c2_i.read(),
                               in_c3_i.read(), in_c4_i.read(), in_c5_i.read(),
                               in_c6_i.read(), in_c7_i.read(), in_c8_i.read()};
        for (int i = 0; i < 9; ++i) in.c[i] = c[i];
        in.id = in_id_i.read();
        in.tag = in_tag_i.read();
        const uint32_t cam[3] = {cam_x_i.read(), cam_y_i.read(), cam_z_i.read()};
        in = compute(in, vtu_on_i.read(), cam);
      }
      chain_.edge(valid, in, out_ready_i.read());
    }
    changed_.write(!changed_.read());
  }
  void comb() {
    in_ready_o.write(chain_.in_ready(out_ready_i.read()));
    out_valid_o.write(chain_.out_valid());
    const VtuRec& o = chain_.out();
    out_kind_o.write(o.kind);
    out_node_o.write(o.node);
    out_k_o.write(o.k);
    out_flags_o.write(o.flags);
    sc_core::sc_out<uint32_t>* oc[9] = {&out_c0_o, &out_c1_o, &out_c2_o, &out_c3_o, &out_c4_o,
                                        &out_c5_o, &out_c6_o, &out_c7_o, &out_c8_o};
    for (int i = 0; i < 9; ++i) oc[i]->write(o.c[i]);
    out_id_o.write(o.id);
    out_tag_o.write(o.tag);
  }

  ReadyChain<VtuRec> chain_;
  sc_core::sc_signal<bool> changed_;
};

// The cycle-level view of a pin-level VTU: write inputs for this cycle, read the outputs the last
// edge produced. One implementation over the signals; the bound model is the derived class's.
class VtuPort {
 public:
  virtual ~VtuPort() = default;
  void config(bool on, const uint32_t cam[3]) {
    s.vtu_on.write(on);
    s.cam_x.write(cam[0]);
    s.cam_y.write(cam[1]);
    s.cam_z.write(cam[2]);
  }
  void drive(const VtuRec& r) {
    s.in_valid.write(true);
    s.in_kind.write(r.kind);
    s.in_node.write(r.node);
    s.in_k.write(r.k);
    s.in_flags.write(r.flags);
    for (int i = 0; i < 9; ++i) s.in_c[i].write(r.c[i]);
    s.in_id.write(r.id);
    s.in_tag.write(r.tag);
  }
  void idle() { s.in_valid.write(false); }
  void out_ready(bool r) { s.out_ready.write(r); }
  bool in_ready() const { return s.in_ready.read(); }
  bool out_valid() const { return s.out_valid.read(); }
  VtuRec out() const {
    VtuRec r;
    r.kind = s.out_kind.read();
    r.node = s.out_node.read();
    r.k = s.out_k.read();
    r.flags = s.out_flags.read();
    for (int i = 0; i < 9; ++i) r.c[i] = s.out_c[i].read();
    r.id = s.out_id.read();
    r.tag = s.out_tag.read();
    return r;
  }
  virtual const char* model() const = 0;
  VtuSignals s;
};

template <class M>
class VtuPortT : public VtuPort {
 public:
  template <class... Args>
  VtuPortT(const char* name, const char* model_name, sc_core::sc_signal<bool>& clk,
           sc_core::sc_signal<bool>& rst_n, Args&&... args)
      : model_(model_name), m_(name, std::forward<Args>(args)...) {
    bind_vtu(m_, s, clk, rst_n);
    s.out_ready.write(true);
  }
  const char* model() const override { return model_; }
  M& module() { return m_; }

 private:
  const char* model_;
  M m_;
};

}  // namespace raycore::sc::pins
