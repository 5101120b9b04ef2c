// systemc/pins/membus_if.h - the memory bus interface at pin level: the ports of
// rtl/units/membus_if.v exactly as a Verilated --sc model has them (toolchain.md pitfall 14: 1 bit
// bool, 2..32 bits uint32_t, 33..64 uint64_t, wider sc_dt::sc_bv<N>), its SystemC twin
// MembusIfTwin, and bind_membus_if() (one template for both).
//
// The rules are systemc/membus.*'s, without the memory behind the bus (its latency and bytes):
// one request accepted per cycle, round-robin from the requester after the last one accepted,
// only while fewer than DEPTH are outstanding (and the memory is ready); lines come back in
// acceptance order as max(1, ceil(bytes / BEAT_BYTES)) beats, each routed (one register) to its
// requester, rsp_last_o on the last one, whose edge frees the slot; take_*_o show the beat taken
// in the cycle (its request's tag, index, last), before its register. See rtl/units/membus_if.v.
#pragma once

#include <systemc>

#include <cstdint>
#include <deque>
#include <type_traits>

namespace raycore::sc::pins {

// The C++ type of a Verilated --sc port of `bits` bits.
template <unsigned bits>
using port_t = std::conditional_t<
    bits == 1, bool,
    std::conditional_t<bits <= 32, uint32_t,
                       std::conditional_t<bits <= 64, uint64_t, sc_dt::sc_bv<bits>>>>;

constexpr unsigned clog2(unsigned v) {
  unsigned b = 0;
  while ((1u << b) < v) ++b;
  return b;
}

// Bits [lo, lo + width) of a port value (width <= 64).
inline uint64_t port_bits(bool v, unsigned lo, unsigned width) {
  return (lo == 0 && width >= 1) ? uint64_t(v) : 0u;
}
inline uint64_t port_bits(uint32_t v, unsigned lo, unsigned width) {
  return width >= 64 ? (uint64_t(v) >> lo) : ((uint64_t(v) >> lo) & ((uint64_t(1) << width) - 1));
}
inline uint64_t port_bits(uint64_t v, unsigned lo, unsigned width) {
  return width >= 64 ? (v >> lo) : ((v >> lo) & ((uint64_t(1) << width) - 1));
}
template <int W>
uint64_t port_bits(const sc_dt::sc_bv<W>& v, unsigned lo, unsigned width) {
  return v.range(int(lo + width - 1), int(lo)).to_uint64();
}
// A value of at most 64 bits as a port value.
template <class T>
T to_port(uint64_t v) {
  if constexpr (std::is_same_v<T, bool>) {
    return (v & 1u) != 0;
  } else if constexpr (std::is_integral_v<T>) {
    return T(v);
  } else {
    T r;
    r = v;
    return r;
  }
}
// Sets bits [lo, lo + width) of a port value (width <= 64).
template <class T>
void set_port_bits(T& p, unsigned lo, unsigned width, uint64_t v) {
  if constexpr (std::is_same_v<T, bool>) {
    p = (v & 1u) != 0;
  } else if constexpr (std::is_integral_v<T>) {
    const uint64_t m = (width >= 64 ? ~uint64_t(0) : ((uint64_t(1) << width) - 1)) << lo;
    p = T((uint64_t(p) & ~m) | ((v << lo) & m));
  } else {
    p.range(int(lo + width - 1), int(lo)) = v;
  }
}

template <unsigned N, unsigned ADDR_BITS = 32, unsigned LEN_BITS = 12, unsigned TAG_BITS = 8,
          unsigned DEPTH = 32, unsigned BEAT_BYTES = 16>
struct MembusIfTypes {
  static constexpr unsigned port_bits = N > 1 ? clog2(N) : 1;
  static constexpr unsigned cnt_bits = clog2(DEPTH + 1);
  static constexpr unsigned data_bits = 8 * BEAT_BYTES;
  using valid_t = port_t<N>;
  using addr_t = port_t<N * ADDR_BITS>;
  using bytes_t = port_t<N * LEN_BITS>;
  using tags_t = port_t<N * TAG_BITS>;
  using maddr_t = port_t<ADDR_BITS>;
  using len_t = port_t<LEN_BITS>;
  using port_idx_t = port_t<port_bits>;
  using tag_t = port_t<TAG_BITS>;
  using data_t = port_t<data_bits>;
  using cnt_t = port_t<cnt_bits>;
};

template <class T>
struct MembusIfSignals {
  sc_core::sc_signal<typename T::valid_t> req_valid, req_ready, rsp_valid;
  sc_core::sc_signal<typename T::addr_t> req_addr;
  sc_core::sc_signal<typename T::bytes_t> req_bytes;
  sc_core::sc_signal<typename T::tags_t> req_tag;
  sc_core::sc_signal<bool> mem_valid, mem_ready, beat_valid, rsp_last, take, take_last;
  sc_core::sc_signal<typename T::maddr_t> mem_addr;
  sc_core::sc_signal<typename T::len_t> mem_bytes, rsp_beat, take_beat;
  sc_core::sc_signal<typename T::port_idx_t> mem_port, rsp_port;
  sc_core::sc_signal<typename T::tag_t> mem_tag, rsp_tag, take_tag;
  sc_core::sc_signal<typename T::data_t> beat_data, rsp_data;
  sc_core::sc_signal<typename T::cnt_t> outstanding;
};

// Binds a membus_if at pin level (MembusIfTwin or a Verilated --sc model) to the signals.
template <class M, class S>
void bind_membus_if(M& m, S& s, sc_core::sc_signal<bool>& clk, sc_core::sc_signal<bool>& rst_n) {
  m.clk_i(clk);
  m.rst_ni(rst_n);
  m.req_valid_i(s.req_valid);
  m.req_ready_o(s.req_ready);
  m.req_addr_i(s.req_addr);
  m.req_bytes_i(s.req_bytes);
  m.req_tag_i(s.req_tag);
  m.mem_valid_o(s.mem_valid);
  m.mem_ready_i(s.mem_ready);
  m.mem_addr_o(s.mem_addr);
  m.mem_bytes_o(s.mem_bytes);
  m.mem_port_o(s.mem_port);
  m.mem_tag_o(s.mem_tag);
  m.beat_valid_i(s.beat_valid);
  m.beat_data_i(s.beat_data);
  m.rsp_valid_o(s.rsp_valid);
  m.rsp_port_o(s.rsp_port);
  m.rsp_tag_o(s.rsp_tag);
  m.rsp_data_o(s.rsp_data);
  m.rsp_beat_o(s.rsp_beat);
  m.rsp_last_o(s.rsp_last);
  m.outstanding_o(s.outstanding);
  m.take_o(s.take);
  m.take_tag_o(s.take_tag);
  m.take_beat_o(s.take_beat);
  m.take_last_o(s.take_last);
}

// The SystemC twin of rtl/units/membus_if.v with the same parameters.
template <unsigned N, unsigned ADDR_BITS = 32, unsigned LEN_BITS = 12, unsigned TAG_BITS = 8,
          unsigned DEPTH = 32, unsigned BEAT_BYTES = 16>
class MembusIfTwin : public sc_core::sc_module {
  static_assert(N >= 1 && DEPTH >= 1 && BEAT_BYTES >= 1, "membus_if: N, DEPTH, BEAT_BYTES >= 1");
  static_assert(ADDR_BITS <= 64 && LEN_BITS < 64 && TAG_BITS <= 64, "fields of at most 64 bits");

