// systemc/hit_rtl.cpp - the Verilated hit_unit bound into the frame (see hit_rtl.h). Built with the
// Verilated models (RAYCORE_RTL=ON); the variants are rtl/units/hit_unit.cmake's list.
#include "systemc/hit_rtl.h"

#include <stdexcept>

// The models are built into the frame library with the SystemC ones (VM_SC=1): Verilator's
// runtime then names sc_time_stamp unqualified, as systemc.h declares it.
#include <systemc.h>

#include "rtl_hit_unit_models.h"
#include "systemc/rtl_fields.h"
#include "systemc/vl_bits.h"

namespace raycore::sc {
namespace {

using vl::get_bits;
using vl::set_bits;

template <class M, unsigned W, unsigned SLOT_BITS, unsigned PIPES>
class HitRtlT final : public HitRtl {
  static constexpr unsigned BW = 67 + 5 * W;  // a best record

 public:
  HitRtlT(const char* name, RtuChannels& ch, const SimConfig& cfg) : name_(name), ch_(ch) {
    if (cfg.rays_in_flight > (1u << SLOT_BITS) || cfg.trv_pipes > PIPES)
      throw ConfigError("--rtl hit: " + name_ + " is built for at most " +
                        std::to_string(1u << SLOT_BITS) + " --rays-in-flight and " +
                        std::to_string(PIPES) + " --trv-pipes (rtl/units/hit_unit.cmake)");
    vl::async_reset(m_);
  }
  ~HitRtlT() override { m_.final(); }

  std::string name() const override { return name_; }

  void config(const pins::HitConfig& c) override {
    m_.light_x_i = c.light[0];
    m_.light_y_i = c.light[1];
    m_.light_z_i = c.light[2];
    m_.tmin_i = c.tmin;
    m_.strategy_i = uint8_t(uint32_t(c.sp.spawn) & 7u);
    m_.segment_i = c.sp.segment;
    m_.all_i = c.sp.spawn_all;
    m_.back_i = uint32_t(c.g.back);
    m_.scale_i = c.g.scale;
    m_.fixed_i = c.g.fixed;
    m_.slab_scale_i = c.g.slab_scale;
  }

  bool tick(Cycle now, HitLeave& out) override {
    if (!ch_.hit_q.empty()) throw std::logic_error("--rtl hit: finished rays left from the last cycle");
    // A cycle with no ray inside hit.v and the head not ready changes nothing in the RTL.
    stepped_ = vl::queue_steps(m_, now);
    probe_ = HitProbe{};
    probe_.cycle = now;
    probe_.head_valid = m_.head_valid_o;
    if (!stepped_) return false;
    m_.clk_i = 0;  // the falling edge: nothing is sensitive to it
    m_.now_i = uint32_t(now);
    m_.fin_valid_i = 0;
    m_.eval();
    if (m_.rd_valid_o) {  // the slot of the ray entering: {shadow, best, d zyx, o zyx}
      const Slot& r = ch_.slots[m_.rd_slot_o];
      for (unsigned i = 0; i < 3; ++i) {
        set_bits(m_.rd_i, i * W, W, r.ray.o[i]);
        set_bits(m_.rd_i, (3 + i) * W, W, r.ray.d[i]);
      }
      vl::set_best(m_.rd_i, 6 * W, W, r.best, 0, W <= 24 ? 7 : 0);  // hit_unit.v's t: the key's top bits
      set_bits(m_.rd_i, 6 * W + BW, 1, r.shadow);
      m_.eval();
      probe_.in = true;
      probe_.in_slot = m_.rd_slot_o;
    }
    if (!m_.out_valid_o) return true;
    out = HitLeave{};
    out.slot = uint16_t(m_.out_slot_o);
    out.shadow = m_.out_shadow_o;
    out.found = m_.out_found_o;
    out.free = m_.out_free_o;
    out.spawn = m_.out_spawn_o;
    hls::ShadowSetup& s = out.ss;
    for (unsigned i = 0; i < 3; ++i) s.h[i] = get_bits(m_.out_h_o, i * W, W);
    s.front = m_.out_front_o;
    s.spawn = m_.out_spawn_o;
    s.dens = m_.out_dens_o;
    s.ray = vl::get_ray(m_.out_ray_o, 0, W);
    s.skip_id = m_.out_skip_id_o;
    probe_.out = true;
    probe_.spawn = out.spawn;
    probe_.out_slot = out.slot;
    return true;
  }

  void edge(Cycle now) override {
    // This cycle's finished rays (RtuChannels::hit_q), one per lane in push order.
    m_.fin_valid_i = 0;
    unsigned lanes = 0;
    while (!ch_.hit_q.empty()) {
      if (lanes == PIPES)
        throw std::logic_error("--rtl hit: more finished rays in a cycle than the RTL's lanes");
      const Cycle ready = ch_.hit_q.head_ready();
      const uint16_t s = ch_.hit_q.pop();
      set_bits(m_.fin_valid_i, lanes, 1, 1);
      set_bits(m_.fin_slot_i, lanes * SLOT_BITS, SLOT_BITS, s);
      set_bits(m_.fin_ready_i, lanes * 32, 32, uint32_t(ready));
      ++lanes;
    }
    probe_.fin = m_.fin_valid_i;
    vl::queue_edge(m_, stepped_, lanes != 0, now, [](M&) {});
  }

  HitProbe probe(Cycle now) const override {
    if (probe_.cycle == now) return probe_;
    HitProbe p;
    p.cycle = now;
    p.head_valid = m_.head_valid_o;
    return p;
  }

  Cycle next_event(Cycle now) const override { return vl::queue_next_event(m_, now); }

  uint64_t busy() const override { return m_.cnt_busy_o; }

 private:
  std::string name_;
  RtuChannels& ch_;
  M m_;
  bool stepped_ = false;  // this cycle's tick evaluated the model
  HitProbe probe_;
};

}  // namespace

std::unique_ptr<HitRtl> make_rtl_hit_unit(hls::FormatId f, hls::Rounding r, unsigned stages,
                                          RtuChannels& ch, const SimConfig& cfg) {
#define RAYCORE_RTL_HITU_VARIANT(prefix, fmt, mode, st, width, slot_bits, pipes)             \
  if (vl::variant_is(#fmt, #mode, f, r) && stages == st)                                    \
    return std::make_unique<HitRtlT<prefix, width, slot_bits, pipes>>(                      \
        "Verilated hit_unit " #fmt " " #mode " S=" #st, ch, cfg);
#include "rtl_hit_unit_variants.h"
#undef RAYCORE_RTL_HITU_VARIANT
  return nullptr;
}

std::string rtl_hit_unit_built() {
  std::string s;
#define RAYCORE_RTL_HITU_VARIANT(prefix, fmt, mode, st, width, slot_bits, pipes)             \
  s += std::string(s.empty() ? "" : ", ") + "hit_unit " #fmt " " #mode " S=" #st " (slots " + \
       std::to_string(1u << slot_bits) + ", pipes " #pipes ")";
#include "rtl_hit_unit_variants.h"
#undef RAYCORE_RTL_HITU_VARIANT
  return s.empty() ? "none" : s;
}

}  // namespace raycore::sc
