// systemc/ascache.cpp - see ascache.h.
#include "systemc/ascache.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

namespace raycore::sc {

Ascache::Ascache(sc_core::sc_module_name name, const CacheConfig& cfg, uint64_t base,
                 uint32_t line_bytes)
    : sc_core::sc_module(name), line_(line_bytes), ways_(cfg.ways), base_(base) {
  if (line_ == 0 || ways_ == 0 || cfg.mshrs == 0)
    throw std::invalid_argument(std::string(this->name()) + ": line, ways and MSHRs must be >= 1");
  sets_ = std::max<uint32_t>(1, cfg.size_bytes / (line_ * ways_));
  tag_.assign(size_t(sets_) * ways_, 0);
  stamp_.assign(size_t(sets_) * ways_, 0);
  pin_.assign(size_t(sets_) * ways_, 0);
  data_.assign(size_t(sets_) * ways_ * line_, 0);
  hit_latency = cfg.hit_latency;
  mshr_.resize(cfg.mshrs);
  for (auto& m : mshr_) m.buf.assign(line_, 0);
  req_.reset(cfg.mshrs);
}

bool Ascache::present(uint64_t line) {
  settle();
  if (rtl_) throw std::logic_error(std::string(name()) + ": present() with the RTL bound");
  const size_t set = size_t(line % sets_) * ways_;
  for (uint32_t w = 0; w < ways_; ++w)
    if (tag_[set + w] == line + 1) return true;
  return false;
}

const uint8_t* Ascache::access(uint64_t line) {
  settle();
  accessed_ = now;
  ++probe_now().accesses;
  if (rtl_) return access_rtl(line);
  ++st_.accesses;
  const size_t set = size_t(line % sets_) * ways_;
  for (uint32_t w = 0; w < ways_; ++w)
    if (tag_[set + w] == line + 1) {
      ++st_.hits;
      ++probe_.hits;
      stamp_[set + w] = ++clock_;
      pin_[set + w] = 0;
      return data_.data() + (set + w) * line_;
    }
  ++st_.misses;
  ++st_.cycles_lost;
  for (const auto& m : mshr_)
    if (m.valid && m.line == line) {
      ++st_.mshr_merges;
      return nullptr;
    }
  if (busy_ == mshr_.size()) {
    ++st_.mshr_full;
    return nullptr;
  }
  if (set_full(line)) {
    ++st_.set_full;
    return nullptr;
  }
  allocate(line);
  return nullptr;
}

bool Ascache::set_full(uint64_t line) const {
  const uint64_t s = line % sets_;
  uint32_t n = 0;
  for (uint32_t w = 0; w < ways_; ++w) n += pin_[size_t(s) * ways_ + w];
  for (const auto& m : mshr_) n += m.valid && m.line % sets_ == s;
  return n >= ways_;
}

uint32_t Ascache::allocate(uint64_t line) {
  for (uint32_t i = 0; i < mshr_.size(); ++i)
    if (!mshr_[i].valid) {
      mshr_[i].valid = true;
      mshr_[i].line = line;
      ++busy_;
      req_.push({base_ + line * line_, line_, i, mshr_[i].buf.data()}, now + 1);
      return i;
    }
  throw std::logic_error(std::string(name()) + ": no free MSHR");
}

void Ascache::fill(uint32_t tag) {
  settle();
  if (tag >= mshr_.size() || !mshr_[tag].valid)
    throw std::logic_error(std::string(name()) + ": fill of a free MSHR");
  if (pend_.valid)
    throw std::logic_error(std::string(name()) + ": a second fill in cycle " + std::to_string(now) +
                           " (the cache has one fill port)");
  if (accessed_ == now)
    throw std::logic_error(std::string(name()) + ": a fill after an access in cycle " +
                           std::to_string(now) + " (the cycle's fill comes first: its victim is "
                           "chosen from the state at the cycle's start)");
  ++probe_now().fills;
  ++st_.fills;
  pend_ = Pending{true, now, tag, SIZE_MAX};
  if (rtl_) {
    rtl_->at(now);  // a new cycle: the RTL's edge closing the last one
    sync_pops();
    rtl_->fill(tag, mshr_[tag].buf.data());
    return;
  }
  // The victim: the first invalid way, else the least recently used way that is not pinned (there
  // is one: a miss takes an MSHR only while pinned + awaited < ways in its set, and this fill's
  // MSHR is one of the awaited).
  const Mshr& m = mshr_[tag];
  const size_t set = size_t(m.line % sets_) * ways_;
  size_t victim = SIZE_MAX;
  for (uint32_t w = 0; w < ways_; ++w) {
    if (tag_[set + w] == 0) {
      victim = set + w;
      break;
    }
    if (!pin_[set + w] && (victim == SIZE_MAX || stamp_[set + w] < stamp_[victim])) victim = set + w;
  }
  if (victim == SIZE_MAX)
    throw std::logic_error(std::string(name()) + ": fill of line " + std::to_string(m.line) +
                           " into a set whose every way is pinned");
  pend_.victim = victim;
}

// The fill of an earlier cycle, at that cycle's closing edge: its line in the victim way, pinned,
// and its MSHR free. Its LRU stamp stays the victim's: a pinned way is no victim, and its first
// hit makes it the most recent (the others' order is the same whatever its stamp was), as
// ascache.v, which leaves the ranks.
void Ascache::install() {
  Mshr& m = mshr_[pend_.tag];
  if (pend_.victim != SIZE_MAX) {
    tag_[pend_.victim] = m.line + 1;
    pin_[pend_.victim] = 1;
    std::memcpy(data_.data() + pend_.victim * line_, m.buf.data(), line_);
  }
  m.valid = false;
  --busy_;
  pend_.valid = false;
}

const CacheStats& Ascache::stats() const {
  if (rtl_) rtl_->check(st_.hits, st_.misses, st_.mshr_merges, st_.mshr_full, st_.set_full, st_.fills);
  return st_;
}

void Ascache::sync_pops() {
  while (queued_.size() > req_.size()) {  // the bus took the oldest requests
    rtl_->pop(queued_.front().first, queued_.front().second);
    queued_.pop_front();
  }
}

// The RTL decides; the MSHR bookkeeping here must agree with it (the same rules as access()).
const uint8_t* Ascache::access_rtl(uint64_t line) {
  rtl_->at(now);  // a new cycle: the RTL's edge closing the last one
  sync_pops();
  ++st_.accesses;
  const uint8_t* data = nullptr;
  const AscacheRtl::Kind kind = rtl_->access(line, &data);
  if (kind == AscacheRtl::Kind::hit) {
    ++st_.hits;
    ++probe_.hits;
    return data;
  }
  ++st_.misses;
  ++st_.cycles_lost;
  bool inflight = false;
  for (const auto& m : mshr_) inflight |= m.valid && m.line == line;
  const bool full = busy_ == mshr_.size();
  auto differs = [&](const char* rtl_says) {
    return std::logic_error(std::string(name()) + ": the RTL answers line " +
                            std::to_string(line) + " with " + rtl_says + ", but " +
                            (inflight ? "an MSHR fetches it" : full ? "every MSHR is busy"
                                                                    : "an MSHR is free"));
  };
  if (kind == AscacheRtl::Kind::merge) {
    if (!inflight) throw differs("a merge");
    ++st_.mshr_merges;
  } else if (kind == AscacheRtl::Kind::full) {
    if (inflight || !full) throw differs("MSHRs full");
    ++st_.mshr_full;
  } else if (kind == AscacheRtl::Kind::set_full) {  // its set's ways pinned or awaited (the RTL's)
    if (inflight || full) throw differs("set full");
    ++st_.set_full;
  } else {
    if (inflight || full) throw differs("a new MSHR");
    // The lowest free one, as the RTL's (checked when the bus takes the request).
    queued_.emplace_back(line, allocate(line));
  }
  return nullptr;
}

}  // namespace raycore::sc
