// A vector with its capacity fixed at compile time and its storage inside the object.
// Overflow policy: push_back on a full vector returns kCapacityExceeded and changes nothing.
#pragma once

#include <cstddef>

#include "core/base/assert.hpp"
#include "core/base/span.hpp"
#include "core/base/status.hpp"

namespace dpcr {

template <typename T, std::size_t N>
class StaticVector {
  static_assert(N > 0, "a StaticVector needs room for at least one element");

 public:
  static constexpr std::size_t kCapacity = N;

  std::size_t size() const { return size_; }
  static constexpr std::size_t capacity() { return N; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == N; }
  std::size_t available() const { return N - size_; }

  [[nodiscard]] Status push_back(const T& value) {
    if (size_ == N) return Status::kCapacityExceeded;
    data_[size_++] = value;
    return Status::kOk;
  }
  void pop_back() {
    DPCR_ASSERT(size_ > 0);
    --size_;
  }
  void clear() { size_ = 0; }
  // Shrinks, or grows with default values; false (and no change) past the capacity.
  [[nodiscard]] Status resize(std::size_t n) {
    if (n > N) return Status::kCapacityExceeded;
    for (std::size_t i = size_; i < n; ++i) data_[i] = T();
    size_ = n;
    return Status::kOk;
  }

  T& operator[](std::size_t i) {
    DPCR_ASSERT(i < size_);
    return data_[i];
  }
  const T& operator[](std::size_t i) const {
    DPCR_ASSERT(i < size_);
    return data_[i];
  }
  T& back() { return (*this)[size_ - 1]; }
  const T& back() const { return (*this)[size_ - 1]; }

  T* begin() { return data_; }
  T* end() { return data_ + size_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }
  T* data() { return data_; }
  const T* data() const { return data_; }

  Span<T> span() { return Span<T>(data_, size_); }
  Span<const T> span() const { return Span<const T>(data_, size_); }

 private:
  T data_[N] = {};
  std::size_t size_ = 0;
};

}  // namespace dpcr
