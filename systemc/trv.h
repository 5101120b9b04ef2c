// systemc/trv.h - kd-tree traversal for many rays in flight. Each cycle the ray at the head of the
// ready queue takes one step (box clip, one inner node, the leaf's end, one stack pop) and loops
// back trv_latency cycles later. A pass reads the node cache and its outcome follows in the next
// cycle from the word (a registered read: the outcome stage, see tick); a step that reads a list
// line asks the list stage for it, which reads it in the outcome's cycle. A ray whose node or list
// line misses in the ascache loops back the same way and tries again ("looping for the next
// chance"): the pipeline never stalls on memory. A leaf's list entries go to the ist; the ray
// waits for all of its results, then its leaf-end step mirrors the golden tracer's termination
// rules exactly.
#pragma once

#include <systemc>

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

#include "hls/image.h"
#include "hls/trv.h"
#include "systemc/slot.h"
#include "systemc/slot_unit.h"

namespace raycore::sc {

template <class A>
class Trv : public SlotUnit {
  using F = typename A::Fmt;
 public:
  Trv(sc_core::sc_module_name name, FrameCtx& fc, RtuChannels& ch, RtuStats& st, uint32_t latency,
      uint32_t pipes, bool fuse)
      : SlotUnit(name, fc, ch, st, latency), pipes_(pipes), fuse_(fuse) {
    if (pipes_ < 1 || pipes_ > 16) throw std::invalid_argument("trv pipes must be 1..16");
    outs_.reserve(pipes_);
    reads_.reserve(pipes_);
    stage_.reserve(pipes_);
    next_stage_.reserve(pipes_);
  }

  // One cycle. First the outcome stage: the passes of two cycles before, in pipe order, each
  // with its node read's answer (a pass leaves the node's address, the read stage reads it in
  // the next cycle and the outcome follows from the word a cycle later: registered reads). A
  // pass's outcome is one of: back to the ready queue, done (to the hit unit), or a list step for
  // the next cycle's list stage. Then the list stage's effects of the cycle before (its hand-offs
  // to the ist, its rays back to the queue), the list stage (the list steps the outcomes asked for
  // in the cycle before, in pipe order, one list-cache access each: a list pass's own, or a node
  // pass's fused one after a leaf), the read stage (last cycle's passes read their nodes: they
  // share the node cache, one access per pipe and cycle; RayCore's L1s have two request ports for
  // its two traversal units), and each of the pipes takes the ray at the head of the ready queue
  // (pipe 0 first). So no access's address depends on a cache's answer, and only a list step's
  // room depends on the earlier steps' line presence.
  bool tick(Cycle now) {
    bool any = out_stage(now);
    any |= list_effects(now);
    any |= list_stage(now);
    any |= read_stage(now);
    for (uint32_t p = 0; p < pipes_ && step(now); ++p) any = true;
    stage_.swap(next_stage_);
    next_stage_.clear();
    stage_at_ = now + 1;
    return any;
  }

  Cycle next_event() const {
    Cycle t = ch_.trv_q.head_ready();
    if (!reads_.empty()) t = std::min(t, reads_at_);
    if (!outs_.empty()) t = std::min(t, outs_at_);
    if (!stage_.empty()) t = std::min(t, stage_at_);
    if (!requeues_.empty() || !handoffs_.empty()) t = std::min(t, effects_at_);
    return t;
  }

 private:
  // A pass's outcome, made in the cycle after the pass (at + 1): its node read's answer (node:
  // the word, or a miss), then at most one of a queue push, the finish or a list step.
  struct Out {
    uint16_t slot = 0;
    Cycle at = 0;            // the pass's cycle
    bool node = false;       // the pass read the node cache: the node step's outcome follows
    bool node_fused = false; //   in a pass already counted busy
    bool hit = false;        //   the line was there, with the node word
    uint64_t word = 0;
    bool push = false;       // back to the ready queue at ready
    Cycle ready = 0;
    bool fin = false;        // done: to the hit unit
    bool ask = false;        // a list step for this cycle's list stage, ready cycles from base
    bool ask_fused = false;
    Cycle base = 0;
  };

