// sim/sc_options.h - the cycle model's command-line options (raycore simulate / compare):
// --config FILE (JSON, keys of sc::config_json) first, then any option given on the command line.
#pragma once

#include <CLI/CLI.hpp>

#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/cli.h"
#include "systemc/config.h"
#include "systemc/simulate.h"
#include "systemc/timing.h"

namespace raycore::sc {

struct SimOptions {
  SimConfig cfg;
  std::string config_file;
  std::vector<std::function<void(SimConfig&)>> overrides;  // options given on the command line
};

inline void add_sim_options(CLI::App& c, SimOptions& o) {
  auto opt = [&](const char* name, auto member, const char* help, auto lo, auto hi) {
    using T = std::remove_reference_t<decltype(o.cfg.*member)>;
    auto value = std::make_shared<T>(o.cfg.*member);
    c.add_option(name, *value, help)
        ->check(CLI::Range(lo, hi))
        ->default_str(std::to_string(o.cfg.*member))
        ->each([&o, member, value](const std::string&) {
          o.overrides.push_back([member, value](SimConfig& s) { s.*member = *value; });
        });
  };
  opt("--rtus", &SimConfig::rtus, "ray-tracing units sharing the memory bus", 1, 64);
  {
    auto value = std::make_shared<double>(o.cfg.clock_mhz);
    c.add_option("--clock-mhz", *value,
                 "clock for Mrays/s and GB/s (default: the RTU's clock from static timing, "
                 "docs/timing.json)")
        ->check(CLI::Range(1.0, 1e5))
        ->each([&o, value](const std::string&) {
          o.overrides.push_back([value](SimConfig& s) {
            s.clock_mhz = *value;
            s.clock_source = "option";
            s.clock_note.clear();
          });
        });
  }
  opt("--mem-latency", &SimConfig::mem_latency, "memory latency in cycles", 0u, 100000u);
  opt("--mem-bandwidth", &SimConfig::mem_bandwidth, "memory bus bytes per cycle", 1u, 4096u);
  opt("--mem-queue", &SimConfig::mem_queue_depth, "outstanding memory requests", 1u, 4096u);
  opt("--seed", &SimConfig::seed, "randomise memory latency in [L, 2L] (0: fixed)", uint64_t(0),
      ~uint64_t(0));
  // The shared L2 (SimConfig::l2).
  auto l2 = [&](const char* name, uint32_t L2Config::*field, const char* help, uint32_t lo, uint32_t hi) {
    auto value = std::make_shared<uint32_t>(o.cfg.l2.*field);
    c.add_option(name, *value, help)
        ->check(CLI::Range(lo, hi))
        ->default_str(std::to_string(o.cfg.l2.*field))
        ->each([&o, field, value](const std::string&) {
          o.overrides.push_back([field, value](SimConfig& s) { s.l2.*field = *value; });
        });
  };
  {
    auto value = std::make_shared<double>(o.cfg.l2.size_bytes / 1024.0);
    c.add_option("--l2-kb", *value, "L2 shared by all RTUs in front of the memory, KiB (0: none)")
        ->check(CLI::Range(0.0, 1048576.0))
        ->default_str(std::to_string(o.cfg.l2.size_bytes / 1024))
        ->each([&o, value](const std::string&) {
          o.overrides.push_back([value](SimConfig& s) { s.l2.size_bytes = uint32_t(*value * 1024); });
        });
  }
  l2("--l2-ways", &L2Config::ways, "L2 associativity", 1u, 64u);
  l2("--l2-latency", &L2Config::latency, "L2 hit latency in cycles", 1u, 10000u);
  l2("--l2-bandwidth", &L2Config::bandwidth, "L2 to RTU caches, bytes per cycle", 1u, 4096u);
  opt("--vtu-depth", &SimConfig::vtu_depth, "VTU pipeline depth (rtl/units/vtu.v: 2 x STAGES)", 0u, 1000u);
  opt("--rays-in-flight", &SimConfig::rays_in_flight, "ray slots per RTU", 1u, 65535u);
  opt("--mailbox", &SimConfig::mailbox, "per-ray mailbox entries (triangles not tested twice; 0: none)", 0u, 64u);
  opt("--stack-depth", &SimConfig::stack_depth, "traversal stack entries per ray slot", 1u, 64u);
  opt("--trv-latency", &SimConfig::trv_latency, "cycles of one traversal step", 1u, 1000u);
  opt("--trv-pipes", &SimConfig::trv_pipes, "traversal pipelines per RTU (steps per cycle)", 1u, 16u);
  c.add_option("--trv-fuse", o.cfg.trv_fuse,
               "fuse a leaf's first list line into its node step and the popped node's fetch into "
               "the leaf-end / pop step (fewer, longer traversal passes)")
      ->default_str(o.cfg.trv_fuse ? "true" : "false")
      ->each([&o](const std::string& v) {
        const bool on = v == "true" || v == "1" || v == "on";
        if (!on && v != "false" && v != "0" && v != "off")
          throw CLI::ValidationError("must be true/false, on/off or 1/0, not '" + v + "'");
        o.overrides.push_back([on](SimConfig& s) { s.trv_fuse = on; });
      });
  opt("--ist-units", &SimConfig::ist_units, "intersection pipelines per RTU (tests per cycle)", 1u, 16u);
  opt("--ist-latency", &SimConfig::ist_latency,
      "ist pipeline latency (sum of stages; 0: the record kind's at STAGES 2, 20 for --ist wald, 36 for "
      "watertight)",
      0u, 1000u);
  opt("--hit-latency", &SimConfig::hit_latency, "hit unit latency", 1u, 1000u);
  opt("--rgu-latency", &SimConfig::rgu_latency,
      "rgu primary-ray datapath latency (rtl/units/rgu.v: 15 x STAGES)", 0u, 1000u);
  auto kb = [&](const char* name, CacheConfig SimConfig::*cache, const char* help) {
    auto value = std::make_shared<double>((o.cfg.*cache).size_bytes / 1024.0);
    c.add_option(name, *value, help)
        ->check(CLI::Range(0.0625, 65536.0))
        ->default_str(std::to_string((o.cfg.*cache).size_bytes / 1024))
        ->each([&o, cache, value](const std::string&) {
          o.overrides.push_back(
              [cache, value](SimConfig& s) { (s.*cache).size_bytes = uint32_t(*value * 1024); });
        });
  };
  kb("--node-cache-kb", &SimConfig::node_cache, "node cache size per RTU (KiB)");
  kb("--list-cache-kb", &SimConfig::list_cache, "list cache size per RTU (KiB)");
  kb("--tri-cache-kb", &SimConfig::tri_cache, "triangle cache size per RTU (KiB)");
  // Pin-level units: --rtl binds the Verilated model, --pins the SystemC twin, in the unit's place.
  auto views = [&](const char* name, UnitView view, const char* help) {
    auto list = std::make_shared<std::vector<std::string>>();
    c.add_option(name, *list, help)
        ->delimiter(',')
        ->check(CLI::IsMember({"vtu", "ist", "trv", "ascache", "hit", "rgu", "membus", "all", "rtu"}))
        ->each([&o, list, view](const std::string& unit) {
          o.overrides.push_back([unit, view](SimConfig& s) {
            auto set = [&](const std::string& u) {
              UnitView& v = u == "rtu"   ? s.rtu_view
                            : u == "vtu" ? s.vtu_view
                            : u == "ist" ? s.ist_view
                            : u == "trv" ? s.trv_view
                            : u == "ascache" ? s.ascache_view
                            : u == "membus" ? s.membus_view
                            : u == "hit" ? s.hit_view
                                         : s.rgu_view;
              if (v != UnitView::model && v != view)
                throw raycore::cli::UserError("unit '" + u + "' given to both --rtl and --pins");
              v = view;
            };
            if (unit != "all") return set(unit);
            // all: every unit with that view (trv and the frame's caches have no pin-level twin)
            for (const char* u : {"vtu", "ist", "trv", "ascache", "hit", "rgu"})
              if (view == UnitView::rtl || (std::string(u) != "trv" && std::string(u) != "ascache"))
                set(u);
          });
        });
  };
  views("--rtl", UnitView::rtl,
        "units (vtu,ist,trv,ascache,hit,rgu, or all: every unit of the RTUs; and membus) simulated by their "
        "Verilated RTL in the frame (vtu at its pins; trv, ist, hit, rgu: the whole units "
        "rtl/units/{trv,ist,hit,rgu}_unit.v, stepped from C++; ascache: the node, list "
        "and triangle caches, rtl/units/ascache.v stepped from C++; membus: the chip's bus interface "
        "rtl/units/membus_if.v, or with the L2 rtl/units/membus_l2.v: the default 512 KB or --l2-kb 1 --l2-ways 2); "
        "or rtu alone: every RTU one Verilated "
        "rtl/units/rtu.v (all its units and the glue between them) with the bus: membus_l2.v (the "
        "default 512 KB L2, or --l2-kb 1 --l2-ways 2), or membus_if.v with --l2-kb 0");
  views("--pins", UnitView::twin,
        "units (vtu,ist,hit,rgu, or all) simulated by their pin-level SystemC twin (same ports as the RTL; trv "
        "has none)");
  c.add_option("--trace", o.cfg.trace_file, "write a VCD of the top-level handshakes and counters");
  c.add_option("--config", o.config_file, "JSON file with the model's parameters (options override it)");
}

// The configuration: defaults, then --config, then the command line.
inline SimConfig finish_sim_options(const SimOptions& o) {
  SimConfig c = o.cfg;
  if (!o.config_file.empty()) {
    std::ifstream f(o.config_file);
    if (!f) throw raycore::cli::UserError("cannot read config file '" + o.config_file + "'");
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(f);
      config_from_json(j, c);
    } catch (const std::exception& e) {
      throw raycore::cli::UserError("config file '" + o.config_file + "': " + e.what());
    }
    c.trace_file = o.cfg.trace_file;
  }
  for (const auto& f : o.overrides) f(c);
  apply_timed_clock(c);  // no clock given: the RTU's clock from static timing (systemc/timing.h)
  return c;
}

}  // namespace raycore::sc
