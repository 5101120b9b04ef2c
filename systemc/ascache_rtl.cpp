// systemc/ascache_rtl.cpp - the Verilated AS cache bound into the frame (see ascache_rtl.h). Built
// with the Verilated models (RAYCORE_RTL=ON); the geometries are rtl/units/ascache.cmake's frame
// list.
#include "systemc/ascache_rtl.h"

#include <stdexcept>

// The models are built into the frame library with the SystemC ones (VM_SC=1): Verilator's
// runtime then names sc_time_stamp unqualified, as systemc.h declares it.
#include <systemc.h>

#include "rtl_ascache_frame_models.h"
#include "systemc/vl_bits.h"

namespace raycore::sc {
namespace {

using vl::get_bits;
using vl::set_bits;

constexpr unsigned kLineW = 26;  // ascache.cmake's LINE_W: line indices below 2^26

template <class M, unsigned SETS, unsigned WAYS, unsigned LB, unsigned MSHRS, unsigned PORTS>
class AscacheRtlT final : public AscacheRtl {

 public:
  AscacheRtlT() { vl::async_reset(m_); }
  ~AscacheRtlT() override { m_.final(); }

  unsigned ports() const override { return PORTS; }
  std::string name() const override {
    return "Verilated ascache " + std::to_string(SETS) + "x" + std::to_string(WAYS) + "x" +
           std::to_string(LB) + "B, " + std::to_string(MSHRS) + " MSHRs, " +
           std::to_string(PORTS) + " ports";
  }

  Kind access(uint64_t line, const uint8_t** data) override {
    if (line >> kLineW)
      throw std::runtime_error(name() + ": line index " + std::to_string(line) +
                               " beyond the RTL's 26 bits (an image over 4 GB)");
    if (n_acc_ == PORTS)
      throw std::logic_error(name() + ": more than " + std::to_string(PORTS) +
                             " accesses in one cycle");
    const unsigned k = n_acc_++;
    set_bits(m_.acc_valid_i, k, 1, 1);
    set_bits(m_.acc_line_i, k * kLineW, kLineW, uint32_t(line));
    m_.eval();
    if (get_bits(m_.rsp_hit_o, k, 1)) {
      vl::get_bytes(m_.rsp_data_o, k * LB * 8, LB, line_);
      *data = line_;
      return Kind::hit;
    }
    *data = nullptr;
    if (get_bits(m_.rsp_merge_o, k, 1)) return Kind::merge;
    if (get_bits(m_.rsp_full_o, k, 1)) return Kind::full;
    if (get_bits(m_.rsp_set_full_o, k, 1)) return Kind::set_full;
    return Kind::alloc;
  }

  void fill(uint32_t tag, const uint8_t* data) override {
    if (fill_ || n_acc_)
      throw std::logic_error(name() + ": a fill after this cycle's fill or accesses");
    m_.fill_valid_i = 1;
    m_.fill_tag_i = static_cast<std::remove_reference_t<decltype(m_.fill_tag_i)>>(tag);
    vl::set_bytes(m_.fill_data_i, 0, LB, data);
    m_.eval();
    fill_ = true;
  }

  void pop(uint64_t line, uint32_t tag) override {
    if (fill_ || n_acc_)
      throw std::logic_error(name() + ": the bus took a request after this cycle's fill or accesses");
    if (pop_) edge();  // an edge of its own (see ascache_rtl.h)
    if (!m_.req_valid_o || m_.req_line_o != line || m_.req_tag_o != tag)
      throw std::logic_error(name() + ": the bus took line " + std::to_string(line) + " (MSHR " +
                             std::to_string(tag) + "), the RTL's request queue holds " +
                             (m_.req_valid_o ? "line " + std::to_string(m_.req_line_o) +
                                                   " (MSHR " + std::to_string(m_.req_tag_o) + ")"
                                             : std::string("nothing")));
    m_.req_ready_i = 1;
    pop_ = true;
  }

  void at(uint64_t cycle) override {
    if (cycle != cycle_ && (pop_ || fill_ || n_acc_)) edge();
    cycle_ = cycle;
  }
  void check(uint64_t hits, uint64_t misses, uint64_t merges, uint64_t full, uint64_t set_full,
             uint64_t fills) override {
    if (pop_ || fill_ || n_acc_) edge();
    const uint64_t rtl[6] = {m_.cnt_hits_o, m_.cnt_misses_o, m_.cnt_merges_o, m_.cnt_full_o,
                             m_.cnt_set_full_o, m_.cnt_fills_o};
    const uint64_t model[6] = {hits, misses, merges, full, set_full, fills};
    const char* names[6] = {"hits", "misses", "merges", "full", "set full", "fills"};
    for (int i = 0; i < 6; ++i)
      if (rtl[i] != model[i])
        throw std::logic_error(name() + ": " + names[i] + " " + std::to_string(rtl[i]) +
                               " in the RTL, " + std::to_string(model[i]) + " counted");
  }

 private:
  // The pending edge: the pop, the fill and the accesses driven since the last one.
  void edge() {
    m_.clk_i = 1;
    m_.eval();
    m_.acc_valid_i = 0;
    m_.fill_valid_i = 0;
    m_.req_ready_i = 0;
    m_.clk_i = 0;
    m_.eval();
    n_acc_ = 0;
    fill_ = pop_ = false;
  }

  M m_;
  unsigned n_acc_ = 0;
  uint64_t cycle_ = 0;
  bool fill_ = false, pop_ = false;
  uint8_t line_[LB] = {};
};

}  // namespace

std::unique_ptr<AscacheRtl> make_rtl_ascache(uint32_t sets, uint32_t ways, uint32_t line_bytes,
                                             uint32_t mshrs) {
#define RAYCORE_RTL_ASCF_VARIANT(prefix, s, w, lb, m, p)                   \
  if (sets == s && ways == w && line_bytes == lb && mshrs == m)           \
    return std::make_unique<AscacheRtlT<prefix, s, w, lb, m, p>>();
#include "rtl_ascache_frame_variants.h"
#undef RAYCORE_RTL_ASCF_VARIANT
  return nullptr;
}

std::string rtl_ascache_built() {
  std::string s;
#define RAYCORE_RTL_ASCF_VARIANT(prefix, s_, w, lb, m, p) \
  s += std::string(s.empty() ? "" : ", ") + #s_ " sets x " #w " ways x " #lb " B, " #m " MSHRs";
#include "rtl_ascache_frame_variants.h"
#undef RAYCORE_RTL_ASCF_VARIANT
  return s.empty() ? "none" : s;
}

}  // namespace raycore::sc
