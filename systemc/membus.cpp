// systemc/membus.cpp - see membus.h.
#include "systemc/membus.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace raycore::sc {

Membus::Membus(sc_core::sc_module_name name, const std::vector<uint8_t>& image, uint32_t latency,
               uint32_t bandwidth, uint32_t queue_depth, uint64_t seed)
    : sc_core::sc_module(name),
      mem_(image),
      latency_(latency),
      bandwidth_(bandwidth),
      depth_(queue_depth),
      rng_(seed) {
  if (bandwidth_ == 0) throw std::invalid_argument("membus: bandwidth must be >= 1 byte/cycle");
  if (depth_ == 0) throw std::invalid_argument("membus: queue depth must be >= 1");
  std::vector<Resp> storage;
  storage.reserve(depth_);
  resp_ = decltype(resp_)(std::greater<Resp>(), std::move(storage));
}

void Membus::add_requester(TimedFifo<MemReq>* req, MemClient* client, uint32_t port) {
  reqs_.push_back({req, client, port});
}

void Membus::set_l2(const L2Config& c) {
  l2_ = c;
  l2_lines_.clear();
  l2_sets_ = 0;
  if (c.size_bytes == 0) return;
  auto pow2 = [](uint64_t x) { return x != 0 && (x & (x - 1)) == 0; };
  if (!pow2(c.line_bytes) || c.line_bytes < 8) throw std::invalid_argument("L2: line bytes must be a power of two >= 8");
  if (c.ways == 0 || c.size_bytes % (c.line_bytes * c.ways) != 0)
    throw std::invalid_argument("L2: size must be a multiple of ways x line bytes");
  if (c.bandwidth == 0) throw std::invalid_argument("L2: bandwidth must be >= 1 byte/cycle");
  l2_sets_ = c.size_bytes / (c.line_bytes * c.ways);
  l2_lines_.assign(size_t(l2_sets_) * c.ways, L2Line{});
}

const Membus::L2Line* Membus::l2_find(uint64_t line) const {
  const size_t set = size_t(line % l2_sets_) * l2_.ways;
  for (uint32_t w = 0; w < l2_.ways; ++w)
    if (l2_lines_[set + w].valid && l2_lines_[set + w].tag == line) return &l2_lines_[set + w];
  return nullptr;
}
Membus::L2Line* Membus::l2_find(uint64_t line) {
  return const_cast<L2Line*>(static_cast<const Membus*>(this)->l2_find(line));
}

std::pair<uint64_t, uint64_t> Membus::l2_span(uint64_t addr, uint32_t bytes) const {
  const uint64_t lb = l2_.line_bytes;
  return {addr / lb, (addr + std::max<uint32_t>(bytes, 1) - 1) / lb};
}

bool Membus::l2_hit(uint64_t addr, uint32_t bytes, Cycle& ready) {
  ready = 0;
  const auto [first, last] = l2_span(addr, bytes);
  for (uint64_t l = first; l <= last; ++l) {
    const L2Line* x = l2_find(l);
    if (!x) return false;
    ready = std::max(ready, x->ready);
  }
  for (uint64_t l = first; l <= last; ++l) l2_find(l)->stamp = ++l2_clock_;  // LRU: used now
  return true;
}

bool Membus::l2_victims(uint64_t addr, uint32_t bytes, Cycle now, std::vector<L2Line*>& out) {
  out.clear();
  const auto [first, last] = l2_span(addr, bytes);
  for (uint64_t l = first; l <= last; ++l) {
    if (l2_find(l)) continue;
    const size_t set = size_t(l % l2_sets_) * l2_.ways;
    L2Line* x = nullptr;
    for (uint32_t w = 0; w < l2_.ways; ++w) {
      L2Line& c = l2_lines_[set + w];
      if (std::find(out.begin(), out.end(), &c) != out.end()) continue;  // taken by this request
      if (!c.valid) { x = &c; break; }
      if (c.ready > now || c.readers != 0) continue;
      if (!x || c.stamp < x->stamp) x = &c;
    }
    if (!x) return false;
    out.push_back(x);
  }
  return true;
}

void Membus::l2_install(uint64_t addr, uint32_t bytes, Cycle ready,
                        const std::vector<L2Line*>& victims) {
  const auto [first, last] = l2_span(addr, bytes);
  size_t v = 0;
  for (uint64_t l = first; l <= last; ++l) {
    L2Line* x = l2_find(l);
    if (!x) {
      x = victims.at(v++);
      x->valid = true;
      x->tag = l;
      x->ready = ready;
      x->readers = 0;
    } else {
      x->ready = std::min(x->ready, ready);
    }
    x->stamp = ++l2_clock_;
  }
}

