// tb/rtl/test_rtl_vtu.cpp - co-simulation of rtl/units/vtu.v (Verilator --cc, clocked from C++)
// against hls::Vtu<F, R>::node / ::tri, bit for bit, in order.
//
// One test per Verilated variant (format, rounding, STAGES; listed once in rtl/CMakeLists.txt,
// RAYCORE_RTL_VTU_VARIANTS). Each streams, through the unit's valid/ready handshake:
//   1. fullrate: 4096 records with no stalls (checks one record per cycle and latency 3*STAGES),
//   2. random: RAYCORE_RTL_VTU_RANDOM (default 200000) records with random input gaps and random
//      output back-pressure (bursty rates, new every 256 cycles),
// each a node (1/2; a quarter of them leaves) or a triangle (random k, flags, id; constants with
// magnitudes 1e-3..1e4, some zeros of either sign and some raw bit patterns), with a camera that
// changes every few records (magnitudes 1e-3..1e4, some zero coordinates) and vtu_on_i off for
// about 1/8 of the records (then the record must come out unchanged). A 16-bit sequence number
// rides in the tag. Summary line per run: `VTUSUM <variant> <set> vectors=N mismatches=M ...`;
// zero vectors or any mismatch fails; the first 10 mismatches print the record, the camera, the
// expected and the received fields.
#include <gtest/gtest.h>
#include <verilated.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>

#include "hls/fp.h"
#include "hls/image.h"
#include "hls/vtu.h"
#include "hls/wald.h"
#include "tb/rtl/rtl_cosim.h"
#include "tb/rtl/stimulus.h"

#include "rtl_vtu_models.h"

namespace raycore::rtltest {
namespace {

using hls::FP24;
using hls::FP32;
using hls::Rounding;

uint64_t random_count() {
  const char* s = std::getenv("RAYCORE_RTL_VTU_RANDOM");
  if (s == nullptr || *s == '\0') return 200000;
  return std::strtoull(s, nullptr, 10);
}

// Assigns to a Verilated port of any width (CData/SData/IData/QData) without -Wconversion noise.
template <class P, class U>
void set(P& port, U v) {
  port = static_cast<P>(v);
}

template <class F>
struct Out {
  bool tri = false;
  uint64_t node = 0;
  hls::WaldTri<F> t;
  bool operator==(const Out& o) const {
    if (tri != o.tri) return false;
    return tri ? t == o.t : node == o.node;
  }
};

std::string hex(uint64_t x) {
  char b[24];
  std::snprintf(b, sizeof b, "0x%llx", static_cast<unsigned long long>(x));
  return b;
}

template <class F>
std::string show(const Out<F>& o) {
  std::ostringstream s;
  if (!o.tri) {
    s << "node " << hex(o.node);
    return s.str();
  }
  s << "tri k=" << o.t.k << " flags=" << hex(o.t.flags) << " id=" << o.t.id << " c=[";
  for (int i = 0; i < 9; ++i) s << (i ? " " : "") << hex(o.t.c[i]);
  s << "]";
  return s.str();
}

template <class F>
std::string show(const Record<F>& r) {
  Out<F> o;
  o.tri = r.tri;
  o.node = r.node;
  o.t = r.t;
  std::ostringstream s;
  s << show(o) << " cam=[" << hex(r.cam[0]) << " " << hex(r.cam[1]) << " " << hex(r.cam[2])
    << "] on=" << r.on;
  return s.str();
}

template <class F, Rounding R>
Out<F> expect(const Record<F>& r) {
  Out<F> o;
  o.tri = r.tri;
  if (!r.on) {
    o.node = r.node;
    o.t = r.t;
    return o;
  }
  hls::Vtu<F, R> v;
  for (int i = 0; i < 3; ++i) v.c[i] = r.cam[i];
  if (r.tri)
    o.t = v.tri(r.t);
  else
    o.node = v.node(r.node);
  return o;
}

template <class V, class F, Rounding R>
class VtuCosim {
 public:
  VtuCosim(std::string name, int stages, uint64_t seed)
      : name_(std::move(name)), stages_(stages), gen_(seed), dut_(seed) {}

