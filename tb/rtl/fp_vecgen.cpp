// tb/rtl/fp_vecgen.cpp - writes fp_add test vectors for the Icarus Verilog testbench
// (tb/rtl/tb_fp_add.v): operands and the result expected from hls/fp.h.
//
//   fp_vecgen <FP24|FP32> <rtz|rne|raycore> <count> <file>   (raycore: FP24 only)
//
// The vectors: all pairs of the C++ tests' small directed set (tb/fp/fp_check.h) with sub 0 and 1,
// then random ones from the same generator (fptest::Gen) up to `count`, seeded from the format and
// mode (and RAYCORE_FP_SEED). One line per vector, for $readmemh: 32 hex digits =
// {a, b, sub, expected}, 32 bits each. Prints the number of vectors written.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "hls/fp.h"
#include "tb/fp/fp_check.h"

namespace {

using raycore::hls::Rounding;
namespace fptest = raycore::fptest;

template <class F, Rounding R>
uint64_t write_vectors(uint64_t count, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw std::runtime_error("cannot write vector file '" + path + "'");
  uint64_t n = 0;
  auto put = [&](uint32_t a, uint32_t b, bool sub) {
    const uint32_t r = sub ? raycore::hls::sub<F, R>(a, b) : raycore::hls::add<F, R>(a, b);
    std::fprintf(f, "%08x%08x%08x%08x\n", a, b, unsigned(sub), r);
    ++n;
  };
  const std::vector<uint32_t> d = fptest::directed_set<F>(true);
  for (uint32_t a : d)
    for (uint32_t b : d)
      for (bool sub : {false, true})
        if (n < count) put(a, b, sub);
  fptest::Gen<F> gen(fptest::seed_for(std::string("icarus.") + fptest::fmt_name<F>() +
                                      "." + fptest::mode_name(R)));
  while (n < count) {
    uint32_t a, b;
    const bool sub = gen.coin();
    gen.pair(sub ? fptest::Op::sub : fptest::Op::add, a, b);
    put(a, b, sub);
  }
  if (std::fclose(f) != 0) throw std::runtime_error("error writing vector file '" + path + "'");
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc != 5) throw std::runtime_error("usage: fp_vecgen <FP24|FP32> <rtz|rne|raycore> <count> <file>");
    const std::string fmt = argv[1], mode = argv[2], path = argv[4];
    char* end = nullptr;
    const unsigned long long count = std::strtoull(argv[3], &end, 10);
    if (end == argv[3] || *end != '\0' || count == 0) throw std::runtime_error("bad count '" + std::string(argv[3]) + "'");
    uint64_t n = 0;
    if (fmt == "FP24" && mode == "rtz") n = write_vectors<raycore::hls::FP24, Rounding::rtz>(count, path);
    else if (fmt == "FP24" && mode == "rne") n = write_vectors<raycore::hls::FP24, Rounding::rne>(count, path);
    else if (fmt == "FP24" && mode == "raycore") n = write_vectors<raycore::hls::FP24, Rounding::raycore>(count, path);
    else if (fmt == "FP32" && mode == "rtz") n = write_vectors<raycore::hls::FP32, Rounding::rtz>(count, path);
    else if (fmt == "FP32" && mode == "rne") n = write_vectors<raycore::hls::FP32, Rounding::rne>(count, path);
    else throw std::runtime_error("unknown format/mode '" + fmt + " " + mode + "'");
    std::printf("%llu\n", (unsigned long long)n);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fp_vecgen: %s\n", e.what());
    return 1;
  }
}