uint32_t Membus::draw_latency() {
  if (rng_ == 0) return latency_;
  // splitmix64
  uint64_t z = (rng_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return latency_ + uint32_t(z % (uint64_t(latency_) + 1));
}

void Membus::copy_line(const MemReq& q) const {
  // The data: the image's bytes (zero past its end).
  const uint64_t end = std::min<uint64_t>(q.addr + q.bytes, mem_.size());
  const size_t have = q.addr < end ? size_t(end - q.addr) : 0;
  if (have) std::memcpy(q.data, mem_.data() + q.addr, have);
  if (have < q.bytes) std::memset(q.data + have, 0, q.bytes - have);
}

bool Membus::tick(Cycle now) {
  if (rtl_) return tick_rtl(now);
  bool active = false;
  // Responses whose last beat has arrived go to the requester's vtu port.
  while (!resp_.empty() && resp_.top().arrival <= now) {
    const Resp r = resp_.top();
    resp_.pop();
    if (r.dram) --dram_out_;
    else
      for (uint64_t l = r.l2_first; l <= r.l2_last; ++l) --l2_find(l)->readers;
    reqs_[r.requester].client->mem_resp(reqs_[r.requester].port, r.tag, now);
    active = true;
  }
  // Accept one request, round-robin.
  const size_t n = reqs_.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t i = (rr_ + k) % n;
    if (!reqs_[i].req->can_pop(now)) continue;
    const MemReq& front = reqs_[i].req->front();
    Cycle l2_ready = 0;
    if (l2_sets_ != 0 && l2_hit(front.addr, front.bytes, l2_ready)) {
      // Served by the L2: no memory queue place, no memory traffic.
      const MemReq q = reqs_[i].req->pop();
      copy_line(q);
      const Cycle beats = (q.bytes + l2_.bandwidth - 1) / l2_.bandwidth;
      const Cycle first = std::max({now + l2_.latency, l2_ready, l2_free_});
      const Cycle arrival = first + beats;
      l2_free_ = arrival;
      const auto [lf, ll] = l2_span(q.addr, q.bytes);
      for (uint64_t l = lf; l <= ll; ++l) ++l2_find(l)->readers;
      resp_.push({arrival, seq_++, uint32_t(i), q.tag, false, lf, ll});
      ++st_.l2_accesses;
      ++(l2_ready > now + l2_.latency ? st_.l2_merges : st_.l2_hits);
      st_.l2_bytes += q.bytes;
      st_.l2_busy_cycles += beats;
      rr_ = i + 1;
      return true;
    }
    if (dram_out_ >= depth_) {
      ++st_.queue_full_cycles;
      return true;
    }
    if (l2_sets_ != 0 && !l2_victims(front.addr, front.bytes, now, victims_)) {
      ++st_.l2_stall_cycles;
      return true;
    }
    const MemReq q = reqs_[i].req->pop();
    copy_line(q);
    const Cycle arrival = dram_accept(q.bytes, now).second;
    resp_.push({arrival, seq_++, uint32_t(i), q.tag, true});
    if (l2_sets_ != 0) {
      ++st_.l2_accesses;
      l2_install(q.addr, q.bytes, arrival, victims_);
    }
    rr_ = i + 1;
    return true;
  }
  return active;
}

std::pair<Cycle, Cycle> Membus::dram_accept(uint32_t bytes, Cycle now) {
  const Cycle beats = (bytes + bandwidth_ - 1) / bandwidth_;
  const Cycle first = std::max<Cycle>(now + draw_latency(), data_free_);
  const Cycle arrival = first + beats;
  data_free_ = arrival;
  ++dram_out_;
  ++st_.requests;
  st_.bytes += bytes;
  st_.busy_cycles += beats;
  st_.latency_sum += arrival - now;
  return {first, arrival};
}

Cycle Membus::next_event(Cycle now) const {
  if (rtl_) return next_event_rtl(now);
  Cycle t = resp_.empty() ? kNever : resp_.top().arrival;
  for (const auto& r : reqs_)
    if (!r.req->empty()) t = std::min(t, std::max(now + 1, r.req->head_ready()));
  return t;
}

// ---- RTL view ----------------------------------------------------------------------------------

