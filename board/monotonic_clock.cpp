#include "board/monotonic_clock.hpp"

#include <ctime>

namespace dpcr::board {

std::int64_t MonotonicClock::NowUs() const {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

}  // namespace dpcr::board
