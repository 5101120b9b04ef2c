// tb/fp/fp_check.h - test plumbing for the hls/fp.h oracle tests: knobs from the environment,
// the mismatch tally with its summary line, the directed operand sets and the random operand
// generators.
//
// Environment:
//   RAYCORE_FP_RANDOM             random vectors per op, mode and format (default 1e6; `make bench`
//                                 runs 1e8). Accepts integers or forms like 1e8.
//   RAYCORE_FP_SEED               base seed of the random generators (default 0x52415943).
//   RAYCORE_FP_EXHAUSTIVE_STRIDE  step through the 2^24 FP24 patterns (default 1 = all of them);
//                                 for slow sanitizer builds only.
//   RAYCORE_FP_SUMMARY            file to which every summary line is appended as well.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "tb/fp/fp_ref.h"

namespace raycore::fptest {

inline uint64_t env_count(const char* name, uint64_t dflt) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == '\0') return dflt;
  errno = 0;
  char* end = nullptr;
  const double d = std::strtod(v, &end);
  if (errno != 0 || end == v || *end != '\0' || !(d >= 0) || d > 1e15 || d != double(uint64_t(d)))
    throw std::runtime_error(std::string("environment variable ") + name + "='" + v +
                             "' is not a non-negative integer");
  return uint64_t(d);
}
inline uint64_t random_count() { return env_count("RAYCORE_FP_RANDOM", 1000000); }
inline uint64_t base_seed() { return env_count("RAYCORE_FP_SEED", 0x52415943); }
inline uint32_t exhaustive_stride() {
  const uint64_t s = env_count("RAYCORE_FP_EXHAUSTIVE_STRIDE", 1);
  if (s == 0 || s > (1u << 20))
    throw std::runtime_error("RAYCORE_FP_EXHAUSTIVE_STRIDE must be in 1..2^20");
  return uint32_t(s);
}
// A seed per test, from the base seed and the test's name.
inline uint64_t seed_for(const std::string& name) {
  uint64_t h = 1469598103934665603ull ^ base_seed();
  for (char c : name) h = (h ^ uint8_t(c)) * 1099511628211ull;
  return h;
}

// Counts vectors and mismatches of one (format, op, mode, vector set). Prints at most
// kMaxReported mismatches (as gtest failures) and then asks the loop to stop; on finish() prints
// the summary line `FPSUM <fmt> <op> <mode> <set> vectors=N mismatches=K ...`, fails if no vector
// was checked, and fails if any mismatched.
class Tally {
 public:
  static constexpr uint64_t kMaxReported = 10;
  Tally(std::string fmt, std::string op, std::string mode, std::string set)
      : fmt_(std::move(fmt)), op_(std::move(op)), mode_(std::move(mode)), set_(std::move(set)) {}
  Tally(const Tally&) = delete;
  Tally& operator=(const Tally&) = delete;
  ~Tally() {
    if (!finished_) finish();
  }

  // Records one vector; on a mismatch, `describe()` gives the operands. Returns true if the
  // loop may go on.
  template <class T, class Describe>
  bool check(const T& got, const T& expected, Describe&& describe) {
    ++vectors_;
    if (got == expected) return true;
    ++mismatches_;
    if (mismatches_ <= kMaxReported)
      ADD_FAILURE() << fmt_ << " " << op_ << " " << mode_ << " [" << set_ << "] mismatch #"
                    << mismatches_ << "\n  operands: " << describe() << "\n  expected: "
                    << expected_str(expected) << "\n  got:      " << expected_str(got);
    return mismatches_ < kMaxReported;
  }
  void skip() { ++skipped_; }
  // For a tally that does not apply to this run: no summary line, no checks.
  void discard() { finished_ = true; }
  void note(const std::string& s) { notes_ += " " + s; }
  bool stopped() const { return mismatches_ >= kMaxReported; }
  uint64_t vectors() const { return vectors_; }
  uint64_t mismatches() const { return mismatches_; }

