// systemc/membus.cpp - see membus.h.
#include "systemc/membus.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

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

void Membus::l2_install(uint64_t addr, uint32_t bytes, Cycle ready) {
  const auto [first, last] = l2_span(addr, bytes);
  for (uint64_t l = first; l <= last; ++l) {
    L2Line* x = l2_find(l);
    if (!x) {  // the set's invalid way, else its least recently used
      const size_t set = size_t(l % l2_sets_) * l2_.ways;
      x = &l2_lines_[set];
      for (uint32_t w = 0; w < l2_.ways; ++w) {
        L2Line& c = l2_lines_[set + w];
        if (!c.valid) { x = &c; break; }
        if (c.stamp < x->stamp) x = &c;
      }
      x->valid = true;
      x->tag = l;
      x->ready = ready;
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
  bool active = false;
  // Responses whose last beat has arrived go to the requester's vtu port.
  while (!resp_.empty() && resp_.top().arrival <= now) {
    const Resp r = resp_.top();
    resp_.pop();
    if (r.dram) --dram_out_;
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
      resp_.push({arrival, seq_++, uint32_t(i), q.tag, false});
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
    const MemReq q = reqs_[i].req->pop();
    copy_line(q);
    const Cycle beats = (q.bytes + bandwidth_ - 1) / bandwidth_;
    const Cycle first = std::max<Cycle>(now + draw_latency(), data_free_);
    const Cycle arrival = first + beats;
    data_free_ = arrival;
    resp_.push({arrival, seq_++, uint32_t(i), q.tag, true});
    ++dram_out_;
    if (l2_sets_ != 0) {
      ++st_.l2_accesses;
      l2_install(q.addr, q.bytes, arrival);
    }
    ++st_.requests;
    st_.bytes += q.bytes;
    st_.busy_cycles += beats;
    st_.latency_sum += arrival - now;
    rr_ = i + 1;
    return true;
  }
  return active;
}

Cycle Membus::next_event(Cycle now) const {
  Cycle t = resp_.empty() ? kNever : resp_.top().arrival;
  for (const auto& r : reqs_)
    if (!r.req->empty()) t = std::min(t, std::max(now + 1, r.req->head_ready()));
  return t;
}

}  // namespace raycore::sc
