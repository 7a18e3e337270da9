// The constant-velocity guess without wheel translation changes by no more than the robot can
// accelerate (core/front_end/acceleration_limit.hpp): a correction is not a speed.
#include "core/front_end/acceleration_limit.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using dpcr::LimitAcceleration;
using dpcr::Pose2;

namespace {
constexpr std::int64_t kStepUs = 200000;  // 5 Hz
}  // namespace

TEST_CASE("A step within the acceleration limit is the next guess unchanged") {
  // 0.30 m/s, then 0.35 m/s: 0.25 m/s^2, under 0.5.
  const Pose2 last{0.06f, 0.0f, 0.0f}, step{0.07f, 0.0f, 0.1f};
  const Pose2 guess = LimitAcceleration(last, kStepUs, step, kStepUs, 0.5f);
  CHECK(guess.x == step.x);
  CHECK(guess.y == step.y);
  CHECK(guess.theta == step.theta);
}

TEST_CASE("A correction against the motion does not reverse the guessed velocity") {
  // Driving at 0.12 m/s; the registration moves the pose 7 cm back (a correction after a turn):
  // taken whole, the guess would be -0.35 m/s. At 0.5 m/s^2 over 0.2 s the velocity changes by
  // 0.1 m/s at most: 0.02 m/s forward, the turn as registered.
  const Pose2 last{0.024f, 0.0f, 0.0f}, step{-0.07f, 0.0f, -0.12f};
  const Pose2 guess = LimitAcceleration(last, kStepUs, step, kStepUs, 0.5f);
  CHECK(guess.x / 0.2f == Approx(0.02f).margin(1e-5));
  CHECK(guess.y == Approx(0.0f).margin(1e-6));
  CHECK(guess.theta == step.theta);
}

TEST_CASE("The velocity change is limited as a vector and scales with the time between scans") {
  // From standing (no step yet), a step of 0.3 m sideways and 0.4 m ahead in 0.25 s (2 m/s):
  // 0.5 m/s^2 allows 0.125 m/s, along the step's direction.
  const Pose2 step{0.4f, 0.3f, 0.0f};
  const Pose2 guess = LimitAcceleration(Pose2{}, 0, step, 250000, 0.5f);
  const float speed = std::hypot(guess.x, guess.y) / 0.25f;
  CHECK(speed == Approx(0.125f).epsilon(1e-4));
  CHECK(guess.y / guess.x == Approx(0.75f).epsilon(1e-4));
  // The last velocity is per second: a 0.1 m step over 0.5 s is 0.2 m/s; the same step over 0.2 s
  // then stays within 0.1 m/s of it.
  const Pose2 after = LimitAcceleration(Pose2{0.1f, 0.0f, 0.0f}, 500000, Pose2{0.1f, 0.0f, 0.0f}, kStepUs, 0.5f);
  CHECK(after.x / 0.2f == Approx(0.3f).epsilon(1e-4));
}

TEST_CASE("No limit at 0 and no step without time") {
  const Pose2 last{0.0f, 0.0f, 0.0f}, step{1.0f, -1.0f, 0.5f};
  const Pose2 unlimited = LimitAcceleration(last, kStepUs, step, kStepUs, 0.0f);
  CHECK(unlimited.x == step.x);
  CHECK(unlimited.y == step.y);
  const Pose2 no_time = LimitAcceleration(last, kStepUs, step, 0, 0.5f);
  CHECK(no_time.x == step.x);
  CHECK(no_time.y == step.y);
}
