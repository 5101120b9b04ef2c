// systemc/trv.h - kd-tree traversal for many rays in flight. Each cycle the ray at the head of the
// ready queue takes one step (box clip, one inner node, the leaf's end, one stack pop) and loops
// back trv_latency cycles later; a step that reads a list line asks the list stage for it, which
// reads it in the next cycle (see tick). A ray whose node or list line misses in the
// ascache loops back the same way and tries again ("looping for the next chance"): the pipeline
// never stalls on memory. A leaf's list entries go to the ist; the ray waits for all of its
// results, then its leaf-end step mirrors the golden tracer's termination rules exactly.
#pragma once

#include <systemc>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "hls/image.h"
#include "hls/trv.h"
#include "systemc/slot.h"
#include "systemc/slot_unit.h"

namespace raycore::sc {

template <class A>
class Trv : public SlotUnit {
 public:
  Trv(sc_core::sc_module_name name, FrameCtx& fc, RtuChannels& ch, RtuStats& st, uint32_t latency,
      uint32_t pipes, bool fuse)
      : SlotUnit(name, fc, ch, st, latency), pipes_(pipes), fuse_(fuse) {
    if (pipes_ < 1 || pipes_ > 16) throw std::invalid_argument("trv pipes must be 1..16");
  }

  // One cycle. First the list stage: the list steps that the pipes' passes asked for in the cycle
  // before, in pipe order, one list-cache access each (a pass asks for at most one: a list pass's
  // own, or a node pass's fused one after a leaf). Then each of the pipes takes the ray at the
  // head of the ready queue (pipe 0 first; they share the node cache, one access per pipe and
  // cycle: RayCore's L1s have two request ports for its two traversal units). So no access's
  // address depends on a cache's answer (the list read follows the node read a cycle later), and
  // only a list step's room depends on the earlier steps' answers.
  bool tick(Cycle now) {
    bool any = list_stage(now);
    for (uint32_t p = 0; p < pipes_ && step(now); ++p) any = true;
    stage_.swap(asked_);
    asked_.clear();
    stage_at_ = now + 1;
    return any;
  }

  Cycle next_event() const {
    return stage_.empty() ? ch_.trv_q.head_ready() : std::min(ch_.trv_q.head_ready(), stage_at_);
  }

 private:
  bool step(Cycle now) {
    if (!ch_.trv_q.can_pop(now)) return false;
    const uint16_t s = ch_.trv_q.pop();
    Slot& r = ch_.slots[s];
    switch (r.state) {
      case SlotState::start: {
        r.best = Best{};
        r.sp = 0;
        r.mbox_n = r.mbox_head = 0;
        r.tmax = r.ray.tmax;
        ++st_.trv_busy;
        if (fc_.empty_tree || !hls::trv_clip_box<A>(fc_.box_lo, fc_.box_hi, r.ray, r.tnear, r.tfar,
                                                             fc_.margins.widen_ulps))
          return finish(s, r, now);
        r.node = 0;
        r.state = SlotState::node;
        ch_.trv_q.push(s, now + lat_);
        return true;
      }
      case SlotState::node:
        return node_step(s, r, now, 0, false);
      case SlotState::list:
        return ask_list(s, now, 0, false);
      case SlotState::leaf_done: {
        ++st_.trv_busy;
        // Results of the leaf, reduced in list order: the closest, ties to the earliest entry.
        // Every test used the leaf-entry tmax (= best.t or the ray's tmax), so a leaf hit is
        // always closer than the best so far (the golden tracer's sequential tmax update).
        if (r.leaf.found) {
          r.best = r.leaf;
          r.tmax = r.leaf.t;
        }
        return leaf_end(s, r, now, 0, fuse_);
      }
      case SlotState::pop:
        ++st_.trv_busy;
        return pop(s, r, now, 0, fuse_);
      default:
        throw std::logic_error("trv: ray in an unexpected state");
    }
  }

  static uint32_t hit_lat(const Ascache& c) { return c.hit_latency; }

