// tb/rtl/test_rtl_rgu.cpp - co-simulation of the ray generation unit (Verilator --cc, clocked from
// C++) against hls/rgu.h, bit for bit, in order.
//
// RtlRgu.<rgu_ray variant> (RAYCORE_RTL_RGU_VARIANTS, rtl/units/rgu.cmake): the datapath
// rtl/units/rgu_ray.v against hls::rgu_primary:
//   1. fullrate: 4096 pixels of one camera with no stalls (one ray per cycle, latency 8*STAGES),
//   2. random: RAYCORE_RTL_RGU_N (default 2*10^5) pixels over 100 cameras (the camera registers
//      change between streams, as between frames), random input gaps and output back-pressure.
//   Cameras: 3 in 4 from hls::rgu_camera for a random orthonormal basis, field of view 5..150
//   degrees and frame size (800 x 480 or random up to 4000 x 3000), origin 0 or a random point;
//   1 in 4 random register contents (any exponent, zeros of both signs). Pixels: a frame corner
//   1 time in 8, else uniform in the frame (raw cameras: any 16-bit coordinate). The tag (a
//   16-bit sequence number) and o, d, inv are compared. Summary `RGUSUM <variant> <set> ...`.
// RtlRguTop.<rgu variant> (RAYCORE_RTL_RGU_TOP_VARIANTS): the unit rtl/units/rgu.v (pixel walk
//   and datapath) runs whole frames for one RTU of N: 60 frames (sizes 1..90 x 1..60 and one
//   800 x 480, N = 1..8, every RTU index), the rays compared in order with hls::RguTiles (the
//   cycle model's order) and hls::rgu_primary: pixel index, o, d, inv. Every third frame runs at
//   full rate (out_ready_i always high: the rays must leave one per cycle, no bubble, the first
//   exactly max(rtu, N) / tiles_x + 2 + 8*STAGES cycles after start_i: hls::RguTiles::startup()
//   + 8*STAGES, the cycle model's start-up), the others with random
//   back-pressure. busy_o must fall after the frame's last ray. Summary `RGUTOPSUM ...`.
#include <gtest/gtest.h>
#include <verilated.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "hls/fp.h"
#include "hls/geom.h"
#include "hls/ray.h"
#include "hls/rgu.h"
#include "systemc/config.h"
#include "tb/rtl/rtl_cosim.h"

#include "rtl_rgu_models.h"
#include "rtl_rgu_top_models.h"

namespace raycore::rtltest {
namespace {

using hls::FP24;
using hls::FP32;
using hls::Rounding;
using hls::Vec3;

uint64_t random_count() {
  const char* s = std::getenv("RAYCORE_RTL_RGU_N");
  if (s == nullptr || *s == '\0') return 200000;
  return std::strtoull(s, nullptr, 10);
}

template <class P, class U>
void set(P& port, U v) {
  port = static_cast<P>(v);
}

// A camera as the unit holds it, with the frame it was made for.
struct Cam {
  hls::RguCamera c;
  uint32_t w = 1, h = 1;
  bool raw = false;
};

template <class A>
class CamGen {
 public:
  using F = typename A::Fmt;
  explicit CamGen(uint64_t seed) : rng_(seed) {}
  std::mt19937_64& rng() { return rng_; }
  double uni(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }

  // A random number of the format: any exponent, zeros of both signs.
  uint32_t raw_number() {
    const uint32_t k = uint32_t(rng_() % 16);
    const uint32_t sign = (rng_() & 1u) ? F::sign_mask : 0u;
    if (k == 0) return sign;
    if (k < 4) return sign | (uint32_t(rng_()) & F::max_mag);
    // Around 1 (a realistic direction component), exponents -8 .. 3.
    const int e = int(rng_() % 12) - 8;
    return sign | (uint32_t(F::bias + e) << F::man_bits) | (uint32_t(rng_()) & F::man_mask);
  }

