// LocErr_ave, ATE and the relations metric against hand-computed cases.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "host_sim/eval/accuracy.hpp"

using dpcr::Pose2;
using dpcr::eval::StampedPose;
using dpcr::eval::Trajectory;

TEST_CASE("MeanOfLargestTenth averages the top 10 percent") {
  std::vector<double> e;
  for (int i = 1; i <= 20; ++i) e.push_back(i);  // top 2 of 20: 20 and 19
  REQUIRE(dpcr::eval::MeanOfLargestTenth(e) == Approx(19.5));
  REQUIRE(dpcr::eval::MeanOfLargestTenth({3.0, 1.0}) == Approx(3.0));  // at least one
  REQUIRE(dpcr::eval::MeanOfLargestTenth({}) == 0.0);
}

TEST_CASE("Errors are measured after aligning the start pose") {
  Trajectory gt, est;
  for (int i = 0; i < 10; ++i) {
    gt.push_back({i * 1000000LL, Pose2{static_cast<float>(i), 0.0f, 0.0f}});
    // The estimate lives in another frame (rotated 90 deg, shifted) and drifts 0.1 m per step in y.
    const Pose2 frame{5.0f, -3.0f, dpcr::kPi / 2};
    est.push_back({i * 1000000LL, frame * Pose2{static_cast<float>(i), 0.1f * static_cast<float>(i), 0.0f}});
  }
  const auto a = dpcr::eval::EvaluateAgainstGroundTruth(est, gt, 1.0);
  REQUIRE(a.samples == 10);
  REQUIRE(a.max_err_m == Approx(0.9).margin(1e-4));
  REQUIRE(a.loc_err_ave_m == Approx(0.9).margin(1e-4));  // top 10 % of 10 samples = the largest
  REQUIRE(a.ate_rmse_m < a.max_err_m);                   // best-fit alignment does better
}

TEST_CASE("Sampling period and unmatched stamps are honoured") {
  Trajectory gt{{0, Pose2{}}, {500000, Pose2{}}, {1000000, Pose2{}}};
  Trajectory est{{0, Pose2{}}, {500000, Pose2{1, 0, 0}}, {1000000, Pose2{}}, {9000000, Pose2{}}};
  const auto a = dpcr::eval::EvaluateAgainstGroundTruth(est, gt, 1.0);
  REQUIRE(a.samples == 2);  // 0 and 1 s; the 0.5 s pose is between samples
  REQUIRE(a.unmatched == 1);
  REQUIRE(a.max_err_m == Approx(0.0).margin(1e-6));
}

TEST_CASE("Relations metric compares relative motions") {
  Trajectory est{{1000000, Pose2{0, 0, 0}}, {2000000, Pose2{1.0f, 0.0f, 0.1f}}, {3000000, Pose2{1.0f, 1.0f, 0.0f}}};
  std::vector<dpcr::eval::Relation> rel{
      {1000000, 2000000, Pose2{1.0f, 0.0f, 0.1f}},   // exact: error 0
      {1000000, 3000000, Pose2{1.0f, 0.7f, 0.0f}},   // 0.3 m off
      {1000000, 5000000, Pose2{}},                    // unmatched
  };
  const auto r = dpcr::eval::EvaluateRelations(est, rel);
  REQUIRE(r.matched == 2);
  REQUIRE(r.unmatched == 1);
  REQUIRE(r.trans_mean_m == Approx(0.15).margin(1e-5));
  REQUIRE(r.trans_std_m == Approx(std::sqrt(0.045)).margin(1e-5));
  REQUIRE(r.rot_mean_deg == Approx(0.0).margin(1e-4));
}

TEST_CASE("TUM files round-trip stamps exactly and reject malformed lines") {
  Trajectory t{{976052857337530LL, Pose2{1.5f, -2.0f, 3.0f}}};
  std::stringstream s;
  dpcr::eval::WriteTum(s, t);
  REQUIRE(s.str().rfind("976052857.337530 1.500000 -2.000000 0 0 0 ", 0) == 0);
  const Trajectory back = dpcr::eval::ReadTum(s);
  REQUIRE(back.size() == 1);
  REQUIRE(back[0].stamp_us == 976052857337530LL);
  REQUIRE(back[0].pose.theta == Approx(3.0f));
  std::istringstream bad("1.0 2.0 3.0\n");
  REQUIRE_THROWS_WITH(dpcr::eval::ReadTum(bad), Catch::Contains("line 1"));
}
