// tb/rtl/test_rtl_hit.cpp - co-simulation of the hit unit rtl/units/hit.v (Verilator --cc, clocked
// from C++) against hls::hit_shadow_regs (hls/hit.h), bit for bit, in order.
//
// RtlHit.<variant> (RAYCORE_RTL_HIT_VARIANTS, rtl/units/hit.cmake):
//   1. fullrate: 4096 hits with no stalls (one per cycle, latency exactly 24*STAGES:
//      systemc/config.h kHitLevels), error-bound
//      with unit shadow rays (the longest data flow),
//   2. random: RAYCORE_RTL_HIT_N (default 10^5) hits in 70 runs with random input gaps and output
//      back-pressure; each run has its own per-frame registers (the pipeline is empty between
//      runs, as between frames): the strategy (run % 7: every one 10 times), segment or unit
//      shadow direction, --shadow-spawn front or all, --spawn-ulps (0..16 mostly, sometimes up
//      to 2^20 or negative), hls::hit_regs of those or (1 run in 5) random register contents,
//      the light (a point around the scene, or random bits) and t_min (2^-12, random small, or
//      random bits).
//   Hits: 85 % a ray aimed at a random triangle (tb/rtl/stimulus.h, as the ist test) with t and
//   den from hls::ist_wald when it hits (else a random t and den computed as the ist does), 15 %
//   random bit patterns for every input. Every output is compared: h, front, spawn, dens, the
//   shadow ray's o, d, inv, tmin, tmax, skip id, and the tag (a sequence number). Summary line
//   `HITSUM <variant> <set> vectors=... mismatches=... spawned=... front=... per-strategy ...`;
//   every strategy must have spawned rays.
// RtlHit.<variant> (RAYCORE_RTL_HIT_SPAWNS_VARIANTS): hit.v built for fewer strategies (SPAWNS),
// as hit_unit builds it (FREE = 1: the carries in fp_delay memories, the output never held back):
// the same runs with the strategies it supports and without back-pressure, and a run with each
// strategy it does not support driven on strategy_i, which must give strategy none's results.
#include <gtest/gtest.h>
#include <verilated.h>

#include <array>
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
#include "hls/hit.h"
#include "hls/ist.h"
#include "hls/margins.h"
#include "systemc/config.h"
#include "tb/fp/fp_check.h"
#include "tb/rtl/rtl_cosim.h"
#include "tb/rtl/stimulus.h"

#include "rtl_hit_models.h"
#if __has_include("rtl_hit_spawns_models.h")
#include "rtl_hit_spawns_models.h"
#endif

