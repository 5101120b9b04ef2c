// systemc/membus.h - the external memory and the bus shared by all RTUs. Holds only the memory
// image's bytes (untransformed). Requests come from the caches' request channels (one per cache
// per RTU); one request is accepted per cycle, round-robin over the requesters, while fewer than
// queue_depth are outstanding. A line's data returns latency cycles after acceptance (with a seed:
// uniform in [latency, 2 latency]), then occupies the shared data bus for ceil(bytes / bandwidth)
// cycles; the response goes to the requester's vtu port.
#pragma once

#include <systemc>

#include <cstdint>
#include <deque>
#include <memory>
#include <queue>
#include <utility>
#include <vector>

#include "systemc/config.h"
#include "systemc/fifo.h"
#include "systemc/membus_rtl.h"

namespace raycore::sc {

// A line request: the payload of the req_* handshake (req_addr, req_bytes, req_tag).
struct MemReq {
  uint64_t addr = 0;
  uint32_t bytes = 0;
  uint32_t tag = 0;        // the requester's MSHR index, returned with the response
  uint8_t* data = nullptr;  // where the line's bytes land (the MSHR's buffer)
};

// The receiving side of a response (the vtu of the requesting RTU).
class MemClient {
 public:
  virtual ~MemClient() = default;
  virtual void mem_resp(uint32_t port, uint32_t tag, Cycle now) = 0;
  // With the bus interface in RTL (bind_rtl): each data beat as membus_if routes it back (l2
  // false) or as the L2 of membus_l2 sends it (l2 true), seen by the requester in cycle `at` (the
  // RTU in RTL, systemc/rtu_rtl.h, takes the beats at its pins; the cycle model's vtu takes the
  // whole line at mem_resp).
  virtual void mem_beat(uint32_t /*port*/, uint32_t /*tag*/, uint32_t /*beat*/, bool /*last*/,
                        const uint8_t* /*data*/, uint32_t /*bytes*/, bool /*l2*/, Cycle /*at*/) {}
};

struct MembusStats {
  uint64_t requests = 0, bytes = 0, busy_cycles = 0;  // memory (DRAM) side: busy = data bus beats
  uint64_t queue_full_cycles = 0;  // cycles a request waited because queue_depth were outstanding
  uint64_t latency_sum = 0;        // accept -> last beat, summed over requests
  // L2 (when configured): every request is an access; a hit (or a merge with a line still on its
  // way from memory) is served by the L2 and costs no memory traffic.
  uint64_t l2_accesses = 0, l2_hits = 0, l2_merges = 0, l2_bytes = 0, l2_busy_cycles = 0;
  // Cycles a missing request waited because no way of its L2 set could take its line: every way
  // still being filled from memory or still to be read by an accepted hit (the victim rule below).
  uint64_t l2_stall_cycles = 0;
};

class Membus : public sc_core::sc_module {
 public:
  Membus(sc_core::sc_module_name name, const std::vector<uint8_t>& image, uint32_t latency,
         uint32_t bandwidth, uint32_t queue_depth, uint64_t seed);

  // Binding: a requester's request channel and where its responses go.
  void add_requester(TimedFifo<MemReq>* req, MemClient* client, uint32_t port);
  void set_l2(const L2Config& c);
  // Binds the Verilated bus interface (systemc/membus_rtl.h, raycore simulate --rtl membus): from
  // now on it arbitrates the requests, looks them up in its L2 and routes the beats; this class is
  // the memory behind it. Throws ConfigError if it cannot run this bus (another L2, more
  // requesters than its ports, another queue depth or bandwidth, or more MSHRs than its L2's
  // response queue holds: `mshrs`, the requesters' outstanding line requests at most).
  void bind_rtl(std::unique_ptr<MembusRtl> rtl, uint64_t mshrs = 0);

  bool tick(Cycle now);        // true if anything happened
  Cycle next_event(Cycle now) const;
  uint32_t outstanding() const { return dram_out_; }  // memory requests accepted, not returned
  const MembusStats& stats() const { return st_; }

