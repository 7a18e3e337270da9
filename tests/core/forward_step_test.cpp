// The constant-velocity guess of a differential drive moves along its heading, never sideways
// (core/front_end/forward_step.hpp).
#include "core/front_end/forward_step.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using dpcr::ForwardStep;
using dpcr::Pose2;

TEST_CASE("A step straight ahead is the guess unchanged") {
  const Pose2 guess = ForwardStep(Pose2{0.06f, 0.0f, 0.0f});
  CHECK(guess.x == Approx(0.06f));
  CHECK(guess.y == Approx(0.0f).margin(1e-7));
  CHECK(guess.theta == 0.0f);
}

TEST_CASE("A sideways slide is no motion of a differential drive") {
  // A registration that let the pose slide 3 cm sideways along a doorway while the robot stood.
  const Pose2 guess = ForwardStep(Pose2{0.0f, 0.03f, 0.0f});
  CHECK(guess.x == Approx(0.0f).margin(1e-7));
  CHECK(guess.y == Approx(0.0f).margin(1e-7));
}

TEST_CASE("The chord of an arc keeps its sideways part in the earlier frame") {
  // Driving 0.3 m/s while turning 60 deg/s for 0.2 s: a radius of 0.286 m; the chord ends
  // R sin(theta) ahead and R (1 - cos(theta)) to the left, along the mid-step heading.
  const float rate = 60.0f * 3.14159265f / 180.0f, theta = 0.2f * rate, radius = 0.3f / rate;
  const Pose2 arc{radius * std::sin(theta), radius * (1.0f - std::cos(theta)), theta};
  const Pose2 guess = ForwardStep(arc);
  CHECK(guess.x == Approx(arc.x).epsilon(1e-5));
  CHECK(guess.y == Approx(arc.y).epsilon(1e-4));
  CHECK(guess.theta == arc.theta);
}

TEST_CASE("A step backwards and sideways keeps only its part along the heading") {
  // The office's slide (gyro alone, seed 2): 6.2 cm back and 1.6 cm to the left in one scan, no
  // turn. The guess keeps the 6.2 cm back (a differential drive reverses too).
  const Pose2 guess = ForwardStep(Pose2{-0.062f, 0.016f, 0.0f});
  CHECK(guess.x == Approx(-0.062f));
  CHECK(guess.y == Approx(0.0f).margin(1e-7));
  // With a turn, the part across the mid-step heading goes.
  const Pose2 turned = ForwardStep(Pose2{0.05f, 0.02f, 0.2f});
  const float c = std::cos(0.1f), s = std::sin(0.1f);
  CHECK(-s * turned.x + c * turned.y == Approx(0.0f).margin(1e-7));
  CHECK(c * turned.x + s * turned.y == Approx(c * 0.05f + s * 0.02f));
  CHECK(turned.theta == 0.2f);
}