void Membus::bind_rtl(std::unique_ptr<MembusRtl> rtl, uint64_t mshrs) {
  const std::string n = rtl->name();
  const L2Config b = rtl->l2();
  if (l2_sets_ != 0 || b.size_bytes != 0) {
    if (b.size_bytes != l2_.size_bytes || b.ways != l2_.ways || b.line_bytes != l2_.line_bytes ||
        b.bandwidth != l2_.bandwidth)
      throw ConfigError("--rtl membus: " + n + " is built for " +
                        (b.size_bytes ? "--l2-kb " + std::to_string(b.size_bytes / 1024) +
                                            " --l2-ways " + std::to_string(b.ways) +
                                            " --l2-bandwidth " + std::to_string(b.bandwidth) + " (" +
                                            std::to_string(b.line_bytes) + "-byte lines)"
                                      : std::string("--l2-kb 0")));
    if (mshrs > rtl->l2_queue())
      throw ConfigError("--rtl membus: " + n + " queues " + std::to_string(rtl->l2_queue()) +
                        " L2 responses, the caches have " + std::to_string(mshrs) + " MSHRs");
    if (l2_.latency > 65535) throw ConfigError("--rtl membus: --l2-latency up to 65535");
  }
  if (latency_ == 0)
    throw ConfigError("--rtl membus: membus_if takes a line's first beat a cycle after the request "
                      "at the earliest (--mem-latency >= 1)");
  if (reqs_.size() > rtl->ports())
    throw ConfigError("--rtl membus: " + n + " has " + std::to_string(rtl->ports()) +
                      " request ports, the frame has " + std::to_string(reqs_.size()) +
                      " requesters (3 per RTU)");
  if (depth_ != rtl->depth() || bandwidth_ != rtl->beat_bytes())
    throw ConfigError("--rtl membus: " + n + " is built for --mem-queue-depth " +
                      std::to_string(rtl->depth()) + " and --mem-bandwidth " +
                      std::to_string(rtl->beat_bytes()));
  rtl_ = std::move(rtl);
}

void Membus::rtl_done(const Resp& r) {
  auto at = done_.end();
  while (at != done_.begin() && *(at - 1) > r) --at;
  done_.insert(at, r);
}

