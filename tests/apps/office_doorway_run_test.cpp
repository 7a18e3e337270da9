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

#include <sstream>
#include <string>

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

// Runs of seeds first..last: how many passed `bound_m` (the run's largest error if `by_max`, else
// its mean error) and the mean errors summed.
struct Tally {
  int over = 0;
  double sum_mean_m = 0.0;
};

// The same seeds with two configurations, and a report of every run for the assertions.
struct Comparison {
  Tally with, without;
  std::string report;
};

Comparison CompareOfficeRuns(std::uint64_t first, std::uint64_t last, const dpcr::MapperConfig& with,
                             const dpcr::MapperConfig& without, const char* without_name, bool by_max, double bound_m) {
  Comparison c;
  std::ostringstream runs;
  runs << "mean / max error (m) by seed, defaults then " << without_name << ":";
  for (std::uint64_t seed = first; seed <= last; ++seed) {
    const dpcr::test::Xv11RunResult a = GyroOnlyOfficeRun(seed, with), b = GyroOnlyOfficeRun(seed, without);
    runs << "\n  " << seed << ": " << a.mean_error_m << " / " << a.max_error_m << ", " << b.mean_error_m << " / " << b.max_error_m;
    c.with.over += (by_max ? a.max_error_m : a.mean_error_m) > bound_m ? 1 : 0;
    c.without.over += (by_max ? b.max_error_m : b.mean_error_m) > bound_m ? 1 : 0;
    c.with.sum_mean_m += a.mean_error_m;
    c.without.sum_mean_m += b.mean_error_m;
  }
  std::ostringstream report;
  report << "runs over " << bound_m << " m" << (by_max ? " at some point" : " on average") << ": " << c.with.over << " of "
         << last - first + 1 << " (mean errors summed " << c.with.sum_mean_m << " m), " << without_name << " " << c.without.over
         << " (" << c.without.sum_mean_m << " m)\n"
         << runs.str();
  c.report = report.str();
  return c;
}

// The change holds the runs (at most `most_with` over the bound, half the summed error or less)
// where the scenario needs it (at least `least_without` over without the change).
void CheckComparison(const Comparison& c, int most_with, int least_without) {
  INFO(c.report);
  CHECK(c.with.over <= most_with);
  CHECK(c.with.sum_mean_m < 0.5 * c.without.sum_mean_m);
  CHECK(c.without.over >= least_without);
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
  // The scenario needs the change: with the steps as registered more runs drove off.
  CheckComparison(CompareOfficeRuns(1, 16, defaults, as_registered, "the steps as registered", true, 1.0), 4, 3);
}

TEST_CASE("A gyro-only robot that turns in place in a doorway stays where it turns") {
  const dpcr::MapperConfig defaults;
  REQUIRE(defaults.front_end.turn_holds_translation);
  dpcr::MapperConfig weak_prior;
  weak_prior.front_end.turn_holds_translation = false;
  // Measured when written, seeds 17-28: runs over 0.2 m mean error 1 (mean errors summed 0.87 m),
  // with the weak translation prior through the turns 5 (8.4 m). dpcr-sim, seeds 1-40: 14 -> 6.
  // The scenario needs the change: with the weak prior more runs walked off.
  CheckComparison(CompareOfficeRuns(17, 28, defaults, weak_prior, "the weak prior", false, 0.2), 3, 4);
}