 public:
  using T = MembusIfTypes<N, ADDR_BITS, LEN_BITS, TAG_BITS, DEPTH, BEAT_BYTES>;
  sc_core::sc_in<bool> clk_i, rst_ni;
  sc_core::sc_in<typename T::valid_t> req_valid_i;
  sc_core::sc_out<typename T::valid_t> req_ready_o;
  sc_core::sc_in<typename T::addr_t> req_addr_i;
  sc_core::sc_in<typename T::bytes_t> req_bytes_i;
  sc_core::sc_in<typename T::tags_t> req_tag_i;
  sc_core::sc_out<bool> mem_valid_o;
  sc_core::sc_in<bool> mem_ready_i;
  sc_core::sc_out<typename T::maddr_t> mem_addr_o;
  sc_core::sc_out<typename T::len_t> mem_bytes_o;
  sc_core::sc_out<typename T::port_idx_t> mem_port_o;
  sc_core::sc_out<typename T::tag_t> mem_tag_o;
  sc_core::sc_in<bool> beat_valid_i;
  sc_core::sc_in<typename T::data_t> beat_data_i;
  sc_core::sc_out<typename T::valid_t> rsp_valid_o;
  sc_core::sc_out<typename T::port_idx_t> rsp_port_o;
  sc_core::sc_out<typename T::tag_t> rsp_tag_o;
  sc_core::sc_out<typename T::data_t> rsp_data_o;
  sc_core::sc_out<typename T::len_t> rsp_beat_o;
  sc_core::sc_out<bool> rsp_last_o;
  sc_core::sc_out<typename T::cnt_t> outstanding_o;
  sc_core::sc_out<bool> take_o;
  sc_core::sc_out<typename T::tag_t> take_tag_o;
  sc_core::sc_out<typename T::len_t> take_beat_o;
  sc_core::sc_out<bool> take_last_o;

