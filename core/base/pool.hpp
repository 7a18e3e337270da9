// A fixed set of slots handed out through handles, with a free list (O(1) acquire/release).
// Overflow policy: Acquire on a full pool returns kPoolFull; nothing is evicted.
// Handles carry a generation so a handle to a released slot is detected (kStaleHandle).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/base/status.hpp"

namespace dpcr {

struct PoolHandle {
  std::uint16_t index = 0xFFFF;
  std::uint16_t generation = 0;
  bool valid() const { return index != 0xFFFF; }
  friend bool operator==(PoolHandle a, PoolHandle b) {
    return a.index == b.index && a.generation == b.generation;
  }
};

template <typename T, std::size_t N>
class Pool {
  static_assert(N > 0 && N < 0xFFFF, "pool capacity must fit a 16-bit index");

 public:
  Pool() { clear(); }

  static constexpr std::size_t capacity() { return N; }
  std::size_t size() const { return used_; }
  bool full() const { return used_ == N; }

  // Takes a free slot, reset to T(); kPoolFull when none is left.
  Result<PoolHandle> Acquire() {
    if (free_head_ == kNone) return Status::kPoolFull;
    const std::uint16_t i = free_head_;
    free_head_ = next_free_[i];
    next_free_[i] = kInUse;
    slots_[i] = T();
    ++used_;
    PoolHandle handle;
    handle.index = i;
    handle.generation = generation_[i];
    return handle;
  }

  Status Release(PoolHandle handle) {
    if (Get(handle) == nullptr) return Status::kStaleHandle;
    ++generation_[handle.index];
    next_free_[handle.index] = free_head_;
    free_head_ = handle.index;
    --used_;
    return Status::kOk;
  }

  // nullptr for an invalid or stale handle.
  T* Get(PoolHandle handle) {
    if (handle.index >= N || next_free_[handle.index] != kInUse ||
        generation_[handle.index] != handle.generation) {
      return nullptr;
    }
    return &slots_[handle.index];
  }
  const T* Get(PoolHandle handle) const { return const_cast<Pool*>(this)->Get(handle); }

  void clear() {
    for (std::size_t i = 0; i < N; ++i) {
      next_free_[i] = static_cast<std::uint16_t>(i + 1 < N ? i + 1 : kNone);
    }
    free_head_ = 0;
    used_ = 0;
  }

 private:
  static constexpr std::uint16_t kNone = 0xFFFF;
  static constexpr std::uint16_t kInUse = 0xFFFE;

  T slots_[N] = {};
  std::uint16_t next_free_[N] = {};
  std::uint16_t generation_[N] = {};
  std::uint16_t free_head_ = 0;
  std::size_t used_ = 0;
};

}  // namespace dpcr
