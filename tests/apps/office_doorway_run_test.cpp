// End to end: an XV-11 (6 m reach) on a robot with a gyro and no wheel encoders, through the
// simulated office, whose rooms are 7 m long. In a doorway between two rooms nothing across the way
// is within reach; the registrations there are degenerate and the pose along the way is the
// constant velocity's guess. A guess that took each such registered step whole also took what the
// registration let slide, sideways and backwards, and the next scans registered close to it: the
// estimate drove off while the robot drove on, and mapped the next room metres away. A
// differential drive cannot move sideways (FrontEndConfig::degenerate_guess_forward). And where
// the robot turns in place in such a doorway, each degenerate registration walked the pose a few
// centimetres while it stood (FrontEndConfig::turn_holds_translation).
#include <catch2/catch.hpp>

#include "tests/apps/xv11_apartment_run.hpp"

namespace {

dpcr::test::Xv11RunResult GyroOnlyOfficeRun(std::uint64_t seed, dpcr::MapperConfig config) {
  dpcr::sim::SimConfig sim_config;
  sim_config.seed = seed;
  sim_config.duration_min = 15.0;
  sim_config.lidar = dpcr::sim::Xv11LidarConfig();
  const dpcr::test::Xv11RunResult run = dpcr::test::RunXv11GyroOnly("office", sim_config, config);
  REQUIRE(run.scans > 1000);
  return run;
}

}  // namespace

TEST_CASE("A gyro-only robot does not slide away through the doorways of long rooms") {
  const dpcr::MapperConfig defaults;
  REQUIRE(defaults.front_end.degenerate_guess_forward);
  dpcr::MapperConfig as_registered;
  as_registered.front_end.degenerate_guess_forward = false;
  // Measured when written, seeds 1-16: runs ever over 1 m off 3 (mean errors summed 1.4 m), with
  // the steps as registered 8 (5.4 m); since turns hold the translation
  // (FrontEndConfig::turn_holds_translation) 0 (0.34 m) against 4 (5.7 m). Degenerate stretches
  // are still guesses: a robot that stops or drives off in a doorway is not followed there
  // (docs/back-end.md).
  int far_with = 0, far_without = 0;
  double sum_with = 0.0, sum_without = 0.0;
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    const dpcr::test::Xv11RunResult with = GyroOnlyOfficeRun(seed, defaults), without = GyroOnlyOfficeRun(seed, as_registered);
    INFO("seed " << seed << ": mean / max error " << with.mean_error_m << " / " << with.max_error_m << " m, the steps as registered "
                 << without.mean_error_m << " / " << without.max_error_m << " m");
    far_with += with.max_error_m > 1.0 ? 1 : 0;
    far_without += without.max_error_m > 1.0 ? 1 : 0;
    sum_with += with.mean_error_m;
    sum_without += without.mean_error_m;
  }
  INFO("runs ever over 1 m off: " << far_with << " of 16 (mean errors summed " << sum_with << " m), the steps as registered "
                                  << far_without << " (" << sum_without << " m)");
  CHECK(far_with <= 4);
  CHECK(sum_with < 0.5 * sum_without);
  // The scenario needs the change: with the steps as registered more runs drove off.
  CHECK(far_without >= 3);
}

TEST_CASE("A gyro-only robot that turns in place in a doorway stays where it turns") {
  const dpcr::MapperConfig defaults;
  REQUIRE(defaults.front_end.turn_holds_translation);
  dpcr::MapperConfig weak_prior;
  weak_prior.front_end.turn_holds_translation = false;
  // Measured when written, seeds 17-28: runs over 0.2 m mean error 1 (mean errors summed 0.87 m),
  // with the weak translation prior through the turns 5 (8.4 m). dpcr-sim, seeds 1-40: 14 -> 6.
  int off_with = 0, off_without = 0;
  double sum_with = 0.0, sum_without = 0.0;
  for (std::uint64_t seed = 17; seed <= 28; ++seed) {
    const dpcr::test::Xv11RunResult with = GyroOnlyOfficeRun(seed, defaults), without = GyroOnlyOfficeRun(seed, weak_prior);
    INFO("seed " << seed << ": mean / max error " << with.mean_error_m << " / " << with.max_error_m << " m, the weak prior "
                 << without.mean_error_m << " / " << without.max_error_m << " m");
    off_with += with.mean_error_m > 0.2 ? 1 : 0;
    off_without += without.mean_error_m > 0.2 ? 1 : 0;
    sum_with += with.mean_error_m;
    sum_without += without.mean_error_m;
  }
  INFO("runs over 0.2 m: " << off_with << " of 12 (mean errors summed " << sum_with << " m), the weak prior " << off_without
                           << " (" << sum_without << " m)");
  CHECK(off_with <= 3);
  CHECK(sum_with < 0.5 * sum_without);
  // The scenario needs the change: with the weak prior more runs walked off.
  CHECK(off_without >= 4);
}
