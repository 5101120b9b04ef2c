// systemc/ist_rtl.cpp - the Verilated ist_unit bound into the frame (see ist_rtl.h). Built with the
// Verilated models (RAYCORE_RTL=ON); the variants are rtl/units/ist_unit.cmake's list.
#include "systemc/ist_rtl.h"

#include <stdexcept>

// The models are built into the frame library with the SystemC ones (VM_SC=1): Verilator's runtime
// then names sc_time_stamp unqualified, as systemc.h declares it.
#include <systemc.h>

#include "hls/wald.h"
#include "rtl_ist_unit_models.h"
#include "systemc/ascache.h"
#include "systemc/rtl_fields.h"
#include "systemc/vl_bits.h"

namespace raycore::sc {
namespace {

using vl::get_bits;
using vl::set_bits;

template <class M, unsigned W, unsigned SLOT_BITS, unsigned IST, unsigned PIPES, unsigned WORDS,
          unsigned QBITS, unsigned RPL, unsigned HLBITS, unsigned WT>
class IstRtlT final : public IstRtl {
  // The closest-hit key's extension bits (hls::KeyFormat: 7 for FP24, 0 for FP32); ist_unit.v's
  // (TX_): the watertight test's t carries them, Wald's is F's (the key's top bits).
  static constexpr unsigned KX = W <= 24 ? 7 : 0;
  static constexpr unsigned TX = WT ? KX : 0, DROP = KX - TX, KW = W + TX;
  static constexpr unsigned BW = 67 + 4 * W + KW;  // a result record
  static constexpr unsigned RW = 32 + 7 * W + KW;  // a ray read
  static constexpr hls::IstKind KIND = WT ? hls::IstKind::watertight : hls::IstKind::wald;
  static constexpr unsigned RB =  // a triangle record's bytes
      unsigned(W <= 24 ? hls::tri_record_bytes<hls::FP24>(KIND) : hls::tri_record_bytes<hls::FP32>(KIND));
  static constexpr unsigned LB = RPL * RB;  // bytes per triangle-cache line

 public:
  IstRtlT(const char* name, FrameCtx& fc, RtuChannels& ch, const SimConfig& cfg)
      : name_(name), fc_(fc), ch_(ch), cfg_(cfg) {
    auto refuse = [&](const std::string& what) {
      throw ConfigError("--rtl ist: " + name_ + " is built for " + what +
                        " (rtl/units/ist_unit.cmake)");
    };
    if (cfg.mailbox != 0) refuse("no mailbox (--mailbox must be 0)");
    if (cfg.ist_units > IST) refuse("at most " + std::to_string(IST) + " --ist-units");
    if (cfg.rays_in_flight > (1u << SLOT_BITS))
      refuse("at most " + std::to_string(1u << SLOT_BITS) + " --rays-in-flight");
    if (cfg.trv_pipes > PIPES) refuse("at most " + std::to_string(PIPES) + " --trv-pipes");
    if (cfg.ist_queue > (1u << QBITS))
      refuse("an ist queue of at most " + std::to_string(1u << QBITS) + " entries");
    if (cfg.list_cache.line_bytes > 4 * WORDS)
      refuse("list cache lines of at most " + std::to_string(4 * WORDS) + " bytes");
    if (ch.tri->line_bytes() != LB)
      refuse(std::to_string(LB) + "-byte triangle cache lines (" + std::to_string(RPL) +
             " records), not " + std::to_string(ch.tri->line_bytes()));
    if (ch.tri->hit_latency >= (1u << HLBITS) || ch.tri->hit_latency < 1)
      refuse("a triangle-cache hit latency of 1 .. " + std::to_string((1u << HLBITS) - 1) +
             " (ist_unit.v registers the cache's answer before ist.v)");
    vl::async_reset(m_);
  }
  ~IstRtlT() override { m_.final(); }

  std::string name() const override { return name_; }