  void finish() {
    finished_ = true;
    std::ostringstream line;
    line << "FPSUM " << fmt_ << " " << op_ << " " << mode_ << " " << set_ << " vectors=" << vectors_
         << " mismatches=" << mismatches_;
    if (skipped_ != 0) line << " skipped=" << skipped_;
    if (stopped()) line << " (stopped after " << kMaxReported << " mismatches)";
    line << notes_;
    std::printf("%s\n", line.str().c_str());
    std::fflush(stdout);
    if (const char* path = std::getenv("RAYCORE_FP_SUMMARY"); path != nullptr && *path != '\0') {
      if (FILE* f = std::fopen(path, "a")) {
        std::fprintf(f, "%s\n", line.str().c_str());
        std::fclose(f);
      } else {
        ADD_FAILURE() << "cannot append to RAYCORE_FP_SUMMARY file '" << path << "'";
      }
    }
    EXPECT_GT(vectors_, 0u) << line.str() << ": checked no vectors";
    EXPECT_EQ(mismatches_, 0u) << line.str();
  }

 private:
  static std::string expected_str(uint32_t v) {
    char b[32];
    std::snprintf(b, sizeof b, "0x%08x", v);
    return b;
  }
  static std::string expected_str(int v) { return std::to_string(v); }
  static std::string expected_str(bool v) { return v ? "true" : "false"; }
  template <class T>
  static std::string expected_str(const T& v) {
    return v.str();
  }

  std::string fmt_, op_, mode_, set_, notes_;
  uint64_t vectors_ = 0, mismatches_ = 0, skipped_ = 0;
  bool finished_ = false;
};

// A pattern shown with its value when it is a result (Tally prints raw hex; this adds values).
template <class F>
struct Shown {
  uint32_t bits;
  bool operator==(const Shown& o) const { return bits == o.bits; }
  std::string str() const { return show<F>(bits); }
};

// ---- directed operand sets ----------------------------------------------------------------------

// Significand fields that exercise rounding: 0, 1, 2, all ones, all ones - 1, top bit, top bit + 1.
template <class F>
std::vector<uint32_t> special_mantissas(bool small) {
  using S = Spec<F>;
  const uint32_t top = uint32_t(1) << (S::M - 1);
  if (small) return {0u, 1u, S::man_all};
  return {0u, 1u, 2u, S::man_all, S::man_all - 1u, top, top | 1u};
}

// Exponents (unbiased) for the directed sets: 1.0's binade and every alignment distance below it
// that the adders treat differently (0..3M+9 covers the 2-input adder's guard/jam window M+1+3 and
// the 3-input adder's W = 3M+6 window and its 2M+6 jam threshold), the binades next to emin and
// emax, and the halves of emin and emax (products and quotients land near flush and saturation).
template <class F>
std::vector<int> directed_exponents(bool small) {
  using S = Spec<F>;
  std::set<int> e;
  if (small) {
    for (int d : {0, 1, 2, S::M + 1, S::M + 2, 2 * S::M + 4, 2 * S::M + 5, 2 * S::M + 6,
                  2 * S::M + 7, 3 * S::M + 5, 3 * S::M + 6, 3 * S::M + 7})
      e.insert(-d);
    for (int x : {S::emin, S::emin + 1, S::emax - 1, S::emax}) e.insert(x);
  } else {
    for (int d = 0; d <= 3 * S::M + 9; ++d) e.insert(-d);
    for (int x : {1, 2, 3, S::M, S::M + 1, S::M + 2, S::emin, S::emin + 1, S::emin + 2,
                  S::emin / 2 - 1, S::emin / 2, S::emin / 2 + 1, S::emax / 2 - 1, S::emax / 2,
                  S::emax / 2 + 1, S::emax - 2, S::emax - 1, S::emax})
      e.insert(x);
  }
  std::vector<int> out;
  for (int x : e)
    if (x >= S::emin && x <= S::emax) out.push_back(x);
  return out;
}