  Cam next(bool realistic) {
    Cam cam;
    if (!realistic || rng_() % 4 == 0) {
      cam.raw = true;
      cam.w = cam.h = 1u << 16;
      for (int i = 0; i < 3; ++i) {
        cam.c.o[i] = raw_number();
        cam.c.d00[i] = raw_number();
        cam.c.dx[i] = raw_number();
        cam.c.dy[i] = raw_number();
      }
      return cam;
    }
    Vec3 f;
    do f = {uni(-1, 1), uni(-1, 1), uni(-1, 1)};
    while (hls::length(f) < 0.1);
    f = hls::normalize(f);
    if (rng_() % 4 == 0) f = Vec3{0, 0, -1};
    const Vec3 a = std::fabs(f.y) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    const Vec3 r = hls::normalize(hls::cross(f, a));
    const Vec3 up = hls::cross(r, f);
    const double yfov = uni(5, 150) * M_PI / 180.0;
    if (rng_() % 3 == 0) {
      cam.w = 800;
      cam.h = 480;
    } else {
      cam.w = 1 + uint32_t(rng_() % 4000);
      cam.h = 1 + uint32_t(rng_() % 3000);
    }
    uint32_t origin[3] = {0, 0, 0};
    if (rng_() % 2 == 0)
      for (int i = 0; i < 3; ++i) origin[i] = A::from_double(uni(-1, 1) * std::pow(10.0, uni(-3, 4)));
    cam.c = hls::rgu_camera<A>(origin, f, r, up, yfov, int(cam.w), int(cam.h));
    return cam;
  }

  // A pixel of the camera's frame: a corner 1 time in 8.
  void pixel(const Cam& cam, uint32_t& x, uint32_t& y) {
    if (rng_() % 8 == 0) {
      x = (rng_() & 1u) ? cam.w - 1 : 0;
      y = (rng_() & 1u) ? cam.h - 1 : 0;
    } else {
      x = uint32_t(rng_() % cam.w);
      y = uint32_t(rng_() % cam.h);
    }
  }

 private:
  std::mt19937_64 rng_;
};

template <class A>
std::string show_ray(const hls::Ray& r) {
  using F = typename A::Fmt;
  std::ostringstream s;
  auto v = [&](const char* n, const uint32_t* p) {
    s << n << "=[" << fptest::show<F>(p[0]) << " " << fptest::show<F>(p[1]) << " "
      << fptest::show<F>(p[2]) << "] ";
  };
  v("o", r.o);
  v("d", r.d);
  v("inv", r.inv);
  return s.str();
}

template <class A>
std::string show_cam(const hls::RguCamera& c, uint32_t x, uint32_t y) {
  using F = typename A::Fmt;
  std::ostringstream s;
  s << "pixel " << x << "," << y;
  auto v = [&](const char* n, const uint32_t* p) {
    s << " " << n << "=[" << fptest::show<F>(p[0]) << " " << fptest::show<F>(p[1]) << " "
      << fptest::show<F>(p[2]) << "]";
  };
  v("o", c.o);
  v("d00", c.d00);
  v("dx", c.dx);
  v("dy", c.dy);
  return s.str();
}

bool same_ray(const hls::Ray& a, const hls::Ray& b) {
  for (int i = 0; i < 3; ++i)
    if (a.o[i] != b.o[i] || a.d[i] != b.d[i] || a.inv[i] != b.inv[i]) return false;
  return true;
}

template <class V>
void drive_cam(V& m, const hls::RguCamera& c) {
  set(m.cam_o_x_i, c.o[0]);
  set(m.cam_o_y_i, c.o[1]);
  set(m.cam_o_z_i, c.o[2]);
  set(m.cam_d00_x_i, c.d00[0]);
  set(m.cam_d00_y_i, c.d00[1]);
  set(m.cam_d00_z_i, c.d00[2]);
  set(m.cam_dx_x_i, c.dx[0]);
  set(m.cam_dx_y_i, c.dx[1]);
  set(m.cam_dx_z_i, c.dx[2]);
  set(m.cam_dy_x_i, c.dy[0]);
  set(m.cam_dy_y_i, c.dy[1]);
  set(m.cam_dy_z_i, c.dy[2]);
}

template <class V>
hls::Ray read_ray(const V& m) {
  hls::Ray r;
  r.o[0] = m.out_o_x_o;
  r.o[1] = m.out_o_y_o;
  r.o[2] = m.out_o_z_o;
  r.d[0] = m.out_d_x_o;
  r.d[1] = m.out_d_y_o;
  r.d[2] = m.out_d_z_o;
  r.inv[0] = m.out_inv_x_o;
  r.inv[1] = m.out_inv_y_o;
  r.inv[2] = m.out_inv_z_o;
  return r;
}

// ---- the datapath -------------------------------------------------------------------------------

template <class V, class A>
class RayCosim {
 public:
  RayCosim(std::string name, int stages, uint64_t seed)
      : name_(std::move(name)), stages_(stages), gen_(seed), dut_(seed) {}

