// systemc/membus_rtl.cpp - the Verilated membus_if bound into the frame (see membus_rtl.h). Built
// with the Verilated models (RAYCORE_RTL=ON); the variants are rtl/units/membus_if.cmake's frame
// list (membus_if.v, membus_l2.v).
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

// membus_if.v (L2B 0) or membus_l2.v (SETS x WAYS x LINE bytes, L2B bytes per cycle, QD
// responses queued at most).
template <class M, unsigned N, unsigned DEPTH, unsigned BEAT, unsigned SETS = 0, unsigned WAYS = 0,
          unsigned LINE = 0, unsigned L2B = 0, unsigned QD = 0>
class MembusRtlT final : public MembusRtl {
  static constexpr unsigned kAddr = 32, kLen = 12, kTag = 8;
  static constexpr bool kL2 = L2B != 0;

 public:
  MembusRtlT() { vl::async_reset(m_); }
  ~MembusRtlT() override { m_.final(); }
  unsigned ports() const override { return N; }
  unsigned depth() const override { return DEPTH; }
  unsigned beat_bytes() const override { return BEAT; }
  L2Config l2() const override {
    if (!kL2) return L2Config{};
    return L2Config{SETS * WAYS * LINE, WAYS, LINE, 0, L2B};
  }
  unsigned l2_queue() const override { return QD; }
  std::string name() const override {
    std::string s = std::string(kL2 ? "Verilated membus_l2" : "Verilated membus_if") + " (" +
                    std::to_string(N) + " requesters, " + std::to_string(DEPTH) +
                    " outstanding, " + std::to_string(BEAT) + "-byte beats";
    if (kL2)
      s += ", an L2 of " + std::to_string(SETS * WAYS * LINE / 1024) + " KB: " +
           std::to_string(SETS) + " sets x " + std::to_string(WAYS) + " ways x " +
           std::to_string(LINE) + " bytes, " + std::to_string(L2B) + " bytes per cycle";
    return s + ")";
  }
  void l2_inputs(uint32_t now, uint32_t latency) override {
    if constexpr (kL2) {
      m_.now_i = now;
      m_.lat_i = uint16_t(latency);
    }
  }
  bool hit() const override {
    if constexpr (kL2)
      return m_.acc_valid_o && m_.acc_hit_o;
    else
      return false;
  }
  bool stalled() const override {
    if constexpr (kL2)
      return m_.stall_o;
    else
      return false;
  }
  bool l2_busy() const override {
    if constexpr (kL2)
      return m_.l2_busy_o;
    else
      return false;
  }
  Rsp l2_rsp() const override {
    if constexpr (kL2)
      return read_rsp<L2B>(m_.l2_valid_o, m_.l2_last_o, m_.l2_port_o, m_.l2_tag_o, m_.l2_beat_o,
                           m_.l2_data_o, l2_data_);
    else
      return Rsp{};
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
    if constexpr (kL2)
      return m_.acc_valid_o ? int(m_.acc_port_o) : -1;
    else
      return m_.mem_valid_o ? int(m_.mem_port_o) : -1;
  }
  bool full() const override { return m_.outstanding_o == DEPTH; }
  Rsp edge() override {
    m_.clk_i = 1;
    m_.eval();
    m_.clk_i = 0;
    m_.eval();
    const Rsp r = read_rsp<BEAT>(m_.rsp_valid_o, m_.rsp_last_o, m_.rsp_port_o, m_.rsp_tag_o,
                                 m_.rsp_beat_o, m_.rsp_data_o, data_);
    m_.beat_valid_i = 0;  // the next cycle's inputs start idle
    for (unsigned i = 0; i < N; ++i) set_bits(m_.req_valid_i, i, 1, 0);
    return r;
  }

 private:
  // A channel's routed beat (rsp_* or l2_*): valid if any requester's bit is set.
  template <unsigned BYTES, class V, class D>
  static Rsp read_rsp(const V& valid, bool last, uint32_t port, uint32_t tag, uint32_t beat,
                      const D& data, uint8_t* buf) {
    Rsp r;
    bool any = false;
    for (unsigned i = 0; i < N; ++i) any |= get_bits(valid, i, 1) != 0;
    if (!any) return r;
    r.valid = true;
    r.last = last;
    r.port = port;
    r.tag = tag;
    r.beat = beat;
    vl::get_bytes(data, 0, BYTES, buf);
    r.data = buf;
    return r;
  }
  M m_;
  uint8_t data_[BEAT] = {};
  mutable uint8_t l2_data_[L2B ? L2B : 1] = {};
};

}  // namespace

std::unique_ptr<MembusRtl> make_rtl_membus(unsigned requesters, unsigned depth, unsigned beat_bytes,
                                           const L2Config& l2) {
#define RAYCORE_RTL_MEMBUS_FRAME_VARIANT(prefix, n, d, b)                      \
  if (l2.size_bytes == 0 && requesters <= n && depth == d && beat_bytes == b) \
    return std::make_unique<MembusRtlT<prefix, n, d, b>>();
#define RAYCORE_RTL_MEMBUS_L2_FRAME_VARIANT(prefix, n, d, b, s_, w_, lb_, l2b_, qd_) \
  if (requesters <= n && depth == d && beat_bytes == b &&                           \
      l2.size_bytes == uint64_t(s_) * w_ * lb_ && l2.ways == w_ &&                  \
      l2.line_bytes == lb_ && l2.bandwidth == l2b_)                                 \
    return std::make_unique<MembusRtlT<prefix, n, d, b, s_, w_, lb_, l2b_, qd_>>();
#include "rtl_membus_if_frame_variants.h"
#undef RAYCORE_RTL_MEMBUS_FRAME_VARIANT
#undef RAYCORE_RTL_MEMBUS_L2_FRAME_VARIANT
  return nullptr;
}

std::string rtl_membus_built() {
  std::string s;
#define RAYCORE_RTL_MEMBUS_FRAME_VARIANT(prefix, n, d, b) \
  s += std::string(s.empty() ? "" : ", ") + "up to " #n " requesters (" + std::to_string(n / 3) + \
       " RTUs), " #d " outstanding, " #b "-byte beats";
#define RAYCORE_RTL_MEMBUS_L2_FRAME_VARIANT(prefix, n, d, b, s_, w_, lb_, l2b_, qd_)            \
  s += std::string(s.empty() ? "" : ", ") + "up to " #n " requesters, " #d " outstanding, " #b   \
       "-byte beats with an L2 of " + std::to_string(s_ * w_ * lb_ / 1024) + " KB (" #w_ " ways, " \
       #lb_ "-byte lines, " #l2b_ " bytes per cycle)";
#include "rtl_membus_if_frame_variants.h"
#undef RAYCORE_RTL_MEMBUS_FRAME_VARIANT
#undef RAYCORE_RTL_MEMBUS_L2_FRAME_VARIANT
  return s.empty() ? "none" : s;
}

}  // namespace raycore::sc
