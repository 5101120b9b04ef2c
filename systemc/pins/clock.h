// systemc/pins/clock.h - the clock and reset that pin-level units (SystemC twins or Verilated
// models, bound through the same ports) see inside the cycle model. The model's thread calls
// edge() for a cycle in which a pin-level unit has work: inputs written before it are sampled at
// the rising edge (as a flip-flop samples what the cycle drove), and outputs read after it are the
// registers' new values. Cycles in which no pin-level unit has work get no edge (their registers
// hold, as with a gated clock), so idle units cost no host time.
#pragma once

#include <systemc>

#include <cstdint>

namespace raycore::sc::pins {

class PinClock {
 public:
  explicit PinClock(sc_core::sc_time period) : half_(period / 2.0) {}
  sc_core::sc_signal<bool> clk{"clk_i", false}, rst_n{"rst_ni", false};

  // Call from an SC_THREAD. One full clock period: rising edge, then falling edge.
  void edge() {
    clk.write(true);
    sc_core::wait(half_);
    clk.write(false);
    sc_core::wait(half_);
    ++edges_;
  }
  // rst_ni low for two edges (asynchronous in the RTL; the twins sample it at the edge).
  void reset() {
    rst_n.write(false);
    edge();
    edge();
    rst_n.write(true);
    sc_core::wait(sc_core::SC_ZERO_TIME);
  }
  // Let combinational outputs (in_ready_o after out_ready_i changed) settle without an edge.
  static void settle() {
    sc_core::wait(sc_core::SC_ZERO_TIME);
    sc_core::wait(sc_core::SC_ZERO_TIME);
  }
  uint64_t edges() const { return edges_; }
  sc_core::sc_time period() const { return half_ * 2.0; }

 private:
  sc_core::sc_time half_;
  uint64_t edges_ = 0;
};

}  // namespace raycore::sc::pins