  // Streams `count` pixels of camera cam; returns the number checked.
  uint64_t run(const std::string& set_name, const Cam& cam, uint64_t count, bool full) {
    struct Item {
      uint32_t x = 0, y = 0;
      hls::Ray expected;
    };
    V& m = *dut_;
    drive_cam(m, cam.c);
    const uint64_t latency = uint64_t(sc::kRguLevels) * uint64_t(stages_);
    const StreamSpec spec{name_, count, full, latency, "15*STAGES", 1000u + 64u * latency};
    std::mt19937_64& rng = gen_.rng();
    const StreamStats st = stream(
        dut_, spec, rng, rng,
        [&](uint64_t) {
          Item it;
          gen_.pixel(cam, it.x, it.y);
          it.expected = hls::rgu_primary<A>(cam.c, it.x, it.y, 0);
          set(m.in_x_i, it.x);
          set(m.in_y_i, it.y);
          return it;
        },
        [&] {  // junk coordinates
          set(m.in_x_i, rng() & 0xffffu);
          set(m.in_y_i, rng() & 0xffffu);
        },
        [&](const Item& it, uint16_t seq, uint64_t cycle) {
          const hls::Ray got = read_ray(m);
          if (!same_ray(got, it.expected)) {
            ++mismatches_;
            ADD_FAILURE() << mismatch(name_ + " [" + set_name + "] #" + std::to_string(mismatches_),
                                      seq, cycle, show_cam<A>(cam.c, it.x, it.y),
                                      show_ray<A>(it.expected), show_ray<A>(got));
          }
        },
        [&] { return mismatches_ >= 10; });
    EXPECT_EQ(st.checked, count);
    cycles_ += st.cycles;
    min_lat_ = std::min(min_lat_, st.min_lat);
    max_lat_ = std::max(max_lat_, st.max_lat);
    return st.checked;
  }

  void summary(const std::string& set_name, uint64_t vectors) {
    EXPECT_EQ(mismatches_, 0u);
    std::printf("RGUSUM %s %s vectors=%llu mismatches=%llu cycles=%llu latency=%llu..%llu\n",
                name_.c_str(), set_name.c_str(), (unsigned long long)vectors,
                (unsigned long long)mismatches_, (unsigned long long)cycles_,
                (unsigned long long)min_lat_, (unsigned long long)max_lat_);
    cycles_ = 0;
    min_lat_ = ~uint64_t(0);
    max_lat_ = 0;
  }
  CamGen<A>& gen() { return gen_; }

