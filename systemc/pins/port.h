// systemc/pins/port.h - what the pin-level units with a valid/ready datapath (vtu, ist, trv) share:
// the signals, the bind template, the SystemC twin's ports and handshake, and the cycle-level Port
// the cycle model (or a lockstep test) drives. A unit writes only its pin list, its records and
// its computation; everything else is generated here from the list, so the twin and the Verilated
// --sc model are bound by one template (a port whose name or type differed would not compile).
//
// Every unit has clk_i, rst_ni and the handshake in_valid_i / in_ready_o / out_valid_o /
// out_ready_i. Its data pins are a list macro LIST(CFG, IN, OUT, E), one entry per pin or group:
//   CFG(E, type, name, shape)  port name[sfx]_i       signal s.name[sfx]      (no record field)
//   IN(E, type, name, shape)   port in_name[sfx]_i    signal s.in_name[sfx]   field In::name[i]
//   OUT(E, type, name, shape)  port out_name[sfx]_o   signal s.out_name[sfx]  field Out::name[i]
// shape: one (a single pin, no sfx), xyz (sfx _x _y _z = field [0..2]), n4 (sfx 0..3 = [0..3]),
// c9 (sfx 0..8 = [0..8]).
// type is the Verilated --sc port type (toolchain.md pitfall 14: 1 bit bool, 2..32 bits uint32_t,
// 33..64 bits uint64_t); record fields convert to and from it with static_cast.
//
// RAYCORE_PINS_UNIT(Name, LIST, In, Out) then defines struct Name with
//   Signals                the wires: the handshake and one sc_signal per data pin;
//   Ports                  the twin's sc_in / sc_out, read_in() and write_out();
//   bind(m, s, clk, rst_n) binds every port of m (the twin or a Verilated model) to s;
//   drive(s, in), get(s)   the IN pins from a record, a record from the OUT pins.
#pragma once

#include <systemc>

#include <cstdint>
#include <utility>

#include "systemc/pins/chain.h"

