#include "core/front_end/odometry_calibration.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace {

using dpcr::OdometryCalibration;
using dpcr::Pose2;

// A robot's true step k of a drive that goes straight, turns left, goes straight, turns right:
// 0.1 m and up to 0.2 rad per scan.
Pose2 TrueStep(int k) {
  const float turn = 0.2f * std::sin(0.05f * static_cast<float>(k));
  return Pose2{0.1f * std::cos(turn), 0.1f * std::sin(turn), turn};
}

// Wheels whose radius is `scale` times what the odometry assumes, and whose track width makes
// every turn `turn_scale` times too large.
Pose2 Wheels(const Pose2& truth, float scale, float turn_scale) {
  return Pose2{truth.x * scale, truth.y * scale, truth.theta * turn_scale};
}

}  // namespace

TEST_CASE("Odometry calibration leaves the wheels alone until it has seen enough") {
  OdometryCalibration c;
  const Pose2 w{0.1f, 0.0f, 0.05f};
  for (int k = 0; k < 40; ++k) c.Add(Pose2{0.095f, 0.0f, 0.048f}, w);  // 4 m, 2 rad: under both bounds
  CHECK(c.translation_scale() == 1.0f);
  CHECK(c.turn_scale() == 1.0f);
  const Pose2 applied = c.Apply(w);
  CHECK(applied.x == w.x);
  CHECK(applied.theta == w.theta);
}

TEST_CASE("Odometry calibration finds wheels that overstate steps and turns") {
  OdometryCalibration c;
  for (int k = 0; k < 600; ++k) c.Add(TrueStep(k), Wheels(TrueStep(k), 1.04f, 1.05f));
  CHECK(c.translation_scale() == Approx(1.0f / 1.04f).epsilon(0.002));
  CHECK(c.turn_scale() == Approx(1.0f / 1.05f).epsilon(0.002));
  const Pose2 w = Wheels(TrueStep(17), 1.04f, 1.05f);
  const Pose2 applied = c.Apply(w);
  CHECK(applied.x == Approx(TrueStep(17).x).epsilon(0.002));
  CHECK(applied.theta == Approx(TrueStep(17).theta).epsilon(0.002));
}

TEST_CASE("Odometry calibration converges while the registrations lean on its own prediction") {
  // The first registration's odometry prior pulls each registered step half-way back toward the
  // prediction; the prediction is the calibrated wheels. Its fixed point is still the truth.
  OdometryCalibration c;
  for (int k = 0; k < 12000; ++k) {
    const Pose2 truth = TrueStep(k);
    const Pose2 wheels = Wheels(truth, 0.95f, 1.06f);
    const Pose2 predicted = c.Apply(wheels);
    const Pose2 registered{0.5f * (truth.x + predicted.x), 0.5f * (truth.y + predicted.y), 0.5f * (truth.theta + predicted.theta)};
    c.Add(registered, wheels);
  }
  CHECK(c.translation_scale() == Approx(1.0f / 0.95f).epsilon(0.005));
  CHECK(c.turn_scale() == Approx(1.0f / 1.06f).epsilon(0.005));
}

TEST_CASE("Odometry calibration ignores slips, long steps and what is not finite") {
  OdometryCalibration c;
  for (int k = 0; k < 600; ++k) c.Add(TrueStep(k), TrueStep(k));
  REQUIRE(c.translation_scale() == Approx(1.0f).margin(1e-4));
  for (int k = 0; k < 200; ++k) {
    c.Add(Pose2{0.3f, 0.0f, 0.0f}, TrueStep(k));              // a slip: 0.2 m off the prediction
    c.Add(Pose2{0.05f, 0.0f, 0.0f}, Pose2{0.9f, 0.0f, 0.0f});  // a logger's catch-up
    c.Add(Pose2{NAN, 0.0f, 0.0f}, TrueStep(k));
  }
  CHECK(c.translation_scale() == Approx(1.0f).margin(1e-4));
  CHECK(c.turn_scale() == Approx(1.0f).margin(1e-4));
}

TEST_CASE("Odometry calibration clamps what is no calibration error and learns nothing from gross ones") {
  // Wheels that say 30 % too far and turn 30 % too little: the factors stop at their bounds.
  OdometryCalibration c;
  for (int k = 0; k < 4000; ++k) c.Add(TrueStep(k), Wheels(TrueStep(k), 1.3f, 0.7f));
  CHECK(c.translation_scale() == Approx(1.0f - OdometryCalibration::kMaxScaleError));
  CHECK(c.turn_scale() == Approx(1.0f + OdometryCalibration::kMaxScaleError));
  // Wheels that say twice the distance: every step is farther from the registration than a slip,
  // and none is taken (WheelCheck sets such wheels aside).
  OdometryCalibration gross;
  for (int k = 0; k < 4000; ++k) gross.Add(TrueStep(k), Wheels(TrueStep(k), 2.0f, 1.0f));
  CHECK(gross.translation_scale() == 1.0f);
}
