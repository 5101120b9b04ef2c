// systemc/pins/ist.h - the intersection unit at pin level: the ports of rtl/units/ist.v exactly as
// a Verilated --sc model has them (toolchain.md pitfall 14), its SystemC twin, and IstPort, the
// cycle-level view the cycle model's ist uses with either bound in the same place (bind_ist() is
// one template for both).
//
// The twin computes each test at the input through hls::ist_wald (the one definition of the test)
// and carries {exit, t, den, tag} through a ReadyChain of 10 * STAGES registers: the RTL's latency
// and handshake, cycle for cycle.
#pragma once

#include <systemc>

#include <cstdint>
#include <memory>

#include "hls/ist.h"
#include "systemc/pins/chain.h"

namespace raycore::sc::pins {

// One test in: projection axis, the record's nine constants, the ray, its interval, a tag.
struct IstIn {
  uint32_t k = 0, c[9] = {}, o[3] = {}, d[3] = {}, tmin = 0, tmax = 0, tag = 0;
};
// Its result: hls::IstExit code, t, den, the tag.
struct IstOutRec {
  uint32_t exit = 0, t = 0, den = 0, tag = 0;
};

#define RAYCORE_IST_C(X) X(0) X(1) X(2) X(3) X(4) X(5) X(6) X(7) X(8)

struct IstSignals {
  sc_core::sc_signal<bool> in_valid, in_ready, out_valid, out_ready;
  sc_core::sc_signal<uint32_t> in_k, in_c[9], in_o[3], in_d[3], in_tmin, in_tmax, in_tag;
  sc_core::sc_signal<uint32_t> out_exit, out_t, out_den, out_tag;
};

template <class M>
void bind_ist(M& m, IstSignals& s, sc_core::sc_signal<bool>& clk, sc_core::sc_signal<bool>& rst_n) {
  m.clk_i(clk);
  m.rst_ni(rst_n);
  m.in_valid_i(s.in_valid);
  m.in_ready_o(s.in_ready);
  m.in_k_i(s.in_k);
#define RAYCORE_BIND_IST_C(i) m.in_c##i##_i(s.in_c[i]);
  RAYCORE_IST_C(RAYCORE_BIND_IST_C)
#undef RAYCORE_BIND_IST_C
  m.in_o_x_i(s.in_o[0]);
  m.in_o_y_i(s.in_o[1]);
  m.in_o_z_i(s.in_o[2]);
  m.in_d_x_i(s.in_d[0]);
  m.in_d_y_i(s.in_d[1]);
  m.in_d_z_i(s.in_d[2]);
  m.in_tmin_i(s.in_tmin);
  m.in_tmax_i(s.in_tmax);
  m.in_tag_i(s.in_tag);
  m.out_valid_o(s.out_valid);
  m.out_ready_i(s.out_ready);
  m.out_exit_o(s.out_exit);
  m.out_t_o(s.out_t);
  m.out_den_o(s.out_den);
  m.out_tag_o(s.out_tag);
}

// The SystemC twin of rtl/units/ist.v for the arithmetic A (hls::Arith<F, R>).
template <class A>
class IstTwin : public sc_core::sc_module {
 public:
  sc_core::sc_in<bool> clk_i, rst_ni, in_valid_i;
  sc_core::sc_out<bool> in_ready_o;
  sc_core::sc_in<uint32_t> in_k_i;
  sc_core::sc_in<uint32_t> in_c0_i, in_c1_i, in_c2_i, in_c3_i, in_c4_i, in_c5_i, in_c6_i, in_c7_i,
      in_c8_i;
  sc_core::sc_in<uint32_t> in_o_x_i, in_o_y_i, in_o_z_i, in_d_x_i, in_d_y_i, in_d_z_i;
  sc_core::sc_in<uint32_t> in_tmin_i, in_tmax_i, in_tag_i;
  sc_core::sc_out<bool> out_valid_o;
  sc_core::sc_in<bool> out_ready_i;
  sc_core::sc_out<uint32_t> out_exit_o, out_t_o, out_den_o, out_tag_o;