 private:
  std::string name_;
  int stages_;
  CamGen<A> gen_;
  Dut<V> dut_;
  uint64_t mismatches_ = 0, cycles_ = 0, min_lat_ = ~uint64_t(0), max_lat_ = 0;
};

template <class V, class F, Rounding R>
void run_ray_variant(const char* name, int stages) {
  using A = hls::Arith<F, R>;
  RayCosim<V, A> sim(name, stages, std::hash<std::string>{}(name));
  Cam cam = sim.gen().next(true);
  while (cam.raw) cam = sim.gen().next(true);
  EXPECT_EQ(sim.run("fullrate", cam, 4096, true), 4096u);
  sim.summary("fullrate", 4096);
  const uint64_t n = random_count();
  const uint64_t cams = std::max<uint64_t>(1, std::min<uint64_t>(100, n));
  uint64_t done = 0;
  for (uint64_t k = 0; k < cams; ++k) {
    const uint64_t c = n / cams + (k < n % cams ? 1 : 0);
    done += sim.run("random", sim.gen().next(k % 4 != 3), c, false);
  }
  EXPECT_EQ(done, n);
  sim.summary("random", done);
}

#define RAYCORE_RTL_RGU_VARIANT(V, module, fmt, mode, stages) \
  TEST(RtlRgu, V) { run_ray_variant<V, fmt, Rounding::mode>(#V, stages); }
#include "rtl_rgu_variants.h"
#undef RAYCORE_RTL_RGU_VARIANT

// ---- the unit: walk + datapath ------------------------------------------------------------------

template <class V, class A>
void run_top_variant(const char* name, int stages, int tile_bits) {
  const uint64_t seed = std::hash<std::string>{}(name);
  CamGen<A> gen(seed);
  std::mt19937_64& rng = gen.rng();
  Dut<V> dut(seed);
  V& m = *dut;
  // Reset (Dut::reset drives in_valid_i, which the unit does not have: its input is start_i).
  m.clk_i = 0;
  m.rst_ni = 1;
  m.start_i = 0;
  m.out_ready_i = 0;
  m.eval();
  m.rst_ni = 0;
  m.eval();
  dut.clock();
  dut.clock();
  m.rst_ni = 1;
  m.eval();
  const int tile = 1 << tile_bits;
  uint64_t rays = 0, mismatches = 0, cycles = 0, frames = 0;
  for (int k = 0; k < 60 && mismatches < 10; ++k) {
    Cam cam = gen.next(true);
    while (cam.raw) cam = gen.next(true);
    int w = 1 + int(rng() % 90), h = 1 + int(rng() % 60);
    if (k == 0) {
      w = 800;
      h = 480;
    }
    const int rtus = 1 + int(rng() % 8), rtu = int(rng() % uint64_t(rtus));
    const uint32_t origin[3] = {cam.c.o[0], cam.c.o[1], cam.c.o[2]};
    // Any camera works for any frame; make it for this one.
    const Vec3 f{0.3, -0.2, -1}, r{1, 0, 0.3}, up{0, 1, -0.2};
    if (rng() % 2 == 0) cam.c = hls::rgu_camera<A>(origin, f, r, up, 0.9, w, h);
    const bool full = k % 3 == 0;
    std::vector<std::pair<uint32_t, hls::Ray>> expect;
    for (hls::RguTiles t(w, h, tile, rtu, rtus); !t.done(); t.next())
      expect.emplace_back(t.pixel(), hls::rgu_primary<A>(cam.c, uint32_t(t.x()), uint32_t(t.y()), 0));
    // The first ray's cycle, counted from the start_i cycle (cycle -1 here): hls::RguTiles's
    // walk start-up (the cycle model's, systemc/rgu.h) + kRguLevels x STAGES.
    const uint64_t setup =
        uint64_t(hls::RguTiles(w, h, tile, rtu, rtus).startup() + sc::kRguLevels * stages);

    drive_cam(m, cam.c);
    set(m.width_i, w);
    set(m.height_i, h);
    set(m.rtu_i, rtu);
    set(m.rtus_i, rtus);
    set(m.start_i, 1);
    set(m.out_ready_i, 0);
    m.eval();
    dut.clock();
    set(m.start_i, 0);
    size_t next = 0;
    uint64_t first = 0, last = 0, c = 0;
    uint32_t p_stall = 0;
    for (;; ++c) {
      if ((c & 63u) == 0) p_stall = uint32_t(rng() % 8);
      set(m.out_ready_i, full || uint32_t(rng() % 8) >= p_stall ? 1 : 0);
      m.eval();
      if (m.out_valid_o && m.out_ready_i) {
        if (next >= expect.size()) {
          ADD_FAILURE() << name << " frame " << k << ": ray after the last one";
          ++mismatches;
          break;
        }
        if (next == 0) first = c;
        last = c;
        const hls::Ray got = read_ray(m);
        const uint32_t pix = m.out_pixel_o;
        if (pix != expect[next].first || !same_ray(got, expect[next].second)) {
          ++mismatches;
          ADD_FAILURE() << name << " frame " << k << " (" << w << "x" << h << ", rtu " << rtu << " of "
                        << rtus << ") ray " << next << ": expected pixel " << expect[next].first << " "
                        << show_ray<A>(expect[next].second) << "\n  got pixel " << pix << " "
                        << show_ray<A>(got);
          if (mismatches >= 10) break;
        }
        ++next;
      }
      if (!m.busy_o) break;
      if (c > 100000 + 20 * expect.size()) {
        ADD_FAILURE() << name << " frame " << k << ": busy_o still high after " << c << " cycles";
        ++mismatches;
        break;
      }
      dut.clock();
    }
    EXPECT_EQ(next, expect.size()) << name << " frame " << k << " (" << w << "x" << h << ", rtu "
                                   << rtu << " of " << rtus << ")";
    if (full && !expect.empty()) {
      EXPECT_EQ(last - first + 1, expect.size()) << name << " frame " << k << ": bubbles at full rate";
      EXPECT_EQ(first + 1, setup) << name << " frame " << k << ": set-up latency";
    }
    rays += next;
    cycles += c;
    ++frames;
    dut.clock();
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(rays, 0u);
  std::printf("RGUTOPSUM %s frames=%llu rays=%llu mismatches=%llu cycles=%llu\n", name,
              (unsigned long long)frames, (unsigned long long)rays, (unsigned long long)mismatches,
              (unsigned long long)cycles);
}

#define RAYCORE_RTL_RGU_TOP_VARIANT(V, mode, e_bits, m_bits, rne_bit, raycore_bit, stages, tile_bits) \
  TEST(RtlRguTop, V) {                                                                           \
    run_top_variant<V, hls::Arith<hls::Format<e_bits, m_bits>, Rounding::mode>>(#V, stages,       \
                                                                               tile_bits);         \
  }
#include "rtl_rgu_top_variants.h"
#undef RAYCORE_RTL_RGU_TOP_VARIANT

}  // namespace
}  // namespace raycore::rtltest
