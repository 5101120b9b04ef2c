// systemc/membus_rtl.h - the memory bus interface as RTL in the running frame (raycore simulate
// --rtl membus): rtl/units/membus_if.v (the requesters' round-robin, the outstanding-request queue,
// the beats routed back), Verilated with --cc and stepped from C++ by Membus (systemc/membus.h) in
// place of its own arbitration. The memory behind it (the image's bytes, the latency, the data
// bus's occupancy) stays in Membus, the testbench's side: it times each accepted line as the
// transaction model does and drives its beats on beat_*; the RTL routes them back, and Membus
// copies them into the requester's MSHR buffer and answers the requester when the RTL shows the
// line's last beat, checking that this is the cycle the transaction model would. With the L2
// (SimConfig::l2), rtl/units/membus_l2.v: the same bus with the L2's tags, data and responses in
// RTL (membus_if.v its memory side); the L2's beats leave on a second channel (l2_rsp()).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "systemc/config.h"

namespace raycore::sc {

class MembusRtl {
 public:
  virtual ~MembusRtl() = default;
  virtual unsigned ports() const = 0;        // N: requesters the model has
  virtual unsigned depth() const = 0;        // DEPTH: outstanding requests
  virtual unsigned beat_bytes() const = 0;   // BEAT_BYTES: the data bus's width
  // The L2 it is built with (membus_l2.v's SETS x WAYS x LINE_BYTES, L2_BEAT; size_bytes 0: none,
  // membus_if.v) and its response queue's depth (QDEPTH: hits accepted and not yet answered).
  virtual L2Config l2() const { return L2Config{}; }
  virtual unsigned l2_queue() const { return 0; }
  // Requester i's request this cycle (valid, byte address, bytes, tag).
  virtual void request(unsigned i, bool valid, uint32_t addr, uint32_t bytes, uint32_t tag) = 0;
  // The memory's beat this cycle (nullptr: none), beat_bytes() bytes.
  virtual void beat(const uint8_t* data) = 0;
  // The L2's inputs for this cycle: the cycle number and its hit latency.
  virtual void l2_inputs(uint32_t /*now*/, uint32_t /*latency*/) {}
  // Evaluates the cycle with the memory ready: the requester accepted (mem_port_o), or -1.
  virtual int accept() = 0;
  virtual bool hit() const { return false; }      // the request accepted hit the L2
  virtual bool stalled() const { return false; }  // a miss waits for a way of its L2 set
  virtual bool l2_busy() const { return false; }  // L2 hits accepted and not yet answered
  virtual bool full() const = 0;  // DEPTH requests outstanding (nobody can be accepted)
  // The clock edge; then the beat routed back (the one driven this cycle), if any.
  struct Rsp {
    bool valid = false, last = false;
    uint32_t port = 0, tag = 0, beat = 0;
    const uint8_t* data = nullptr;  // beat_bytes() bytes, valid until the next edge
  };
  virtual Rsp edge() = 0;
  // After edge(): the L2's beat (l2_*: the L2's width, l2().bandwidth bytes), if any.
  virtual Rsp l2_rsp() const { return Rsp{}; }
  virtual std::string name() const = 0;
};

// The Verilated membus_if (l2.size_bytes 0) or membus_l2 (the L2's size, ways, line and width as
// built; its latency is an input), or nullptr when none is built; rtl_membus_built() lists what is.
std::unique_ptr<MembusRtl> make_rtl_membus(unsigned requesters, unsigned depth, unsigned beat_bytes,
                                           const L2Config& l2 = L2Config{});
std::string rtl_membus_built();

// The Verilated bus for `rtus` RTUs (3 requesters each), the queue depth, the bus width and the
// L2: throws ConfigError (systemc/config.h) naming what is built when there is none.
inline std::unique_ptr<MembusRtl> make_rtl_membus_for(int rtus, unsigned depth, unsigned beat_bytes,
                                                      const L2Config& l2 = L2Config{}) {
  auto r = make_rtl_membus(unsigned(3 * rtus), depth, beat_bytes, l2);
  if (!r) {
    std::string l2s = "no L2";
    if (l2.size_bytes != 0)
      l2s = "--l2-kb " + std::to_string(l2.size_bytes / 1024) + " (" + std::to_string(l2.ways) +
            " ways, " + std::to_string(l2.line_bytes) + "-byte lines, --l2-bandwidth " +
            std::to_string(l2.bandwidth) + ")";
    throw ConfigError("no Verilated membus_if for " + std::to_string(rtus) +
                      " RTUs, --mem-queue-depth " + std::to_string(depth) + ", --mem-bandwidth " +
                      std::to_string(beat_bytes) + " and " + l2s + " in this build; built: " +
                      rtl_membus_built());
  }
  return r;
}

}  // namespace raycore::sc
