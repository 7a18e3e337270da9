// Along a direction the walls barely fix, a registration without wheels keeps near the constant
// velocity's guess (core/registration/weak_direction_hold.hpp).
#include "core/registration/weak_direction_hold.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using dpcr::HoldWeakDirections;
using dpcr::Pose2;

namespace {

// The xy block of 100 inliers' normal equations: `along` and `across` information per inlier on
// two perpendicular directions, the first at `angle` from the x axis.
Eigen::Matrix3f Hessian(float along, float across, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  Eigen::Matrix3f h = Eigen::Matrix3f::Zero();
  h(0, 0) = 100.0f * (along * c * c + across * s * s);
  h(1, 1) = 100.0f * (along * s * s + across * c * c);
  h(0, 1) = h(1, 0) = 100.0f * (along - across) * c * s;
  h(2, 2) = 50.0f;
  return h;
}

}  // namespace

TEST_CASE("A registration that slides back along a lane keeps within the bound of the guess") {
  // A lane along the diagonal: little hold along it (0.01 per inlier), the walls across it fix it
  // (0.2). The registration pulled 10 cm back along the lane and 1 cm across it.
  const float angle = 0.7853982f, c = std::cos(angle), s = std::sin(angle);
  const Pose2 predicted{1.0f, 2.0f, 0.3f};
  Pose2 registered{predicted.x - 0.10f * c - 0.01f * s, predicted.y - 0.10f * s + 0.01f * c, 0.31f};
  REQUIRE(HoldWeakDirections(Hessian(0.01f, 0.2f, angle), 100, predicted, 0.1f, 0.04f, &registered));
  const float dx = registered.x - predicted.x, dy = registered.y - predicted.y;
  CHECK(dx * c + dy * s == Approx(-0.04f).margin(1e-5));   // along: clamped to the bound
  CHECK(-dx * s + dy * c == Approx(0.01f).margin(1e-5));   // across: as registered
  CHECK(registered.theta == 0.31f);                          // the turn: as registered
}

TEST_CASE("A registration the walls fix both ways is kept as it is") {
  const Pose2 predicted{0.0f, 0.0f, 0.0f};
  Pose2 registered{0.08f, -0.05f, 0.02f};
  CHECK_FALSE(HoldWeakDirections(Hessian(0.15f, 0.2f, 0.3f), 100, predicted, 0.1f, 0.04f, &registered));
  CHECK(registered.x == 0.08f);
  CHECK(registered.y == -0.05f);
}

TEST_CASE("A weak direction within the bound is not moved") {
  const Pose2 predicted{0.0f, 0.0f, 0.0f};
  Pose2 registered{0.03f, 0.0f, 0.0f};  // 3 cm along the x axis, the weak one; bound 4 cm
  CHECK_FALSE(HoldWeakDirections(Hessian(0.01f, 0.2f, 0.0f), 100, predicted, 0.1f, 0.04f, &registered));
  CHECK(registered.x == 0.03f);
}

TEST_CASE("An axis-aligned corridor clamps only its own axis") {
  // b = 0: one of the two eigenvector formulas vanishes; the other must be taken.
  const Pose2 predicted{0.0f, 0.0f, 0.0f};
  Pose2 registered{0.02f, 0.09f, 0.0f};  // weak along y
  REQUIRE(HoldWeakDirections(Hessian(0.02f, 0.3f, 1.5707964f), 100, predicted, 0.1f, 0.04f, &registered));
  CHECK(registered.x == Approx(0.02f).margin(1e-6));
  CHECK(registered.y == Approx(0.04f).margin(1e-6));
}

TEST_CASE("Nothing fixed either way clamps both directions") {
  // An isotropic weak block (an open room past the reach, a few returns): both directions held.
  const Pose2 predicted{0.0f, 0.0f, 0.0f};
  Pose2 registered{-0.06f, 0.07f, 0.0f};
  REQUIRE(HoldWeakDirections(Hessian(0.05f, 0.05f, 0.0f), 100, predicted, 0.1f, 0.04f, &registered));
  CHECK(registered.x == Approx(-0.04f).margin(1e-6));
  CHECK(registered.y == Approx(0.04f).margin(1e-6));
}

TEST_CASE("No inliers or no threshold hold nothing") {
  const Pose2 predicted{0.0f, 0.0f, 0.0f};
  Pose2 registered{0.2f, 0.0f, 0.0f};
  CHECK_FALSE(HoldWeakDirections(Hessian(0.01f, 0.2f, 0.0f), 0, predicted, 0.1f, 0.04f, &registered));
  CHECK_FALSE(HoldWeakDirections(Hessian(0.01f, 0.2f, 0.0f), 100, predicted, 0.0f, 0.04f, &registered));
  CHECK(registered.x == 0.2f);
}
