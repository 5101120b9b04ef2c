// tb/rtl/test_rtl_vtu.cpp - co-simulation of rtl/units/vtu.v (Verilator --cc, clocked from C++)
// against hls::Vtu<F, R>::node / ::tri, bit for bit, in order.
//
// One test per Verilated variant (format, rounding, STAGES; listed once in rtl/CMakeLists.txt,
// RAYCORE_RTL_VTU_VARIANTS). Each streams, through the unit's valid/ready handshake:
//   1. fullrate: 4096 records with no stalls (checks one record per cycle and latency 2*STAGES),
//   2. random: RAYCORE_RTL_VTU_RANDOM (default 200000) records with random input gaps and random
//      output back-pressure (bursty rates, new every 256 cycles),
// each a node record (1/2) or a triangle (random k, flags, id; constants with magnitudes
// 1e-3..1e4, some zeros of either sign and some raw bit patterns), with a camera that changes
// every few records (magnitudes 1e-3..1e4, some zero coordinates) and vtu_on_i off for about 1/8
// of the records (then the record must come out unchanged). A node record is four nodes (lanes
// 0..3, each its own axis; a quarter of them leaves) with a lane mask in_nmask_i, half of the
// time random, half of the time a prefix 1, 3, 7 or 15 (a line's last group): lane j must come
// out as hls::Vtu::node if masked in, unchanged if not. A triangle gets random nodes and mask on
// the (don't-care) node inputs,
//   3. far: RAYCORE_RTL_VTU_RANDOM / 2 records far from the origin (FarGen): a camera near a point
//      with coordinates near 10^5 and real triangles (hls::make_wald) and splits near it (every
//      lane of a node record), so the constants are near 10^5 or above and the translated ones
//      small: the sops' heavy cancellation, with random gaps and back-pressure.
// A 16-bit sequence number rides in the tag. Summary line per run: `VTUSUM <variant> <set>
// vectors=N mismatches=M ... moved=a/b/c/d` (per lane, the node records whose split the VTU
// changed); zero vectors or any mismatch fails; the first 10 mismatches print the record, the
// camera, the expected and the received fields.
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

// vtu.v's node lanes.
constexpr int kLanes = 4;

// One record as driven: Record (the triangle, the camera, the enable; its node unused) and the
// four node lanes with their mask (for a triangle: don't-care junk).
template <class F>
struct Rec4 {
  Record<F> r;
  uint64_t node[kLanes] = {0, 0, 0, 0};
  uint32_t mask = 0;
};

template <class F>
struct Out {
  bool tri = false;
  uint64_t node[kLanes] = {0, 0, 0, 0};
  hls::WaldTri<F> t;
  bool operator==(const Out& o) const {
    if (tri != o.tri) return false;
    if (tri) return t == o.t;
    for (int j = 0; j < kLanes; ++j)
      if (node[j] != o.node[j]) return false;
    return true;
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
    s << "nodes";
    for (int j = 0; j < kLanes; ++j) s << " " << hex(o.node[j]);
    return s.str();
  }
  s << "tri k=" << o.t.k << " flags=" << hex(o.t.flags) << " id=" << o.t.id << " c=[";
  for (int i = 0; i < 9; ++i) s << (i ? " " : "") << hex(o.t.c[i]);
  s << "]";
  return s.str();
}

template <class F>
std::string show(const Rec4<F>& x) {
  const Record<F>& r = x.r;
  Out<F> o;
  o.tri = r.tri;
  for (int j = 0; j < kLanes; ++j) o.node[j] = x.node[j];
  o.t = r.t;
  std::ostringstream s;
  s << show(o);
  if (!r.tri) s << " mask=" << hex(x.mask);
  s << " cam=[" << hex(r.cam[0]) << " " << hex(r.cam[1]) << " " << hex(r.cam[2]) << "] on=" << r.on;
  return s.str();
}

template <class F, Rounding R>
Out<F> expect(const Rec4<F>& x) {
  const Record<F>& r = x.r;
  Out<F> o;
  o.tri = r.tri;
  o.t = r.t;
  for (int j = 0; j < kLanes; ++j) o.node[j] = x.node[j];
  if (!r.on) return o;
  hls::Vtu<F, R> v;
  for (int i = 0; i < 3; ++i) v.c[i] = r.cam[i];
  if (r.tri) {
    o.t = v.tri(r.t);
  } else {
    for (int j = 0; j < kLanes; ++j)
      if ((x.mask >> j) & 1u) o.node[j] = v.node(x.node[j]);
  }
  return o;
}

