// End to end: an XV-11 returning half its readings at 3.5-5 Hz on a robot with a gyro and no wheel
// encoders (as the real recordings: an IMU's yaw, no wheel translation), on the simulated
// apartment. The translation is the constant velocity's guess and the sparse scans give little
// hold along a lane:
// - a registration that corrects the pose must not become that guess's new speed
//   (FrontEndConfig::max_acceleration_mps2). Without the limit a correction after the start's
//   in-place turn became a backward speed that the sparse scans then followed (seed 5: over a
//   metre off within two seconds);
// - a robot that lost track where it was (not carried) takes a fix past the near window of its
//   belief only when it is clear or a second round agrees (FrontEnd::PastNearWindow). Taken at once,
//   seed 4's fix put it 3.4 m back along its lane for the rest of the run.
#include <catch2/catch.hpp>

#include <algorithm>

#include "tests/apps/xv11_apartment_run.hpp"

namespace {

dpcr::test::Xv11RunResult GyroOnlyRun(std::uint64_t seed, double minutes, dpcr::MapperConfig config) {
  dpcr::sim::SimConfig sim_config;
  sim_config.seed = seed;
  sim_config.duration_min = minutes;
  sim_config.lidar = dpcr::sim::Xv11LidarConfig();
  sim_config.lidar.invalid_probability = 0.5;
  sim_config.lidar.rate_min_hz = 3.5;
  const dpcr::test::Xv11RunResult run = dpcr::test::RunXv11GyroOnly("apartment", sim_config, config);
  REQUIRE(run.scans > 80);
  return run;
}

}  // namespace

TEST_CASE("A gyro-only robot with sparse scans does not take a correction for a speed") {
  const dpcr::MapperConfig defaults;
  REQUIRE(defaults.front_end.max_acceleration_mps2 > 0.0f);
  // The scenario as recorded, with the weak translation prior through turns: held firm there
  // (FrontEndConfig::turn_holds_translation) the start's turn gives no correction to take for a
  // speed, and no run drives off with or without the limit (measured: worst 0.018 / 0.013 m).
  dpcr::MapperConfig limited;
  limited.front_end.turn_holds_translation = false;
  dpcr::MapperConfig unlimited = limited;
  unlimited.front_end.max_acceleration_mps2 = 0.0f;
  double worst_with = 0.0, worst_without = 0.0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const double as_shipped = GyroOnlyRun(seed, 0.5, defaults).mean_error_m;
    const double with = GyroOnlyRun(seed, 0.5, limited).mean_error_m, without = GyroOnlyRun(seed, 0.5, unlimited).mean_error_m;
    INFO("seed " << seed << ": mean error " << with << " m, without the limit " << without << " m, as shipped " << as_shipped << " m");
    CHECK(as_shipped < 0.1);
    CHECK(with < 0.1);
    worst_with = std::max(worst_with, with);
    worst_without = std::max(worst_without, without);
  }
  INFO("worst mean error over seeds 1-6: " << worst_with << " m, without the limit " << worst_without << " m");
  // The scenario needs the change: without it some run drove off backwards.
  CHECK(worst_without > 0.3);
}

TEST_CASE("A gyro-only robot that lost track in a lane takes no far look-alike fix at once") {
  // Seed 4 loses track at 589 s (three second registrations rejected for their inlier ratio while
  // the estimate is 2 cm off) and is found again.
  // As recorded, with the weak translation prior through turns; held firm there
  // (FrontEndConfig::turn_holds_translation) seed 4 does not lose track (measured: 0.010 / 0.073 m
  // with every fix at once too).
  const dpcr::MapperConfig defaults;
  REQUIRE(defaults.localisation.near_window_m > 0.0f);
  dpcr::MapperConfig recorded;
  recorded.front_end.turn_holds_translation = false;
  dpcr::MapperConfig every_fix_at_once = recorded;  // near window 0: any verified fix is taken at once
  every_fix_at_once.localisation.near_window_m = 0.0f;
  const dpcr::test::Xv11RunResult as_shipped = GyroOnlyRun(4, 10.0, defaults);
  const dpcr::test::Xv11RunResult with = GyroOnlyRun(4, 10.0, recorded), without = GyroOnlyRun(4, 10.0, every_fix_at_once);
  INFO("mean / max error " << with.mean_error_m << " / " << with.max_error_m << " m; every fix at once " << without.mean_error_m << " / "
                           << without.max_error_m << " m; as shipped " << as_shipped.mean_error_m << " / " << as_shipped.max_error_m << " m");
  CHECK(as_shipped.max_error_m < 0.5);
  CHECK(with.max_error_m < 0.5);
  CHECK(with.mean_error_m < 0.05);
  // The scenario needs the change: taken at once, the look-alike fix put the robot metres off.
  CHECK(without.max_error_m > 2.0);
}