namespace raycore::rtltest {
namespace {

using hls::FP24;
using hls::FP32;

uint64_t random_count() {
  const char* s = std::getenv("RAYCORE_RTL_HIT_N");
  if (s == nullptr || *s == '\0') return 100000;
  return std::strtoull(s, nullptr, 10);
}

template <class P, class U>
void set(P& port, U v) {
  port = static_cast<P>(v);
}

// The per-frame registers of one run.
struct Regs {
  hls::SpawnParams sp;
  hls::HitRegs g;
  uint32_t light[3] = {};
  uint32_t tmin = 0;
};

// One hit's inputs.
struct HitIn {
  hls::Ray pr;
  uint32_t t = 0;
  hls::HitTri tri{};
};

template <class A>
std::string show_in(const HitIn& x, const Regs& r) {
  using F = typename A::Fmt;
  std::ostringstream s;
  auto v = [&](const char* n, const uint32_t* p) {
    s << n << "=[" << fptest::show<F>(p[0]) << " " << fptest::show<F>(p[1]) << " "
      << fptest::show<F>(p[2]) << "] ";
  };
  v("o", x.pr.o);
  v("d", x.pr.d);
  s << "t=" << fptest::show<F>(x.t) << " k=" << x.tri.k << " nu=" << fptest::show<F>(x.tri.n_u)
    << " nv=" << fptest::show<F>(x.tri.n_v) << " nd=" << fptest::show<F>(x.tri.n_d)
    << " den=" << fptest::show<F>(x.tri.den) << " id=" << x.tri.id << " | strategy "
    << int(r.sp.spawn) << " segment " << r.sp.segment << " all " << r.sp.spawn_all << " ";
  v("light", r.light);
  s << "tmin=" << fptest::show<F>(r.tmin) << " scale=" << fptest::show<F>(r.g.scale)
    << " fixed=" << fptest::show<F>(r.g.fixed) << " slab=" << fptest::show<F>(r.g.slab_scale)
    << " back=" << r.g.back;
  return s.str();
}

template <class A>
std::string show_out(const hls::ShadowSetup& s) {
  using F = typename A::Fmt;
  std::ostringstream o;
  auto v = [&](const char* n, const uint32_t* p) {
    o << n << "=[" << fptest::show<F>(p[0]) << " " << fptest::show<F>(p[1]) << " "
      << fptest::show<F>(p[2]) << "] ";
  };
  v("h", s.h);
  o << "front=" << s.front << " spawn=" << s.spawn << " dens=" << fptest::show<F>(s.dens) << " ";
  v("o", s.ray.o);
  v("d", s.ray.d);
  v("inv", s.ray.inv);
  o << "tmin=" << fptest::show<F>(s.ray.tmin) << " tmax=" << fptest::show<F>(s.ray.tmax)
    << " skip=" << s.skip_id;
  return o.str();
}

bool same(const hls::ShadowSetup& a, const hls::ShadowSetup& b) {
  for (int i = 0; i < 3; ++i)
    if (a.h[i] != b.h[i] || a.ray.o[i] != b.ray.o[i] || a.ray.d[i] != b.ray.d[i] ||
        a.ray.inv[i] != b.ray.inv[i])
      return false;
  return a.front == b.front && a.spawn == b.spawn && a.dens == b.dens && a.ray.tmin == b.ray.tmin &&
         a.ray.tmax == b.ray.tmax && a.skip_id == b.skip_id;
}

template <class V>
void drive_regs(V& m, const Regs& r) {
  set(m.light_x_i, r.light[0]);
  set(m.light_y_i, r.light[1]);
  set(m.light_z_i, r.light[2]);
  set(m.tmin_i, r.tmin);
  set(m.strategy_i, uint32_t(r.sp.spawn));
  set(m.segment_i, r.sp.segment ? 1 : 0);
  set(m.all_i, r.sp.spawn_all ? 1 : 0);
  set(m.back_i, uint32_t(r.g.back));
  set(m.scale_i, r.g.scale);
  set(m.fixed_i, r.g.fixed);
  set(m.slab_scale_i, r.g.slab_scale);
}

template <class V>
void drive_in(V& m, const HitIn& x) {
  set(m.in_o_x_i, x.pr.o[0]);
  set(m.in_o_y_i, x.pr.o[1]);
  set(m.in_o_z_i, x.pr.o[2]);
  set(m.in_d_x_i, x.pr.d[0]);
  set(m.in_d_y_i, x.pr.d[1]);
  set(m.in_d_z_i, x.pr.d[2]);
  set(m.in_t_i, x.t);
  set(m.in_k_i, x.tri.k);
  set(m.in_nu_i, x.tri.n_u);
  set(m.in_nv_i, x.tri.n_v);
  set(m.in_nd_i, x.tri.n_d);
  set(m.in_den_i, x.tri.den);
  set(m.in_id_i, x.tri.id);
}

template <class V>
hls::ShadowSetup read_out(const V& m) {
  hls::ShadowSetup s{};
  s.h[0] = m.out_h_x_o;
  s.h[1] = m.out_h_y_o;
  s.h[2] = m.out_h_z_o;
  s.front = m.out_front_o != 0;
  s.spawn = m.out_spawn_o != 0;
  s.dens = m.out_dens_o;
  s.ray.o[0] = m.out_o_x_o;
  s.ray.o[1] = m.out_o_y_o;
  s.ray.o[2] = m.out_o_z_o;
  s.ray.d[0] = m.out_d_x_o;
  s.ray.d[1] = m.out_d_y_o;
  s.ray.d[2] = m.out_d_z_o;
  s.ray.inv[0] = m.out_inv_x_o;
  s.ray.inv[1] = m.out_inv_y_o;
  s.ray.inv[2] = m.out_inv_z_o;
  s.ray.tmin = m.out_tmin_o;
  s.ray.tmax = m.out_tmax_o;
  s.skip_id = m.out_skip_id_o;
  return s;
}

template <class V, class A>
class HitCosim {
  using F = typename A::Fmt;

 public:
  // free: the variant is built FREE = 1 (its output is never held back: no back-pressure).
  HitCosim(std::string name, int stages, uint64_t seed, bool free = false)
      : name_(std::move(name)), stages_(stages), free_(free), rng_(seed), stim_(seed ^ 0x5eedu),
        dut_(seed) {}

