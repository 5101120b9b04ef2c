// fp_bench: software throughput (operations per second) of the hls/fp.h operations, FP24 and
// FP32 in rtz and rne, with the host's float and double for scale.
//
// Each benchmark runs one operation over pre-filled arrays of kN random operands (magnitudes
// log-uniform in [2^-10, 2^10), random signs: coordinates and distances of a scene) and stores
// every result, so nothing is constant-folded and the operations are independent (throughput,
// not latency). items_per_second is the number of operations per second on one core.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "hls/fp.h"

namespace {

using raycore::hls::FP24;
using raycore::hls::FP32;
using raycore::hls::Rounding;
namespace hls = raycore::hls;

constexpr int kN = 1024;  // 3 x 4 KiB of operands: stays in L1

struct Operands {
  std::vector<double> d[3];
  explicit Operands(uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> expo(-10.0, 10.0);
    for (auto& v : d) {
      v.resize(kN);
      for (double& x : v) x = std::exp2(expo(rng)) * ((rng() & 1u) ? -1.0 : 1.0);
    }
  }
};
const Operands& operands() {
  static const Operands ops(20240611);
  return ops;
}

template <class F>
std::vector<uint32_t> patterns(int k) {
  std::vector<uint32_t> v(kN);
  for (int i = 0; i < kN; ++i) v[i] = hls::from_double<F, Rounding::rne>(operands().d[k][i]);
  return v;
}

// One loop shape for every operation: out[i] = f(a[i], b[i], c[i]).
template <class In, class Out, class Fn>
void run(benchmark::State& state, const std::vector<In>& a, const std::vector<In>& b,
         const std::vector<In>& c, Fn fn) {
  std::vector<Out> out(kN);
  for (auto _ : state) {
    for (int i = 0; i < kN; ++i) out[i] = fn(a[i], b[i], c[i]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * kN);
}

template <class F, Rounding R>
void register_format(const std::string& fmt) {
  const std::string mode = R == Rounding::rtz ? "rtz" : "rne";
  auto name = [&](const char* op) { return fmt + "/" + op + "/" + mode; };
  using P = std::vector<uint32_t>;
  auto reg_named = [&](const std::string& full, auto fn) {
    benchmark::RegisterBenchmark(full.c_str(), [fn](benchmark::State& s) {
      static const P a = patterns<F>(0), b = patterns<F>(1), c = patterns<F>(2);
      run<uint32_t, uint32_t>(s, a, b, c, fn);
    });
  };
  auto reg = [&](const char* op, auto fn) { reg_named(name(op), fn); };
  auto reg_any = [&](const char* op, auto fn) { reg_named(fmt + "/" + op, fn); };
  reg("add", [](uint32_t x, uint32_t y, uint32_t) { return hls::add<F, R>(x, y); });
  reg("sub", [](uint32_t x, uint32_t y, uint32_t) { return hls::sub<F, R>(x, y); });
  reg("add3", [](uint32_t x, uint32_t y, uint32_t z) { return hls::add3<F, R>(x, y, z); });
  reg("mul", [](uint32_t x, uint32_t y, uint32_t) { return hls::mul<F, R>(x, y); });
  reg("div", [](uint32_t x, uint32_t y, uint32_t) { return hls::div<F, R>(x, y); });
  reg("rcp", [](uint32_t x, uint32_t, uint32_t) { return hls::rcp<F, R>(x); });
  if constexpr (R == Rounding::rtz) {  // rounding-independent: listed once
    reg_any("lt", [](uint32_t x, uint32_t y, uint32_t) { return uint32_t(hls::lt<F>(x, y)); });
    reg_any("cmp", [](uint32_t x, uint32_t y, uint32_t) { return uint32_t(hls::cmp<F>(x, y) + 1); });
    reg_any("min", [](uint32_t x, uint32_t y, uint32_t) { return hls::min<F>(x, y); });
    benchmark::RegisterBenchmark((fmt + "/to_double").c_str(), [](benchmark::State& s) {
      static const P a = patterns<F>(0);
      run<uint32_t, double>(s, a, a, a, [](uint32_t x, uint32_t, uint32_t) { return hls::to_double<F>(x); });
    });
  }
  benchmark::RegisterBenchmark(name("from_double").c_str(), [](benchmark::State& s) {
    const auto& d = operands().d;
    run<double, uint32_t>(s, d[0], d[1], d[2],
                          [](double x, double, double) { return hls::from_double<F, R>(x); });
  });
}

template <class T>
void register_host(const std::string& name) {
  auto reg = [&](const char* op, auto fn) {
    benchmark::RegisterBenchmark((name + "/" + op).c_str(), [fn](benchmark::State& s) {
      static const std::vector<T> a(operands().d[0].begin(), operands().d[0].end()),
          b(operands().d[1].begin(), operands().d[1].end()),
          c(operands().d[2].begin(), operands().d[2].end());
      run<T, T>(s, a, b, c, fn);
    });
  };
  reg("add", [](T x, T y, T) { return x + y; });
  reg("add3", [](T x, T y, T z) { return x + y + z; });
  reg("mul", [](T x, T y, T) { return x * y; });
  reg("div", [](T x, T y, T) { return x / y; });
  reg("rcp", [](T x, T, T) { return T(1) / x; });
  reg("lt", [](T x, T y, T) { return T(x < y); });
}

}  // namespace

int main(int argc, char** argv) {
  register_format<FP24, Rounding::rtz>("FP24");
  register_format<FP24, Rounding::rne>("FP24");
  register_format<FP32, Rounding::rtz>("FP32");
  register_format<FP32, Rounding::rne>("FP32");
  register_host<float>("host_float");
  register_host<double>("host_double");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