// A lane mask: half of the time random, half of the time a prefix (a line's last group).
inline uint32_t lane_mask(std::mt19937_64& rng) {
  if (rng() & 1u) return uint32_t(rng() & 15u);
  static constexpr uint32_t kPrefix[] = {1, 3, 7, 15};
  return kPrefix[rng() & 3u];
}

// A further node like Gen's (stimulus.h): any axis (a quarter leaves), random upper bits; a leaf
// any count, an inner node a split in the format.
template <class F, Rounding R>
uint64_t extra_node(Gen<F, R>& g) {
  std::mt19937_64& rng = g.rng();
  const uint64_t axis = rng() & 3u;
  uint64_t hi = (uint64_t(rng()) << 32) & ~(uint64_t(3) << 56);
  hi |= axis << 56;
  const uint32_t lo = axis == hls::node_leaf_axis ? uint32_t(rng()) : g.value();
  return hi | lo;
}

// Records far from the origin (the VTU's reason for one rounding): a region around a point P whose
// coordinates are near 10^5 (2^15 .. 2^18, random signs), a camera within 2^-4 .. 2^10 of P (now
// and then exactly at a triangle's vertex), triangles of size 2^-6 .. 2^10 near P (hls::make_wald:
// n_d near 10^5, b_d and c_d near 10^5 / size; now and then an edge parallel to an axis, zero
// products), inner nodes with a split near P's coordinate on their axis (a few leaves). The
// camera moves every few records; vtu_on_i is off for 1/16 of the records.
template <class F, Rounding R>
class FarGen {
 public:
  explicit FarGen(uint64_t seed) : rng_(seed) { new_region(); }
  Record<F> next() {
    if ((rng_() & 255u) == 0) new_region();
    if ((rng_() & 7u) == 0) move_camera();
    Record<F> r;
    r.on = (rng_() & 15u) != 0;
    r.tri = (rng_() & 3u) != 0;
    if (r.tri) {
      hls::Tri t;
      t[0] = {p_.x + off(-6, 10), p_.y + off(-6, 10), p_.z + off(-6, 10)};
      const double size = std::ldexp(1.0, int(rng_() % 17) - 6);
      for (int i = 1; i < 3; ++i)
        t[i] = {t[0].x + size * uni(-1, 1), t[0].y + size * uni(-1, 1), t[0].z + size * uni(-1, 1)};
      if ((rng_() & 7u) == 0) {  // an edge parallel to an axis plane: a zero normal component
        const int a = int(rng_() % 3);
        t[1][a] = t[0][a];
      }
      r.t = hls::make_wald<F, R>(t, uint32_t(rng_()));
      r.t.flags |= uint32_t(rng_() & 0xF0u);
      if ((rng_() & 15u) == 0)  // the camera exactly at the first vertex
        for (int i = 0; i < 3; ++i) cam_[i] = hls::from_double<F, R>(t[0][i]);
    } else {
      r.node = node();
    }
    for (int i = 0; i < 3; ++i) r.cam[i] = cam_[i];
    return r;
  }
  // An inner node with a split near P's coordinate on its axis (1/16 leaves).
  uint64_t node() {
    const uint64_t axis = (rng_() & 15u) == 0 ? hls::node_leaf_axis : rng_() % 3u;
    hls::Node n;
    n.axis = uint32_t(axis);
    n.index = uint32_t(rng_()) & hls::node_index_mask;
    n.split_or_count = axis == hls::node_leaf_axis
                           ? uint32_t(rng_())
                           : hls::from_double<F, R>(p_[int(axis)] + off(-6, 12));
    return hls::encode_node(n);
  }
  std::mt19937_64& rng() { return rng_; }

 private:
  double uni(double a, double b) { return a + (b - a) * (double(rng_() >> 11) * 0x1p-53); }
  // A random offset of magnitude 2^lo .. 2^hi, either sign.
  double off(int lo, int hi) {
    const double m = std::ldexp(uni(0.5, 1), lo + int(rng_() % uint64_t(hi - lo + 1)));
    return (rng_() & 1u) ? -m : m;
  }
  void new_region() {
    for (int i = 0; i < 3; ++i) {
      const double m = std::ldexp(uni(1, 8), 15);
      p_[i] = (rng_() & 1u) ? -m : m;
    }
    move_camera();
  }
  void move_camera() {
    for (int i = 0; i < 3; ++i) cam_[i] = hls::from_double<F, R>(p_[i] + off(-4, 10));
  }
  std::mt19937_64 rng_;
  hls::Vec3 p_;
  uint32_t cam_[3] = {0, 0, 0};
};

template <class F, Rounding R>
uint64_t extra_node(FarGen<F, R>& g) {
  return g.node();
}

