// The Clock of a replay: its time is the recorded time the replay has reached, set by whoever
// drives it. Capture-file ports given this clock deliver only what was recorded up to it, as
// live ports would, and the firmware's timers run on recorded time instead of the host's.
#pragma once

#include <cstdint>

#include "hal/ports.hpp"

namespace dpcr {

class ReplayClock : public Clock {
 public:
  explicit ReplayClock(std::int64_t start_us = 0) : now_us_(start_us) {}
  std::int64_t NowUs() const override { return now_us_; }
  // Moves to `stamp_us` if later: a monotonic clock never steps back.
  void AdvanceTo(std::int64_t stamp_us) {
    if (stamp_us > now_us_) now_us_ = stamp_us;
  }

 private:
  std::int64_t now_us_;
};

}  // namespace dpcr
