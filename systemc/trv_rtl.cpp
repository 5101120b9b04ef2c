// systemc/trv_rtl.cpp - the Verilated trv_unit bound into the frame (see trv_rtl.h). Built with the
// Verilated models (RAYCORE_RTL=ON); the variants are rtl/units/trv_unit.cmake's list.
#include "systemc/trv_rtl.h"

#include <algorithm>
#include <stdexcept>
#include <type_traits>

// The models are built into the frame library with the SystemC ones (VM_SC=1): Verilator's
// runtime then names sc_time_stamp unqualified, as systemc.h declares it.
#include <systemc.h>

#include "rtl_trv_unit_models.h"
#include "systemc/rtl_fields.h"
#include "systemc/vl_bits.h"

namespace raycore::sc {
namespace {

using vl::get_bits;
using vl::set_bits;

template <class M, unsigned W, unsigned SLOT_BITS, unsigned PIPES, unsigned IST, unsigned WORDS>
class TrvRtlT final : public TrvRtl {
  // The closest-hit key's extension bits (hls::KeyFormat), as trv_unit.cmake builds every model
  // (TX: 7 for FP24, 0 for FP32): the slots' tmax and the records' t are the model's keys.
  static constexpr unsigned TX = W <= 24 ? 7 : 0, KW = W + TX;
  static constexpr unsigned BW = 67 + 4 * W + KW;

 public:
  TrvRtlT(const char* name, FrameCtx& fc, RtuChannels& ch, const SimConfig& cfg)
      : name_(name), fc_(fc), ch_(ch), cfg_(cfg) {
    if (cfg.mailbox != 0)
      throw ConfigError("--rtl trv: the RTL has no mailbox (--mailbox must be 0)");
    if (cfg.trv_pipes > PIPES || cfg.ist_units > IST || cfg.rays_in_flight > (1u << SLOT_BITS) ||
        cfg.list_cache.line_bytes > 4 * WORDS || cfg.trv_latency > 0xFFFF ||
        cfg.node_cache.hit_latency > 0xFFFF || cfg.list_cache.hit_latency > 0xFFFF)
      throw ConfigError(
          "--rtl trv: " + name_ + " is built for at most " + std::to_string(PIPES) +
          " --trv-pipes, " + std::to_string(IST) + " --ist-units, " +
          std::to_string(1u << SLOT_BITS) + " --rays-in-flight and " + std::to_string(4 * WORDS) +
          "-byte list cache lines (rtl/units/trv_unit.cmake)");
    if (uint64_t(cfg.trv_latency) + cfg.node_cache.hit_latency < kTrvRtlMinLoop)
      throw ConfigError("--rtl trv: " + name_ + " writes an inner node's split back " +
                        std::to_string(kTrvRtlMinLoop - 1) +
                        " cycles after the pass: --trv-latency plus the node cache's hit latency "
                        "must be at least " + std::to_string(kTrvRtlMinLoop));
    ch_.ist_results = &results_;
    vl::async_reset(m_);
  }
  ~TrvRtlT() override {
    ch_.ist_results = nullptr;
    m_.final();
  }

  std::string name() const override { return name_; }

