// tb/sweep/spawn_vecgen.cpp - vectors for rtl/units/spawn.v's skip-slab / skip-back datapath from
// hls/hit.h (hls::detail::slab_tmin, hls::add_ulps), for tb/sweep/tb_spawn_slab.v.
//   spawn_vecgen <FP24|FP32> <rtz|rne|raycore> <slab ulps> <back ulps> <count> <file>  (raycore: FP24)
// One line per vector, ten hex words: h_x h_y h_z dens tmin scale t back | tmin' t_back; prints
// the number of vectors written.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "hls/fp.h"
#include "hls/hit.h"

namespace {

using namespace raycore::hls;

template <class A>
int gen(int slab, int back, int count, FILE* out) {
  using F = typename A::Fmt;
  std::mt19937_64 rng(20261122u + uint64_t(slab) * 7u + uint64_t(back));
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  // A random value of magnitude 2^[lo, hi), either sign; sometimes zero.
  auto any = [&](double lo, double hi, bool sign) {
    if (u01(rng) < 0.03) return A::zero;
    const double m = std::exp2(lo + (hi - lo) * u01(rng)) * (1.0 + u01(rng));
    return A::from_double(sign && u01(rng) < 0.5 ? -m : m);
  };
  const uint32_t tmin = A::from_double(1.0 / 4096.0);
  const uint32_t scale = A::from_double(2.0 * double(slab));
  for (int i = 0; i < count; ++i) {
    uint32_t h[3];
    for (auto& c : h) c = any(-30, 30, true);
    const uint32_t dens = any(-12, 1, true);  // below and above the 1/16 floor
    // t: ordinary, or a few ulps above the smallest normal (the back-off saturates to zero).
    const uint32_t t = u01(rng) < 0.05 ? F::min_mag + uint32_t(rng() % 4) : any(-20, 20, false);
    const uint32_t tmin2 = detail::slab_tmin<A>(h, dens, slab, tmin);
    const uint32_t tback = add_ulps<F>(t, -back);
    std::fprintf(out, "%08x%08x%08x%08x%08x%08x%08x%08x%08x%08x\n", h[0], h[1], h[2], dens, tmin, scale, t,
                 uint32_t(back), tmin2, tback);
  }
  return count;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr, "usage: %s <FP24|FP32> <rtz|rne|raycore> <slab ulps> <back ulps> <count> <file>\n", argv[0]);
    return 2;
  }
  const std::string fmt = argv[1], mode = argv[2];
  const int slab = std::atoi(argv[3]), back = std::atoi(argv[4]), count = std::atoi(argv[5]);
  if ((fmt != "FP24" && fmt != "FP32") || (mode != "rtz" && mode != "rne" && mode != "raycore") ||
      (mode == "raycore" && fmt != "FP24") || slab < 1 || back < 0 || count < 1) {
    std::fprintf(stderr, "spawn_vecgen: bad arguments\n");
    return 2;
  }
  FILE* out = std::fopen(argv[6], "w");
  if (!out) {
    std::fprintf(stderr, "spawn_vecgen: cannot write %s\n", argv[6]);
    return 1;
  }
  using R = Rounding;
  int n = 0;
  if (fmt == "FP24" && mode == "raycore")
    n = gen<Arith<FP24, R::raycore>>(slab, back, count, out);
  else if (fmt == "FP24")
    n = mode == "rtz" ? gen<Arith<FP24, R::rtz>>(slab, back, count, out) : gen<Arith<FP24, R::rne>>(slab, back, count, out);
  else
    n = mode == "rtz" ? gen<Arith<FP32, R::rtz>>(slab, back, count, out) : gen<Arith<FP32, R::rne>>(slab, back, count, out);
  std::fclose(out);
  std::printf("%d\n", n);
  return 0;
}