// Both signs of every (exponent, mantissa) combination, plus +-0 and the unflushed zeros (exponent
// field 0 with a nonzero mantissa field, which are zeros too).
template <class F>
std::vector<uint32_t> directed_set(bool small) {
  using S = Spec<F>;
  std::vector<uint32_t> v = {0u, S::sign_bit};
  if (!small) {
    v.push_back(1u);
    v.push_back(S::sign_bit | S::man_all);
  }
  for (int e : directed_exponents<F>(small))
    for (uint32_t m : special_mantissas<F>(small))
      for (bool s : {false, true}) v.push_back(S::make(s, e, m));
  return v;
}

// ---- random operands ----------------------------------------------------------------------------

enum class Op { add, sub, mul, div, add3 };
inline const char* op_name(Op op) {
  switch (op) {
    case Op::add: return "add";
    case Op::sub: return "sub";
    case Op::mul: return "mul";
    case Op::div: return "div";
    case Op::add3: return "add3";
  }
  return "?";
}

// gtest prints a test parameter with this (instead of its raw bytes).
inline void PrintTo(Op op, std::ostream* os) { *os << op_name(op); }

// Random operands that reach every path, not only uniform bits: uniform patterns (zeros and the
// range ends included), "close" operands (same or adjacent exponents, mostly opposite signs, or
// a value and its negation a few ulps apart: cancellation), controlled exponent distances (every
// alignment and jam case of the adders), and exponents whose sum or difference lands near the
// flush and saturation thresholds (mul, div).
template <class F>
class Gen {
 public:
  using S = Spec<F>;
  explicit Gen(uint64_t seed) : rng_(seed) {}

  uint64_t bits() { return rng_(); }
  uint32_t below(uint32_t n) { return uint32_t(rng_() % n); }
  bool coin() { return (rng_() & 1u) != 0; }
  int range(int lo, int hi) { return lo + int(below(uint32_t(hi - lo + 1))); }

  uint32_t uniform() { return uint32_t(rng_()) & S::all; }
  uint32_t mantissa() {
    switch (below(10)) {
      case 0: return 0;
      case 1: return S::man_all;
      case 2: return 1;
      case 3: return S::man_all - below(4);
      case 4: return below(4);
      default: return uint32_t(rng_()) & S::man_all;
    }
  }
  // A nonzero pattern with an exponent clamped into range.
  uint32_t make(bool s, int e, uint32_t m) {
    if (e < S::emin) e = S::emin;
    if (e > S::emax) e = S::emax;
    return S::make(s, e, m);
  }
  uint32_t structured() { return make(coin(), range(S::emin, S::emax), mantissa()); }
  uint32_t any() {
    const uint32_t k = below(8);
    if (k < 3) return uniform();
    if (k == 3) return make(coin(), coin() ? range(S::emin, S::emin + 3) : range(S::emax - 3, S::emax),
                            mantissa());
    return structured();
  }
  // A nonzero operand around exponent e0 (a typical magnitude) unless near an end.
  uint32_t anchor() {
    return below(4) == 0 ? any() : make(coin(), range(S::emin + 3 * S::M + 10, S::emax), mantissa());
  }
  // x moved by k ulps in its pattern (staying within nonzero magnitudes).
  static uint32_t step(uint32_t x, int k) {
    if (S::zero(x)) return x;
    const int64_t mag = int64_t(x & S::max_mag) + k;
    const int64_t lo = int64_t(S::make(false, S::emin, 0)), hi = int64_t(S::max_mag);
    const int64_t m = mag < lo ? lo : (mag > hi ? hi : mag);
    return (x & S::sign_bit) | uint32_t(m);
  }
  // An operand at exponent distance d below a (or above it if up), random sign and mantissa.
  uint32_t at_distance(uint32_t a, int d, bool up = false) {
    const int ea = S::zero(a) ? 0 : S::exp_field(a) - S::bias;
    return make(coin(), up ? ea + d : ea - d, mantissa());
  }
  int distance() {
    const uint32_t k = below(4);
    if (k == 0) return range(0, 3);
    if (k == 1) return range(S::M - 1, S::M + 4);
    return range(0, 3 * S::M + 9);
  }
  // A close partner of a: same or adjacent exponent, opposite sign 3 times in 4, or -a +- k ulps.
  uint32_t close_to(uint32_t a) {
    if (S::zero(a)) return structured();
    if (coin()) {
      const uint32_t b = step(a ^ S::sign_bit, range(-3, 3));
      return below(4) == 0 ? (b ^ S::sign_bit) : b;
    }
    const int ea = S::exp_field(a) - S::bias;
    const bool s = below(4) == 0 ? S::sign(a) : !S::sign(a);
    return make(s, ea + range(-1, 1), mantissa());
  }

