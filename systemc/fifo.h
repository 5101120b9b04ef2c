// systemc/fifo.h - the registered channel between units: a bounded FIFO whose entries become
// visible to the consumer at a given cycle (ready = cycle pushed + the producer's latency >= 1).
// valid/ready of a handshake map to can_pop(now) / can_push(); the payload struct's field names are
// the port names of the Verilated twin (without the _i/_o suffix). Storage is allocated once.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace raycore::sc {

using Cycle = uint64_t;
constexpr Cycle kNever = ~Cycle(0);

template <class T>
class TimedFifo {
 public:
  explicit TimedFifo(size_t capacity = 1) { reset(capacity); }
  void reset(size_t capacity) {
    if (capacity == 0) throw std::invalid_argument("TimedFifo: capacity 0");
    buf_.assign(capacity, Entry{});
    head_ = size_ = 0;
    cap_ = capacity;
  }
  // Lowers the capacity to n (at most the storage's): a channel that stands for the room left in
  // a queue held elsewhere (the ist's queue in RTL, systemc/ist_rtl.h).
  void limit(size_t n) {
    if (n > buf_.size() || n < size_) throw std::logic_error("TimedFifo: limit out of range");
    cap_ = n;
  }
  size_t size() const { return size_; }
  size_t capacity() const { return cap_; }
  bool empty() const { return size_ == 0; }
  bool can_push() const { return size_ < cap_; }  // ready
  bool can_pop(Cycle now) const { return size_ != 0 && buf_[head_].ready <= now; }  // valid
  Cycle head_ready() const { return size_ ? buf_[head_].ready : kNever; }
  void push(const T& v, Cycle ready) {
    if (!can_push()) throw std::logic_error("TimedFifo: push on a full channel");
    size_t i = head_ + size_;
    if (i >= buf_.size()) i -= buf_.size();
    buf_[i] = Entry{v, ready};
    ++size_;
  }
  const T& front() const { return buf_[head_].v; }
  T pop() {
    T v = buf_[head_].v;
    if (++head_ == buf_.size()) head_ = 0;
    --size_;
    return v;
  }

 private:
  struct Entry {
    T v{};
    Cycle ready = 0;
  };
  std::vector<Entry> buf_;
  size_t head_ = 0, size_ = 0, cap_ = 1;
};

}  // namespace raycore::sc
