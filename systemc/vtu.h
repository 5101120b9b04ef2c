// systemc/vtu.h - the viewport transfer unit on the fill path between membus and the ascache.
// Fully pipelined, depth cycles deep, one 8-byte node or one triangle record per cycle (a list line,
// which the VTU does not change, passes in one cycle). Applies hls::Vtu per record (Vtu::node,
// Vtu::tri_record): the caches hold translated data, the memory the untranslated image. Off: the
// unit is bypassed (the line goes to the cache in the cycle it arrives).
#pragma once

#include <systemc>

#include <algorithm>
#include <array>
#include <cstdint>

#include "hls/image.h"
#include "hls/vtu.h"
#include "systemc/ascache.h"
#include "systemc/fifo.h"
#include "systemc/membus.h"

namespace raycore::sc {

enum Port : uint32_t { kNodePort = 0, kListPort = 1, kTriPort = 2 };

template <class F, hls::Rounding R>
class VtuUnit : public sc_core::sc_module, public MemClient {
 public:
  VtuUnit(sc_core::sc_module_name name, bool on, const hls::Vtu<F, R>& vtu, uint32_t depth,
          const hls::ImageHeader& h, std::array<Ascache*, 3> caches, uint32_t fill_slots)
      : sc_core::sc_module(name), on_(on), vtu_(vtu), depth_(depth), h_(h), caches_(caches),
        fills_(fill_slots) {}

  // A line's last beat arrived (membus side).
  void mem_resp(uint32_t port, uint32_t tag, Cycle now) override {
    Ascache& c = *caches_[port];
    if (!on_) {
      fills_.push({port, tag}, now);
      return;
    }
    uint8_t* p = c.mshr_data(tag);
    const uint64_t line = c.mshr_line(tag);
    const uint32_t lb = c.line_bytes();
    uint32_t records = 1;
    if (port == kNodePort) {
      const uint64_t first = line * lb / 8;
      records = 0;
      for (uint32_t i = 0; i < lb / 8; ++i) {
        if (first + i >= h_.node_count) break;
        uint8_t* q = p + size_t(i) * 8;
        hls::detail::put_le(q, vtu_.node(hls::detail::get_le(q, 8)), 8);
        ++records;
      }
    } else if (port == kTriPort) {
      constexpr uint32_t rb = uint32_t(hls::tri_record_bytes<F>());
      const uint64_t first = line * lb / rb;
      records = 0;
      for (uint32_t i = 0; i < lb / rb; ++i) {
        if (first + i >= h_.tri_count) break;
        vtu_.tri_record(p + size_t(i) * rb);
        ++records;
      }
    }
    records = std::max<uint32_t>(records, 1);
    const Cycle start = std::max(now, free_);
    free_ = start + records;
    busy_ += records;
    fills_.push({port, tag}, start + records - 1 + depth_);
  }

  // Lines leaving the pipeline are installed in their cache.
  bool tick(Cycle now) {
    bool active = false;
    while (fills_.can_pop(now)) {
      const Fill f = fills_.pop();
      caches_[f.port]->fill(f.tag);
      active = true;
    }
    return active;
  }
  Cycle next_event() const { return fills_.head_ready(); }
  uint64_t busy() const { return busy_; }

 private:
  struct Fill {
    uint32_t port = 0, tag = 0;
  };
  bool on_;
  hls::Vtu<F, R> vtu_;
  uint32_t depth_;
  hls::ImageHeader h_;
  std::array<Ascache*, 3> caches_;
  TimedFifo<Fill> fills_;
  Cycle free_ = 0;
  uint64_t busy_ = 0;
};

}  // namespace raycore::sc