TEST_CASE("A gyro-only robot whose lidar returns 40 percent of its readings keeps its walls in the submap") {
  // The submap's obstacle threshold scaled with the share of returns (core/front_end/return_share.hpp):
  // with the threshold of a full lidar the walls of the sparse scans' submap had holes, and more
  // registrations were rejected (each one a step of the constant velocity's guess).
  const dpcr::MapperConfig defaults;
  REQUIRE(defaults.front_end.sparse_reference_full_share > 0.0f);
  dpcr::MapperConfig fixed_threshold;
  fixed_threshold.front_end.sparse_reference_full_share = 0.0f;
  double rejected_with = 0.0, rejected_without = 0.0, worst_without = 0.0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    dpcr::sim::SimConfig sim_config;
    sim_config.seed = seed;
    sim_config.duration_min = 10.0;
    sim_config.lidar = dpcr::sim::Xv11LidarConfig();
    sim_config.lidar.invalid_probability = 0.6;
    sim_config.lidar.rate_min_hz = 3.5;
    const dpcr::test::Xv11RunResult with = dpcr::test::RunXv11GyroOnly("apartment", sim_config, defaults);
    const dpcr::test::Xv11RunResult without = dpcr::test::RunXv11GyroOnly("apartment", sim_config, fixed_threshold);
    INFO("seed " << seed << ": mean / max error " << with.mean_error_m << " / " << with.max_error_m << " m, "
                 << 100.0 * with.rejected_share << " % rejected; with a full lidar's threshold " << without.mean_error_m << " / "
                 << without.max_error_m << " m, " << 100.0 * without.rejected_share << " %");
    REQUIRE(with.scans > 1500);
    CHECK(with.max_error_m < 1.0);  // measured at most 0.31 m (seed 5)
    rejected_with += with.rejected_share;
    rejected_without += without.rejected_share;
    worst_without = std::max(worst_without, without.max_error_m);
  }
  INFO("first registrations rejected, mean over seeds 1-8: " << 100.0 * rejected_with / 8.0 << " %, with a full lidar's threshold "
                                                              << 100.0 * rejected_without / 8.0 << " %");
  CHECK(rejected_with < 0.5 * rejected_without);  // measured 0.49 % against 1.8 %
  // The scenario needs the change: with a full lidar's threshold some run lost its way by metres.
  CHECK(worst_without > 1.0);
}

TEST_CASE("A gyro-only robot in a lane with little hold along it keeps the speed of its guess") {
  // Seed 53 drives down a lane at 250 s whose far end is sparse: registrations that pulled the pose
  // 4-10 cm back along it, taken whole, slowed the constant velocity's guess until the estimate
  // stood and then drove backwards while the robot drove on. Along the directions the walls barely
  // fix, the registration now keeps near the guess (FrontEndConfig::weak_direction_information).
  const dpcr::MapperConfig defaults;
  REQUIRE(defaults.front_end.weak_direction_information > 0.0f);
  dpcr::MapperConfig as_registered;
  as_registered.front_end.weak_direction_information = 0.0f;
  const dpcr::test::Xv11RunResult with = GyroOnlyRun(53, 5.0, defaults), without = GyroOnlyRun(53, 5.0, as_registered);
  INFO("seed 53, 5 min: mean / max error " << with.mean_error_m << " / " << with.max_error_m << " m; as registered "
                                            << without.mean_error_m << " / " << without.max_error_m << " m");
  CHECK(with.max_error_m < 0.3);
  // The scenario needs the change: as registered, the estimate ended metres from the robot.
  CHECK(without.max_error_m > 1.0);
}
