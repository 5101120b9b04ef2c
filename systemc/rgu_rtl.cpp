// systemc/rgu_rtl.cpp - the Verilated rgu_unit bound into the frame (see rgu_rtl.h). Built with the
// Verilated models (RAYCORE_RTL=ON); the variants are rtl/units/rgu_unit.cmake's list.
#include "systemc/rgu_rtl.h"

#include <stdexcept>
#include <type_traits>

// The models are built into the frame library with the SystemC ones (VM_SC=1): Verilator's
// runtime then names sc_time_stamp unqualified, as systemc.h declares it.
#include <systemc.h>

#include "rtl_rgu_unit_models.h"
#include "systemc/rtl_fields.h"
#include "systemc/vl_bits.h"

namespace raycore::sc {
namespace {

template <class M, unsigned W, unsigned SLOT_BITS>
class RguRtlT final : public RguRtl {
 public:
  RguRtlT(const char* name, const SimConfig& cfg) : name_(name) {
    if (cfg.rays_in_flight > (1u << SLOT_BITS))
      throw ConfigError("--rtl rgu: " + name_ + " is built for at most " +
                        std::to_string(1u << SLOT_BITS) +
                        " --rays-in-flight (rtl/units/rgu_unit.cmake)");
    vl::async_reset(m_);
  }
  ~RguRtlT() override { m_.final(); }

  std::string name() const override { return name_; }

  void config(const RguRegs& r) override {
    m_.cam_o_x_i = r.cam.o[0], m_.cam_o_y_i = r.cam.o[1], m_.cam_o_z_i = r.cam.o[2];
    m_.cam_d00_x_i = r.cam.d00[0], m_.cam_d00_y_i = r.cam.d00[1], m_.cam_d00_z_i = r.cam.d00[2];
    m_.cam_dx_x_i = r.cam.dx[0], m_.cam_dx_y_i = r.cam.dx[1], m_.cam_dx_z_i = r.cam.dx[2];
    m_.cam_dy_x_i = r.cam.dy[0], m_.cam_dy_y_i = r.cam.dy[1], m_.cam_dy_z_i = r.cam.dy[2];
    m_.width_i = uint16_t(r.width);
    m_.height_i = uint16_t(r.height);
    m_.rtu_i = uint8_t(r.rtu);
    m_.rtus_i = uint8_t(r.rtus);
    m_.tmin_i = r.tmin;
    m_.slots_i = static_cast<std::remove_reference_t<decltype(m_.slots_i)>>(r.slots);
    m_.clk_i = 0;
    m_.eval();
  }

  RguIssue cycle(bool start, int freed, int shadow) override {
    m_.clk_i = 0;  // the falling edge: nothing is sensitive to it
    m_.start_i = start;
    m_.free_valid_i = freed >= 0;
    m_.free_slot_i = static_cast<std::remove_reference_t<decltype(m_.free_slot_i)>>(freed >= 0 ? freed : 0);
    m_.shadow_valid_i = shadow >= 0;
    m_.shadow_slot_i = static_cast<std::remove_reference_t<decltype(m_.shadow_slot_i)>>(shadow >= 0 ? shadow : 0);
    m_.eval();
    RguIssue o;
    o.valid = m_.out_valid_o;
    o.shadow = m_.out_shadow_o;
    o.slot = uint16_t(m_.out_slot_o);
    o.pixel = m_.out_pixel_o;
    o.ray = vl::get_ray(m_.out_ray_o, 0, W);
    m_.clk_i = 1;
    m_.eval();
    return o;
  }

  uint32_t free_slots() const override { return m_.free_count_o; }
  bool busy() const override { return m_.busy_o; }
  void stats(RtuStats& s) const override {
    s.primary_rays = m_.cnt_primary_o;
    s.shadow_rays = m_.cnt_shadow_o;
    s.rgu_stall_no_slot = m_.cnt_stall_o;
  }

 private:
  std::string name_;
  M m_;
};

}  // namespace

std::unique_ptr<RguRtl> make_rtl_rgu_unit(hls::FormatId f, hls::Rounding r, unsigned stages,
                                          unsigned tile, const SimConfig& cfg) {
#define RAYCORE_RTL_RGUU_VARIANT(prefix, fmt, mode, st, width, tile_px, slot_bits)    \
  if (vl::variant_is(#fmt, #mode, f, r) && stages == st && tile == tile_px)          \
    return std::make_unique<RguRtlT<prefix, width, slot_bits>>(                      \
        "Verilated rgu_unit " #fmt " " #mode " S=" #st, cfg);
#include "rtl_rgu_unit_variants.h"
#undef RAYCORE_RTL_RGUU_VARIANT
  return nullptr;
}

std::string rtl_rgu_unit_built() {
  std::string s;
#define RAYCORE_RTL_RGUU_VARIANT(prefix, fmt, mode, st, width, tile_px, slot_bits)            \
  s += std::string(s.empty() ? "" : ", ") + "rgu_unit " #fmt " " #mode " S=" #st " (" #tile_px \
       " x " #tile_px " tiles, slots " + std::to_string(1u << slot_bits) + ")";
#include "rtl_rgu_unit_variants.h"
#undef RAYCORE_RTL_RGUU_VARIANT
  return s.empty() ? "none" : s;
}

}  // namespace raycore::sc