  bool tick(Cycle now, std::vector<IstRes>& out) override {
    if (!configured_) configure();
    if (!ch_.ist_q.empty()) throw std::logic_error("--rtl ist: hand-offs left from the last cycle");
    // A cycle in which no test is inside, none leaves and the head is not ready changes nothing in
    // the RTL (every register holds): neither evaluate nor clock it.
    stepped_ = vl::queue_steps(m_, now);
    probe_ = IstProbe{};
    probe_.cycle = now;
    probe_.head_valid = m_.head_valid_o;
    if (!stepped_) {
      ch_.ist_q.limit(cfg_.ist_queue - m_.count_o);
      return false;
    }
    m_.clk_i = 0;  // the falling edge: nothing is sensitive to it
    m_.now_i = uint32_t(now);
    m_.rsp_hit_i = 0;
    m_.eval();
    // The rays of the units' entries (the C++ slots: rgu, hit and trv write them), then the
    // triangle-cache accesses in unit order.
    for (unsigned u = 0; u < IST; ++u) {
      if (!get_bits(m_.acc_valid_o, u, 1)) break;  // the units that take an entry: a prefix
      const Slot& r = ch_.slots[get_bits(m_.ray_slot_o, u * SLOT_BITS, SLOT_BITS)];
      const uint32_t f[7] = {r.ray.o[0], r.ray.o[1], r.ray.o[2], r.ray.d[0],
                             r.ray.d[1], r.ray.d[2], r.ray.tmin};
      for (unsigned i = 0; i < 7; ++i) set_bits(m_.ray_i, u * RW + i * W, W, f[i]);
      set_bits(m_.ray_i, u * RW + 7 * W, KW, r.tmax >> DROP);  // the key (Wald's: its F top bits)
      set_bits(m_.ray_i, u * RW + 7 * W + KW, 32, r.skip_id);
    }
    bool any = false;
    for (unsigned u = 0; u < IST; ++u) {
      if (!get_bits(m_.acc_valid_o, u, 1)) break;
      any = true;
      const uint8_t* line = ch_.tri->access(get_bits(m_.acc_line_o, u * 32, 32));
      if (!line) continue;  // a miss: the entry loops
      set_bits(m_.rsp_hit_i, u, 1, 1);
      vl::set_bytes(m_.rsp_data_i, u * 8 * LB, LB, line);
    }
    probe_.acc_valid = m_.acc_valid_o;
    probe_.rsp_hit = m_.rsp_hit_i;
    m_.eval();
    for (unsigned u = 0; u < IST; ++u) {
      if (!get_bits(m_.res_valid_o, u, 1)) continue;
      const Best x = vl::get_best(m_.res_rec_o, u * BW, W, TX, DROP);  // its top bit 1: a result
      const IstRes o{uint16_t(get_bits(m_.res_slot_o, u * SLOT_BITS, SLOT_BITS)),
                     get_bits(m_.res_hit_o, u, 1) != 0, x.pos, x.t, x.den, x.id, x.k, x.nu, x.nv,
                     x.nd};
      out.push_back(o);
      any = true;
    }
    probe_.res_valid = m_.res_valid_o;
    probe_.busy = m_.busy_o;
    ch_.ist_q.limit(m_.room_o);
    return any || m_.busy_o;
  }

