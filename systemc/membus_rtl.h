// systemc/membus_rtl.h - the memory bus interface as RTL in the running frame (raycore simulate
// --rtl membus): rtl/units/membus_if.v (the requesters' round-robin, the outstanding-request queue,
// the beats routed back), Verilated with --cc and stepped from C++ by Membus (systemc/membus.h) in
// place of its own arbitration. The memory behind it (the image's bytes, the latency, the data
// bus's occupancy) stays in Membus, the testbench's side: it times each accepted line as the
// transaction model does and drives its beats on beat_*; the RTL routes them back, and Membus
// copies them into the requester's MSHR buffer and answers the requester when the RTL shows the
// line's last beat, checking that this is the cycle the transaction model would (the L2 has no
// RTL: refused).
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
  // Requester i's request this cycle (valid, byte address, bytes, tag).
  virtual void request(unsigned i, bool valid, uint32_t addr, uint32_t bytes, uint32_t tag) = 0;
  // The memory's beat this cycle (nullptr: none), beat_bytes() bytes.
  virtual void beat(const uint8_t* data) = 0;
  // Evaluates the cycle with the memory ready: the requester accepted (mem_port_o), or -1.
  virtual int accept() = 0;
  virtual bool full() const = 0;  // DEPTH requests outstanding (nobody can be accepted)
  // The clock edge; then the beat routed back (the one driven this cycle), if any.
  struct Rsp {
    bool valid = false, last = false;
    uint32_t port = 0, tag = 0, beat = 0;
    const uint8_t* data = nullptr;  // beat_bytes() bytes, valid until the next edge
  };
  virtual Rsp edge() = 0;
  virtual std::string name() const = 0;
};

// The Verilated membus_if, or nullptr when none is built; rtl_membus_built() lists what is.
std::unique_ptr<MembusRtl> make_rtl_membus(unsigned requesters, unsigned depth, unsigned beat_bytes);
std::string rtl_membus_built();

// The Verilated membus_if for `rtus` RTUs (3 requesters each), the queue depth and the bus width:
// throws ConfigError (systemc/config.h) naming what is built when there is none.
inline std::unique_ptr<MembusRtl> make_rtl_membus_for(int rtus, unsigned depth, unsigned beat_bytes) {
  auto r = make_rtl_membus(unsigned(3 * rtus), depth, beat_bytes);
  if (!r)
    throw ConfigError("no Verilated membus_if for " + std::to_string(rtus) +
                      " RTUs, --mem-queue-depth " + std::to_string(depth) + " and --mem-bandwidth " +
                      std::to_string(beat_bytes) + " in this build; built: " + rtl_membus_built());
  return r;
}

}  // namespace raycore::sc