  SC_HAS_PROCESS(IstTwin);
  IstTwin(sc_core::sc_module_name name, unsigned stages)
      : sc_core::sc_module(name), chain_(10 * stages) {
    SC_METHOD(seq);
    sensitive << clk_i.pos() << rst_ni.neg();
    dont_initialize();
    SC_METHOD(comb);
    sensitive << out_ready_i << changed_;
  }

  // One test as the RTL computes it (k = 3 is treated as k = 0).
  static IstOutRec compute(const IstIn& in) {
    const hls::IstOut x =
        hls::ist_wald<A>(in.k == 3 ? 0 : in.k, in.c, in.o, in.d, in.tmin, in.tmax);
    return IstOutRec{uint32_t(x.exit), x.t, x.den, in.tag};
  }

 private:
  void seq() {
    if (!rst_ni.read()) {
      chain_.reset();
    } else {
      IstOutRec r;
      const bool valid = in_valid_i.read();
      if (valid) {
        IstIn in;
        in.k = in_k_i.read();
        const uint32_t c[9] = {in_c0_i.read(), in_c1_i.read(), in_c2_i.read(),
                               in_c3_i.read(), in_c4_i.read(), in_c5_i.read(),
                               in_c6_i.read(), in_c7_i.read(), in_c8_i.read()};
        for (int i = 0; i < 9; ++i) in.c[i] = c[i];
        in.o[0] = in_o_x_i.read();
        in.o[1] = in_o_y_i.read();
        in.o[2] = in_o_z_i.read();
        in.d[0] = in_d_x_i.read();
        in.d[1] = in_d_y_i.read();
        in.d[2] = in_d_z_i.read();
        in.tmin = in_tmin_i.read();
        in.tmax = in_tmax_i.read();
        in.tag = in_tag_i.read();
        r = compute(in);
      }
      chain_.edge(valid, r, out_ready_i.read());
    }
    changed_.write(!changed_.read());
  }
  void comb() {
    in_ready_o.write(chain_.in_ready(out_ready_i.read()));
    out_valid_o.write(chain_.out_valid());
    const IstOutRec& o = chain_.out();
    out_exit_o.write(o.exit);
    out_t_o.write(o.t);
    out_den_o.write(o.den);
    out_tag_o.write(o.tag);
  }

  ReadyChain<IstOutRec> chain_;
  sc_core::sc_signal<bool> changed_;
};

class IstPort {
 public:
  virtual ~IstPort() = default;
  void drive(const IstIn& in) {
    s.in_valid.write(true);
    s.in_k.write(in.k);
    for (int i = 0; i < 9; ++i) s.in_c[i].write(in.c[i]);
    for (int i = 0; i < 3; ++i) {
      s.in_o[i].write(in.o[i]);
      s.in_d[i].write(in.d[i]);
    }
    s.in_tmin.write(in.tmin);
    s.in_tmax.write(in.tmax);
    s.in_tag.write(in.tag);
  }
  void idle() { s.in_valid.write(false); }
  void out_ready(bool r) { s.out_ready.write(r); }
  bool in_ready() const { return s.in_ready.read(); }
  bool out_valid() const { return s.out_valid.read(); }
  IstOutRec out() const {
    return IstOutRec{s.out_exit.read(), s.out_t.read(), s.out_den.read(), s.out_tag.read()};
  }
  virtual const char* model() const = 0;
  IstSignals s;
};

template <class M>
class IstPortT : public IstPort {
 public:
  template <class... Args>
  IstPortT(const char* name, const char* model_name, sc_core::sc_signal<bool>& clk,
           sc_core::sc_signal<bool>& rst_n, Args&&... args)
      : model_(model_name), m_(name, std::forward<Args>(args)...) {
    bind_ist(m_, s, clk, rst_n);
    s.out_ready.write(true);
  }
  const char* model() const override { return model_; }
  M& module() { return m_; }

 private:
  const char* model_;
  M m_;
};

}  // namespace raycore::sc::pins
