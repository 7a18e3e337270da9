// Logged odometry that stalls and then catches up in one step (mit-csail.clf: the laser records
// repeat one odometry pose for 0.8 s, then step by 0.85 m and 50 deg): the catch-up is taken from
// where the odometry stalled (core/front_end/odometry_stall.hpp). Odometry that jumps without a
// stall (a glitch, a reset of the odometry frame): from the jump's prediction no registration
// converges, and the fallback pose sends the robot lost; the first registration is tried again
// from the constant velocity (FrontEndConfig::odometry_doubt_*).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/mapper.hpp"
#include "tests/core/cabinet_room.hpp"

namespace {

using M = dpcr::Mapper<dpcr::VacuumProfile>;

// Driving at 0.25 m/s while turning at 0.5 rad/s, from (1.5, 1.2).
dpcr::Pose2 Truth(float t) {
  constexpr float kSpeed = 0.25f, kTurn = 0.5f;
  const float theta = kTurn * t;
  return dpcr::Pose2{1.5f + kSpeed / kTurn * std::sin(theta), 1.2f + kSpeed / kTurn * (1.0f - std::cos(theta)), theta};
}

struct GlitchResult {
  std::uint32_t rejected = 0;
  std::uint32_t overruled = 0;
  std::uint32_t stalls = 0;
  float worst_after_step_m = 0.0f;  // the largest position error from the catch-up on
};

enum class Glitch { kStall, kJump };

// 40 scans at 5 Hz, the odometry logged with each (as a CARMEN laser record carries it). kStall:
// scans 15-22 repeat scan 14's odometry pose, scan 23's catches up. kJump: from scan 23 on the
// odometry's frame is moved (its steps stay right).
GlitchResult Drive(const dpcr::MapperConfig& config, Glitch glitch) {
  auto m = std::make_unique<M>();
  REQUIRE(m->Init(config) == dpcr::Status::kOk);
  const dpcr::Pose2 start = Truth(0.0f);
  // The jump: at scan 23 the odometry says the robot went 0.4 m and 0.8 rad farther than it did
  // (what the stall's catch-up says), and counts on from there.
  const dpcr::Pose2 at_jump = start.Inverse() * Truth(0.2f * 23.0f);
  const dpcr::Pose2 jump = at_jump * dpcr::Pose2{0.4f, 0.1f, 0.8f} * at_jump.Inverse();
  GlitchResult r;
  for (int s = 0; s < 40; ++s) {
    const float t = 0.2f * static_cast<float>(s);
    dpcr::OdometrySample o;
    o.stamp_us = static_cast<std::int64_t>(s) * 200000;
    const bool stalled = glitch == Glitch::kStall && s >= 15 && s <= 22;
    o.pose = start.Inverse() * Truth(stalled ? 0.2f * 14.0f : t);
    if (glitch == Glitch::kJump && s >= 23) o.pose = jump * o.pose;
    m->AddOdometry(o);
    M::ScanType scan;
    scan.stamp_us = o.stamp_us;
    const dpcr::Pose2 robot = Truth(t);
    for (int b = 0; b < 360; ++b) {
      dpcr::Beam beam;
      beam.angle_rad = dpcr::NormalizeAngle(2.0f * dpcr::kPi * static_cast<float>(b) / 360.0f);
      beam.range_m = dpcr::test::CabinetRoomRange(robot.x, robot.y, robot.theta + beam.angle_rad);
      (void)scan.beams.push_back(beam);
    }
    (void)m->AddScan(scan);
    const dpcr::Pose2 truth = start.Inverse() * robot;
    if (s >= 23) r.worst_after_step_m = std::fmax(r.worst_after_step_m, std::hypot(m->pose().x - truth.x, m->pose().y - truth.y));
  }
  r.rejected = m->front_end_counters().first_rejected;
  r.overruled = m->front_end_counters().odometry_overruled;
  r.stalls = m->front_end_counters().odometry_stalls;
  return r;
}

}  // namespace

TEST_CASE("Odometry that stalls and then catches up in one step is taken from where it stalled") {
  // Without the constant velocity's retry: the catch-up's prediction must be right on its own.
  // (Before the stall was taken out of it, it was rejected here and the robot placed where it
  // said: 0.2 m and more off.)
  dpcr::MapperConfig trusting;
  trusting.front_end.odometry_doubt_m = 0.0f;
  trusting.front_end.odometry_doubt_rad = 0.0f;
  const GlitchResult r = Drive(trusting, Glitch::kStall);
  INFO("rejected " << r.rejected << ", stalls " << r.stalls << ", worst error after the step " << r.worst_after_step_m << " m");
  CHECK(r.stalls == 1);
  CHECK(r.rejected == 0);
  CHECK(r.worst_after_step_m < 0.03f);
}

TEST_CASE("Odometry that jumps is overruled by the constant velocity") {
  const GlitchResult r = Drive(dpcr::MapperConfig{}, Glitch::kJump);
  INFO("rejected " << r.rejected << ", overruled " << r.overruled << ", worst error after the jump " << r.worst_after_step_m << " m");
  CHECK(r.overruled >= 1);
  CHECK(r.stalls == 0);
  CHECK(r.worst_after_step_m < 0.03f);
  // Without the retry the jump's prediction is rejected, and the robot is placed where it says.
  dpcr::MapperConfig trusting;
  trusting.front_end.odometry_doubt_m = 0.0f;
  trusting.front_end.odometry_doubt_rad = 0.0f;
  const GlitchResult t = Drive(trusting, Glitch::kJump);
  INFO("trusting the odometry: rejected " << t.rejected << ", worst error after the jump " << t.worst_after_step_m << " m");
  CHECK(t.overruled == 0);
  CHECK(t.rejected >= 1);
  CHECK(t.worst_after_step_m > 0.2f);
}
