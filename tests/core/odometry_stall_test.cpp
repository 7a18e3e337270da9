#include "core/front_end/odometry_stall.hpp"

#include <catch2/catch.hpp>

namespace {

using dpcr::OdometryStall;
using dpcr::Pose2;

}  // namespace

TEST_CASE("A stall's catch-up is taken from where the odometry stalled") {
  OdometryStall stall;
  bool caught_up = true;
  // Moving: steps pass through.
  Pose2 step = stall.Step(Pose2{0.1f, 0.0f, 0.0f}, false, Pose2{0.1f, 0.0f, 0.0f}, &caught_up);
  CHECK_FALSE(caught_up);
  CHECK(step.x == 0.1f);
  stall.AddRegistered(Pose2{0.1f, 0.0f, 0.0f});
  // Three scans on which the odometry repeats its pose while the robot drives 0.1 m and turns 0.1
  // rad each (as registered).
  for (int k = 0; k < 3; ++k) {
    step = stall.Step(Pose2::Identity(), true, Pose2{0.1f, 0.0f, 0.1f}, &caught_up);
    CHECK_FALSE(caught_up);
    stall.AddRegistered(Pose2{0.1f, 0.0f, 0.1f});
  }
  // The catch-up: the four steps at once, as seen from where the odometry stalled.
  const Pose2 one{0.1f, 0.0f, 0.1f};
  const Pose2 all = one * one * one * one;
  step = stall.Step(all, false, one, &caught_up);
  CHECK(caught_up);
  CHECK(step.x == Approx(one.x).margin(1e-5));
  CHECK(step.y == Approx(one.y).margin(1e-5));
  CHECK(step.theta == Approx(one.theta).margin(1e-5));
  // After it, steps pass through again.
  stall.AddRegistered(one);
  step = stall.Step(one, false, one, &caught_up);
  CHECK_FALSE(caught_up);
  CHECK(step.theta == one.theta);
}

TEST_CASE("A standing robot's jitter over a stall is not taken out of the next step") {
  OdometryStall stall;
  bool caught_up = true;
  (void)stall.Step(Pose2{0.1f, 0.0f, 0.0f}, false, Pose2{0.1f, 0.0f, 0.0f}, &caught_up);
  for (int k = 0; k < 20; ++k) {
    (void)stall.Step(Pose2::Identity(), true, Pose2{0.1f, 0.0f, 0.1f}, &caught_up);
    stall.AddRegistered(Pose2{0.001f, -0.001f, 0.001f});  // 2 cm and 1.1 deg in all: below both bounds
  }
  const Pose2 step = stall.Step(Pose2{0.05f, 0.0f, 0.0f}, false, Pose2{0.05f, 0.0f, 0.0f}, &caught_up);
  CHECK_FALSE(caught_up);
  CHECK(step.x == 0.05f);
  CHECK(step.y == 0.0f);
}

TEST_CASE("A reset stall forgets what was registered during it") {
  OdometryStall stall;
  bool caught_up = true;
  (void)stall.Step(Pose2::Identity(), true, Pose2{0.1f, 0.0f, 0.1f}, &caught_up);
  stall.AddRegistered(Pose2{0.5f, 0.0f, 0.0f});
  stall.Reset();
  const Pose2 step = stall.Step(Pose2{0.6f, 0.0f, 0.0f}, false, Pose2{0.1f, 0.0f, 0.0f}, &caught_up);
  CHECK_FALSE(caught_up);
  CHECK(step.x == 0.6f);
}

TEST_CASE("Wheels that resume where they stopped keep their step") {
  // A wheel board silent for three scans that then counts on from its last pose: its first step
  // is one step, not the three missed; taking the registered motion out of it would throw the
  // robot back by them.
  OdometryStall stall;
  bool caught_up = true;
  const Pose2 one{0.1f, 0.0f, 0.0f};
  (void)stall.Step(one, false, one, &caught_up);
  stall.AddRegistered(one);
  for (int k = 0; k < 3; ++k) {
    (void)stall.Step(Pose2::Identity(), true, one, &caught_up);
    stall.AddRegistered(one);
  }
  const Pose2 step = stall.Step(one, false, one, &caught_up);
  CHECK_FALSE(caught_up);
  CHECK(step.x == one.x);
}
