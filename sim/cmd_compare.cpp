// `raycore compare`: golden tracer and cycle model on the same configuration; lists the first
// differing pixels with both results; exits non-zero on any difference.
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "sim/cli.h"
#include "sim/run.h"
#include "sim/sc_options.h"
#include "systemc/simulate.h"

namespace raycore::cli {
namespace {

void print_pixel(const char* who, const sim::PixelResult& p) {
  std::printf("    %-6s tri %d t_bits 0x%08x (t %.9g) shadow_ray %d lit %d shadow_tri %d shade %u\n", who,
              p.tri, p.t_bits, p.t, int(p.shadow_ray), int(p.lit), p.shadow_tri, unsigned(p.shade));
}

void run_compare(const sim::RunOptions& o, const sc::SimOptions& so, int max_list) {
  sim::TraceConfig cfg = sim::trace_config(o);
  sc::SimConfig scfg = sc::finish_sim_options(so);
  scfg.progress = !o.quiet;
  sim::Prepared p = sim::prepare(o, cfg);
  const sim::Frame golden = sim::trace_golden(p.image, p.scene.camera, p.scene.light, cfg);
  const sc::SimResult r = sc::simulate(p.image, p.scene.camera, p.scene.light, cfg, scfg);
  uint64_t n = 0;
  const auto d = sc::diff_frames(golden, r.frame, size_t(max_list), &n);
  const size_t pixels = golden.px.size();
  if (n == 0) {
    if (!o.quiet)
      std::printf("match: all %zu pixels equal (%s, %dx%d, %llu cycles)\n", pixels,
                  sim::config_tag(cfg).c_str(), cfg.width, cfg.height, (unsigned long long)r.cycles);
    return;
  }
  std::printf("%llu of %zu pixels differ (%s, %dx%d); first %zu:\n", (unsigned long long)n, pixels,
              sim::config_tag(cfg).c_str(), cfg.width, cfg.height, d.size());
  for (const auto& x : d) {
    std::printf("  pixel (%d, %d)\n", x.x, x.y);
    print_pixel("golden", x.a);
    print_pixel("cycle", x.b);
  }
  throw std::runtime_error("cycle model and golden tracer differ in " + std::to_string(n) + " pixels");
}

void register_compare(CLI::App& app) {
  auto o = std::make_shared<sim::RunOptions>();
  auto so = std::make_shared<sc::SimOptions>();
  auto max_list = std::make_shared<int>(10);
  auto* c = app.add_subcommand("compare", "Golden tracer vs cycle model: first differing pixels, non-zero exit on any");
  sim::add_run_options(*c, *o);
  sc::add_sim_options(*c, *so);
  c->add_option("--max-list", *max_list, "differing pixels to list")->check(CLI::Range(0, 1000000));
  c->callback([o, so, max_list] { run_compare(*o, *so, *max_list); });
}

}  // namespace
RAYCORE_COMMAND(register_compare);
}  // namespace raycore::cli