  bool tick(Cycle now) override {
    if (!configured_) configure();
    // A cycle in which no pipe can take a ray and no result comes changes nothing in the RTL
    // (every register holds): neither evaluate nor clock it (edge() clocks only with a ray in).
    stepped_ = !results_.empty() || m_.pend_o || (m_.head_valid_o && at(now, m_.head_ready_o) <= now);
    probe_ = TrvProbe{};
    probe_.cycle = now;
    probe_.head_valid = m_.head_valid_o;
    if (!stepped_) return false;
    m_.clk_i = 0;  // the falling edge: nothing is sensitive to it
    m_.now_i = uint32_t(now);
    // This cycle's ist results (the ist ticked before).
    if (results_.size() > IST)
      throw std::logic_error("--rtl trv: more ist results in a cycle than the RTL's ports");
    m_.res_valid_i = 0;
    m_.res_hit_i = 0;
    for (unsigned u = 0; u < results_.size(); ++u) {
      const IstRes& o = results_[u];
      set_bits(m_.res_valid_i, u, 1, 1);
      set_bits(m_.res_slot_i, u * SLOT_BITS, SLOT_BITS, o.slot);
      set_bits(m_.res_hit_i, u, 1, o.hit);
      // The record with its top bit 1 (a result), as ist_unit.v puts it out.
      vl::set_best(m_.res_rec_i, u * BW, W, Best{true, o.t, o.den, o.pos, o.id, o.k, o.nu, o.nv, o.nd}, TX);
    }
    const bool had_results = !results_.empty();
    results_.clear();
    m_.room_i = uint16_t(ch_.ist_room(now));
    m_.nrsp_hit_i = 0;
    m_.lrsp_hit_i = 0;
    m_.eval();
    // The cache accesses in the model's order: the list stage's (stage p's access valid depends on
    // the answers to stages 0 .. p-1 through the ist queue's room: re-evaluate after a hit), then
    // the pipes' node reads (their answers are registered for the next cycle's outcomes).
    uint32_t acc = 0, hit = 0;  // the probe's ports: 2p the pipe's node read, 2p + 1 its list read
    auto access = [&](Ascache& c, uint32_t byte, unsigned port) -> const uint8_t* {
      acc |= 1u << port;
      const uint8_t* line = c.access(byte / c.line_bytes());
      if (line) hit |= 1u << port;
      return line;  // null: a miss, the response's default
    };
    for (unsigned p = 0; p < PIPES; ++p) {
      if (!get_bits(m_.lacc_valid_o, p, 1)) continue;
      const uint32_t byte = get_bits(m_.lacc_byte_o, p * 32, 32);
      const uint8_t* line = access(*ch_.list, byte, 2 * p + 1);
      if (!line) continue;
      const uint32_t lb = ch_.list->line_bytes(), off = byte % lb;
      set_bits(m_.lrsp_hit_i, p, 1, 1);
      for (uint32_t i = 0; i < (lb - off) / 4; ++i)
        set_bits(m_.lrsp_data_i, (p * WORDS + i) * 32, 32,
                 uint32_t(hls::detail::get_le(line + off + 4 * i, 4)));
      m_.eval();
    }
    for (unsigned p = 0; p < PIPES; ++p) {
      if (!get_bits(m_.nacc_valid_o, p, 1)) continue;
      const uint32_t byte = get_bits(m_.nacc_byte_o, p * 32, 32);
      const uint8_t* line = access(*ch_.node, byte, 2 * p);
      if (!line) continue;
      set_bits(m_.nrsp_hit_i, p, 1, 1);
      for (uint32_t i = 0; i < 2; ++i)
        set_bits(m_.nrsp_node_i, (p * 2 + i) * 32, 32,
                 uint32_t(hls::detail::get_le(line + byte % ch_.node->line_bytes() + 4 * i, 4)));
    }
    // A node read's answer goes into registers for the outcome: nothing reads it in this cycle.
    probe_.res_valid = m_.res_valid_i;
    probe_.go = m_.go_o;
    probe_.fin = m_.fin_o;
    probe_.acc_valid = acc;
    probe_.rsp_hit = hit;
    for (unsigned p = 0; p < PIPES; ++p) probe_.ist_entries += get_bits(m_.ist_n_o, p * 6, 6);
    if (m_.err_o)
      throw std::runtime_error("trv: a ray needs more than the " + std::to_string(fc_.stack_depth) +
                               " stack entries of --stack-depth (at most 64, the deepest tree)");
    // The list stage's hand-offs, then the pipes' finished rays, in pipe order.
    bool any = m_.pend_o;
    for (unsigned p = 0; p < PIPES; ++p) {
      const uint32_t n = get_bits(m_.ist_n_o, p * 6, 6);
      if (n == 0) continue;
      const uint16_t s = uint16_t(get_bits(m_.ist_slot_o, p * SLOT_BITS, SLOT_BITS));
      ch_.slots[s].tmax = get_bits(m_.ist_tmax_o, p * KW, KW);  // the leaf-entry tmax (a key) it tests with
      const uint32_t pos = get_bits(m_.ist_pos_o, p * 32, 32);
      const Cycle ready = at(now, get_bits(m_.ist_ready_o, p * 32, 32));
      for (uint32_t i = 0; i < n; ++i)
        ch_.ist_q.push({s, pos + i, get_bits(m_.ist_words_o, (p * WORDS + i) * 32, 32)}, ready);
    }
    // The outcomes' finished rays (passes of the cycle before), in pipe order.
    if (m_.go_o) any = true;
    for (unsigned p = 0; p < PIPES; ++p) {
      if (!get_bits(m_.fin_o, p, 1)) continue;
      any = true;
      const uint16_t s = uint16_t(get_bits(m_.fin_slot_o, p * SLOT_BITS, SLOT_BITS));
      Slot& r = ch_.slots[s];
      r.best = vl::get_best(m_.best_o, p * BW, W, TX);
      r.state = SlotState::done;
      ch_.hit_q.push(s, at(now, m_.fin_ready_o));
    }
    return any || had_results;
  }

