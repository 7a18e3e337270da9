// WheelLiftState: a status frame's state from its device time on, the one before it for earlier
// frames, nothing known before the first, stale after kStaleUs, across the 24-bit wrap.
#include <catch2/catch.hpp>

#include "hal/wheel_lift_state.hpp"

using dpcr::RobotStatus;
using dpcr::WheelLiftState;

namespace {
RobotStatus At(std::int64_t device_time_us, bool lifted) {
  RobotStatus s;
  s.device_time_us = device_time_us;
  s.lifted = lifted;
  return s;
}
}  // namespace

TEST_CASE("lift state: never lifted without a status frame") {
  const WheelLiftState lift;
  CHECK_FALSE(lift.LiftedAt(0));
  CHECK_FALSE(lift.LiftedAt(123456789));
}

TEST_CASE("lift state: a status holds from its device time on, earlier frames get the state before it") {
  WheelLiftState lift;
  lift.Observe(At(1000000, true));
  CHECK_FALSE(lift.LiftedAt(999990));  // before the first status: nothing known, not lifted
  CHECK(lift.LiftedAt(1000000));
  CHECK(lift.LiftedAt(1500000));
  lift.Observe(At(2000000, false));
  CHECK(lift.LiftedAt(1999990));  // a ticks frame taken before the put-down, arriving after it
  CHECK_FALSE(lift.LiftedAt(2000000));
  CHECK_FALSE(lift.LiftedAt(2500000));
}

TEST_CASE("lift state: a lifted status older than kStaleUs no longer counts (the sender gone)") {
  WheelLiftState lift;
  lift.Observe(At(5000000, true));
  CHECK(lift.LiftedAt(5000000 + WheelLiftState::kStaleUs));
  CHECK_FALSE(lift.LiftedAt(5000000 + WheelLiftState::kStaleUs + 10));
  lift.Observe(At(9000000, true));  // it speaks again
  CHECK(lift.LiftedAt(9000000));
  CHECK_FALSE(lift.LiftedAt(8999990));  // the state before it had gone stale
}

TEST_CASE("lift state: device times of streams unwrapped from different first frames compare modulo the wrap") {
  const std::int64_t wrap_us = dpcr::kWheelTimeWrapUnits * dpcr::kWheelTimeUnitUs;
  CHECK(dpcr::DeviceTimeDifferenceUs(wrap_us + 50, 40) == 10);
  CHECK(dpcr::DeviceTimeDifferenceUs(40, wrap_us + 50) == -10);
  CHECK(dpcr::DeviceTimeDifferenceUs(3 * wrap_us + 1000, 2 * wrap_us + 3000) == -2000);
  WheelLiftState lift;
  // The status stream started after the ticks stream had wrapped once: its times are a wrap lower.
  lift.Observe(At(500000, true));
  CHECK(lift.LiftedAt(wrap_us + 500000));
  CHECK(lift.LiftedAt(wrap_us + 600000));
  CHECK_FALSE(lift.LiftedAt(wrap_us + 400000));
}