  bool step(Cycle now) {
    if (!ch_.trv_q.can_pop(now)) return false;
    const uint16_t s = ch_.trv_q.pop();
    reads_at_ = now + 1;  // the read stage ran (reads_ is empty) before the pipes
    reads_.push_back(Out{});
    Out& o = reads_.back();
    o.slot = s;
    o.at = now;
    Slot& r = ch_.slots[s];
    switch (r.state) {
      case SlotState::start: {
        r.best = Best{};
        r.sp = 0;
        r.mbox_n = r.mbox_head = 0;
        r.tmax = hls::t_key<F>(r.ray.tmax);  // a key (hls::KeyFormat), as the best record's t
        ++st_.trv_busy;
        if (fc_.empty_tree || !hls::trv_clip_box<A>(fc_.box_lo, fc_.box_hi, r.ray, r.tnear, r.tfar,
                                                             fc_.margins.widen_ulps))
          return finish(o, r);
        r.node = 0;
        r.state = SlotState::node;
        return push(o, now + lat_);
      }
      case SlotState::node:
        return node_step(o, false);
      case SlotState::list:
        return ask_list(o, 0, false);
      case SlotState::leaf_done: {
        ++st_.trv_busy;
        // Results of the leaf, reduced in list order: the closest, ties to the earliest entry.
        // Every test used the leaf-entry tmax (= best.t or the ray's tmax), so a leaf hit is
        // always closer than the best so far (the golden tracer's sequential tmax update).
        if (r.leaf.found) {
          r.best = r.leaf;
          r.tmax = r.leaf.t;
        }
        return leaf_end(o, r, 0, fuse_);
      }
      case SlotState::pop:
        ++st_.trv_busy;
        return pop(o, r, 0, fuse_);
      default:
        throw std::logic_error("trv: ray in an unexpected state");
    }
  }

  // The read stage: last cycle's passes in pipe order, each reading its node (if it has one to
  // read) from the address it left in the ray's record; their outcomes follow in the next cycle.
  bool read_stage(Cycle now) {
    if (reads_.empty()) return false;
    if (now != reads_at_) throw std::logic_error("trv: the read stage skipped its cycle");
    for (Out& o : reads_)
      if (o.node) node_read(o, ch_.slots[o.slot]);
    outs_.swap(reads_);  // the outcome stage ran: outs_ was empty
    reads_.clear();
    outs_at_ = now + 1;
    return true;
  }

  // Back to the ready queue: ready cycles count from the pass, but a ray pushed in cycle now
  // is taken in the next cycle at the earliest (the RTL's head window is refilled at the edge;
  // only --trv-latency 1 and 2 see it).
  void requeue(uint16_t s, Cycle ready, Cycle now) { ch_.trv_q.push(s, std::max<Cycle>(ready, now + 1)); }

