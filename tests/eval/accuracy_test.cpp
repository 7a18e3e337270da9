// LocErr_ave, ATE and the relations metric against hand-computed cases.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

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

TEST_CASE("The rigid-aligned LocErr_ave leaves out the start pose's heading error") {
  // Every position right, but the first pose's heading 0.2 deg off: the start alignment turns the
  // whole run about the start, the least-squares alignment does not.
  Trajectory gt, est;
  const float heading_error = 0.2f * dpcr::kPi / 180.0f;
  for (int i = 0; i < 10; ++i) {
    gt.push_back({i * 1000000LL, Pose2{static_cast<float>(i), 0.0f, 0.0f}});
    est.push_back({i * 1000000LL, Pose2{static_cast<float>(i), 0.0f, i == 0 ? heading_error : 0.0f}});
  }
  const auto a = dpcr::eval::EvaluateAgainstGroundTruth(est, gt, 1.0);
  REQUIRE(a.loc_err_ave_m == Approx(9.0 * std::sin(heading_error)).margin(1e-5));  // 3.1 cm at 9 m
  REQUIRE(a.rigid_loc_err_ave_m == Approx(0.0).margin(1e-5));
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

TEST_CASE("Relations files are read with exact stamps, a bad stamp names the file and line") {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("dpcr_relations_" + std::to_string(::getpid()) + ".txt")).string();
  {
    std::ofstream f(path);
    f << "# t1 t2 x y z roll pitch yaw\n976052857.337530 976052858.1 0.5 -0.25 0 0 0 0.1\n";
  }
  const auto rel = dpcr::eval::ReadRelationsFile(path);
  REQUIRE(rel.size() == 1);
  REQUIRE(rel[0].t1_us == 976052857337530LL);
  REQUIRE(rel[0].t2_us == 976052858100000LL);
  REQUIRE(rel[0].delta.x == 0.5f);
  REQUIRE(rel[0].delta.theta == 0.1f);
  {
    std::ofstream f(path, std::ios::app);
    f << "1e9 2 0 0 0 0 0 0\n";
  }
  REQUIRE_THROWS_WITH(dpcr::eval::ReadRelationsFile(path), Catch::Contains(path + ": line 3: bad timestamp"));
  std::remove(path.c_str());
}