  void pair(Op op, uint32_t& a, uint32_t& b) {
    const uint32_t k = below(10);
    if (op == Op::add || op == Op::sub) {
      a = anchor();
      if (k < 2) {
        a = uniform();
        b = uniform();
      } else if (k < 5) {
        b = close_to(a);
        if (op == Op::sub) b ^= S::sign_bit;  // sub negates: keep the cancellation
      } else if (k < 9) {
        b = at_distance(a, distance());
      } else {
        b = any();
      }
      if (coin()) std::swap(a, b);
      return;
    }
    // mul, div: exponents whose sum (difference) is near emin-1..emin+1 or emax-1..emax+1.
    if (k < 4) {
      a = uniform();
      b = uniform();
    } else if (k < 7) {
      const bool low = coin();
      const int target = (low ? S::emin : S::emax) + range(-2, 1);
      const int ea = range(S::emin, S::emax);
      int eb = op == Op::mul ? target - ea : ea - target;
      a = make(coin(), ea, mantissa());
      b = make(coin(), eb, mantissa());
    } else {
      a = structured();
      b = structured();
    }
  }

  void triple(uint32_t& a, uint32_t& b, uint32_t& c) {
    const uint32_t k = below(12);
    a = anchor();
    if (k < 2) {
      a = uniform();
      b = uniform();
      c = uniform();
    } else if (k < 5) {  // every pair of alignment distances
      b = at_distance(a, distance());
      c = at_distance(a, distance());
    } else if (k < 7) {  // a and b cancel (partly), c anywhere below
      b = close_to(a);
      c = at_distance(a, distance());
    } else if (k < 9) {  // c cancels a + b (nearly): a result far below the operands
      b = coin() ? at_distance(a, distance()) : close_to(a);
      const uint32_t s = hls::add<F, Rounding::rtz>(a, b);  // stimulus only, not the reference
      c = S::zero(s) ? any() : step(s ^ S::sign_bit, range(-2, 2));
      if (below(3) == 0) c = step(c, range(-64, 64));
    } else if (k < 10) {  // an exact pair cancellation with a third operand
      b = a ^ S::sign_bit;
      c = coin() ? any() : at_distance(a, distance());
    } else {  // all three close
      b = close_to(a);
      c = close_to(coin() ? a : b);
    }
    // Random order: the adder sorts its inputs itself.
    switch (below(6)) {
      case 0: break;
      case 1: std::swap(a, b); break;
      case 2: std::swap(a, c); break;
      case 3: std::swap(b, c); break;
      case 4: { const uint32_t t = a; a = b; b = c; c = t; break; }
      default: { const uint32_t t = a; a = c; c = b; b = t; break; }
    }
  }

 private:
  std::mt19937_64 rng_;
};

// ---- six operands: hls::sop's a + b + x1*y1 + x2*y2 (tb/fp/test_fp_sop.cpp, tb/rtl's fp_sop) ----