  SC_HAS_PROCESS(MembusIfTwin);
  explicit MembusIfTwin(sc_core::sc_module_name name) : sc_core::sc_module(name) {
    SC_METHOD(seq);
    sensitive << clk_i.pos() << rst_ni.neg();
    dont_initialize();
    SC_METHOD(comb);
    sensitive << req_valid_i << req_addr_i << req_bytes_i << req_tag_i << mem_ready_i << beat_valid_i
              << changed_;
  }

 private:
  struct Entry {
    uint32_t port = 0;
    uint64_t tag = 0, bytes = 0;
  };
  struct Grant {
    bool found = false;
    uint32_t port = 0;
  };
  // Membus::tick's search: the first valid requester from rr_.
  Grant arbitrate() const {
    const auto v = req_valid_i.read();
    for (uint32_t k = 0; k < N; ++k) {
      const uint32_t i = (rr_ + k) % N;
      if (port_bits(v, i, 1)) return {true, i};
    }
    return {};
  }
  bool room() const { return fifo_.size() < DEPTH; }

  void seq() {
    if (!rst_ni.read()) {
      rr_ = 0;
      fifo_.clear();
      done_ = beat_ = 0;
      rsp_valid_ = 0;
    } else {
      const Grant g = arbitrate();
      const bool accept = g.found && room() && mem_ready_i.read();
      const bool take = beat_valid_i.read() && !fifo_.empty();
      rsp_valid_ = 0;
      if (take) {
        const Entry h = fifo_.front();
        const bool last = done_ + BEAT_BYTES >= h.bytes;
        rsp_valid_ = uint64_t(1) << h.port;
        rsp_port_ = h.port;
        rsp_tag_ = h.tag;
        rsp_data_ = beat_data_i.read();
        rsp_beat_ = beat_;
        rsp_last_ = last;
        if (last) {
          done_ = beat_ = 0;
          fifo_.pop_front();
        } else {
          done_ += BEAT_BYTES;
          ++beat_;
        }
      }
      if (accept) {
        fifo_.push_back({g.port, port_bits(req_tag_i.read(), g.port * TAG_BITS, TAG_BITS),
                         port_bits(req_bytes_i.read(), g.port * LEN_BITS, LEN_BITS)});
        rr_ = (g.port + 1) % N;
      }
    }
    changed_.write(!changed_.read());
  }

  void comb() {
    const Grant g = arbitrate();
    const bool valid = g.found && room();
    const bool accept = valid && mem_ready_i.read();
    mem_valid_o.write(valid);
    mem_addr_o.write(to_port<typename T::maddr_t>(
        port_bits(req_addr_i.read(), g.port * ADDR_BITS, ADDR_BITS)));
    mem_bytes_o.write(to_port<typename T::len_t>(
        port_bits(req_bytes_i.read(), g.port * LEN_BITS, LEN_BITS)));
    mem_port_o.write(to_port<typename T::port_idx_t>(g.port));
    mem_tag_o.write(to_port<typename T::tag_t>(
        port_bits(req_tag_i.read(), g.port * TAG_BITS, TAG_BITS)));
    req_ready_o.write(to_port<typename T::valid_t>(accept ? uint64_t(1) << g.port : 0u));
    rsp_valid_o.write(to_port<typename T::valid_t>(rsp_valid_));
    rsp_port_o.write(to_port<typename T::port_idx_t>(rsp_port_));
    rsp_tag_o.write(to_port<typename T::tag_t>(rsp_tag_));
    rsp_data_o.write(rsp_data_);
    rsp_beat_o.write(to_port<typename T::len_t>(rsp_beat_));
    rsp_last_o.write(rsp_last_);
    outstanding_o.write(to_port<typename T::cnt_t>(fifo_.size()));
    const bool take = beat_valid_i.read() && !fifo_.empty();
    take_o.write(take);
    // The head's fields (the RTL's register file reads its head whatever the beat): only the
    // taken beat's are compared.
    take_tag_o.write(to_port<typename T::tag_t>(take ? fifo_.front().tag : 0u));
    take_beat_o.write(to_port<typename T::len_t>(beat_));
    take_last_o.write(take && done_ + BEAT_BYTES >= fifo_.front().bytes);
  }

  uint32_t rr_ = 0;
  std::deque<Entry> fifo_;
  uint64_t done_ = 0, beat_ = 0;
  uint64_t rsp_valid_ = 0, rsp_tag_ = 0, rsp_beat_ = 0;
  uint32_t rsp_port_ = 0;
  typename T::data_t rsp_data_{};
  bool rsp_last_ = false;
  sc_core::sc_signal<bool> changed_;
};

}  // namespace raycore::sc::pins
