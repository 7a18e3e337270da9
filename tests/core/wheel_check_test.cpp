// WheelCheck: wheels that miss the motion the lidar registers (ticks made of an IMU's yaw, a dead
// encoder) are set aside window after window; wheels that agree, a robot standing still and
// scans that were not tracked never switch anything.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/front_end/wheel_check.hpp"

namespace {

using dpcr::OdometrySample;
using dpcr::Pose2;
using dpcr::WheelCheck;

// What the wheels report for a true pose.
enum class Wheels { kTrue, kHeadingOnly, kDead };

OdometrySample WheelSample(std::int64_t stamp_us, const Pose2& truth, Wheels wheels) {
  OdometrySample s;
  s.stamp_us = stamp_us;
  if (wheels == Wheels::kTrue) s.pose = truth;
  if (wheels == Wheels::kHeadingOnly) s.pose = Pose2{0.0f, 0.0f, truth.theta};
  return s;
}

// A robot driving at 0.25 m/s along a gentle curve (0.3 rad/s) for `seconds`, a scan every 0.1 s
// registered at the true pose, 10 wheel samples per scan. Returns the final true pose.
Pose2 Drive(WheelCheck* check, Wheels wheels, float seconds, Pose2 start = Pose2::Identity(), std::int64_t t0_us = 0) {
  Pose2 p = start;
  const int scans = static_cast<int>(seconds * 10.0f);
  for (int i = 1; i <= scans; ++i) {
    const Pose2 before = p;
    for (int k = 1; k <= 10; ++k) {
      p = p * Pose2{0.0025f, 0.0f, 0.003f};
      check->AddOdometry(WheelSample(t0_us + (i - 1) * 100000 + k * 10000, p, wheels));
    }
    check->AddScan(dpcr::Between(before, p), WheelSample(0, p, wheels).pose, t0_us + i * 100000, true);
  }
  return p;
}

// Stuck after driving to `at` (5 s in): for up to 6 s the wheels drive on at 0.25 m/s while every
// scan registers the same pose, until the wheels are set aside. Every `poor_every`-th registration
// does not fit cleanly (0: all do).
void StandStuck(WheelCheck* check, const Pose2& at, int poor_every) {
  REQUIRE_FALSE(check->translation_doubted());
  Pose2 wheels = at;
  for (int i = 1; i <= 60 && !check->translation_ignored(); ++i) {
    for (int k = 1; k <= 10; ++k) {
      wheels = wheels * Pose2{0.0025f, 0.0f, 0.0f};
      check->AddOdometry(WheelSample(5000000 + (i - 1) * 100000 + k * 10000, wheels, Wheels::kTrue));
    }
    check->AddScan(Pose2::Identity(), wheels, 5000000 + i * 100000, true, poor_every == 0 || i % poor_every != 0);
  }
}

}  // namespace

TEST_CASE("WheelCheck: wheels that measure the motion are kept") {
  WheelCheck check;
  (void)Drive(&check, Wheels::kTrue, 60.0f);
  CHECK_FALSE(check.translation_ignored());
  CHECK(check.translation_misses() == 0);
  CHECK(check.heading_used());
  const OdometrySample in = WheelSample(1, Pose2{1.0f, 2.0f, 0.5f}, Wheels::kTrue);
  const OdometrySample out = check.Filter(in);
  CHECK(out.has_wheels);
  CHECK(out.pose.x == in.pose.x);
  CHECK_FALSE(out.has_gyro);
}

TEST_CASE("WheelCheck: ticks that carry only the heading become a heading source") {
  WheelCheck check;
  // Three windows of 0.3 m each: about 3.6 s at 0.25 m/s.
  (void)Drive(&check, Wheels::kHeadingOnly, 2.0f);
  CHECK_FALSE(check.translation_ignored());
  (void)Drive(&check, Wheels::kHeadingOnly, 3.0f, Pose2::Identity(), 2000000);
  REQUIRE(check.translation_ignored());
  CHECK(check.translation_switched_off() == 1);
  CHECK(check.heading_used());  // the turns agree (0.3 rad/s for 5 s)
  // A filtered sample: no wheels, the wheels' turn rate as a gyro rate.
  check.AddOdometry(WheelSample(5010000, Pose2{0.0f, 0.0f, 1.0f}, Wheels::kHeadingOnly));
  check.AddOdometry(WheelSample(5020000, Pose2{0.0f, 0.0f, 1.005f}, Wheels::kHeadingOnly));
  const OdometrySample out = check.Filter(WheelSample(5020000, Pose2{0.0f, 0.0f, 1.005f}, Wheels::kHeadingOnly));
  CHECK_FALSE(out.has_wheels);
  CHECK(out.has_gyro);
  CHECK(out.gyro_yaw_rate == Approx(0.5f).epsilon(0.01));
  CHECK(out.pose.theta == 1.005f);  // kept: the check reads the wheels' pose back from the buffer
}

TEST_CASE("WheelCheck: a real gyro's rate is kept when the wheels' translation is set aside") {
  WheelCheck check;
  (void)Drive(&check, Wheels::kHeadingOnly, 6.0f);
  REQUIRE(check.translation_ignored());
  OdometrySample in = WheelSample(7000000, Pose2{0.0f, 0.0f, 2.0f}, Wheels::kHeadingOnly);
  in.has_gyro = true;
  in.gyro_yaw_rate = -0.25f;
  const OdometrySample out = check.Filter(in);
  CHECK_FALSE(out.has_wheels);
  CHECK(out.has_gyro);
  CHECK(out.gyro_yaw_rate == -0.25f);
}