bool Membus::tick_rtl(Cycle now) {
  bool active = false;
  // Lines whose last beat came back at the previous edge go to the requester's vtu port, in
  // (arrival, acceptance) order as the transaction model's.
  while (!done_.empty() && done_.front().arrival <= now) {
    const Resp r = done_.front();
    done_.pop_front();
    if (r.dram) --dram_out_;
    reqs_[r.requester].client->mem_resp(reqs_[r.requester].port, r.tag, now);
    active = true;
  }
  // The requests (the RTL arbitrates).
  bool any = false;
  for (size_t i = 0; i < reqs_.size(); ++i) {
    if (!reqs_[i].req->can_pop(now)) continue;
    const MemReq& f = reqs_[i].req->front();
    if (f.addr + f.bytes > (uint64_t(1) << 32) || f.bytes >= (1u << 12) || f.tag >= 256)
      throw std::runtime_error("--rtl membus: a request beyond membus_if's 32-bit addresses, "
                               "12-bit lengths or 8-bit tags");
    if (l2_sets_ != 0 && (f.bytes != l2_.line_bytes || f.addr % l2_.line_bytes != 0))
      throw ConfigError("--rtl membus: membus_l2 takes whole L2 lines (" +
                        std::to_string(l2_.line_bytes) + " bytes at a multiple of " +
                        std::to_string(l2_.line_bytes) + "); a cache asked for " +
                        std::to_string(f.bytes) + " bytes at " + std::to_string(f.addr) +
                        " (its lines must be the L2's)");
    rtl_->request(unsigned(i), true, uint32_t(f.addr), f.bytes, f.tag);
    any = true;
  }
  rtl_->l2_inputs(uint32_t(now), l2_.latency);
  // The memory: the next beat of the data bus, if this is its cycle.
  const uint8_t* beat = nullptr;
  if (drive_ < lines_.size()) {
    Line& l = lines_[drive_];
    const Cycle at = l.first + l.driven;
    if (at < now) throw std::logic_error("--rtl membus: a beat's cycle was skipped");
    if (at == now) {
      beat = l.bytes.data() + size_t(l.driven) * bandwidth_;
      if (++l.driven == l.beats) ++drive_;
    }
  }
  rtl_->beat(beat);
  const int g = rtl_->accept();
  if (g >= 0) {  // as tick(): the memory times the line
    const size_t i = size_t(g);
    if (i >= reqs_.size() || !reqs_[i].req->can_pop(now))
      throw std::logic_error("--rtl membus: the RTL granted requester " + std::to_string(g) +
                             ", which has no request");
    const MemReq q = reqs_[i].req->pop();
    if (l2_sets_ != 0) ++st_.l2_accesses;
    if (rtl_->hit()) {  // the L2's: the merge is the memory's knowledge of the lines in flight
      Cycle ready = 0;
      for (const Line& l : lines_)
        if (l.q.addr == q.addr) ready = l.arrival;
      ++(ready > now + l2_.latency ? st_.l2_merges : st_.l2_hits);
      st_.l2_bytes += q.bytes;
      st_.l2_busy_cycles += (q.bytes + l2_.bandwidth - 1) / l2_.bandwidth;
      l2_rsp_.push_back({uint32_t(i), q, seq_++});
    } else {
      const auto [first, arrival] = dram_accept(q.bytes, now);
      Line l{uint32_t(i), q, first, arrival, uint32_t(arrival - first), 0, 0, {}, seq_++};
      l.bytes.assign(size_t(l.beats) * bandwidth_, 0);
      MemReq staged = q;
      staged.data = l.bytes.data();
      copy_line(staged);
      lines_.push_back(std::move(l));
    }
    active = true;
  } else if (any && rtl_->stalled()) {
    ++st_.l2_stall_cycles;
    active = true;
  } else if (any && rtl_->full()) {
    ++st_.queue_full_cycles;
    active = true;
  }
  if (!any && !beat && !rtl_->l2_busy()) return active;
  const MembusRtl::Rsp r = rtl_->edge();
  if (beat) {  // its beat comes back routed, in the next cycle
    if (!r.valid || lines_.empty())
      throw std::logic_error("--rtl membus: a beat driven did not come back");
    Line& f = lines_.front();
    if (r.port != f.requester || r.tag != f.q.tag || r.beat != f.got)
      throw std::logic_error("--rtl membus: beat " + std::to_string(r.beat) + " of requester " +
                             std::to_string(r.port) + " (tag " + std::to_string(r.tag) +
                             ") came back; expected beat " + std::to_string(f.got) + " of " +
                             std::to_string(f.requester) + " (tag " + std::to_string(f.q.tag) +
                             ")");
    const uint32_t off = f.got * bandwidth_;
    std::memcpy(f.q.data + off, r.data, std::min<uint32_t>(bandwidth_, f.q.bytes - off));
    reqs_[f.requester].client->mem_beat(reqs_[f.requester].port, f.q.tag, f.got, r.last, r.data,
                                        bandwidth_, false, now + 1);
    ++f.got;
    if (r.last != (f.got == f.beats) || (r.last && now + 1 != f.arrival))
      throw std::logic_error("--rtl membus: the line's last beat came back in cycle " +
                             std::to_string(now + 1) + ", the memory's timing says " +
                             std::to_string(f.arrival));
    if (r.last) {
      rtl_done({f.arrival, f.seq, f.requester, f.q.tag, true});
      lines_.pop_front();
      --drive_;
    }
  } else if (r.valid) {
    throw std::logic_error("--rtl membus: a beat came back that the memory did not drive");
  }
  const MembusRtl::Rsp h = rtl_->l2_rsp();
  if (h.valid) {  // the L2's beat, seen by its requester in the next cycle
    if (l2_rsp_.empty()) throw std::logic_error("--rtl membus: an L2 beat with no L2 hit accepted");
    L2Rsp& f = l2_rsp_.front();
    if (h.port != f.requester || h.tag != f.q.tag || h.beat != f.got)
      throw std::logic_error("--rtl membus: L2 beat " + std::to_string(h.beat) + " of requester " +
                             std::to_string(h.port) + " (tag " + std::to_string(h.tag) +
                             ") came back; expected beat " + std::to_string(f.got) + " of " +
                             std::to_string(f.requester) + " (tag " + std::to_string(f.q.tag) +
                             ")");
    const uint32_t bw = l2_.bandwidth, off = f.got * bw;
    std::memcpy(f.q.data + off, h.data, std::min<uint32_t>(bw, f.q.bytes - off));
    reqs_[f.requester].client->mem_beat(reqs_[f.requester].port, f.q.tag, f.got, h.last, h.data,
                                        bw, true, now + 1);
    ++f.got;
    if (h.last != (f.got * bw >= f.q.bytes))
      throw std::logic_error("--rtl membus: the L2's last beat of a line came after " +
                             std::to_string(f.got) + " beats");
    if (h.last) {
      rtl_done({now + 1, f.seq, f.requester, f.q.tag, false});
      l2_rsp_.pop_front();
    }
  }
  return active;
}

Cycle Membus::next_event_rtl(Cycle now) const {
  Cycle t = done_.empty() ? kNever : done_.front().arrival;
  if (rtl_->l2_busy()) t = std::min(t, now + 1);  // the L2's responses move every cycle
  if (drive_ < lines_.size()) t = std::min(t, lines_[drive_].first + lines_[drive_].driven);
  for (const auto& r : reqs_)
    if (!r.req->empty()) t = std::min(t, std::max(now + 1, r.req->head_ready()));
  return t;
}

}  // namespace raycore::sc
