// systemc/pins/ascache.h - the AS cache at pin level: the ports of rtl/units/ascache.v exactly as a
// Verilated --sc model has them (names, and types per toolchain.md pitfall 14: 1 bit bool, 2..32
// bits uint32_t, the line sc_dt::sc_bv<8 * LINE_BYTES>), and AscacheTwin: the SystemC twin behind
// those ports, whose behaviour is raycore::sc::Ascache (systemc/ascache.h, the one definition of
// the cache policy: lookup, LRU victim, MSHR allocate / merge / full, fill). The twin only maps
// pins to that class's calls, in the RTL's order within a clock edge:
//
//   1. request pop   req_valid_o && req_ready_i   -> Ascache::req().pop()
//   2. fill          fill_valid_i                 -> fill_data_i into Ascache::mshr_data(tag),
//                                                    then Ascache::fill(tag) (its victim chosen
//                                                    now, installed at this edge)
//   3. access        acc_valid_i                  -> Ascache::access(acc_line_i) with now = the
//                                                    cycle; the result (hit + line, or the miss
//                                                    kind, told by which counter moved) enters a
//                                                    delay line of hit_latency registers
//
// and after the edge (Ascache::advance to the next cycle: the fill installed, its MSHR free):
// rsp_* = the delay line's end, req_valid_o = Ascache::req().can_pop(next
// cycle) (a request is visible the cycle after its miss, as Ascache pushes it with ready now + 1),
// req_line_o / req_tag_o = its head, mshr_busy_o, cnt_* = Ascache::mshrs_busy(), stats(). Every
// output is registered (no combinational path from an input), as in the RTL. rsp_hit_o ..
// rsp_data_o hold the last response's values while rsp_valid_o is low; rsp_data_o holds the last
// hit's line (both as the RTL's registers, which load only on a valid response / a hit).
//
// Limits of the twin (the RTL has none of them): MSHRS >= 3 (so the MSHR index ports are uint32_t,
// not bool), TAG_BITS and LINE_W 2..32; a fill of a free or out-of-range MSHR throws (Ascache::fill
// does; the RTL ignores it); reset (rst_ni low) is allowed only before the first access or fill,
// since Ascache has no reset (it would need `void reset();` clearing tags, stamps, clock, MSHRs,
// request queue and stats).
#pragma once

#include <systemc>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "systemc/ascache.h"
#include "systemc/config.h"

