// systemc/config.h - parameters of the cycle model (one plain struct, as the style guide asks)
// and the counters it reports.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "hls/wald.h"

namespace raycore::sc {

// Registers per STAGES of each pipelined datapath (rtl/units/*.v): at pin level and in RTL a unit's
// latency is levels x STAGES. The vtu's fp_sop phases, ist.v's and rgu.v's operator levels; hit.v
// shares its registers out by the logic of its sublevels (scripts/gen_hit.py: weights totalling
// 47 registers for 95 FO4, plus the hit unit's registered slot read: 48, so 24 per STAGES).
inline constexpr uint32_t kVtuLevels = 2, kIstLevels = 10, kHitLevels = 24, kRguLevels = 15;
// ist_watertight.v's: the shear, the edge functions, det, Woop's T and its division, the key
// compares (rtl/units/ist_watertight.v: 36 registers at STAGES 2, 14 of them the shear format's divider).
inline constexpr uint32_t kIstWatertightLevels = 18;
// The ist pipeline of a record kind: its levels (ist.v's or ist_watertight.v's).
inline constexpr uint32_t ist_levels(hls::IstKind k) {
  return k == hls::IstKind::watertight ? kIstWatertightLevels : kIstLevels;
}
// The least trv_latency + node cache hit latency that rtl/units/trv_unit.v runs: it writes an
// inner node's split back at the end of the fifth cycle after the pass (the node read a cycle
// after the pass, the outcome and the split's first level in the next, its second level, its
// third and fourth, its registered results written back), so the ray may be taken in the sixth.
inline constexpr uint32_t kTrvRtlMinLoop = 6;
// Cycles from a ray's issue (the rgu's primary ray, or the hit unit's shadow ray handed over) to
// its entry into the trv's ready queue: trv_unit.v registers the entering ray and clips it against
// the scene box on the way (trv.v op 1 with a register after its subtraction, its multiplication,
// its comparisons and its comparator tree), its result written with the queue push at the end of
// the fifth cycle after the issue.
inline constexpr uint32_t kTrvEntryDelay = 5;

struct CacheConfig {
  uint32_t size_bytes = 16 * 1024;
  uint32_t ways = 4;
  uint32_t line_bytes = 64;  // triangle cache: rounded to a whole number of records
  uint32_t mshrs = 8;        // outstanding distinct line misses
  uint32_t hit_latency = 1;  // cycles added to the requester's loop on a hit
};

// The optional L2 shared by all RTUs, between their caches and the memory (RayCore: per-core L1s
// in front of L2s shared by all cores). size_bytes 0 = none (requests go straight to memory).
struct L2Config {
  uint32_t size_bytes = 0;
  uint32_t ways = 8;
  uint32_t line_bytes = 64;
  uint32_t latency = 20;    // cycles from accepting a request to its first beat on a hit
  uint32_t bandwidth = 32;  // bytes per cycle from the L2 to the RTUs' caches
};

// A configuration the model refuses because of what is built or what a pin-level unit's ports
// allow (a latency that is no multiple of its operator levels, a format or depth with no Verilated
// model, rgu tiles that are no power of two): the user's error, the CLI exits with status 2.
struct ConfigError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// How a unit with a pin-level form is modelled in the frame: the fast transaction-level model
// (default), its SystemC twin at pin level (systemc/pins/), or its Verilated RTL bound to the same
// pins. All three give the same cycles and bits (tests: tb/systemc).
enum class UnitView : uint8_t { model, twin, rtl };
const char* unit_view_name(UnitView v);  // "model" / "twin" / "rtl"

struct SimConfig {
  int rtus = 6;
  // The clock of Mrays/s and GB/s (systemc/timing.h): "assumed" (500 MHz, the library default),
  // "option" (--clock-mhz, a --config file's clock_mhz) or "timing" (the RTU's clock from
  // docs/timing.json, which the CLI applies when no clock is given); the report says which.
  double clock_mhz = 500;
  std::string clock_source = "assumed";
  std::string clock_note;  // what the clock rests on, for the report
  // membus: DRAM + bus shared by all RTUs.
  uint32_t mem_latency = 100;     // cycles from accepting a request to its first data beat
  uint32_t mem_bandwidth = 16;    // bytes per cycle on the shared data bus
  uint32_t mem_queue_depth = 32;  // requests accepted and not yet returned
  uint64_t seed = 0;              // 0: fixed latency; else latency uniform in [L, 2L] per request
  L2Config l2{512 * 1024};        // shared L2 in front of the memory (size 0: none)
  // The bus interface: the model (systemc/membus.h) or the RTL Verilated (systemc/membus_rtl.h):
  // rtl/units/membus_if.v without an L2, rtl/units/membus_l2.v with it.
  UnitView membus_view = UnitView::model;
  // vtu: pipeline depth (four 8-byte nodes or one triangle record per cycle); rtl/units/vtu.v's
  // fp_sops have 2 x STAGES registers (four phases, one register each at STAGES 2): 4 = STAGES 2.
  uint32_t vtu_depth = 4;
  UnitView vtu_view = UnitView::model;
  // ascache, per RTU.
  CacheConfig node_cache{32 * 1024, 4, 64, 8, 1};
  CacheConfig list_cache{8 * 1024, 4, 64, 8, 1};
  CacheConfig tri_cache{32 * 1024, 4, 64, 8, 1};
  // The three caches: the model (systemc/ascache.h) or rtl/units/ascache.v Verilated at the
  // cache's geometry (systemc/ascache_rtl.h; no pin-level twin in the frame: the frame's caches
  // answer within the cycle, the twin at ascache.v's registered pins does not).
  UnitView ascache_view = UnitView::model;
  // rgu / trv / ist / hit.
  // Defaults of the levers below (and the node cache's 32 KB above) chosen by the numbers of `make
  // throughput` (docs/results.md: the least RTU area found that reaches 0.08 rays/cycle per RTU on
  // sponza-paper, sibenik-paper and corridor at <= 1.1 GB/s: 5 trv pipes for sibenik-paper's 61
  // passes per ray, 4 ist units for corridor's 40 tests per ray); the RayCore-like baseline of the
  // paper runs is configs/baseline.json.
  uint32_t rays_in_flight = 96;  // ray slots per RTU (each with its own stack)
  uint32_t stack_depth = 64;     // stack entries per ray slot (1..64; a ray that needs more stops
                                 //   the run with an error: the report's stack_max says what a
                                 //   scene needs)
  uint32_t trv_latency = 5;      // cycles of one traversal step (loop back to the ready queue)
  uint32_t trv_pipes = 5;        // traversal pipelines per RTU (steps per cycle; RayCore has 2),
                                 //   sharing the ray slots and the node and list caches' ports
  bool trv_fuse = true;          // fuse a leaf's first list line into its node step, and the popped
                                 //   node's fetch into the leaf-end / pop step (a longer pass)
  uint32_t mailbox = 0;          // per-ray mailbox of the last M triangles tested (0: none); a list
                                 //   entry found in it is not tested again (its test could not win:
                                 //   a miss misses again, a hit is not closer than the best)
  uint32_t ist_units = 4;        // intersection pipelines per RTU (tests issued per cycle),
                                 //   sharing the triangle cache's ports
  uint32_t ist_latency = 0;      // 0: the record kind's pipeline at STAGES 2 (ist_latency_for:
                                 //   ist.v's 10 levels, 20 cycles; ist_watertight.v's 18, 36)
  UnitView ist_view = UnitView::model;
  // trv: the transaction model (systemc/trv.h) or rtl/units/trv_unit.v Verilated (no pin-level
  // twin: the transaction model is its twin; systemc/trv_rtl.h).
  UnitView trv_view = UnitView::model;
  uint32_t ist_queue = 32;       // ist input queue (triangle tests waiting)
  uint32_t hit_latency = 48;     // rtl/units/hit.v: kHitLevels (24) x STAGES 2 (hit point,
                                 //   shadow ray, spawn; sqrt, rcp)
  UnitView hit_view = UnitView::model;
  uint32_t tile = 8;             // rgu: square tiles of tile x tile pixels, round-robin over RTUs
  // rgu: the primary-ray datapath's latency; rtl/units/rgu.v has 8 operator levels of STAGES
  // registers: 16 = STAGES 2. The first primary ray leaves hls::RguTiles::startup() (the walk's
  // set-up after start in cycle 0) + rgu_latency cycles into the frame, as from rgu.v.
  uint32_t rgu_latency = 30;
  UnitView rgu_view = UnitView::model;
  // The whole RTU: rtl/units/rtu.v Verilated (systemc/rtu_rtl.h), every RTU one model stepped from
  // C++ with the Verilated bus interface (membus_if.v); rtl only, alone (no other unit's view).
  UnitView rtu_view = UnitView::model;
  // Simulator.
  std::string trace_file;  // VCD of the top-level handshakes and counters
  bool progress = false;   // progress bar on stderr
};

// Counters of one cache.
struct CacheStats {
  uint64_t accesses = 0, hits = 0, misses = 0;
  uint64_t mshr_merges = 0;    // misses on a line already being fetched
  uint64_t mshr_full = 0;      // misses that found no free MSHR (retried later)
  uint64_t set_full = 0;       // misses refused an MSHR: every way of the set pinned (filled, not
                               //   hit since) or awaited by an MSHR (retried later)
  uint64_t fills = 0;
  uint64_t cycles_lost = 0;    // issue slots of the requester wasted by misses
};

struct RtuStats {
  uint64_t primary_rays = 0, shadow_rays = 0, retired = 0;
  uint64_t rgu_busy = 0, rgu_stall_no_slot = 0;
  uint64_t rgu_primary_end = 0;   // cycle after the last primary ray was issued
  uint64_t rgu_busy_primary = 0;  // rgu_busy up to then (the rest of that span is stalled)
  uint64_t trv_busy = 0, trv_idle = 0, trv_node_miss = 0, trv_list_miss = 0, trv_ist_full = 0;
  uint64_t inner_steps = 0, leaf_visits = 0, pops = 0;
  uint64_t list_steps = 0;  // list lines read (one per list step or fused list access)
  uint64_t trv_fused = 0;   // accesses fused into a pass that had one already (--trv-fuse)
  uint64_t mailbox_skips = 0;  // list entries not sent to the ist: found in the ray's mailbox
  uint64_t stack_max = 0;   // deepest stack any ray of the RTU reached
  uint64_t ist_busy = 0, ist_tri_miss = 0, tri_tests = 0;
  uint64_t hit_busy = 0;
  uint64_t vtu_busy = 0;  // records transformed (one per cycle)
  // Cycles in which two lines arrived at the RTU (the memory's and the L2's last beats together),
  // and lines waiting for their cache's one fill port (bypassed lines, summed over the cycles
  // each waits: two lines of one cache arriving together).
  uint64_t vtu_paired = 0, vtu_fill_waits = 0;
  CacheStats node, list, tri;
};

// The ist's latency for records of `kind`: cfg.ist_latency, or with 0 the kind's pipeline at
// STAGES 2 (ist_levels x 2).
inline uint32_t ist_latency_for(const SimConfig& cfg, hls::IstKind kind) {
  return cfg.ist_latency != 0 ? cfg.ist_latency : 2 * ist_levels(kind);
}
// cfg with ist_latency 0 resolved so (the report's configuration).
inline SimConfig resolved_ist_latency(SimConfig cfg, hls::IstKind kind) {
  cfg.ist_latency = ist_latency_for(cfg, kind);
  return cfg;
}

}  // namespace raycore::sc
