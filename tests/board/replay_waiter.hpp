// The firmware loop's wait on recorded streams: each Wait moves a replay clock to the next
// recorded byte or frame (or by the timeout, when none is due sooner) and says which port has
// it; at `stop_at_us` it reports a stop request. No sleeps, no threads: a run of minutes takes
// the time its mapping takes.
#pragma once

#include <cstdint>
#include <functional>

#include "hal/ports.hpp"
#include "host_sim/drivers/replay_clock.hpp"

namespace dpcr::test {

class ReplayWaiter : public PortWaiter {
 public:
  using NextStamp = std::function<std::int64_t()>;  // INT64_MAX: nothing more
  ReplayWaiter(ReplayClock* clock, NextStamp lidar, NextStamp can, std::int64_t stop_at_us)
      : clock_(clock), lidar_(std::move(lidar)), can_(std::move(can)), stop_at_us_(stop_at_us) {}

  PortEvents Wait(std::int64_t timeout_us) override {
    ++waits;
    PortEvents e;
    const std::int64_t now = clock_->NowUs();
    if (now >= stop_at_us_) {
      e.stop = true;
      return e;
    }
    const std::int64_t lidar = lidar_();
    const std::int64_t can = can_();
    const std::int64_t next = lidar < can ? lidar : can;
    std::int64_t until = now + timeout_us;
    if (until > stop_at_us_) until = stop_at_us_;
    if (next <= until) {
      clock_->AdvanceTo(next);
      e.lidar = lidar <= next;
      e.can = can <= next;
    } else {
      clock_->AdvanceTo(until);
    }
    return e;
  }
  std::uint64_t waits = 0;

 private:
  ReplayClock* clock_;
  NextStamp lidar_;
  NextStamp can_;
  std::int64_t stop_at_us_;
};

}  // namespace dpcr::test