  double uni(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  uint32_t bits() { return uint32_t(rng_()) & F::mask; }

  Regs regs(hls::Spawn strategy) {
    Regs r;
    r.sp.spawn = strategy;
    r.sp.segment = (rng_() & 1u) != 0;
    r.sp.spawn_all = (rng_() & 1u) != 0;
    const uint32_t u = uint32_t(rng_() % 8);
    r.sp.ulps = u < 6 ? int32_t(rng_() % 17) : u == 6 ? int32_t(rng_() % (1u << 20)) : -int32_t(rng_() % 64);
    r.g = hls::hit_regs<A>(r.sp);
    if (rng_() % 5 == 0) {
      r.g.scale = bits();
      r.g.fixed = bits();
      r.g.slab_scale = bits();
      r.g.back = int32_t(uint32_t(rng_()));
    }
    if (rng_() % 5 == 0) {
      for (uint32_t& l : r.light) l = bits();
    } else {
      const double s = std::ldexp(1.0, int(rng_() % 13) - 4);
      for (uint32_t& l : r.light) l = A::from_double(uni(-s, s));
    }
    const uint32_t tk = uint32_t(rng_() % 4);
    r.tmin = tk < 2 ? A::from_double(std::ldexp(1.0, -12)) : tk == 2 ? A::from_double(uni(0, 0.1)) : bits();
    return r;
  }

  HitIn next() {
    HitIn x;
    x.tri.id = uint32_t(rng_());
    const IstIn s = stim_.next();
    x.tri.k = s.k;
    x.tri.n_u = s.c[hls::kNU];
    x.tri.n_v = s.c[hls::kNV];
    x.tri.n_d = s.c[hls::kND];
    for (int i = 0; i < 3; ++i) {
      x.pr.o[i] = s.o[i];
      x.pr.d[i] = s.d[i];
    }
    if (rng_() % 100 < 15) {  // every input random
      x.t = bits();
      x.tri.den = bits();
      x.tri.n_u = bits();
      x.tri.n_v = bits();
      x.tri.n_d = bits();
      for (int i = 0; i < 3; ++i) {
        x.pr.o[i] = bits();
        x.pr.d[i] = bits();
      }
      return x;
    }
    const hls::IstOut o = hls::ist_wald<A>(s.k, s.c, s.o, s.d, s.tmin, s.tmax, hls::Margins{});
    if (o.exit == hls::IstExit::hit) {
      x.t = o.t;
      x.tri.den = o.den;
    } else {
      const int u = hls::axis_u(s.k), v = hls::axis_v(s.k);
      x.t = A::from_double(std::ldexp(uni(0.5, 1), int(rng_() % 16) - 6));
      x.tri.den = A::add3(s.d[s.k], A::mul(x.tri.n_u, s.d[u]), A::mul(x.tri.n_v, s.d[v]));
    }
    return x;
  }

  // Streams `count` hits under the registers r; returns the number checked.
  // drive >= 0: strategy_i is driven with it instead of r's (a strategy the variant lacks; r's is
  // none, whose results it must give).
  uint64_t run(const Regs& r, uint64_t count, bool full, int drive = -1) {
    struct Item {
      HitIn x;
      hls::ShadowSetup expected;
    };
    V& m = *dut_;
    drive_regs(m, r);
    if (drive >= 0) set(m.strategy_i, uint32_t(drive));
    const uint64_t latency = uint64_t(sc::kHitLevels) * stages_;
    StreamSpec spec{name_, count, full, latency, "24*STAGES", 1000u + 64u * latency};
    spec.never_stall = free_;
    const StreamStats st = stream(
        dut_, spec, rng_, rng_,
        [&](uint64_t) {
          Item it;
          it.x = next();
          it.expected = hls::hit_shadow_regs<A>(it.x.pr, it.x.t, it.x.tri, r.light, r.tmin, r.sp, r.g);
          drive_in(m, it.x);
          return it;
        },
        [&] {  // junk inputs
          HitIn j;
          for (int i = 0; i < 3; ++i) {
            j.pr.o[i] = bits();
            j.pr.d[i] = bits();
          }
          j.t = bits();
          j.tri = {uint32_t(rng_()), uint32_t(rng_() % 4), bits(), bits(), bits(), bits()};
          drive_in(m, j);
        },
        [&](const Item& it, uint16_t seq, uint64_t cycle) {
          const hls::ShadowSetup got = read_out(m);
          const hls::ShadowSetup& e = it.expected;
          if (!same(got, e)) {
            ++mismatches_;
            ADD_FAILURE() << mismatch(name_ + " #" + std::to_string(mismatches_), seq, cycle,
                                      show_in<A>(it.x, r), show_out<A>(e), show_out<A>(got));
          }
          spawned_ += e.spawn;
          front_ += e.front;
          if (e.spawn) ++per_[size_t(r.sp.spawn)];
        },
        [&] { return mismatches_ >= 10; });
    EXPECT_EQ(st.checked, count);
    cycles_ += st.cycles;
    min_lat_ = std::min(min_lat_, st.min_lat);
    max_lat_ = std::max(max_lat_, st.max_lat);
    return st.checked;
  }

  // every_strategy: each strategy in the mask `spawns` must have spawned rays.
  void summary(const std::string& set_name, uint64_t vectors, bool every_strategy,
               unsigned spawns = 127) {
    EXPECT_EQ(mismatches_, 0u);
    std::string per;
    for (size_t i = 0; i < per_.size(); ++i) {
      per += " s" + std::to_string(i) + "=" + std::to_string(per_[i]);
      if (every_strategy && ((spawns >> i) & 1u) != 0) {
        EXPECT_GT(per_[i], 0u) << name_ << ": strategy " << i << " never spawned";
      }
    }
    std::printf("HITSUM %s %s vectors=%llu mismatches=%llu spawned=%llu front=%llu cycles=%llu "
                "latency=%llu..%llu%s\n",
                name_.c_str(), set_name.c_str(), (unsigned long long)vectors,
                (unsigned long long)mismatches_, (unsigned long long)spawned_,
                (unsigned long long)front_, (unsigned long long)cycles_,
                (unsigned long long)min_lat_, (unsigned long long)max_lat_, per.c_str());
    spawned_ = front_ = cycles_ = 0;
    per_.fill(0);
    min_lat_ = ~uint64_t(0);
    max_lat_ = 0;
  }

 private:
  std::string name_;
  int stages_;
  bool free_;
  std::mt19937_64 rng_;
  Stimulus<F, A::rounding> stim_;
  Dut<V> dut_;
  uint64_t mismatches_ = 0, spawned_ = 0, front_ = 0, cycles_ = 0;
  uint64_t min_lat_ = ~uint64_t(0), max_lat_ = 0;
  std::array<uint64_t, 7> per_{};
};

// spawns: the mask of strategies the variant supports (hit.v's SPAWNS).
template <class V, class F, hls::Rounding R>
void run_variant(const char* name, int stages, unsigned spawns = 127, bool free = false) {
  using A = hls::Arith<F, R>;
  std::vector<hls::Spawn> have;
  for (int s = 0; s < 7; ++s)
    if ((spawns >> s) & 1u) have.push_back(hls::Spawn(s));
  ASSERT_FALSE(have.empty()) << name << ": SPAWNS " << spawns << " supports no strategy";
  HitCosim<V, A> sim(name, stages, std::hash<std::string>{}(name), free);
  const bool eb = ((spawns >> int(hls::Spawn::error_bound)) & 1u) != 0;
  Regs full = sim.regs(eb ? hls::Spawn::error_bound : have.back());
  full.sp.segment = false;
  full.sp.spawn_all = false;
  full.sp.ulps = 0;
  full.g = hls::hit_regs<A>(full.sp);
  EXPECT_EQ(sim.run(full, 4096, true), 4096u);
  sim.summary("fullrate", 4096, false);
  const uint64_t n = random_count();
  constexpr uint64_t kRuns = 70;
  uint64_t done = 0;
  for (uint64_t k = 0; k < kRuns; ++k) {
    const uint64_t c = n / kRuns + (k < n % kRuns ? 1 : 0);
    done += sim.run(sim.regs(have[k % have.size()]), c, false);
  }
  EXPECT_EQ(done, n);
  sim.summary("random", done, n >= 7000, spawns);
  if (spawns == 127 || ((spawns & 1u) == 0)) return;
  // The strategies not built act as none.
  uint64_t lacking = 0;
  for (int s = 1; s < 8; ++s) {
    if (s < 7 && ((spawns >> s) & 1u) != 0) continue;
    Regs r = sim.regs(hls::Spawn::none);
    lacking += sim.run(r, 500, false, s);
  }
  sim.summary("lacking", lacking, false);
}

#define RAYCORE_RTL_HIT_VARIANT(V, module, fmt, mode, stages) \
  TEST(RtlHit, V) { run_variant<V, fmt, hls::Rounding::mode>(#V, stages); }
#include "rtl_hit_variants.h"
#undef RAYCORE_RTL_HIT_VARIANT

#if __has_include("rtl_hit_spawns_variants.h")
#define RAYCORE_RTL_HIT_SPAWNS_VARIANT(V, spawns, free) \
  TEST(RtlHit, V) { run_variant<V, FP24, hls::Rounding::rtz>(#V, 2, spawns, free != 0); }
#include "rtl_hit_spawns_variants.h"
#undef RAYCORE_RTL_HIT_SPAWNS_VARIANT
#endif

}  // namespace
}  // namespace raycore::rtltest
