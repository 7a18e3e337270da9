// SE(2) property tests on seeded random poses.
#include <catch2/catch.hpp>

#include <random>

#include "core/geometry/pose2.hpp"

using dpcr::Pose2;

namespace {
Pose2 RandomPose(std::mt19937& rng) {
  std::uniform_real_distribution<float> pos(-50.0f, 50.0f);
  std::uniform_real_distribution<float> ang(-10.0f, 10.0f);
  return Pose2{pos(rng), pos(rng), dpcr::NormalizeAngle(ang(rng))};
}
void RequireNear(const Pose2& a, const Pose2& b, float tol) {
  REQUIRE(a.x == Approx(b.x).margin(tol));
  REQUIRE(a.y == Approx(b.y).margin(tol));
  REQUIRE(dpcr::NormalizeAngle(a.theta - b.theta) == Approx(0.0f).margin(tol));
}
}  // namespace

TEST_CASE("NormalizeAngle wraps into the half-open range -pi to pi") {
  REQUIRE(dpcr::NormalizeAngle(0.0f) == Approx(0.0f).margin(1e-6));
  REQUIRE(dpcr::NormalizeAngle(dpcr::kPi) == Approx(dpcr::kPi));
  REQUIRE(dpcr::NormalizeAngle(-dpcr::kPi) == Approx(dpcr::kPi));
  REQUIRE(dpcr::NormalizeAngle(3.0f * dpcr::kPi / 2.0f) == Approx(-dpcr::kPi / 2.0f));
  REQUIRE(dpcr::NormalizeAngle(-7.0f) == Approx(-7.0f + 2.0f * dpcr::kPi));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> any(-100.0f, 100.0f);
  for (int i = 0; i < 1000; ++i) {
    const float a = dpcr::NormalizeAngle(any(rng));
    REQUIRE(a > -dpcr::kPi - 1e-6f);
    REQUIRE(a <= dpcr::kPi + 1e-6f);
  }
}

TEST_CASE("Pose2 group laws hold on random poses") {
  std::mt19937 rng(42);
  for (int i = 0; i < 200; ++i) {
    const Pose2 a = RandomPose(rng), b = RandomPose(rng), c = RandomPose(rng);
    RequireNear(a * a.Inverse(), Pose2::Identity(), 1e-4f);
    RequireNear(a.Inverse() * a, Pose2::Identity(), 1e-4f);
    RequireNear((a * b) * c, a * (b * c), 2e-3f);
    RequireNear(a * dpcr::Between(a, b), b, 1e-3f);
    // Apply agrees with composition on the translation part.
    const dpcr::Point2 p = a.Apply(dpcr::Point2{b.x, b.y});
    const Pose2 ab = a * b;
    REQUIRE(p.x == Approx(ab.x).margin(1e-3));
    REQUIRE(p.y == Approx(ab.y).margin(1e-3));
  }
}

TEST_CASE("Pose2 composes a known quarter turn") {
  const Pose2 a{1.0f, 0.0f, dpcr::kPi / 2};
  const Pose2 b{2.0f, 0.0f, 0.0f};
  RequireNear(a * b, Pose2{1.0f, 2.0f, dpcr::kPi / 2}, 1e-5f);
}