TEST_CASE("WheelCheck: dead encoders give neither translation nor heading") {
  WheelCheck check;
  (void)Drive(&check, Wheels::kDead, 10.0f);
  REQUIRE(check.translation_ignored());
  CHECK_FALSE(check.heading_used());
  const OdometrySample out = check.Filter(WheelSample(1, Pose2::Identity(), Wheels::kDead));
  CHECK_FALSE(out.has_wheels);
  CHECK_FALSE(out.has_gyro);
}

TEST_CASE("WheelCheck: wheels that agree again are taken back") {
  WheelCheck check;
  const Pose2 p = Drive(&check, Wheels::kHeadingOnly, 6.0f);
  REQUIRE(check.translation_ignored());
  (void)Drive(&check, Wheels::kTrue, 6.0f, p, 6000000);
  CHECK_FALSE(check.translation_ignored());
}

TEST_CASE("WheelCheck: a standing robot's jitter and untracked scans never switch the wheels off") {
  WheelCheck check;
  // Standing: registered poses jitter by 1 cm, the wheels stay put, for ten minutes.
  Pose2 registered = Pose2::Identity();
  for (int i = 1; i <= 6000; ++i) {
    check.AddOdometry(WheelSample(i * 100000 - 50000, Pose2::Identity(), Wheels::kTrue));
    const float j = (i % 2 == 0 ? 0.01f : -0.01f);
    const Pose2 now{j, -j, 0.5f * j};
    check.AddScan(dpcr::Between(registered, now), Pose2::Identity(), i * 100000, true);
    registered = now;
  }
  CHECK(check.translation_misses() == 0);
  // A robot carried 1 m while lost (its scans untracked), over and over: the wheels standing
  // still then are not a miss.
  for (int k = 0; k < 10; ++k) {
    const std::int64_t t = 700000000 + k * 2000000;
    check.AddScan(Pose2::Identity(), Pose2::Identity(), t, true);
    check.AddScan(Pose2{1.0f, 0.0f, 0.0f}, Pose2::Identity(), t + 100000, false);
    check.AddScan(Pose2::Identity(), Pose2::Identity(), t + 200000, true);
  }
  CHECK(check.translation_misses() == 0);
  CHECK_FALSE(check.translation_ignored());
}

TEST_CASE("WheelCheck: wheels that spin on while the lidar sees the robot stand are set aside") {
  WheelCheck check;
  StandStuck(&check, Drive(&check, Wheels::kTrue, 5.0f), 0);
  CHECK(check.translation_ignored());
  CHECK(check.translation_misses() == 3);
}

TEST_CASE("WheelCheck: registrations that fit poorly do not say the wheels spin on") {
  // As on mit-csail.clf after a fast turn: registrations caught on the wrong wall hold the robot
  // back scan after scan at a high residual while the wheels drive on. Only clean fits may set the
  // wheels aside; one poor fit in a window keeps that window from voting.
  for (const int poor_every : {1, 5}) {
    WheelCheck check;
    StandStuck(&check, Drive(&check, Wheels::kTrue, 5.0f), poor_every);
    CHECK_FALSE(check.translation_ignored());
    CHECK(check.translation_misses() == 0);
  }
}

TEST_CASE("WheelCheck: logged odometry that stalls and then catches up is not switched off") {
  // As mit-csail.clf logs it: the wheels' pose stands still for two windows while the robot
  // drives on, then jumps the whole way in one step. Two misses one way and one the other are
  // neither wheels that miss the motion nor wheels that spin on.
  WheelCheck check;
  Pose2 p = Drive(&check, Wheels::kTrue, 5.0f);
  REQUIRE_FALSE(check.translation_doubted());
  std::int64_t t = 5000000;
  for (int cycle = 0; cycle < 5; ++cycle) {
    const Pose2 stalled = p;
    // 0.75 m registered (two windows and a half) with the wheels standing still...
    for (int i = 1; i <= 30; ++i) {
      const Pose2 before = p;
      p = p * Pose2{0.025f, 0.0f, 0.0f};
      t += 100000;
      check.AddOdometry(WheelSample(t, stalled, Wheels::kTrue));
      check.AddScan(dpcr::Between(before, p), stalled, t, true);
    }
    // ...then the wheels catch up in one sample while the robot stands.
    t += 100000;
    check.AddOdometry(WheelSample(t, p, Wheels::kTrue));
    check.AddScan(Pose2::Identity(), p, t, true);
    p = Drive(&check, Wheels::kTrue, 2.0f, p, t);
    t += 2000000;
    CHECK_FALSE(check.translation_ignored());
  }
  CHECK(check.translation_misses() >= 5);  // they are misses, just not one fault
  // The same stall without the catch-up (the ticks carry no translation): switched off.
  const Pose2 stalled = p;
  for (int i = 1; i <= 60 && !check.translation_ignored(); ++i) {
    const Pose2 before = p;
    p = p * Pose2{0.025f, 0.0f, 0.0f};
    t += 100000;
    check.AddOdometry(WheelSample(t, stalled, Wheels::kTrue));
    check.AddScan(dpcr::Between(before, p), stalled, t, true);
  }
  CHECK(check.translation_ignored());
}