  // Whether triangle index tri is in the ray's mailbox; if not, it goes in (oldest out).
  bool in_mailbox(Slot& r, uint32_t tri) const {
    for (uint32_t k = 0; k < r.mbox_n; ++k)
      if (r.mbox[k] == tri) return true;
    if (r.mbox_n < fc_.mailbox) {
      r.mbox[r.mbox_n++] = tri;
    } else {
      r.mbox[r.mbox_head] = tri;
      r.mbox_head = (r.mbox_head + 1) % fc_.mailbox;
    }
    return false;
  }

  // The steps below run at cycle now; `extra` is how far into a fused pass the step starts (the
  // cycles of the accesses before it), `fused` that the pass is already counted busy. A ray goes
  // back to the ready queue now + extra + lat_ (+ the cache's hit latency after an access).
  bool node_step(uint16_t s, Slot& r, Cycle now, uint32_t extra, bool fused) {
    const Cycle again = now + extra + lat_;
    const uint32_t lb = ch_.node->line_bytes();
    const uint64_t byte = uint64_t(r.node) * 8;
    const uint8_t* line = ch_.node->access(byte / lb);
    if (!line) {
      if (!fused) ++st_.trv_node_miss;
      ch_.trv_q.push(s, again);
      return true;
    }
    if (!fused) ++st_.trv_busy;
    const hls::Node nd = hls::decode_node(hls::detail::get_le(line + byte % lb, 8));
    const uint32_t x = extra + hit_lat(*ch_.node);
    const Cycle next = again + hit_lat(*ch_.node);
    if (!nd.leaf()) {
      ++st_.inner_steps;
      const hls::SplitStep sp = hls::trv_split<A>(nd.split_or_count, nd.axis, r.ray, r.tnear, r.tfar,
                                                        fc_.margins.widen_ulps);
      const uint32_t first = sp.below_first ? r.node + 1 : nd.index;
      const uint32_t second = sp.below_first ? nd.index : r.node + 1;
      if (sp.visit == hls::Visit::first) {
        r.node = first;
      } else if (sp.visit == hls::Visit::second) {
        r.node = second;
      } else {
        if (r.sp >= int(fc_.stack_depth))
          throw std::runtime_error("trv: a ray needs more than the " + std::to_string(fc_.stack_depth) +
                                   " stack entries of --stack-depth (at most 64, the deepest tree)");
        r.stack[size_t(r.sp++)] = {second, sp.tsplit, r.tfar};
        st_.stack_max = std::max<uint64_t>(st_.stack_max, uint64_t(r.sp));
        r.node = first;
        r.tfar = sp.tsplit;
      }
      ch_.trv_q.push(s, next);
      return true;
    }
    ++st_.leaf_visits;
    if (nd.split_or_count == 0) return leaf_end(s, r, now, x, false);  // one node access a pass
    r.list_first = nd.index;
    r.list_count = nd.split_or_count;
    r.list_pos = 0;
    r.results = 0;
    r.leaf = Best{};
    r.state = SlotState::list;
    if (fuse_) {  // the leaf's first list line fused into the pass (read by the list stage)
      ++st_.trv_fused;
      return ask_list(s, now, x, true);
    }
    ch_.trv_q.push(s, next);
    return true;
  }

  // A list step asked for by the pass at cycle now, `extra` into it: the list stage makes it in
  // the next cycle, its ready cycles counted from base = now + extra (at least the stage's cycle).
  bool ask_list(uint16_t s, Cycle now, uint32_t extra, bool fused) {
    asked_.push_back({s, std::max<Cycle>(now + extra, now + 1), fused});
    return true;
  }

  // The list stage: the steps asked for in the cycle before, in pipe order, each with the ist
  // queue's room as the steps before it left it (a step that misses takes none: so a ray whose
  // line is pinned for it is never kept from reading it by a step that cannot go on). The room is
  // the queue's at the cycle's start (RtuChannels::ist_room: the ist's pops of this cycle make
  // room from the next cycle on).
  bool list_stage(Cycle now) {
    if (stage_.empty()) return false;
    if (now != stage_at_) throw std::logic_error("trv: the list stage skipped its cycle");
    for (const Asked& a : stage_) list_step(a.slot, ch_.slots[a.slot], a.base, a.fused, now);
    stage_.clear();
    return true;
  }