  void drive(const Record<F>& r) {
    V& m = *dut_;
    set(m.vtu_on_i, r.on);
    set(m.cam_x_i, r.cam[0]);
    set(m.cam_y_i, r.cam[1]);
    set(m.cam_z_i, r.cam[2]);
    set(m.in_kind_i, r.tri);
    set(m.in_node_i, r.node);
    set(m.in_k_i, r.t.k);
    set(m.in_flags_i, r.t.flags);
    set(m.in_c0_i, r.t.c[0]);
    set(m.in_c1_i, r.t.c[1]);
    set(m.in_c2_i, r.t.c[2]);
    set(m.in_c3_i, r.t.c[3]);
    set(m.in_c4_i, r.t.c[4]);
    set(m.in_c5_i, r.t.c[5]);
    set(m.in_c6_i, r.t.c[6]);
    set(m.in_c7_i, r.t.c[7]);
    set(m.in_c8_i, r.t.c[8]);
    set(m.in_id_i, r.t.id);
  }

  Out<F> read() {
    const V& m = *dut_;
    Out<F> o;
    o.tri = m.out_kind_o != 0;
    if (!o.tri) {
      o.node = m.out_node_o;
      return o;
    }
    o.t.k = m.out_k_o;
    o.t.flags = m.out_flags_o;
    o.t.id = m.out_id_o;
    o.t.c[0] = m.out_c0_o;
    o.t.c[1] = m.out_c1_o;
    o.t.c[2] = m.out_c2_o;
    o.t.c[3] = m.out_c3_o;
    o.t.c[4] = m.out_c4_o;
    o.t.c[5] = m.out_c5_o;
    o.t.c[6] = m.out_c6_o;
    o.t.c[7] = m.out_c7_o;
    o.t.c[8] = m.out_c8_o;
    return o;
  }

  // Streams `count` records; returns the number checked.
  uint64_t run(const std::string& set_name, uint64_t count, bool full) {
    struct Item {
      Record<F> r;
      Out<F> expected;
    };
    const uint64_t latency = 3u * uint64_t(stages_);
    const StreamSpec spec{name_, count, full, latency, "3*STAGES", 1000u + 64u * latency};
    std::mt19937_64& rng = gen_.rng();
    uint64_t mismatches = 0;
    const StreamStats st = stream(
        dut_, spec, rng, rng,
        [&](uint64_t) {
          Item it{gen_.next(), {}};
          it.expected = expect<F, R>(it.r);
          drive(it.r);
          return it;
        },
        [&] { drive(gen_.next()); },  // junk inputs
        [&](const Item& it, uint16_t seq, uint64_t cycle) {
          const Out<F> got = read();
          if (!(got == it.expected)) {
            ++mismatches;
            ADD_FAILURE() << mismatch(name_ + " [" + set_name + "] #" + std::to_string(mismatches),
                                      seq, cycle, show(it.r), show(it.expected), show(got));
          }
        },
        [&] { return mismatches >= 10; });
    EXPECT_GT(st.checked, 0u) << "no vectors checked";
    EXPECT_EQ(mismatches, 0u);
    std::printf("VTUSUM %s %s vectors=%llu mismatches=%llu cycles=%llu latency=%llu..%llu\n",
                name_.c_str(), set_name.c_str(), static_cast<unsigned long long>(st.checked),
                static_cast<unsigned long long>(mismatches),
                static_cast<unsigned long long>(st.cycles),
                static_cast<unsigned long long>(st.min_lat),
                static_cast<unsigned long long>(st.max_lat));
    return st.checked;
  }

 private:
  std::string name_;
  int stages_;
  Gen<F, R> gen_;
  Dut<V> dut_;
};

template <class V, class F, Rounding R>
void run_variant(const char* name, int stages) {
  const uint64_t seed = std::hash<std::string>{}(name);
  VtuCosim<V, F, R> sim(name, stages, seed);
  EXPECT_EQ(sim.run("fullrate", 4096, true), 4096u);
  const uint64_t n = random_count();
  EXPECT_EQ(sim.run("random", n, false), n);
}

#define RAYCORE_RTL_VTU_VARIANT(V, module, fmt, mode, stages) \
  TEST(RtlVtu, V) { run_variant<V, fmt, Rounding::mode>(#V, stages); }
#include "rtl_vtu_variants.h"
#undef RAYCORE_RTL_VTU_VARIANT

}  // namespace
}  // namespace raycore::rtltest
