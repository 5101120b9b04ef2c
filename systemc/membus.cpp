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

uint32_t Membus::draw_latency() {
  if (rng_ == 0) return latency_;
  // splitmix64
  uint64_t z = (rng_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return latency_ + uint32_t(z % (uint64_t(latency_) + 1));
}

bool Membus::tick(Cycle now) {
  bool active = false;
  // Responses whose last beat has arrived go to the requester's vtu port.
  while (!resp_.empty() && resp_.top().arrival <= now) {
    const Resp r = resp_.top();
    resp_.pop();
    reqs_[r.requester].client->mem_resp(reqs_[r.requester].port, r.tag, now);
    active = true;
  }
  // Accept one request, round-robin.
  const size_t n = reqs_.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t i = (rr_ + k) % n;
    if (!reqs_[i].req->can_pop(now)) continue;
    if (resp_.size() >= depth_) {
      ++st_.queue_full_cycles;
      return true;
    }
    const MemReq q = reqs_[i].req->pop();
    // The data: the image's bytes (zero past its end).
    const uint64_t end = std::min<uint64_t>(q.addr + q.bytes, mem_.size());
    const size_t have = q.addr < end ? size_t(end - q.addr) : 0;
    if (have) std::memcpy(q.data, mem_.data() + q.addr, have);
    if (have < q.bytes) std::memset(q.data + have, 0, q.bytes - have);
    const Cycle beats = (q.bytes + bandwidth_ - 1) / bandwidth_;
    const Cycle first = std::max<Cycle>(now + draw_latency(), data_free_);
    const Cycle arrival = first + beats;
    data_free_ = arrival;
    resp_.push({arrival, seq_++, uint32_t(i), q.tag});
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