  bool list_step(uint16_t s, Slot& r, Cycle base, bool fused, Cycle now) {
    const Cycle again = base + lat_;
    const uint32_t lb = ch_.list->line_bytes();
    const uint64_t byte = uint64_t(r.list_first + r.list_pos) * 4;
    const size_t room = ch_.ist_room(now);
    if (room == 0) {
      if (!fused) ++st_.trv_ist_full;
      ch_.trv_q.push(s, again);
      return true;
    }
    const uint8_t* line = ch_.list->access(byte / lb);
    if (!line) {
      if (!fused) ++st_.trv_list_miss;
      ch_.trv_q.push(s, again);
      return true;
    }
    if (!fused) ++st_.trv_busy;
    ++st_.list_steps;
    uint32_t n = std::min<uint32_t>(r.list_count - r.list_pos, uint32_t((lb - byte % lb) / 4));
    n = std::min<uint32_t>(n, uint32_t(room));
    const Cycle ready = base + 1 + hit_lat(*ch_.list);
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t tri = uint32_t(hls::detail::get_le(line + byte % lb + size_t(i) * 4, 4));
      if (fc_.mailbox != 0 && in_mailbox(r, tri)) {  // tested before: cannot win, counts as done
        ++st_.mailbox_skips;
        ++r.results;
        continue;
      }
      ch_.ist_q.push({s, r.list_pos + i, tri}, ready);
    }
    r.list_pos += n;
    if (r.list_pos == r.list_count && r.results == r.list_count) {
      r.state = SlotState::leaf_done;  // nothing left at the ist (the mailbox took the rest)
      ch_.trv_q.push(s, again + hit_lat(*ch_.list));
    } else if (r.list_pos == r.list_count)
      r.state = SlotState::wait_ist;  // the ist re-queues the ray with its last result
    else
      ch_.trv_q.push(s, again + hit_lat(*ch_.list));
    return true;
  }

  bool leaf_end(uint16_t s, Slot& r, Cycle now, uint32_t extra, bool fuse) {
    // A hit in this cell ends the walk; an any-hit shadow ray ends at its first leaf with a hit.
    if (r.best.found && ((r.shadow && fc_.spawn.any_hit) || !A::lt(r.tfar, r.best.t)))
      return finish(s, r, now);
    return pop(s, r, now, extra, fuse);
  }
  // One stack entry per step; entries beyond the best hit are skipped (one step each). With fuse
  // (a pass that has not read the node cache yet), the popped node is fetched in the same pass.
  bool pop(uint16_t s, Slot& r, Cycle now, uint32_t extra, bool fuse) {
    if (r.sp == 0) return finish(s, r, now);
    const Slot::Entry e = r.stack[size_t(--r.sp)];
    ++st_.pops;
    if (r.best.found && A::lt(r.best.t, e.tnear)) {
      r.state = SlotState::pop;
    } else {
      r.node = e.node;
      r.tnear = e.tnear;
      r.tfar = e.tfar;
      r.state = SlotState::node;
      if (fuse) {
        ++st_.trv_fused;
        return node_step(s, r, now, extra, true);
      }
    }
    ch_.trv_q.push(s, now + extra + lat_);
    return true;
  }
  bool finish(uint16_t s, Slot& r, Cycle now) {
    r.state = SlotState::done;
    ch_.hit_q.push(s, now + lat_);
    return true;
  }

  struct Asked {  // a list step for the list stage
    uint16_t slot;
    Cycle base;
    bool fused;
  };
  uint32_t pipes_;
  bool fuse_;
  std::vector<Asked> stage_, asked_;  // this cycle's list steps; the ones asked for it
  Cycle stage_at_ = 0;                // the cycle stage_ runs in
};

}  // namespace raycore::sc
