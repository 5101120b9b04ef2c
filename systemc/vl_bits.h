// systemc/vl_bits.h - bit fields of Verilated --cc ports (an integer type or a VlWide), for the
// C++ bindings that step a Verilated model from the cycle model (trv_rtl.cpp, ascache_rtl.cpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "hls/fp.h"
#include "hls/image.h"

namespace raycore::sc::vl {

// Bits [lo, lo + n) of a port, n <= 32.
template <class T>
uint32_t get_bits(const T& s, unsigned lo, unsigned n) {
  if constexpr (std::is_integral_v<T>) {
    return uint32_t((uint64_t(s) >> lo) & ((uint64_t(1) << n) - 1));
  } else {
    uint64_t w = s[lo / 32];
    if (lo % 32 + n > 32) w |= uint64_t(s[lo / 32 + 1]) << 32;
    return uint32_t((w >> (lo % 32)) & ((uint64_t(1) << n) - 1));
  }
}
// Sets bits [lo, lo + n) of a port to v, n <= 32.
template <class T>
void set_bits(T& s, unsigned lo, unsigned n, uint32_t v) {
  const uint64_t mask = ((uint64_t(1) << n) - 1);
  if constexpr (std::is_integral_v<T>) {
    s = T((uint64_t(s) & ~(mask << lo)) | ((uint64_t(v) & mask) << lo));
  } else {
    for (unsigned b = 0; b < n;) {  // word by word
      const unsigned i = (lo + b) / 32, o = (lo + b) % 32, k = std::min(n - b, 32 - o);
      const uint32_t m = k == 32 ? ~0u : ((1u << k) - 1) << o;
      s[i] = (s[i] & ~m) | ((uint32_t(v >> b) << o) & m);
      b += k;
    }
  }
}

// n bytes of a port from bit lo on (byte i at bits [lo + 8i, lo + 8i + 8)), into out.
template <class T>
void get_bytes(const T& s, unsigned lo, unsigned n, uint8_t* out) {
  for (unsigned i = 0; i < n; i += 4) {
    const unsigned k = std::min(4u, n - i);
    const uint32_t v = get_bits(s, lo + 8 * i, 8 * k);
    for (unsigned b = 0; b < k; ++b) out[i + b] = uint8_t(v >> (8 * b));
  }
}
// n bytes from in into a port from bit lo on.
template <class T>
void set_bytes(T& s, unsigned lo, unsigned n, const uint8_t* in) {
  for (unsigned i = 0; i < n; i += 4) {
    const unsigned k = std::min(4u, n - i);
    uint32_t v = 0;
    for (unsigned b = 0; b < k; ++b) v |= uint32_t(in[i + b]) << (8 * b);
    set_bits(s, lo + 8 * i, 8 * k, v);
  }
}

// The asynchronous reset of a model with clk_i and rst_ni (active low): a falling edge of rst_ni
// (Verilator's inputs start at 0, so driving 0 first would be no edge and reset nothing), then
// released, the clock low.
// With edges > 0, the clock rises that many times while the reset is held: the registers without a
// reset load their inputs (rtu.v's frame registers), the reset ones stay reset.
template <class M>
void async_reset(M& m, int edges = 0) {
  m.clk_i = 0;
  m.rst_ni = 1;
  m.eval();
  m.rst_ni = 0;
  m.eval();
  for (int e = 0; e < edges; ++e) {
    m.clk_i = 1;
    m.eval();
    m.clk_i = 0;
    m.eval();
  }
  m.rst_ni = 1;
  m.eval();
}

// A 32-bit cycle number of an RTL model (its ready cycles, compared with now_i as a signed
// difference) as a cycle of the model, within 2^31 of now.
inline uint64_t cycle_at(uint64_t now, uint32_t c) {
  return uint64_t(int64_t(now) + int32_t(c - uint32_t(now)));
}

// The units with a ready-cycle queue stepped from C++ (ist_unit, hit_unit: head_valid_o,
// head_ready_o, busy_o, now_i, clk_i). A cycle changes such a unit only while something is inside
// it or its head is ready; otherwise neither evaluate nor clock it (every register holds).
template <class M>
bool queue_steps(const M& m, uint64_t now) {
  return m.busy_o || (m.head_valid_o && cycle_at(now, m.head_ready_o) <= now);
}
// Its next event for the cycle model: the next cycle while busy, else the head's ready cycle.
template <class M>
uint64_t queue_next_event(const M& m, uint64_t now) {
  if (m.busy_o) return now + 1;
  if (!m.head_valid_o) return ~uint64_t(0);
  return cycle_at(now, m.head_ready_o);
}
// The cycle's clock edge, after its pushes were driven: none if the unit neither stepped nor got
// pushes; if it got only pushes, first the cycle's other inputs as its tick would drive them
// (idle(m)), then the rising edge.
template <class M, class Idle>
void queue_edge(M& m, bool stepped, bool pushes, uint64_t now, Idle idle) {
  if (!stepped && !pushes) return;
  if (!stepped) {
    m.clk_i = 0;
    m.now_i = uint32_t(now);
    idle(m);
    m.eval();
  }
  m.clk_i = 1;  // the inputs and the rising edge in one evaluation
  m.eval();
}

// A built model's format and rounding as its variant line spells them ("FP24", "rtz" | "rne" |
// "raycore") against the frame's.
inline bool variant_is(const char* fmt, const char* mode, hls::FormatId f, hls::Rounding r) {
  const hls::FormatId mf = std::strcmp(fmt, "FP24") == 0 ? hls::FormatId::fp24 : hls::FormatId::fp32;
  const hls::Rounding mr = std::strcmp(mode, "rne") == 0       ? hls::Rounding::rne
                           : std::strcmp(mode, "raycore") == 0 ? hls::Rounding::raycore
                                                               : hls::Rounding::rtz;
  return mf == f && mr == r;
}

}  // namespace raycore::sc::vl
