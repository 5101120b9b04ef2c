// systemc/ascache_rtl.h - an AS cache as RTL in the running frame (raycore simulate --rtl ascache):
// rtl/units/ascache.v with HIT_LATENCY 0 (responses in the access's cycle, as Ascache::access
// answers the cycle model's requesters) and PORTS accesses per edge, Verilated with --cc and
// stepped from C++ by Ascache (systemc/ascache.h) in place of its own arrays.
//
// The Verilated cache holds the tags, valid bits, LRU ranks, the lines, the MSHRs' lines and the
// request queue, and decides every access (hit, merge, full, set full or a new MSHR). Ascache keeps what the
// bus and the vtu need around it: the MSHR buffers the memory writes and the vtu transforms, the
// request channel to the bus (Ascache::req()) and the counters, and checks the RTL against its
// own bookkeeping (a merge needs the line in flight, a new MSHR a free one, the lowest free one;
// the request queue's head when the bus takes it; the RTL's counters at the end).
//
// Edges: the binding clocks the cache when Ascache tells it of a new cycle (at(cycle)), and within
// a cycle in ascache.v's order (request pop, fill, then up to PORTS accesses in port order): a pop
// after a pop is an edge of its own (the bus's pops are passed on late, several at once; a pop
// changes only the request queue). A pop after the cycle's fill or accesses, a second fill or an
// access beyond PORTS in one cycle throw std::logic_error: the fill acts at the cycle's closing
// edge, so an edge inside the cycle would show it to the cycle's later accesses.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace raycore::sc {

class AscacheRtl {
 public:
  enum class Kind { hit, merge, full, set_full, alloc };
  virtual ~AscacheRtl() = default;
  // One access (Ascache::access(line)): its kind and, on a hit, the line's bytes (valid until
  // the next access).
  virtual Kind access(uint64_t line, const uint8_t** data) = 0;
  // The fill of MSHR tag with the line's bytes (Ascache::fill).
  virtual void fill(uint32_t tag, const uint8_t* data) = 0;
  // The events from now on are of this cycle: if it is a new one, the last cycle's edge.
  virtual void at(uint64_t cycle) = 0;
  // The bus took the request queue's head, which the caller expects to be (line, tag): throws
  // std::logic_error if the RTL's head is not that.
  virtual void pop(uint64_t line, uint32_t tag) = 0;
  // Clocks the pending edge, then compares the RTL's counters with these: throws
  // std::logic_error on a difference.
  virtual void check(uint64_t hits, uint64_t misses, uint64_t merges, uint64_t full,
                     uint64_t set_full, uint64_t fills) = 0;
  virtual unsigned ports() const = 0;     // accesses per cycle (PORTS)
  virtual std::string name() const = 0;  // "Verilated ascache 64x4x64B, 8 MSHRs, 8 ports"
};

// The Verilated cache of that geometry, or nullptr when none is built (then rtl_ascache_built()
// lists what is).
std::unique_ptr<AscacheRtl> make_rtl_ascache(uint32_t sets, uint32_t ways, uint32_t line_bytes,
                                             uint32_t mshrs);
std::string rtl_ascache_built();

}  // namespace raycore::sc