 private:
  struct Requester {
    TimedFifo<MemReq>* req;
    MemClient* client;
    uint32_t port;
  };
  struct Resp {
    Cycle arrival;
    uint64_t seq;
    uint32_t requester, tag;
    bool dram;  // holds one of the memory queue's places until it returns
    uint64_t l2_first = 0, l2_last = 0;  // an L2 hit: the L2 lines it reads (readers until then)
    bool operator>(const Resp& o) const {
      return arrival != o.arrival ? arrival > o.arrival : seq > o.seq;
    }
  };
  uint32_t draw_latency();
  // A line of bytes accepted for the memory now: its first beat and its arrival (the data bus is
  // busy until then); the memory queue place and the counters.
  std::pair<Cycle, Cycle> dram_accept(uint32_t bytes, Cycle now);
  void copy_line(const MemReq& q) const;
  struct L2Line {
    uint64_t tag = 0, stamp = 0;
    Cycle ready = 0;  // when its data is in the L2 (a line on its way from memory: later)
    uint32_t readers = 0;  // L2 hits accepted whose responses have not been delivered yet
    bool valid = false;
  };
  // The L2 lines covering [addr, addr + bytes), first and last.
  std::pair<uint64_t, uint64_t> l2_span(uint64_t addr, uint32_t bytes) const;
  // Whether all of them are in the L2 (ready: when the last of them has its data); if so they
  // become the most recently used.
  bool l2_hit(uint64_t addr, uint32_t bytes, Cycle& ready);
  // The victim rule: a missing line takes its set's first invalid way, else the least recently
  // used of the ways that are neither being filled (ready > now) nor still to be read (readers):
  // the data a filling or a waiting response needs is never overwritten (in RTL, membus_l2.v, the
  // L2's data array is what the responses read). False if some missing line of [addr, addr +
  // bytes) finds no such way: the request waits (l2_stall_cycles); fills arrive and responses
  // drain without any request, so it is accepted later.
  bool l2_victims(uint64_t addr, uint32_t bytes, Cycle now, std::vector<L2Line*>& out);
  void l2_install(uint64_t addr, uint32_t bytes, Cycle ready, const std::vector<L2Line*>& victims);
  L2Line* l2_find(uint64_t line);
  const L2Line* l2_find(uint64_t line) const;

  // RTL view (bind_rtl): the lines accepted, in acceptance order (the order the memory's data bus
  // serves them): the beats of lines_[drive_] are driven next; lines_.front() is the line whose
  // beats come back; a line whose last beat came back waits in done_ for its cycle.
  struct Line {
    uint32_t requester;
    MemReq q;
    Cycle first, arrival;
    uint32_t beats, driven = 0, got = 0;
    std::vector<uint8_t> bytes;  // the memory's data, beats x beat bytes
    uint64_t seq = 0;            // acceptance order (responses of one cycle go in this order)
  };
  // An L2 hit the RTL accepted: its beats come back on the L2's channel, in acceptance order.
  struct L2Rsp {
    uint32_t requester;
    MemReq q;
    uint64_t seq;
    uint32_t got = 0;
  };
  void rtl_done(const Resp& r);  // into done_, in (arrival, seq) order
  bool tick_rtl(Cycle now);
  Cycle next_event_rtl(Cycle now) const;
  std::unique_ptr<MembusRtl> rtl_;
  std::deque<Line> lines_;
  size_t drive_ = 0;
  std::deque<Resp> done_;
  std::deque<L2Rsp> l2_rsp_;

  const std::vector<uint8_t>& mem_;
  uint32_t latency_, bandwidth_, depth_;
  uint64_t rng_;
  std::vector<Requester> reqs_;
  size_t rr_ = 0;
  Cycle data_free_ = 0;
  uint64_t seq_ = 0;
  std::priority_queue<Resp, std::vector<Resp>, std::greater<Resp>> resp_;
  MembusStats st_;
  uint32_t dram_out_ = 0;
  L2Config l2_;
  uint32_t l2_sets_ = 0;
  std::vector<L2Line> l2_lines_;  // l2_sets_ x ways
  uint64_t l2_clock_ = 0;
  Cycle l2_free_ = 0;
  std::vector<L2Line*> victims_;  // l2_victims' answer for the request being accepted
};

}  // namespace raycore::sc