  void edge(Cycle now) override {
    // This cycle's hand-offs (RtuChannels::ist_q): runs of consecutive list positions of one slot
    // with one ready cycle, one per lane, in push order.
    m_.hin_n_i = 0;
    unsigned lanes = 0, n = 0;
    IstReq last{};
    Cycle last_ready = 0;
    while (!ch_.ist_q.empty()) {
      const Cycle ready = ch_.ist_q.head_ready();
      const IstReq q = ch_.ist_q.pop();
      const bool joins = n != 0 && q.slot == last.slot && q.pos == last.pos + 1 &&
                         ready == last_ready && n < WORDS;
      if (!joins) {
        if (n != 0) set_bits(m_.hin_n_i, (lanes - 1) * 6, 6, n);
        if (++lanes > PIPES)
          throw std::logic_error("--rtl ist: more hand-off runs in a cycle than the RTL's lanes");
        n = 0;
        const unsigned p = lanes - 1;
        set_bits(m_.hin_slot_i, p * SLOT_BITS, SLOT_BITS, q.slot);
        set_bits(m_.hin_pos_i, p * 32, 32, q.pos);
        set_bits(m_.hin_ready_i, p * 32, 32, uint32_t(ready));
      }
      set_bits(m_.hin_words_i, ((lanes - 1) * WORDS + n) * 32, 32, q.tri);
      ++n;
      last = q;
      last_ready = ready;
    }
    if (n != 0) set_bits(m_.hin_n_i, (lanes - 1) * 6, 6, n);
    probe_.hin = 0;
    for (unsigned p = 0; p < lanes; ++p) probe_.hin += get_bits(m_.hin_n_i, p * 6, 6);
    vl::queue_edge(m_, stepped_, lanes != 0, now, [](M& m) { m.rsp_hit_i = 0; });
  }

  IstProbe probe(Cycle now) const override {
    if (probe_.cycle == now) return probe_;
    IstProbe p;
    p.cycle = now;
    p.head_valid = m_.head_valid_o;
    return p;
  }

  Cycle next_event(Cycle now) const override { return vl::queue_next_event(m_, now); }

  void stats(RtuStats& s) const override {
    s.ist_busy = m_.cnt_busy_o;
    s.ist_tri_miss = m_.cnt_miss_o;
    s.tri_tests = m_.cnt_tests_o;
  }

 private:
  void configure() {  // the per-frame registers (the margins are set before the
                      // frame)
    m_.eps_i = fc_.margins.eps;
    m_.one_eps_i = fc_.margins.one_eps;
    m_.qcap_i = uint16_t(cfg_.ist_queue);
    m_.hl_i = uint8_t(ch_.tri->hit_latency);
    m_.units_i = uint8_t(cfg_.ist_units);
    configured_ = true;
  }

  std::string name_;
  FrameCtx& fc_;
  RtuChannels& ch_;
  const SimConfig& cfg_;
  M m_;
  bool configured_ = false;
  bool stepped_ = false;  // this cycle's tick evaluated the model
  IstProbe probe_;
};

}  // namespace

std::unique_ptr<IstRtl> make_rtl_ist_unit(hls::FormatId f, hls::Rounding r, unsigned stages, hls::IstKind kind,
                                          FrameCtx& fc, RtuChannels& ch, const SimConfig& cfg) {
#define RAYCORE_RTL_ISTU_VARIANT(prefix, fmt, mode, st, width, slot_bits, ist, pipes, words,      \
                                 qbits, rpl, hlbits, wt)                                          \
  if (vl::variant_is(#fmt, #mode, f, r) && stages == st && (kind == hls::IstKind::watertight) == (wt != 0)) \
    return std::make_unique<                                                                      \
        IstRtlT<prefix, width, slot_bits, ist, pipes, words, qbits, rpl, hlbits, wt>>(            \
        wt ? "Verilated ist_unit " #fmt " " #mode " watertight S=" #st                             \
           : "Verilated ist_unit " #fmt " " #mode " S=" #st, fc, ch, cfg);
#include "rtl_ist_unit_variants.h"
#undef RAYCORE_RTL_ISTU_VARIANT
  return nullptr;
}

std::string rtl_ist_unit_built() {
  std::string s;
#define RAYCORE_RTL_ISTU_VARIANT(prefix, fmt, mode, st, width, slot_bits, ist, pipes, words, \
                                 qbits, rpl, hlbits, wt)                                     \
  s += std::string(s.empty() ? "" : ", ") + "ist_unit " #fmt " " #mode +                     \
       (wt ? " watertight" : "") + " S=" #st " (units " #ist ", slots " +                    \
       std::to_string(1u << slot_bits) + ", queue " + std::to_string(1u << qbits) + ")";
#include "rtl_ist_unit_variants.h"
#undef RAYCORE_RTL_ISTU_VARIANT
  return s.empty() ? "none" : s;
}

}  // namespace raycore::sc