struct Six {
  uint32_t a = 0, b = 0, x1 = 0, y1 = 0, x2 = 0, y2 = 0;
};
// Any bits of the format in every operand (tb/rtl/rtl_cosim.h's junk for idle cycles).
template <class F, class Rng>
void randomize(Six& x, Rng& rng) {
  for (uint32_t* v : {&x.a, &x.b, &x.x1, &x.y1, &x.x2, &x.y2}) *v = uint32_t(rng()) & F::mask;
}
template <class F>
struct SopGen {
  using S = fptest::Spec<F>;
  static constexpr uint32_t kNeg0 = S::sign_bit;  // -0: an absent addend; -0 * +0 an absent product
  static int exp_of(uint32_t x) { return S::exp_field(x) - S::bias; }
  static uint32_t neg(uint32_t x) { return x ^ S::sign_bit; }
  // A pair whose product has (unbiased) exponent about e (each factor's exponent in range).
  static void product_near(Gen<F>& g, int e, uint32_t& x, uint32_t& y) {
    int ex = g.range(S::emin, S::emax);
    if (e - ex < S::emin) ex = e - S::emin;
    if (e - ex > S::emax) ex = e - S::emax;
    x = g.make(g.coin(), ex, g.mantissa());
    y = g.make(g.coin(), e - ex, g.mantissa());
  }
  // A moderate operand (products of two stay far from flush and saturation).
  static uint32_t moderate(Gen<F>& g) {
    return g.make(g.coin(), g.range(S::emin / 2 + 2, S::emax / 2 - 2), g.mantissa());
  }
  // A signed zero of either sign, now and then an unflushed one (exponent field 0, mantissa != 0).
  static uint32_t some_zero(Gen<F>& g) {
    const uint32_t z = g.coin() ? S::sign_bit : 0u;
    return g.below(4) == 0 ? (z | (uint32_t(g.bits()) & S::man_all)) : z;
  }
  // A distance below a term's top: the adders' distances, or beyond the window (S = 3M+7: jammed,
  // or a term entirely below it) up to far below.
  static int sop_distance(Gen<F>& g) {
    switch (g.below(4)) {
      case 0: return g.range(3 * S::M + 2, 3 * S::M + 12);
      case 1: return g.range(0, 6 * S::M);
      default: return g.distance();
    }
  }
};

