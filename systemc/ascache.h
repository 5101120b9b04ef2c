// systemc/ascache.h - one acceleration-structure cache (the RTU has three: node, list, triangle).
// Set-associative, LRU, lines of line_bytes; non-blocking: a miss allocates an MSHR (or merges into
// the one already fetching the line) and sends a line request to membus, and the requester loops
// (it retries later) while hits behind it proceed. A miss that finds every MSHR busy is retried as
// well (counted as mshr_full). Lines are addressed by index within the cache's region of the image.
// The fill comes back through the vtu (transformed or not), then fill(tag) installs it.
//
// A fill acts at the clock edge that ends its cycle (the RTL's cut of the fill path: nothing an
// access of a cycle sees depends on that cycle's fill): fill(tag) chooses the victim from the
// state at the cycle's start (it is called before the cycle's accesses; one fill per cycle, the
// RTL's one fill port), and the line is installed, pinned and its MSHR freed when the cache
// first sees a later cycle (now > the fill's cycle). So an access in the fill's own cycle sees the
// line still fetched (a merge) and may hit the victim's old line. The fill does not touch the LRU
// order (its line is pinned until its first hit, which makes it the most recent).
//
// Forward progress (no livelock of looping for the next chance): a filled line is pinned (never a
// victim) until its first hit, and a miss gets an MSHR only while its set has a way neither pinned
// nor awaited by an MSHR (pinned + awaited < ways; else it is refused and retried, counted as
// set_full), so every fill finds an unpinned victim (its own MSHR is among the awaited until the
// install) and never waits. The requester whose
// miss took the MSHR retries exactly that line until it hits it, so each fill is hit at least once
// (systemc/README.md, "Utilisation and the livelock guard").
#pragma once

#include <systemc>

#include <cstdint>
#include <deque>
#include <memory>
#include <utility>
#include <vector>

#include "systemc/ascache_rtl.h"
#include "systemc/config.h"
#include "systemc/fifo.h"
#include "systemc/membus.h"

namespace raycore::sc {

class Ascache : public sc_core::sc_module {
 public:
  // base: byte address of the region in the image; line_bytes: fetched per miss.
  Ascache(sc_core::sc_module_name name, const CacheConfig& cfg, uint64_t base, uint32_t line_bytes);

  // The line's bytes on a hit, nullptr on a miss (then the line is being fetched, or will be once
  // an MSHR is free).
  const uint8_t* access(uint64_t line);
  // Whether the line is present in cycle `now` (a fill of an earlier cycle installed), without
  // touching LRU or counters (tests; the model's arrays: throws with the RTL bound).
  bool present(uint64_t line);
  // Binds the Verilated cache (systemc/ascache_rtl.h, raycore simulate --rtl ascache): from now on
  // it decides every access and holds the lines; this class keeps the MSHR buffers, the request
  // channel and the counters, and checks the RTL against them.
  void bind_rtl(std::unique_ptr<AscacheRtl> rtl) { rtl_ = std::move(rtl); }
  const AscacheRtl* rtl() const { return rtl_.get(); }

  // The fill path: the MSHR buffer the membus writes and the vtu transforms, then the install
  // (at the end of the fill's cycle, see above).
  uint8_t* mshr_data(uint32_t tag) { return mshr_[tag].buf.data(); }
  uint64_t mshr_line(uint32_t tag) const { return mshr_[tag].line; }
  void fill(uint32_t tag);
  // The cycle from now on (the owner calls it at every cycle's start): a fill of an earlier cycle
  // is installed. access() and fill() do the same with the cycle in `now`.
  void advance(Cycle cycle) {
    now = cycle;
    settle();
  }

  // This cycle's activity (the waveform, --trace): accesses, hits and fills with now as set.
  struct Probe {
    Cycle cycle = kNever;
    uint32_t accesses = 0, hits = 0, fills = 0;
  };
  Probe probe(Cycle at) const { return probe_.cycle == at ? probe_ : Probe{at, 0, 0, 0}; }

  TimedFifo<MemReq>& req() { return req_; }  // req_valid_o / req_ready_i / req_addr_o ...
  uint32_t line_bytes() const { return line_; }
  uint32_t sets() const { return sets_; }
  uint32_t ways() const { return ways_; }
  uint32_t mshrs_busy() const { return busy_; }  // the fill's MSHR is busy until its install
  uint32_t mshrs_total() const { return uint32_t(mshr_.size()); }
  CacheStats& stats() { return st_; }
  // With the RTL bound: clocks its pending edge and checks its counters against these first.
  const CacheStats& stats() const;
  Cycle now = 0;  // set by the owner each cycle (request timestamps)
  uint32_t hit_latency = 1;

 private:
  struct Mshr {
    bool valid = false;
    uint64_t line = 0;
    std::vector<uint8_t> buf;
  };
  uint32_t line_, ways_, sets_;
  uint64_t base_;
  std::vector<uint64_t> tag_;    // line + 1; 0 = invalid
  std::vector<uint64_t> stamp_;  // LRU: last use
  std::vector<uint8_t> pin_;     // filled, not hit since: not a victim
  std::vector<uint8_t> data_;
  uint64_t clock_ = 0;
  std::vector<Mshr> mshr_;
  uint32_t busy_ = 0;
  // The fill of cycle `at` (MSHR tag, its victim way's index in the arrays; SIZE_MAX with the RTL
  // bound, which installs at its own edge), installed by settle() once now > at.
  struct Pending {
    bool valid = false;
    Cycle at = 0;
    uint32_t tag = 0;
    size_t victim = 0;
  };
  Pending pend_;
  Cycle accessed_ = kNever;  // the cycle of the last access (a fill must come before them)
  // Every access and fill checks for a fill of an earlier cycle (inline: the frame's inner loop).
  void settle() {
    if (pend_.valid && now > pend_.at) install();
  }
  void install();
  TimedFifo<MemReq> req_;
  CacheStats st_;
  // RTL view: the Verilated cache, and the requests queued in it (line, MSHR) that the bus has not
  // taken as far as it knows (the bus pops req_ itself; sync_pops() passes those pops on).
  const uint8_t* access_rtl(uint64_t line);
  uint32_t allocate(uint64_t line);  // the lowest free MSHR takes the line, its request queued
  bool set_full(uint64_t line) const;  // every way of the line's set pinned or awaited by an MSHR
  void sync_pops();
  std::unique_ptr<AscacheRtl> rtl_;
  std::deque<std::pair<uint64_t, uint32_t>> queued_;
  Probe probe_;
  Probe& probe_now() {
    if (probe_.cycle != now) probe_ = Probe{now, 0, 0, 0};
    return probe_;
  }
};

}  // namespace raycore::sc
