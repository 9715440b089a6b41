// A first-in first-out queue of fixed capacity, storage placed at construction: the request queue
// of every parameter channel's master side (the VF1000 communication-word client, the MC6000
// driver's PCP requests), the CANLust outboxes of frames. push, pop, clear and the accessors
// allocate nothing and throw nothing; the index wraps without a division.
#pragma once

#include <cstddef>
#include <vector>

namespace ibs {

template <typename T>
class BoundedQueue {
 public:
  explicit BoundedQueue(std::size_t capacity) : items_(capacity), capacity_(capacity) {}

  // Appends `v`; false, and nothing changed, when the queue is full.
  bool push(const T& v) noexcept {
    if (full()) return false;
    items_[slot(count_)] = v;
    ++count_;
    return true;
  }
  // The oldest entry; the queue must not be empty.
  [[nodiscard]] T& front() noexcept { return items_[head_]; }
  [[nodiscard]] const T& front() const noexcept { return items_[head_]; }
  // Drops the oldest entry (nothing when empty).
  void pop() noexcept {
    if (count_ == 0) return;
    head_ = slot(1);
    --count_;
  }
  // Drops every entry.
  void clear() noexcept {
    head_ = 0;
    count_ = 0;
  }
  // The i-th entry from the front (i < size()).
  [[nodiscard]] const T& operator[](std::size_t i) const noexcept { return items_[slot(i)]; }

  [[nodiscard]] std::size_t size() const noexcept { return count_; }
  [[nodiscard]] bool empty() const noexcept { return count_ == 0; }
  [[nodiscard]] bool full() const noexcept { return count_ == capacity_; }
  [[nodiscard]] std::size_t capacity() const noexcept { return capacity_; }

 private:
  [[nodiscard]] std::size_t slot(std::size_t i) const noexcept {
    const std::size_t s = head_ + i;
    return s >= capacity_ ? s - capacity_ : s;
  }

  std::vector<T> items_;
  // items_.size(), kept: the vector's size is a division of its ends by sizeof(T) (issue 26:
  // every push and pop of a CANLust frame asked for it).
  std::size_t capacity_;
  std::size_t head_ = 0;
  std::size_t count_ = 0;
};

}  // namespace ibs
