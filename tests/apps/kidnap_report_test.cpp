// dpcr-sim's relocalisation figures (host_sim/apps/kidnap_report.hpp) on hand-made fixes.
#include <catch2/catch.hpp>

#include <vector>

#include "host_sim/apps/kidnap_report.hpp"

using dpcr::Pose2;
using dpcr::apps::Recovery;

TEST_CASE("Every fix is measured, and those farther off than the threshold count as wrong") {
  // The map's frame is the world turned by 90 degrees: the truth is carried into it first.
  const Pose2 align{1.0f, 0.0f, dpcr::kPi / 2};
  std::vector<Recovery> fixes;
  const Pose2 truth{2.0f, 1.0f, 0.0f};
  const Pose2 in_map = align * truth;
  fixes.push_back({1'000'000, in_map, truth});                                              // exact
  fixes.push_back({2'000'000, Pose2{in_map.x + 0.2f, in_map.y, in_map.theta}, truth});       // 0.2 m off
  fixes.push_back({3'000'000, Pose2{in_map.x, in_map.y - 0.5f, in_map.theta + dpcr::kPi}, truth});  // turned round
  const nlohmann::json j = dpcr::apps::FixMetrics(fixes, align, 0.3);
  REQUIRE(j["fixes"] == 3);
  REQUIRE(j["wrong_fixes"] == 1);
  REQUIRE(j["max_error_m"].get<double>() == Approx(0.5).margin(1e-4));
  REQUIRE(j["max_error_deg"].get<double>() == Approx(180.0).margin(1e-2));
  REQUIRE(j["each"][0]["error_m"].get<double>() == Approx(0.0).margin(1e-5));
  REQUIRE(j["each"][1]["error_m"].get<double>() == Approx(0.2).margin(1e-4));
  REQUIRE(j["each"][2]["t_s"].get<double>() == Approx(3.0));
}

TEST_CASE("A run without fixes reports none") {
  const nlohmann::json j = dpcr::apps::FixMetrics({}, Pose2::Identity(), 0.3);
  REQUIRE(j["fixes"] == 0);
  REQUIRE(j["wrong_fixes"] == 0);
  REQUIRE(j["each"].empty());
}

TEST_CASE("A kidnap is recovered by the first fix after its put-down, not by one before it") {
  std::vector<dpcr::sim::KidnapEvent> kidnaps(1);
  kidnaps[0].lift_us = 10'000'000;
  kidnaps[0].down_us = 14'000'000;
  const Pose2 truth{1.0f, 1.0f, 0.0f};
  const std::vector<Recovery> fixes{{5'000'000, Pose2{9.0f, 9.0f, 0.0f}, truth},   // an earlier loss, far off
                                    {16'000'000, Pose2{1.05f, 1.0f, 0.0f}, truth}};  // 2 s after put-down
  const nlohmann::json j = dpcr::apps::KidnapMetrics(kidnaps, fixes, Pose2::Identity(), 3.0, 0.3);
  REQUIRE(j["kidnaps"] == 1);
  REQUIRE(j["recovered_in_time"] == 1);
  REQUIRE(j["wrong_fixes"] == 0);
  REQUIRE(j["each"][0]["time_to_recover_s"].get<double>() == Approx(2.0));
  REQUIRE(j["each"][0]["error_m"].get<double>() == Approx(0.05).margin(1e-4));
}