// One entry of a list, for each of its pins: E(io, type, port, signal, field).
#define RAYCORE_PINS_EACH_one(E, io, T, pre, name, post) E(io, T, pre##name##post, pre##name, name)
#define RAYCORE_PINS_EACH_xyz(E, io, T, pre, name, post)   \
  E(io, T, pre##name##_x##post, pre##name##_x, name[0]) \
  E(io, T, pre##name##_y##post, pre##name##_y, name[1]) \
  E(io, T, pre##name##_z##post, pre##name##_z, name[2])
#define RAYCORE_PINS_EACH_n4(E, io, T, pre, name, post)  \
  E(io, T, pre##name##0##post, pre##name##0, name[0]) \
  E(io, T, pre##name##1##post, pre##name##1, name[1]) \
  E(io, T, pre##name##2##post, pre##name##2, name[2]) \
  E(io, T, pre##name##3##post, pre##name##3, name[3])
#define RAYCORE_PINS_EACH_c9(E, io, T, pre, name, post)  \
  E(io, T, pre##name##0##post, pre##name##0, name[0]) \
  E(io, T, pre##name##1##post, pre##name##1, name[1]) \
  E(io, T, pre##name##2##post, pre##name##2, name[2]) \
  E(io, T, pre##name##3##post, pre##name##3, name[3]) \
  E(io, T, pre##name##4##post, pre##name##4, name[4]) \
  E(io, T, pre##name##5##post, pre##name##5, name[5]) \
  E(io, T, pre##name##6##post, pre##name##6, name[6]) \
  E(io, T, pre##name##7##post, pre##name##7, name[7]) \
  E(io, T, pre##name##8##post, pre##name##8, name[8])

// The three kinds of entry, and SKIP for a kind a pass leaves out.
#define RAYCORE_PINS_CFG(E, T, name, shape) RAYCORE_PINS_EACH_##shape(E, in, T, , name, _i)
#define RAYCORE_PINS_IN(E, T, name, shape) RAYCORE_PINS_EACH_##shape(E, in, T, in_, name, _i)
#define RAYCORE_PINS_OUT(E, T, name, shape) RAYCORE_PINS_EACH_##shape(E, out, T, out_, name, _o)
#define RAYCORE_PINS_SKIP(E, T, name, shape)

// What one pin becomes in each pass.
#define RAYCORE_PINS_SIGNAL(io, T, port, sig, field) sc_core::sc_signal<T> sig;
#define RAYCORE_PINS_PORT(io, T, port, sig, field) sc_core::sc_##io<T> port;
#define RAYCORE_PINS_BIND(io, T, port, sig, field) m.port(s.sig);
#define RAYCORE_PINS_DRIVE(io, T, port, sig, field) s.sig.write(static_cast<T>(r.field));
#define RAYCORE_PINS_GET(io, T, port, sig, field) \
  ::raycore::sc::pins::detail::put(r.field, s.sig.read());
#define RAYCORE_PINS_READ(io, T, port, sig, field) \
  ::raycore::sc::pins::detail::put(r.field, port.read());
#define RAYCORE_PINS_WRITE(io, T, port, sig, field) port.write(static_cast<T>(r.field));

#define RAYCORE_PINS_UNIT(NAME, LIST, IN_T, OUT_T)                                                \
  struct NAME {                                                                                 \
    using In = IN_T;                                                                            \
    using Out = OUT_T;                                                                          \
    struct Signals {                                                                            \
      sc_core::sc_signal<bool> in_valid, in_ready, out_valid, out_ready;                        \
      LIST(RAYCORE_PINS_CFG, RAYCORE_PINS_IN, RAYCORE_PINS_OUT, RAYCORE_PINS_SIGNAL)            \
    };                                                                                          \
    struct Ports {                                                                              \
      sc_core::sc_in<bool> clk_i, rst_ni, in_valid_i;                                           \
      sc_core::sc_out<bool> in_ready_o, out_valid_o;                                            \
      sc_core::sc_in<bool> out_ready_i;                                                         \
      LIST(RAYCORE_PINS_CFG, RAYCORE_PINS_IN, RAYCORE_PINS_OUT, RAYCORE_PINS_PORT)              \
      In read_in() const {                                                                      \
        In r;                                                                                   \
        LIST(RAYCORE_PINS_SKIP, RAYCORE_PINS_IN, RAYCORE_PINS_SKIP, RAYCORE_PINS_READ)          \
        return r;                                                                               \
      }                                                                                         \
      void write_out(const Out& r) {                                                            \
        LIST(RAYCORE_PINS_SKIP, RAYCORE_PINS_SKIP, RAYCORE_PINS_OUT, RAYCORE_PINS_WRITE)        \
      }                                                                                         \
    };                                                                                          \
    template <class M>                                                                          \
    static void bind(M& m, Signals& s, sc_core::sc_signal<bool>& clk,                           \
                     sc_core::sc_signal<bool>& rst_n) {                                         \
      m.clk_i(clk);                                                                             \
      m.rst_ni(rst_n);                                                                          \
      m.in_valid_i(s.in_valid);                                                                 \
      m.in_ready_o(s.in_ready);                                                                 \
      m.out_valid_o(s.out_valid);                                                               \
      m.out_ready_i(s.out_ready);                                                               \
      LIST(RAYCORE_PINS_CFG, RAYCORE_PINS_IN, RAYCORE_PINS_OUT, RAYCORE_PINS_BIND)              \
    }                                                                                           \
    static void drive(Signals& s, const In& r) {                                                \
      LIST(RAYCORE_PINS_SKIP, RAYCORE_PINS_IN, RAYCORE_PINS_SKIP, RAYCORE_PINS_DRIVE)           \
    }                                                                                           \
    static Out get(const Signals& s) {                                                          \
      Out r;                                                                                    \
      LIST(RAYCORE_PINS_SKIP, RAYCORE_PINS_SKIP, RAYCORE_PINS_OUT, RAYCORE_PINS_GET)            \
      return r;                                                                                 \
    }                                                                                           \
  }

namespace raycore::sc::pins {

namespace detail {
// A record field from a pin's value (bool <-> uint32_t as 0 / 1).
template <class D, class S>
void put(D& d, const S& v) {
  d = static_cast<D>(v);
}
}  // namespace detail

// The SystemC twin of an rtl/ unit with the pins of P: computes each input at the rising edge
// that takes it (step(), the derived twin's) and carries the result through a ReadyChain of
// `registers` registers: the RTL's latency and handshake, cycle for cycle.
template <class P>
class PinTwin : public sc_core::sc_module, public P::Ports {
 public:
  using In = typename P::In;
  using Out = typename P::Out;

  SC_HAS_PROCESS(PinTwin);
  PinTwin(sc_core::sc_module_name name, unsigned registers)
      : sc_core::sc_module(name), chain_(registers) {
    SC_METHOD(seq);
    sensitive << this->clk_i.pos() << this->rst_ni.neg();
    dont_initialize();
    SC_METHOD(comb);
    sensitive << this->out_ready_i << changed_;
  }

 protected:
  // The unit's result for one input (read at the edge; other input pins through this->...).
  virtual Out step(const In& in) = 0;

 private:
  void seq() {
    if (!this->rst_ni.read()) {
      chain_.reset();
    } else {
      Out r{};
      const bool valid = this->in_valid_i.read();
      if (valid) r = step(this->read_in());
      chain_.edge(valid, r, this->out_ready_i.read());
    }
    changed_.write(!changed_.read());
  }
  void comb() {
    this->in_ready_o.write(chain_.in_ready(this->out_ready_i.read()));
    this->out_valid_o.write(chain_.out_valid());
    this->write_out(chain_.out());
  }

  ReadyChain<Out> chain_;
  sc_core::sc_signal<bool> changed_;
};

// The cycle-level view of a pin-level unit with the pins of P: write the inputs for this cycle,
// read the outputs the last edge produced. One implementation over the signals; the bound model
// (twin or Verilated) is BoundPort's.
template <class P>
class Port {
 public:
  using Pins = P;
  virtual ~Port() = default;
  void drive(const typename P::In& in) {
    s.in_valid.write(true);
    P::drive(s, in);
  }
  void idle() { s.in_valid.write(false); }
  void out_ready(bool r) { s.out_ready.write(r); }
  bool in_ready() const { return s.in_ready.read(); }
  bool out_valid() const { return s.out_valid.read(); }
  typename P::Out out() const { return P::get(s); }
  virtual const char* model() const = 0;
  typename P::Signals s;
};

// A Port (Base: Port<P> or a unit's class derived from it) with the module M bound to it;
// out_ready starts high.
template <class Base, class M>
class BoundPort : public Base {
 public:
  template <class... Args>
  BoundPort(const char* name, const char* model_name, sc_core::sc_signal<bool>& clk,
            sc_core::sc_signal<bool>& rst_n, Args&&... args)
      : model_(model_name), m_(name, std::forward<Args>(args)...) {
    Base::Pins::bind(m_, this->s, clk, rst_n);
    this->s.out_ready.write(true);
  }
  const char* model() const override { return model_; }
  M& module() { return m_; }

 private:
  const char* model_;
  M m_;
};

}  // namespace raycore::sc::pins
