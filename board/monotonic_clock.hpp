// The board's Clock port: CLOCK_MONOTONIC (never steps back when the wall clock is set).
#pragma once

#include <cstdint>

#include "hal/ports.hpp"

namespace dpcr::board {

class MonotonicClock : public Clock {
 public:
  std::int64_t NowUs() const override;
};

}  // namespace dpcr::board
