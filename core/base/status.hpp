// Error reporting without exceptions: every expected failure is a named Status.
#pragma once

#include <cstdint>

namespace dpcr {

enum class Status : std::uint8_t {
  kOk = 0,
  kCapacityExceeded,  // a fixed-capacity container is full
  kPoolFull,          // a pool (tiles, regions) has no free slot
  kInvalidArgument,
  kOutOfBounds,       // a coordinate outside a bounded grid
  kNotFound,
  kStaleHandle,       // a pool handle whose slot was released or reused
  kNotEnoughData,     // too few points/correspondences to decide
  kRejected,          // a registration failed its acceptance test
};

// A short stable name for logs and metrics ("pool_full").
const char* ToString(Status status);

// A value or the reason there is none. T must be default-constructible.
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(const T& value) : value_(value), status_(Status::kOk) {}  // NOLINT: implicit by design
  Result(Status status) : value_(), status_(status) {}             // NOLINT: implicit by design

  bool ok() const { return status_ == Status::kOk; }
  Status status() const { return status_; }
  const T& value() const { return value_; }
  T& value() { return value_; }

 private:
  T value_;
  Status status_;
};

}  // namespace dpcr
