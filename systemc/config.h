// systemc/config.h - parameters of the cycle model (one plain struct, as the style guide asks)
// and the counters it reports.
#pragma once

#include <cstdint>
#include <string>

namespace raycore::sc {

struct CacheConfig {
  uint32_t size_bytes = 16 * 1024;
  uint32_t ways = 4;
  uint32_t line_bytes = 64;  // triangle cache: rounded to a whole number of records
  uint32_t mshrs = 8;        // outstanding distinct line misses
  uint32_t hit_latency = 1;  // cycles added to the requester's loop on a hit
};

// How a unit with a pin-level form is modelled in the frame: the fast transaction-level model
// (default), its SystemC twin at pin level (systemc/pins/), or its Verilated RTL bound to the same
// pins. All three give the same cycles and bits (tests: tb/systemc).
enum class UnitView : uint8_t { model, twin, rtl };
const char* unit_view_name(UnitView v);  // "model" / "twin" / "rtl"

struct SimConfig {
  int rtus = 6;
  double clock_mhz = 500;  // an assumption, stated in the report
  // membus: DRAM + bus shared by all RTUs.
  uint32_t mem_latency = 100;     // cycles from accepting a request to its first data beat
  uint32_t mem_bandwidth = 16;    // bytes per cycle on the shared data bus
  uint32_t mem_queue_depth = 32;  // requests accepted and not yet returned
  uint64_t seed = 0;              // 0: fixed latency; else latency uniform in [L, 2L] per request
  // vtu: pipeline depth (one 8-byte node or one triangle record per cycle); rtl/units/vtu.v has
  // 3 operator levels of STAGES registers: 6 = STAGES 2, as in docs/area.md.
  uint32_t vtu_depth = 6;
  UnitView vtu_view = UnitView::model;
  // ascache, per RTU.
  CacheConfig node_cache{16 * 1024, 4, 64, 8, 1};
  CacheConfig list_cache{8 * 1024, 4, 64, 8, 1};
  CacheConfig tri_cache{32 * 1024, 4, 64, 8, 1};
  // rgu / trv / ist / hit.
  uint32_t rays_in_flight = 64;  // ray slots per RTU (each with its own 64-entry stack)
  uint32_t trv_latency = 4;      // cycles of one traversal step (loop back to the ready queue)
  uint32_t ist_latency = 20;     // rtl/units/ist.v: 10 operator levels x STAGES 2
  UnitView ist_view = UnitView::model;
  uint32_t ist_queue = 32;       // ist input queue (triangle tests waiting)
  uint32_t hit_latency = 20;     // hit point + shadow set-up (sqrt, rcp)
  uint32_t tile = 8;             // rgu: square tiles of tile x tile pixels, round-robin over RTUs
  // Simulator.
  std::string trace_file;  // VCD of the top-level handshakes and counters
  bool progress = false;   // progress bar on stderr
};

// Counters of one cache.
struct CacheStats {
  uint64_t accesses = 0, hits = 0, misses = 0;
  uint64_t mshr_merges = 0;    // misses on a line already being fetched
  uint64_t mshr_full = 0;      // misses that found no free MSHR (retried later)
  uint64_t fills = 0;
  uint64_t cycles_lost = 0;    // issue slots of the requester wasted by misses
};

struct RtuStats {
  uint64_t primary_rays = 0, shadow_rays = 0, retired = 0;
  uint64_t rgu_busy = 0, rgu_stall_no_slot = 0;
  uint64_t trv_busy = 0, trv_idle = 0, trv_node_miss = 0, trv_list_miss = 0, trv_ist_full = 0;
  uint64_t inner_steps = 0, leaf_visits = 0, pops = 0;
  uint64_t ist_busy = 0, ist_tri_miss = 0, tri_tests = 0;
  uint64_t hit_busy = 0;
  uint64_t vtu_busy = 0;  // records transformed (one per cycle)
  CacheStats node, list, tri;
};

}  // namespace raycore::sc