  // The outcome stage: the passes of two cycles before in pipe order. A node read's outcome
  // first, then the pass's queue push (a ready cycle is at least the next cycle's: a pass's
  // outcome enters the queue at the end of this one), finish or list step (the next cycle's list
  // stage makes it).
  bool out_stage(Cycle now) {
    if (outs_.empty()) return false;
    if (now != outs_at_) throw std::logic_error("trv: the outcome stage skipped its cycle");
    for (Out& o : outs_) {
      Slot& r = ch_.slots[o.slot];
      if (o.node) node_outcome(o, r);
      if (o.fin)
        ch_.hit_q.push(o.slot, o.at + lat_);
      else if (o.push)
        requeue(o.slot, o.ready, now);
      else if (o.ask)
        next_stage_.push_back({o.slot, o.base, o.ask_fused});
    }
    outs_.clear();
    return true;
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

  // The steps below run in the pass (cycle o.at) or, after a node read, in its outcome; `extra`
  // is how far into a fused pass the step starts (the cycles of the accesses before it), `fused`
  // that the pass is already counted busy. A ray goes back to the ready queue o.at + extra + lat_
  // (+ the cache's hit latency after an access).
  bool push(Out& o, Cycle ready) {
    o.push = true;
    o.ready = ready;
    return true;
  }

  // The node step: the pass leaves the node's address in the ray's record, the read stage reads
  // it in the next cycle (the LRU, a miss and its MSHR at that cycle), the outcome stage makes
  // the rest from the word in the cycle after.
  bool node_step(Out& o, bool fused) {  // a node read is the pass's first access (extra 0)
    o.node = true;
    o.node_fused = fused;
    return true;
  }
  void node_read(Out& o, const Slot& r) {
    const uint32_t lb = ch_.node->line_bytes();
    const uint64_t byte = uint64_t(r.node) * 8;
    const uint8_t* line = ch_.node->access(byte / lb);
    o.hit = line != nullptr;
    if (line) o.word = hls::detail::get_le(line + byte % lb, 8);
  }

  void node_outcome(Out& o, Slot& r) {
    const Cycle again = o.at + lat_;
    if (!o.hit) {
      if (!o.node_fused) ++st_.trv_node_miss;
      push(o, again);
      return;
    }
    if (!o.node_fused) ++st_.trv_busy;
    const hls::Node nd = hls::decode_node(o.word);
    const uint32_t x = hit_lat(*ch_.node);
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
      push(o, next);
      return;
    }
    ++st_.leaf_visits;
    if (nd.split_or_count == 0) {  // one node access a pass
      leaf_end(o, r, x, false);
      return;
    }
    r.list_first = nd.index;
    r.list_count = nd.split_or_count;
    r.list_pos = 0;
    r.results = 0;
    r.leaf = Best{};
    r.state = SlotState::list;
    if (fuse_) {  // the leaf's first list line fused into the pass (read by the list stage)
      ++st_.trv_fused;
      ask_list(o, x, true);
      return;
    }
    push(o, next);
  }

  // A list step asked for by the pass at cycle o.at, `extra` into it: the list stage makes it a
  // cycle after the pass's outcome, its ready cycles counted from base = o.at + extra, at least
  // o.at + 1 (a push's ready cycle is at least the cycle after it: requeue).
  bool ask_list(Out& o, uint32_t extra, bool fused) {
    o.ask = true;
    o.ask_fused = fused;
    o.base = std::max<Cycle>(o.at + extra, o.at + 1);
    return true;
  }

  // The list stage: the steps the outcome stage asked for in the cycle before, in pipe order,
  // each with the ist queue's room as the steps before it left it (a step that misses takes none:
  // so a ray whose line is pinned for it is never kept from reading it by a step that cannot go
  // on). The room is the queue's at the cycle's start (RtuChannels::ist_room: the ist's pops of
  // this cycle make room from the next cycle on; the list stage's hand-offs of the cycle before
  // are in it). The stage's effects, the hand-offs to the ist and the rays back to the ready
  // queue, are made in the next cycle (list_effects), from registers in the RTL.
  bool list_stage(Cycle now) {
    if (stage_.empty()) return false;
    if (now != stage_at_) throw std::logic_error("trv: the list stage skipped its cycle");
    effects_at_ = now + 1;
    size_t taken = 0;  // the room the steps before took
    for (const Asked& a : stage_) taken += list_step(a.slot, ch_.slots[a.slot], a.base, a.fused, now, taken);
    stage_.clear();
    return true;
  }

  // Last cycle's list stage's effects, in its step order: the rays back to the ready queue (after
  // the outcomes' pushes) and the hand-offs to the ist.
  bool list_effects(Cycle now) {
    if (requeues_.empty() && handoffs_.empty()) return false;
    if (now != effects_at_) throw std::logic_error("trv: the list stage's effects skipped their cycle");
    for (const auto& q : requeues_) requeue(q.first, q.second, now);
    for (const auto& h : handoffs_) ch_.ist_q.push(h.first, h.second);
    requeues_.clear();
    handoffs_.clear();
    return true;
  }