// Six operands that reach every path of the sop: uniform patterns; terms at controlled distances
// below the largest (exact, jammed, entirely below the window); the VTU's shapes with heavy
// cancellation (a ~ -(x1*y1 + x2*y2) as rounded, products that cancel each other, a translated
// triangle's constants near 10^5 with a camera near 10^5); zeros of either sign; products next to
// flush and saturation; exact cancellations (zero sums).
template <class F>
Six sop_random(Gen<F>& g) {
  using G = SopGen<F>;
  using S = typename G::S;
  constexpr Rounding rz = Rounding::rtz;  // stimulus only, not the reference
  Six x;
  const uint32_t k = g.below(16);
  if (k < 2) {  // uniform-ish
    x = {g.any(), g.any(), g.any(), g.any(), g.any(), g.any()};
  } else if (k < 4) {  // every term at a controlled distance below an anchor
    x.a = g.anchor();
    const int ea = G::exp_of(x.a);
    x.b = g.at_distance(x.a, G::sop_distance(g), g.below(8) == 0);
    G::product_near(g, ea - G::sop_distance(g) + (g.below(4) == 0 ? g.range(1, 4) : 0), x.x1, x.y1);
    G::product_near(g, ea - G::sop_distance(g), x.x2, x.y2);
  } else if (k < 7) {  // the VTU's n_d: a ~ -(x1*y1 + x2*y2) as rounded, b small or absent
    x.x1 = G::moderate(g);
    x.y1 = G::moderate(g);
    x.x2 = g.coin() ? G::moderate(g) : g.at_distance(x.x1, g.range(0, 8));
    x.y2 = g.coin() ? G::moderate(g) : g.at_distance(x.y1, g.range(0, 8));
    const uint32_t p = hls::add<F, rz>(hls::mul<F, rz>(x.x1, x.y1), hls::mul<F, rz>(x.x2, x.y2));
    x.a = S::zero(p) ? g.any() : g.step(G::neg(p), g.range(-3, 3));
    if (g.below(3) == 0) x.a = g.step(x.a, g.range(-1000, 1000));
    switch (g.below(4)) {
      case 0: x.b = G::kNeg0; break;
      case 1: x.b = g.close_to(x.a); break;
      default: x.b = g.at_distance(x.a, G::sop_distance(g)); break;
    }
  } else if (k < 9) {  // the products cancel each other (nearly), a and b below them or absent
    x.x1 = G::moderate(g);
    x.y1 = G::moderate(g);
    x.x2 = g.step(G::neg(x.x1), g.range(-2, 2));
    x.y2 = g.step(x.y1, g.range(-2, 2));
    if (g.coin()) std::swap(x.x2, x.y2);
    const uint32_t p = hls::mul<F, rz>(x.x1, x.y1);
    x.a = g.coin() ? G::kNeg0 : g.at_distance(p, G::sop_distance(g));
    x.b = g.coin() ? G::kNeg0 : g.at_distance(p, G::sop_distance(g));
  } else if (k < 10) {  // a and b cancel, the products below them (often beyond the window)
    x.a = g.anchor();
    x.b = g.close_to(x.a);
    const int ea = G::exp_of(x.a);
    G::product_near(g, ea - G::sop_distance(g), x.x1, x.y1);
    G::product_near(g, ea - G::sop_distance(g), x.x2, x.y2);
  } else if (k < 12) {  // a translated triangle far from the origin (the VTU at 10^5)
    auto val = [&](double lo, double hi) {
      const double v = lo + (hi - lo) * double(g.bits() >> 11) * 0x1p-53;
      return hls::from_double<F, rz>(g.coin() ? -v : v);
    };
    const double far = std::ldexp(1.0, g.range(10, 20));  // 10^3 .. 10^6
    const uint32_t cu = val(far * 0.9, far * 1.1), cv = val(far * 0.9, far * 1.1);
    const uint32_t ck = val(far * 0.9, far * 1.1);
    const uint32_t nu = val(0.0, 2.0), nv = val(0.0, 2.0);
    // n_d = n . p for a point p near the camera: c_k + nu c_u + nv c_v + a small offset.
    const double off = std::ldexp(double(g.bits() >> 11) * 0x1p-53 - 0.5, g.range(-8, 8));
    auto v = [](uint32_t b) { return fptest::ref_value<F>(b); };
    const double nd = v(ck) + v(nu) * v(cu) + v(nv) * v(cv) + off;
    x = {hls::from_double<F, rz>(nd), G::neg(ck), G::neg(nu), cu, G::neg(nv), cv};
    if (g.coin()) x.b = G::kNeg0;  // b_d' / c_d': no c_k term
  } else if (k < 13) {  // zeros: some operands (all, now and then) replaced by signed zeros
    x = {g.any(), g.any(), g.any(), g.any(), g.any(), g.any()};
    const bool all = g.below(4) == 0;
    for (uint32_t* v : {&x.a, &x.b, &x.x1, &x.y1, &x.x2, &x.y2})
      if (all || g.below(3) == 0) *v = G::some_zero(g);
  } else if (k < 14) {  // products next to flush and saturation
    g.pair(fptest::Op::mul, x.x1, x.y1);
    g.pair(fptest::Op::mul, x.x2, x.y2);
    x.a = g.below(3) == 0 ? G::kNeg0 : g.any();
    x.b = g.below(3) == 0 ? G::kNeg0 : g.any();
  } else if (k < 15) {  // exact cancellations: a = -b, x2*y2 = -x1*y1 (one of them perturbed)
    x.a = g.any();
    x.b = G::neg(x.a);
    x.x1 = g.any();
    x.y1 = g.any();
    x.x2 = G::neg(x.x1);
    x.y2 = x.y1;
    if (g.coin()) {  // -(x1 * y1) as (-y1) * x1
      x.x2 = G::neg(x.y1);
      x.y2 = x.x1;
    }
    switch (g.below(4)) {
      case 0: x.b = g.step(x.b, g.coin() ? 1 : -1); break;
      case 1: x.y2 = g.step(x.y2, g.coin() ? 1 : -1); break;
      default: break;
    }
  } else {
    x = {g.structured(), g.structured(), g.structured(), g.structured(), g.structured(),
         g.structured()};
  }
  // The adder's inputs are symmetric: random order of the addends and of the products' factors.
  if (g.coin()) std::swap(x.a, x.b);
  if (g.coin()) std::swap(x.x1, x.y1);
  if (g.coin()) std::swap(x.x2, x.y2);
  if (g.coin()) {
    std::swap(x.x1, x.x2);
    std::swap(x.y1, x.y2);
  }
  return x;
}

}  // namespace raycore::fptest