  void edge(Cycle now) override {
    m_.in_valid_i = 0;
    if (!ch_.trv_q.empty()) {  // the rgu's ray of this cycle (a new primary or a shadow ray)
      const uint16_t s = ch_.trv_q.pop();
      if (!ch_.trv_q.empty()) throw std::logic_error("--rtl trv: two rgu rays in one cycle");
      const Slot& r = ch_.slots[s];
      m_.in_valid_i = 1;
      m_.in_slot_i = static_cast<std::remove_reference_t<decltype(m_.in_slot_i)>>(s);
      m_.in_shadow_i = r.shadow;
      vl::set_ray(m_.in_ray_i, 0, W, r.ray);
      if (probe_.cycle != now) {
        probe_ = TrvProbe{};
        probe_.cycle = now;
      }
      probe_.in_valid = true;
      probe_.in_slot = s;
    }
    if (!stepped_ && !m_.in_valid_i) return;  // nothing happened: the registers hold
    if (!stepped_) {  // only the rgu's ray: the cycle's inputs as tick() would drive them
      m_.clk_i = 0;
      m_.now_i = uint32_t(now);
      m_.res_valid_i = 0;
      m_.nrsp_hit_i = 0;
      m_.lrsp_hit_i = 0;
      m_.room_i = uint16_t(ch_.ist_room(now));
      m_.eval();  // clk low seen, so that the next evaluation has a rising edge
    }
    m_.clk_i = 1;  // the inputs and the rising edge in one evaluation (Verilator settles the
    m_.eval();     // input-driven logic first)
  }

  TrvProbe probe(Cycle now) const override {
    if (probe_.cycle == now) return probe_;
    TrvProbe p;
    p.cycle = now;
    p.head_valid = m_.head_valid_o;
    return p;
  }

  Cycle next_event(Cycle now) const override {
    if (m_.pend_o) return now + 1;  // an outcome or the split works in the next cycle
    if (!m_.head_valid_o) return kNever;
    return at(now, m_.head_ready_o);
  }

  void stats(RtuStats& s) const override {
    s.trv_busy = m_.cnt_busy_o;
    s.trv_node_miss = m_.cnt_node_miss_o;
    s.trv_list_miss = m_.cnt_list_miss_o;
    s.trv_ist_full = m_.cnt_ist_full_o;
    s.inner_steps = m_.cnt_inner_o;
    s.leaf_visits = m_.cnt_leaf_o;
    s.pops = m_.cnt_pops_o;
    s.list_steps = m_.cnt_list_steps_o;
    s.trv_fused = m_.cnt_fused_o;
    s.stack_max = m_.stack_max_o;
    s.mailbox_skips = 0;
  }

 private:
  static Cycle at(Cycle now, uint32_t c) { return vl::cycle_at(now, c); }

  void configure() {  // the per-frame registers (set after the VTU's set-up)
    m_.lat_i = uint16_t(cfg_.trv_latency);
    m_.node_hl_i = uint16_t(ch_.node->hit_latency);
    m_.list_hl_i = uint16_t(ch_.list->hit_latency);
    m_.lwords_i = uint8_t(ch_.list->line_bytes() / 4);
    m_.pipes_i = uint8_t(cfg_.trv_pipes);
    m_.fuse_i = cfg_.trv_fuse;
    m_.any_hit_i = fc_.spawn.any_hit;
    m_.empty_i = fc_.empty_tree;
    m_.depth_i = uint8_t(fc_.stack_depth);
    m_.widen_i = uint8_t(fc_.margins.widen_ulps);
    for (unsigned a = 0; a < 3; ++a) {
      set_bits(m_.box_i, a * W, W, fc_.box_lo[a]);
      set_bits(m_.box_i, (3 + a) * W, W, fc_.box_hi[a]);
    }
    configured_ = true;
  }

  std::string name_;
  FrameCtx& fc_;
  RtuChannels& ch_;
  const SimConfig& cfg_;
  M m_;
  std::vector<IstRes> results_;
  bool configured_ = false;
  bool stepped_ = false;  // this cycle's tick evaluated the model
  TrvProbe probe_;
};

}  // namespace

std::unique_ptr<TrvRtl> make_rtl_trv(hls::FormatId f, hls::Rounding r, FrameCtx& fc, RtuChannels& ch,
                                     const SimConfig& cfg) {
#define RAYCORE_RTL_TRVU_VARIANT(prefix, fmt, mode, width, slot_bits, depth, pipes, ist, words)    \
  if (vl::variant_is(#fmt, #mode, f, r))                                                              \
    return std::make_unique<TrvRtlT<prefix, width, slot_bits, pipes, ist, words>>(                \
        "Verilated trv_unit " #fmt " " #mode, fc, ch, cfg);
#include "rtl_trv_unit_variants.h"
#undef RAYCORE_RTL_TRVU_VARIANT
  return nullptr;
}

std::string rtl_trv_built() {
  std::string s;
#define RAYCORE_RTL_TRVU_VARIANT(prefix, fmt, mode, width, slot_bits, depth, pipes, ist, words) \
  s += std::string(s.empty() ? "" : ", ") + "trv_unit " #fmt " " #mode " (slots " +            \
       std::to_string(1u << slot_bits) + ", stack " #depth ", pipes " #pipes ", ist " #ist ")";
#include "rtl_trv_unit_variants.h"
#undef RAYCORE_RTL_TRVU_VARIANT
  return s.empty() ? "none" : s;
}

}  // namespace raycore::sc
