// A FIFO of fixed capacity (the odometry buffer's). Overflow policy: push on a full ring returns
// kCapacityExceeded; callers that want "drop the oldest" pop it first, so every removal is explicit.
#pragma once

#include <cstddef>

#include "core/base/assert.hpp"
#include "core/base/status.hpp"

namespace dpcr {

template <typename T, std::size_t N>
class RingBuffer {
  static_assert(N > 0, "a RingBuffer needs room for at least one element");

 public:
  std::size_t size() const { return size_; }
  static constexpr std::size_t capacity() { return N; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == N; }

  [[nodiscard]] Status push_back(const T& value) {
    if (size_ == N) return Status::kCapacityExceeded;
    data_[(head_ + size_) % N] = value;
    ++size_;
    return Status::kOk;
  }
  // Reserves the next slot and returns it for in-place filling (large elements, no copy).
  T* emplace_back() {
    if (size_ == N) return nullptr;
    T* slot = &data_[(head_ + size_) % N];
    ++size_;
    return slot;
  }
  void pop_front() {
    DPCR_ASSERT(size_ > 0);
    head_ = (head_ + 1) % N;
    --size_;
  }
  void clear() {
    head_ = 0;
    size_ = 0;
  }

  // Index 0 is the oldest element.
  T& operator[](std::size_t i) {
    DPCR_ASSERT(i < size_);
    return data_[(head_ + i) % N];
  }
  const T& operator[](std::size_t i) const {
    DPCR_ASSERT(i < size_);
    return data_[(head_ + i) % N];
  }
  T& front() { return (*this)[0]; }
  T& back() { return (*this)[size_ - 1]; }
  const T& front() const { return (*this)[0]; }
  const T& back() const { return (*this)[size_ - 1]; }

 private:
  T data_[N] = {};
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace dpcr
