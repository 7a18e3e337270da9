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
  kNotEnoughData,     // too few points/correspondences to decide
  kRejected,          // a registration failed its acceptance test
};

// A short stable name for logs and metrics ("pool_full").
const char* ToString(Status status);

}  // namespace dpcr
