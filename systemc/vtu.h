// systemc/vtu.h - the viewport transfer unit on the fill path between membus and the ascache.
// Fully pipelined, depth cycles deep (rtl/units/vtu.v: 2 x STAGES), per cycle four 8-byte nodes
// (three through the fp_sops a triangle uses, one through a subtractor) or one triangle record:
// 32 bytes of an FP24 line per cycle, so a 64-byte node or triangle line takes 2 cycles. Applies
// hls::Vtu per record (Vtu::node, Vtu::tri_record): the caches hold translated data, the memory
// the untranslated image. List lines hold no coordinates and bypass the unit, as everything does
// when the VTU is off (the line goes to the cache in the cycle it arrives).
//
// Two views of the same unit (SimConfig::vtu_view): the transaction model below (default, fast),
// or a pin-level unit with rtl/units/vtu.v's ports (systemc/pins/vtu.h: the SystemC twin or the
// Verilated RTL) driven record by record (a node record: a group of up to four nodes, lanes outside
// the image masked): a record driven in cycle c leaves in cycle c + depth and is written back into
// the line; the line is installed when its last record is out. Same cycles.
#pragma once

#include <systemc>

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <stdexcept>
#include <vector>

#include "hls/image.h"
#include "hls/vtu.h"
#include "systemc/ascache.h"
#include "systemc/fifo.h"
#include "systemc/membus.h"
#include "systemc/pins/vtu.h"

namespace raycore::sc {

enum Port : uint32_t { kNodePort = 0, kListPort = 1, kTriPort = 2 };

template <class F, hls::Rounding R>
class VtuUnit : public sc_core::sc_module, public MemClient {
 public:
  VtuUnit(sc_core::sc_module_name name, bool on, const hls::Vtu<F, R>& vtu, uint32_t depth,
          const hls::ImageHeader& h, std::array<Ascache*, 3> caches, uint32_t fill_slots)
      : sc_core::sc_module(name), on_(on), vtu_(vtu), depth_(depth), h_(h), caches_(caches),
        fills_(fill_slots), bypass_(fill_slots) {}

  // Drive the pin-level unit (twin or RTL) instead of the transaction model.
  void bind(pins::VtuPort* p) {
    port_ = p;
    for (size_t i = 0; i < 3; ++i) left_[i].assign(caches_[i]->mshrs_total(), 0);
    if (p) p->config(on_, vtu_.c);
  }

  // A line's last beat arrived (membus side).
  void mem_resp(uint32_t port, uint32_t tag, Cycle now) override {
    if (now == last_resp_) ++paired_;  // a second line in this cycle (one per channel at most)
    last_resp_ = now;
    Ascache& c = *caches_[port];
    if (!on_ || port == kListPort) {  // not behind the lines inside the pipeline
      bypass_.push({port, tag}, now);
      return;
    }
    if (port_) {
      queue_records(port, tag);
      return;
    }
    uint8_t* p = c.mshr_data(tag);
    const uint64_t line = c.mshr_line(tag);
    const uint32_t lb = c.line_bytes();
    uint32_t records = 0;
    if (port == kNodePort) {
      const uint64_t first = line * lb / 8;
      for (uint32_t i = 0; i < lb / 8; ++i) {
        if (first + i >= h_.node_count) break;
        uint8_t* q = p + size_t(i) * 8;
        hls::detail::put_le(q, vtu_.node(hls::detail::get_le(q, 8)), 8);
        ++records;
      }
    } else if (port == kTriPort) {
      const uint32_t rb = h_.tri_bytes;
      const uint64_t first = line * lb / rb;
      for (uint32_t i = 0; i < lb / rb; ++i) {
        if (first + i >= h_.tri_count) break;
        vtu_.tri_record(p + size_t(i) * rb, hls::IstKind(h_.ist));
        ++records;
      }
    }
    if (port == kNodePort) records = (records + pins::kVtuNodeLanes - 1) / pins::kVtuNodeLanes;
    records = std::max<uint32_t>(records, 1);
    const Cycle start = std::max(now, free_);
    free_ = start + records;
    busy_ += records;
    fills_.push({port, tag}, start + records - 1 + depth_);
  }

  // Lines leaving the pipeline are installed in their cache, one a cycle per cache (its one fill
  // port): a line that finds its cache's port taken in this cycle (two lines of one cache back
  // together, from the L2 and the memory) waits for the next, and the lines behind it with it.
  bool tick(Cycle now) {
    bool active = false;
    std::array<bool, 3> taken{};
    for (TimedFifo<Fill>* q : {&bypass_, &fills_})
      while (q->can_pop(now) && !taken[q->front().port]) {
        const Fill f = q->pop();
        taken[f.port] = true;
        caches_[f.port]->fill(f.tag);
        active = true;
      }
    // Bypassed lines left: each arrived by now (mem_resp comes before this tick in its cycle) and
    // waits for its cache's fill port.
    waits_ += bypass_.size();
    if (port_) active |= tick_pins();
    return active;
  }
  Cycle next_event(Cycle now) const {
    if (port_ && (!records_.empty() || in_flight_ != 0)) return now + 1;
    return std::min(fills_.head_ready(), bypass_.head_ready());
  }
  // This cycle needs a clock edge on the pin-level unit (it drove a record or has some inside).
  bool wants_edge() const { return edge_; }
  uint64_t busy() const { return busy_; }
  uint64_t paired() const { return paired_; }
  uint64_t fill_waits() const { return waits_; }