namespace raycore::sc::pins {

// The wires between a testbench (or the cycle model) and a unit with ascache.v's ports.
template <unsigned LINE_BYTES>
struct AscacheSignals {
  using Line = sc_dt::sc_bv<8 * LINE_BYTES>;
  sc_core::sc_signal<bool> acc_valid, rsp_valid, rsp_hit, rsp_merge, rsp_full, rsp_set_full,
      req_valid, req_ready, fill_valid;
  sc_core::sc_signal<uint32_t> acc_line, acc_tag, rsp_tag, req_line, req_tag, fill_tag, mshr_busy;
  sc_core::sc_signal<uint32_t> cnt_hits, cnt_misses, cnt_merges, cnt_full, cnt_set_full, cnt_fills;
  sc_core::sc_signal<Line> rsp_data, fill_data;
};

// Binds every port of M (the twin or a Verilated ascache) to s, clock and reset. One template for
// both, so a port whose name or type differed would not compile.
template <class M, unsigned LINE_BYTES>
void bind_ascache(M& m, AscacheSignals<LINE_BYTES>& s, sc_core::sc_signal<bool>& clk,
                  sc_core::sc_signal<bool>& rst_n) {
  m.clk_i(clk);
  m.rst_ni(rst_n);
  m.acc_valid_i(s.acc_valid);
  m.acc_line_i(s.acc_line);
  m.acc_tag_i(s.acc_tag);
  m.rsp_valid_o(s.rsp_valid);
  m.rsp_hit_o(s.rsp_hit);
  m.rsp_merge_o(s.rsp_merge);
  m.rsp_full_o(s.rsp_full);
  m.rsp_set_full_o(s.rsp_set_full);
  m.rsp_tag_o(s.rsp_tag);
  m.rsp_data_o(s.rsp_data);
  m.req_valid_o(s.req_valid);
  m.req_ready_i(s.req_ready);
  m.req_line_o(s.req_line);
  m.req_tag_o(s.req_tag);
  m.fill_valid_i(s.fill_valid);
  m.fill_tag_i(s.fill_tag);
  m.fill_data_i(s.fill_data);
  m.mshr_busy_o(s.mshr_busy);
  m.cnt_hits_o(s.cnt_hits);
  m.cnt_misses_o(s.cnt_misses);
  m.cnt_merges_o(s.cnt_merges);
  m.cnt_full_o(s.cnt_full);
  m.cnt_set_full_o(s.cnt_set_full);
  m.cnt_fills_o(s.cnt_fills);
}

// A line as bytes <-> the sc_bv of a port (byte i at bits [8i+7:8i]).
template <unsigned LINE_BYTES>
void line_to_bv(const uint8_t* p, sc_dt::sc_bv<8 * LINE_BYTES>& v) {
  static_assert(LINE_BYTES % 4 == 0, "lines of whole 32-bit words");
  for (unsigned j = 0; j < LINE_BYTES / 4; ++j) {
    const uint32_t w = uint32_t(p[4 * j]) | uint32_t(p[4 * j + 1]) << 8 |
                       uint32_t(p[4 * j + 2]) << 16 | uint32_t(p[4 * j + 3]) << 24;
    v.set_word(int(j), w);
  }
}
template <unsigned LINE_BYTES>
void bv_to_line(const sc_dt::sc_bv<8 * LINE_BYTES>& v, uint8_t* p) {
  static_assert(LINE_BYTES % 4 == 0, "lines of whole 32-bit words");
  for (unsigned j = 0; j < LINE_BYTES / 4; ++j) {
    const uint32_t w = uint32_t(v.get_word(int(j)));
    for (unsigned b = 0; b < 4; ++b) p[4 * j + b] = uint8_t(w >> (8 * b));
  }
}

// The SystemC twin of rtl/units/ascache.v with cfg's geometry (cfg.line_bytes must be LINE_BYTES;
// SETS = cfg.size_bytes / (LINE_BYTES * cfg.ways), HIT_LATENCY = cfg.hit_latency).
template <unsigned LINE_BYTES>
class AscacheTwin : public sc_core::sc_module {
 public:
  using Line = sc_dt::sc_bv<8 * LINE_BYTES>;
  sc_core::sc_in<bool> clk_i, rst_ni;
  sc_core::sc_in<bool> acc_valid_i;
  sc_core::sc_in<uint32_t> acc_line_i, acc_tag_i;
  sc_core::sc_out<bool> rsp_valid_o, rsp_hit_o, rsp_merge_o, rsp_full_o, rsp_set_full_o;
  sc_core::sc_out<uint32_t> rsp_tag_o;
  sc_core::sc_out<Line> rsp_data_o;
  sc_core::sc_out<bool> req_valid_o;
  sc_core::sc_in<bool> req_ready_i;
  sc_core::sc_out<uint32_t> req_line_o, req_tag_o;
  sc_core::sc_in<bool> fill_valid_i;
  sc_core::sc_in<uint32_t> fill_tag_i;
  sc_core::sc_in<Line> fill_data_i;
  sc_core::sc_out<uint32_t> mshr_busy_o, cnt_hits_o, cnt_misses_o, cnt_merges_o, cnt_full_o,
      cnt_set_full_o, cnt_fills_o;

  SC_HAS_PROCESS(AscacheTwin);
  AscacheTwin(sc_core::sc_module_name name, const CacheConfig& cfg)
      : sc_core::sc_module(name), cache_("cache", cfg, 0, LINE_BYTES), mshrs_(cfg.mshrs) {
    if (cfg.line_bytes != LINE_BYTES)
      throw std::invalid_argument(std::string(this->name()) + ": line_bytes " +
                                  std::to_string(cfg.line_bytes) + " != the port's " +
                                  std::to_string(LINE_BYTES));
    if (cfg.mshrs < 3)
      throw std::invalid_argument(std::string(this->name()) +
                                  ": the pin twin needs >= 3 MSHRs (uint32_t tag ports)");
    if (cfg.hit_latency < 1)
      throw std::invalid_argument(std::string(this->name()) + ": hit_latency must be >= 1");
    pipe_.assign(cfg.hit_latency, Rsp{});
    SC_METHOD(seq);
    sensitive << clk_i.pos() << rst_ni.neg();
    dont_initialize();
  }

