// systemc/membus_rtl.cpp - the Verilated membus_if bound into the frame (see membus_rtl.h). Built
// with the Verilated models (RAYCORE_RTL=ON); the variants are rtl/units/membus_if.cmake's frame
// list.
#include "systemc/membus_rtl.h"

#include <type_traits>

// The models are built into the frame library with the SystemC ones (VM_SC=1): Verilator's
// runtime then names sc_time_stamp unqualified, as systemc.h declares it.
#include <systemc.h>

#include "rtl_membus_if_frame_models.h"
#include "systemc/vl_bits.h"

namespace raycore::sc {
namespace {

using vl::get_bits;
using vl::set_bits;

template <class M, unsigned N, unsigned DEPTH, unsigned BEAT>
class MembusRtlT final : public MembusRtl {
  static constexpr unsigned kAddr = 32, kLen = 12, kTag = 8;

 public:
  MembusRtlT() { vl::async_reset(m_); }
  ~MembusRtlT() override { m_.final(); }
  unsigned ports() const override { return N; }
  unsigned depth() const override { return DEPTH; }
  unsigned beat_bytes() const override { return BEAT; }
  std::string name() const override {
    return "Verilated membus_if (" + std::to_string(N) + " requesters, " + std::to_string(DEPTH) +
           " outstanding, " + std::to_string(BEAT) + "-byte beats)";
  }

  void request(unsigned i, bool valid, uint32_t addr, uint32_t bytes, uint32_t tag) override {
    set_bits(m_.req_valid_i, i, 1, valid);
    if (!valid) return;
    set_bits(m_.req_addr_i, i * kAddr, kAddr, addr);
    set_bits(m_.req_bytes_i, i * kLen, kLen, bytes);
    set_bits(m_.req_tag_i, i * kTag, kTag, tag);
  }
  void beat(const uint8_t* data) override {
    m_.beat_valid_i = data != nullptr;
    if (!data) return;
    vl::set_bytes(m_.beat_data_i, 0, BEAT, data);
  }
  int accept() override {
    m_.mem_ready_i = 1;
    m_.eval();
    return m_.mem_valid_o ? int(m_.mem_port_o) : -1;
  }
  bool full() const override { return m_.outstanding_o == DEPTH; }
  Rsp edge() override {
    m_.clk_i = 1;
    m_.eval();
    m_.clk_i = 0;
    m_.eval();
    Rsp r;
    bool any = false;
    for (unsigned i = 0; i < N; ++i) any |= get_bits(m_.rsp_valid_o, i, 1) != 0;
    if (any) {
      r.valid = true;
      r.last = m_.rsp_last_o;
      r.port = m_.rsp_port_o;
      r.tag = m_.rsp_tag_o;
      r.beat = m_.rsp_beat_o;
      vl::get_bytes(m_.rsp_data_o, 0, BEAT, data_);
      r.data = data_;
    }
    m_.beat_valid_i = 0;  // the next cycle's inputs start idle
    for (unsigned i = 0; i < N; ++i) set_bits(m_.req_valid_i, i, 1, 0);
    return r;
  }

 private:
  M m_;
  uint8_t data_[BEAT] = {};
};

}  // namespace

std::unique_ptr<MembusRtl> make_rtl_membus(unsigned requesters, unsigned depth, unsigned beat_bytes) {
#define RAYCORE_RTL_MEMBUS_FRAME_VARIANT(prefix, n, d, b) \
  if (requesters <= n && depth == d && beat_bytes == b)   \
    return std::make_unique<MembusRtlT<prefix, n, d, b>>();
#include "rtl_membus_if_frame_variants.h"
#undef RAYCORE_RTL_MEMBUS_FRAME_VARIANT
  return nullptr;
}

std::string rtl_membus_built() {
  std::string s;
#define RAYCORE_RTL_MEMBUS_FRAME_VARIANT(prefix, n, d, b) \
  s += std::string(s.empty() ? "" : ", ") + "up to " #n " requesters (" + std::to_string(n / 3) + \
       " RTUs), " #d " outstanding, " #b "-byte beats";
#include "rtl_membus_if_frame_variants.h"
#undef RAYCORE_RTL_MEMBUS_FRAME_VARIANT
  return s.empty() ? "none" : s;
}

}  // namespace raycore::sc
