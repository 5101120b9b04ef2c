// `raycore fp`: evaluate one operation of the number system, showing bits and values.
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "hls/fp.h"
#include "sim/cli.h"

namespace raycore::cli {
namespace {

struct FpArgs {
  std::string op;
  std::vector<std::string> operands;
  std::string format = "fp24";
  std::string rounding = "rtz";
};

// An operand is a decimal number (converted with the policy) or a bit pattern 0x...
template <class F, hls::Rounding R>
uint32_t parse_operand(const std::string& s) {
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    size_t used = 0;
    const unsigned long v = std::stoul(s, &used, 16);
    if (used != s.size() || (v & ~uint64_t(F::mask)) != 0)
      throw UserError("operand '" + s + "' is not a " + std::to_string(F::width) + "-bit pattern");
    return uint32_t(v);
  }
  size_t used = 0;
  double d = 0;
  try {
    d = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || !std::isfinite(d)) throw UserError("operand '" + s + "' is not a finite number");
  return hls::from_double<F, R>(d);
}

template <class F, hls::Rounding R>
void run(const FpArgs& a) {
  using A = hls::Arith<F, R>;
  std::vector<uint32_t> x;
  for (const auto& s : a.operands) x.push_back(parse_operand<F, R>(s));
  auto need = [&](size_t n) {
    if (x.size() != n)
      throw UserError("'" + a.op + "' takes " + std::to_string(n) + " operand(s), got " +
                      std::to_string(x.size()));
  };
  uint32_t r = 0;
  bool is_bool = false;
  if (a.op == "add") { need(2); r = A::add(x[0], x[1]); }
  else if (a.op == "sub") { need(2); r = A::sub(x[0], x[1]); }
  else if (a.op == "add3") { need(3); r = A::add3(x[0], x[1], x[2]); }
  else if (a.op == "mul") { need(2); r = A::mul(x[0], x[1]); }
  else if (a.op == "div") { need(2); r = A::div(x[0], x[1]); }
  else if (a.op == "rcp") { need(1); r = A::rcp(x[0]); }
  else if (a.op == "lt") { need(2); r = A::lt(x[0], x[1]); is_bool = true; }
  else if (a.op == "min") { need(2); r = A::min(x[0], x[1]); }
  else if (a.op == "max") { need(2); r = A::max(x[0], x[1]); }
  else if (a.op == "neg") { need(1); r = A::neg(x[0]); }
  else if (a.op == "abs") { need(1); r = A::abs(x[0]); }
  else if (a.op == "next-up") { need(1); r = A::next_up(x[0]); }
  else if (a.op == "next-down") { need(1); r = A::next_down(x[0]); }
  else if (a.op == "ulp") { need(1); r = hls::ulp<F>(x[0]); }
  else if (a.op == "conv") { need(1); r = x[0]; }
  else throw UserError("unknown op '" + a.op + "'");
  const int hexw = (F::width + 3) / 4;
  for (size_t i = 0; i < x.size(); ++i)
    std::printf("in%zu  0x%0*" PRIX32 "  %.17g\n", i, hexw, x[i], A::to_double(x[i]));
  if (is_bool)
    std::printf("out  %s\n", r ? "true" : "false");
  else
    std::printf("out  0x%0*" PRIX32 "  %.17g\n", hexw, r, A::to_double(r));
}

template <class F>
void run_format(const FpArgs& a) {
  if (a.rounding == "rtz") {
    run<F, hls::Rounding::rtz>(a);
  } else if (a.rounding == "raycore") {
    if constexpr (std::is_same<F, hls::FP24>::value) run<F, hls::Rounding::raycore>(a);
    else throw UserError("rounding 'raycore' is RayCore's FP24 arithmetic: it needs --format fp24");
  } else {
    run<F, hls::Rounding::rne>(a);
  }
}

void register_fp(CLI::App& app) {
  auto args = std::make_shared<FpArgs>();
  auto* c = app.add_subcommand("fp", "Evaluate one number-system operation (bits and values)");
  c->add_option("op", args->op,
                "add sub add3 mul div rcp lt min max neg abs next-up next-down ulp conv")
      ->required();
  c->add_option("operands", args->operands, "decimal numbers or bit patterns (0x...)");
  c->add_option("--format", args->format, "fp24 or fp32")->check(CLI::IsMember({"fp24", "fp32"}));
  c->add_option("--rounding", args->rounding,
                "rtz, rne, or raycore (RayCore's FP24 arithmetic: truncating, 1-guard-bit add, "
                "2-guard-bit add3, table reciprocal)")
      ->check(CLI::IsMember({"rtz", "rne", "raycore"}));
  c->callback([args] {
    if (args->format == "fp24") run_format<hls::FP24>(*args);
    else run_format<hls::FP32>(*args);
  });
}

}  // namespace
RAYCORE_COMMAND(register_fp);
}  // namespace raycore::cli