// The next record of a generator: a node record's lane 0 is the generator's node, lanes 1..3
// further nodes of the same kind; a triangle's node lanes and mask are random junk.
template <class F, class G>
Rec4<F> next_rec(G& gen) {
  Rec4<F> x;
  x.r = gen.next();
  std::mt19937_64& rng = gen.rng();
  if (x.r.tri) {
    for (uint64_t& n : x.node) n = rng();
    x.mask = uint32_t(rng() & 15u);
    return x;
  }
  x.node[0] = x.r.node;
  for (int j = 1; j < kLanes; ++j) x.node[j] = extra_node(gen);
  x.mask = lane_mask(rng);
  return x;
}

template <class V, class F, Rounding R>
class VtuCosim {
 public:
  VtuCosim(std::string name, int stages, uint64_t seed)
      : name_(std::move(name)), stages_(stages), gen_(seed), far_(seed ^ 0x9e3779b97f4a7c15ull),
        dut_(seed) {}

  void drive(const Rec4<F>& x) {
    const Record<F>& r = x.r;
    V& m = *dut_;
    set(m.vtu_on_i, r.on);
    set(m.cam_x_i, r.cam[0]);
    set(m.cam_y_i, r.cam[1]);
    set(m.cam_z_i, r.cam[2]);
    set(m.in_kind_i, r.tri);
    set(m.in_node0_i, x.node[0]);
    set(m.in_node1_i, x.node[1]);
    set(m.in_node2_i, x.node[2]);
    set(m.in_node3_i, x.node[3]);
    set(m.in_nmask_i, x.mask);
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
      o.node[0] = m.out_node0_o;
      o.node[1] = m.out_node1_o;
      o.node[2] = m.out_node2_o;
      o.node[3] = m.out_node3_o;
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

  // Streams `count` records (from Gen, or from FarGen if far); returns the number checked.
  uint64_t run(const std::string& set_name, uint64_t count, bool full, bool far = false) {
    return far ? run_from(set_name, count, full, far_) : run_from(set_name, count, full, gen_);
  }

 private:
  template <class G>
  uint64_t run_from(const std::string& set_name, uint64_t count, bool full, G& gen) {
    struct Item {
      Rec4<F> r;
      Out<F> expected;
    };
    const uint64_t latency = 2u * uint64_t(stages_);
    const StreamSpec spec{name_, count, full, latency, "2*STAGES", 1000u + 64u * latency};
    std::mt19937_64& rng = gen.rng();
    uint64_t mismatches = 0;
    uint64_t moved[kLanes] = {0, 0, 0, 0};  // per lane: nodes whose expected split changed
    const StreamStats st = stream(
        dut_, spec, rng, rng,
        [&](uint64_t) {
          Item it{next_rec<F>(gen), {}};
          it.expected = expect<F, R>(it.r);
          if (!it.r.r.tri)
            for (int j = 0; j < kLanes; ++j) moved[j] += it.expected.node[j] != it.r.node[j];
          drive(it.r);
          return it;
        },
        [&] { drive(next_rec<F>(gen)); },  // junk inputs
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
    std::printf(
        "VTUSUM %s %s vectors=%llu mismatches=%llu cycles=%llu latency=%llu..%llu "
        "moved=%llu/%llu/%llu/%llu\n",
        name_.c_str(), set_name.c_str(), static_cast<unsigned long long>(st.checked),
        static_cast<unsigned long long>(mismatches), static_cast<unsigned long long>(st.cycles),
        static_cast<unsigned long long>(st.min_lat), static_cast<unsigned long long>(st.max_lat),
        static_cast<unsigned long long>(moved[0]), static_cast<unsigned long long>(moved[1]),
        static_cast<unsigned long long>(moved[2]), static_cast<unsigned long long>(moved[3]));
    return st.checked;
  }

  std::string name_;
  int stages_;
  Gen<F, R> gen_;
  FarGen<F, R> far_;
  Dut<V> dut_;
};

template <class V, class F, Rounding R>
void run_variant(const char* name, int stages) {
  const uint64_t seed = std::hash<std::string>{}(name);
  VtuCosim<V, F, R> sim(name, stages, seed);
  EXPECT_EQ(sim.run("fullrate", 4096, true), 4096u);
  const uint64_t n = random_count();
  EXPECT_EQ(sim.run("random", n, false), n);
  EXPECT_EQ(sim.run("far", n / 2, false, true), n / 2);
}

#define RAYCORE_RTL_VTU_VARIANT(V, module, fmt, mode, stages) \
  TEST(RtlVtu, V) { run_variant<V, fmt, Rounding::mode>(#V, stages); }
#include "rtl_vtu_variants.h"
#undef RAYCORE_RTL_VTU_VARIANT

}  // namespace
}  // namespace raycore::rtltest