 private:
  struct Fill {
    uint32_t port = 0, tag = 0;
  };
  struct Record {  // a record waiting for or inside the pin-level unit
    uint32_t port = 0, tag = 0, offset = 0;
    pins::VtuRec rec;
  };

  void queue_records(uint32_t port, uint32_t tag) {
    Ascache& c = *caches_[port];
    uint8_t* p = c.mshr_data(tag);
    const uint64_t line = c.mshr_line(tag);
    const uint32_t lb = c.line_bytes();
    const bool node = port == kNodePort;
    const uint32_t rb = node ? 8u : uint32_t(h_.tri_bytes);
    const uint64_t first = line * lb / rb, count = node ? h_.node_count : h_.tri_count;
    uint32_t n = 0;
    const uint32_t lanes = node ? pins::kVtuNodeLanes : 1u;
    for (uint32_t i = 0; i < lb / rb && first + i < count; i += lanes, ++n) {
      Record r{port, tag, i * rb, {}};
      r.rec.kind = !node;
      if (node) {
        for (uint32_t j = 0; j < lanes && i + j < lb / rb && first + i + j < count; ++j) {
          r.rec.node[j] = hls::detail::get_le(p + r.offset + j * 8, 8);
          r.rec.nmask |= 1u << j;
        }
      } else {
        const hls::WaldTri<F> t = hls::decode_tri<F>(p + r.offset, hls::IstKind::wald);  // simulate refuses the rest
        r.rec.k = t.k;
        r.rec.flags = t.flags;
        for (int j = 0; j < 9; ++j) r.rec.c[j] = t.c[j];
        r.rec.id = t.id;
      }
      records_.push_back(r);
    }
    if (n == 0) {  // nothing of the image in this line (cannot happen for a line that missed)
      bypass_.push({port, tag}, 0);
      return;
    }
    left_[port][tag] = n;
  }

  // One cycle of the pin-level unit: take the record the last edge put out, drive the next one.
  bool tick_pins() {
    edge_ = false;
    if (port_->out_valid()) {
      const pins::VtuRec o = port_->out();
      Record& r = ring_[o.tag % ring_.size()];
      uint8_t* p = caches_[r.port]->mshr_data(r.tag) + r.offset;
      if (!o.kind) {
        for (uint32_t j = 0; j < pins::kVtuNodeLanes; ++j)
          if ((r.rec.nmask >> j) & 1u) hls::detail::put_le(p + j * 8, o.node[j], 8);
      } else {
        hls::WaldTri<F> t;
        t.k = o.k;
        t.flags = o.flags;
        for (int j = 0; j < 9; ++j) t.c[j] = o.c[j];
        t.id = o.id;
        hls::encode_tri<F>(t, p);
      }
      if (--left_[r.port][r.tag] == 0) caches_[r.port]->fill(r.tag);
      --in_flight_;
      edge_ = true;  // the record leaves at this cycle's edge
    }
    if (!records_.empty()) {
      if (!port_->in_ready()) throw std::logic_error("vtu: pin-level unit not ready with out_ready high");
      Record r = records_.front();
      records_.pop_front();
      r.rec.tag = next_tag_;
      ring_[next_tag_ % ring_.size()] = r;
      next_tag_ = (next_tag_ + 1) & 0xFFFFu;  // TAG_BITS 16
      port_->drive(r.rec);
      ++in_flight_;
      ++busy_;
      edge_ = true;
    } else {
      port_->idle();
    }
    edge_ |= in_flight_ != 0;
    return edge_;
  }
  bool on_;
  hls::Vtu<F, R> vtu_;
  uint32_t depth_;
  hls::ImageHeader h_;
  std::array<Ascache*, 3> caches_;
  TimedFifo<Fill> fills_, bypass_;
  Cycle free_ = 0;
  uint64_t busy_ = 0, paired_ = 0, waits_ = 0;
  Cycle last_resp_ = kNever;
  // Pin-level view.
  pins::VtuPort* port_ = nullptr;
  std::deque<Record> records_;
  std::array<Record, 1024> ring_{};  // by tag: records inside the unit (<= depth of them)
  std::array<std::vector<uint32_t>, 3> left_;  // records of a line not yet out, by port and MSHR
  uint32_t next_tag_ = 0, in_flight_ = 0;
  bool edge_ = false;
};

}  // namespace raycore::sc
