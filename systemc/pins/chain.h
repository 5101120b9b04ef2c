// systemc/pins/chain.h - the handshake of a fully pipelined rtl/ unit, for its SystemC twins.
//
// Every rtl/ unit is a chain of fp_pipe registers (STAGES per operator level), and each register
// takes a new item when it is empty or when its own item leaves. So an L-register chain has
//   out_valid_o = valid of the last register,
//   in_ready_o  = out_ready_i || some register is empty   (combinational in out_ready_i),
// and at a clock edge each register i whose ready holds takes the item of register i-1 (register 0
// the input, if in_valid_i). ReadyChain<T> is exactly that, with T the payload a twin computes at
// the input (through hls/) and carries to the output; the twins are cycle-for-cycle equal to the
// RTL's handshake (tb/systemc lockstep tests).
#pragma once

#include <stdexcept>
#include <vector>

namespace raycore::sc::pins {

template <class T>
class ReadyChain {
 public:
  explicit ReadyChain(unsigned registers) : v_(registers, false), d_(registers) {
    if (registers == 0) throw std::invalid_argument("ReadyChain: a pin-level twin needs >= 1 register");
  }
  unsigned length() const { return unsigned(v_.size()); }
  bool in_ready(bool out_ready) const {
    if (out_ready) return true;
    for (bool v : v_)
      if (!v) return true;
    return false;
  }
  bool out_valid() const { return v_.back(); }
  bool any() const {  // some register holds an item
    for (bool v : v_)
      if (v) return true;
    return false;
  }
  const T& out() const { return d_.back(); }
  void reset() { v_.assign(v_.size(), false); }
  // One clock edge; in is taken only if in_valid && in_ready(out_ready).
  void edge(bool in_valid, const T& in, bool out_ready) {
    const size_t n = v_.size();
    // ready into register i = !v[i] || ready into register i+1; ready into "n" = out_ready.
    bool ready = out_ready;
    for (size_t i = n; i-- > 0;) {
      const bool r = !v_[i] || ready;
      if (r) {
        if (i == 0) {
          v_[0] = in_valid;
          if (in_valid) d_[0] = in;
        } else {
          v_[i] = v_[i - 1];
          if (v_[i - 1]) d_[i] = d_[i - 1];
        }
      }
      ready = r;
    }
  }

 private:
  std::vector<bool> v_;
  std::vector<T> d_;
};

}  // namespace raycore::sc::pins
