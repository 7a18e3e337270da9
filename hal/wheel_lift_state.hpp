// Whether the wheels were lifted at a given device time, from the status frames (0x122,
// docs/can-protocol.md). A status frame's state holds from its device time on, until the next
// frame's; the last two are kept, so a ticks frame taken just before a status frame that arrived
// ahead of it still gets the state of its own instant. A robot that never sends a status frame is
// never lifted; one whose status frames stop (the sender gone) counts as not lifted once the
// last is kStaleUs old, rather than lifted for ever (the rejection streak still finds a kidnap).
// Device times of different streams agree modulo the protocol's 24-bit wrap (each is unwrapped
// from its own first frame), so they are compared by that modular difference (within ±83 s).
#pragma once

#include <cstdint>

#include "hal/wheel_can_protocol.hpp"

namespace dpcr {

class WheelLiftState {
 public:
  // Ten periodic resends (10 Hz) missed.
  static constexpr std::int64_t kStaleUs = 1000000;

  void Observe(const RobotStatus& status);
  // The state at `device_time_us` (a ticks or gyro frame's unwrapped device time).
  bool LiftedAt(std::int64_t device_time_us) const;

 private:
  RobotStatus latest_;
  RobotStatus previous_;
  int observed_ = 0;  // 0, 1, 2 (capped): how many of latest_, previous_ hold a frame
};

// a - b for two unwrapped device times of different streams, in ±2^23 units of 10 us.
std::int64_t DeviceTimeDifferenceUs(std::int64_t a_us, std::int64_t b_us);

}  // namespace dpcr