  Ascache& cache() { return cache_; }
  const Ascache& cache() const { return cache_; }
  uint64_t cycle() const { return cycle_; }

 private:
  struct Rsp {
    bool valid = false, hit = false, merge = false, full = false, set_full = false;
    uint32_t tag = 0;
    std::vector<uint8_t> data;
  };

  void seq() {
    if (!rst_ni.read()) {
      if (used_)
        throw std::logic_error(std::string(name()) +
                               ": reset after use (Ascache has no reset; see systemc/pins/ascache.h)");
      for (Rsp& r : pipe_) r.valid = false;
      cycle_ = 0;
      write_outputs();
      return;
    }
    const Cycle now = cycle_;
    cache_.advance(now);
    // 1. The request at the head leaves if the memory side takes it.
    TimedFifo<MemReq>& rq = cache_.req();
    if (rq.can_pop(now) && req_ready_i.read()) rq.pop();
    // 2. Fill, then 3. access: the cycle model's order (the vtu's fill chooses its victim from the
    // state at the cycle's start; its line is installed at this edge, after the accesses).
    if (fill_valid_i.read()) {
      used_ = true;
      const uint32_t tag = fill_tag_i.read();
      if (tag >= mshrs_)
        throw std::logic_error(std::string(name()) + ": fill of MSHR " + std::to_string(tag) +
                               " (there are " + std::to_string(mshrs_) + ")");
      bv_to_line<LINE_BYTES>(fill_data_i.read(), cache_.mshr_data(tag));
      cache_.fill(tag);
    }
    Rsp in;
    if (acc_valid_i.read()) {
      used_ = true;
      const CacheStats before = cache_.stats();
      const uint8_t* p = cache_.access(acc_line_i.read());
      const CacheStats& after = cache_.stats();
      in.valid = true;
      in.hit = p != nullptr;
      in.merge = after.mshr_merges != before.mshr_merges;
      in.full = after.mshr_full != before.mshr_full;
      in.set_full = after.set_full != before.set_full;
      in.tag = acc_tag_i.read();
      if (p) in.data.assign(p, p + LINE_BYTES);
    }
    // The delay line: HIT_LATENCY registers, the access enters the first; the last is the output.
    // A bubble leaving it keeps the held values (the RTL's registers load only on a response).
    for (size_t i = pipe_.size() - 1; i > 0; --i) pipe_[i] = std::move(pipe_[i - 1]);
    pipe_[0] = std::move(in);
    const Rsp& out = pipe_.back();
    if (out.valid) {
      held_ = out;
      if (out.hit) held_data_ = out.data;
    }
    held_.valid = out.valid;
    cache_.advance(++cycle_);
    write_outputs();
  }

  void write_outputs() {
    rsp_valid_o.write(held_.valid);
    rsp_hit_o.write(held_.hit);
    rsp_merge_o.write(held_.merge);
    rsp_full_o.write(held_.full);
    rsp_set_full_o.write(held_.set_full);
    rsp_tag_o.write(held_.tag);
    if (held_data_.size() == LINE_BYTES) {
      Line v;
      line_to_bv<LINE_BYTES>(held_data_.data(), v);
      rsp_data_o.write(v);
    }
    const TimedFifo<MemReq>& rq = cache_.req();
    const bool rv = rq.can_pop(cycle_);
    req_valid_o.write(rv);
    if (rv) {
      const MemReq& r = rq.front();
      req_tag_o.write(r.tag);
      req_line_o.write(uint32_t(cache_.mshr_line(r.tag)));
    }
    mshr_busy_o.write(cache_.mshrs_busy());
    const CacheStats& st = cache_.stats();
    cnt_hits_o.write(uint32_t(st.hits));
    cnt_misses_o.write(uint32_t(st.misses));
    cnt_merges_o.write(uint32_t(st.mshr_merges));
    cnt_full_o.write(uint32_t(st.mshr_full));
    cnt_set_full_o.write(uint32_t(st.set_full));
    cnt_fills_o.write(uint32_t(st.fills));
  }

  Ascache cache_;
  uint32_t mshrs_;
  std::vector<Rsp> pipe_;
  Rsp held_;
  std::vector<uint8_t> held_data_;
  Cycle cycle_ = 0;
  bool used_ = false;
};

}  // namespace raycore::sc::pins