  // One list step; returns the ist queue's room it took.
  size_t list_step(uint16_t s, Slot& r, Cycle base, bool fused, Cycle now, size_t taken) {
    const Cycle again = base + lat_;
    const uint32_t lb = ch_.list->line_bytes();
    const uint64_t byte = uint64_t(r.list_first + r.list_pos) * 4;
    const size_t all = ch_.ist_room(now);
    const size_t room = all > taken ? all - taken : 0;
    if (room == 0) {
      if (!fused) ++st_.trv_ist_full;
      requeues_.push_back({s, again});
      return 0;
    }
    const uint8_t* line = ch_.list->access(byte / lb);
    if (!line) {
      if (!fused) ++st_.trv_list_miss;
      requeues_.push_back({s, again});
      return 0;
    }
    if (!fused) ++st_.trv_busy;
    ++st_.list_steps;
    uint32_t n = std::min<uint32_t>(r.list_count - r.list_pos, uint32_t((lb - byte % lb) / 4));
    n = std::min<uint32_t>(n, uint32_t(room));
    const Cycle ready = base + 1 + hit_lat(*ch_.list);
    size_t pushed = 0;
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t tri = uint32_t(hls::detail::get_le(line + byte % lb + size_t(i) * 4, 4));
      if (fc_.mailbox != 0 && in_mailbox(r, tri)) {  // tested before: cannot win, counts as done
        ++st_.mailbox_skips;
        ++r.results;
        continue;
      }
      handoffs_.push_back({IstReq{s, r.list_pos + i, tri}, ready});
      ++pushed;
    }
    r.list_pos += n;
    if (r.list_pos == r.list_count && r.results == r.list_count) {
      r.state = SlotState::leaf_done;  // nothing left at the ist (the mailbox took the rest)
      requeues_.push_back({s, again + hit_lat(*ch_.list)});
    } else if (r.list_pos == r.list_count)
      r.state = SlotState::wait_ist;  // the ist re-queues the ray with its last result
    else
      requeues_.push_back({s, again + hit_lat(*ch_.list)});
    return pushed;
  }

  bool leaf_end(Out& o, Slot& r, uint32_t extra, bool fuse) {
    // A hit in this cell ends the walk; an any-hit shadow ray ends at its first leaf with a hit.
    if (r.best.found && ((r.shadow && fc_.spawn.any_hit) || !hls::key_lt<F>(hls::t_key<F>(r.tfar), r.best.t)))
      return finish(o, r);
    return pop(o, r, extra, fuse);
  }
  // One stack entry per step; entries beyond the best hit are skipped (one step each). With fuse
  // (a pass that has not read the node cache yet), the popped node is fetched in the same pass.
  bool pop(Out& o, Slot& r, uint32_t extra, bool fuse) {
    if (r.sp == 0) return finish(o, r);
    const Slot::Entry e = r.stack[size_t(--r.sp)];
    ++st_.pops;
    if (r.best.found && hls::key_lt<F>(r.best.t, hls::t_key<F>(e.tnear))) {
      r.state = SlotState::pop;
    } else {
      r.node = e.node;
      r.tnear = e.tnear;
      r.tfar = e.tfar;
      r.state = SlotState::node;
      if (fuse) {
        ++st_.trv_fused;
        return node_step(o, true);
      }
    }
    return push(o, o.at + extra + lat_);
  }
  bool finish(Out& o, Slot& r) {
    r.state = SlotState::done;
    o.fin = true;
    return true;
  }

  struct Asked {  // a list step for the list stage
    uint16_t slot;
    Cycle base;
    bool fused;
  };
  uint32_t pipes_;
  bool fuse_;
  std::vector<Out> reads_;   // the passes whose node reads are made in cycle reads_at_
  Cycle reads_at_ = 0;
  std::vector<Out> outs_;    // the passes whose outcomes are made in cycle outs_at_
  Cycle outs_at_ = 0;
  std::vector<Asked> stage_, next_stage_;  // this cycle's list steps; the next cycle's
  Cycle stage_at_ = 0;
  std::vector<std::pair<uint16_t, Cycle>> requeues_;  // the list stage's effects, made in cycle
  std::vector<std::pair<IstReq, Cycle>> handoffs_;    //   effects_at_
  Cycle effects_at_ = 0;
};

}  // namespace raycore::sc
