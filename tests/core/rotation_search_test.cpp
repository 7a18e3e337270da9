// Coarse pose search (core/registration/rotation_search.hpp) and the first registration that
// falls back on it (core/front_end/first_registration.hpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "core/config.hpp"
#include "core/front_end/first_registration.hpp"
#include "core/registration/plicp.hpp"
#include "core/registration/rotation_search.hpp"
#include "registration_fixtures.hpp"

using dpcr::Point2;
using dpcr::Pose2;
using dpcr_test::GridFixture;
using dpcr_test::Segment;
using dpcr_test::C;
using dpcr_test::SpanOf;

namespace {

constexpr float kDeg = dpcr::kPi / 180.0f;

// An L-shaped room with a cupboard (no symmetry a rotation could alias).
std::vector<Segment> LRoom() {
  const Point2 p0{C(20), C(20)}, p1{C(180), C(20)}, p2{C(180), C(100)}, p3{C(110), C(100)}, p4{C(110), C(180)},
      p5{C(20), C(180)};
  std::vector<Segment> w = {{p0, p1}, {p1, p2}, {p2, p3}, {p3, p4}, {p4, p5}, {p5, p0}};
  const Point2 b0{C(60), C(60)}, b1{C(80), C(60)}, b2{C(80), C(72)}, b3{C(60), C(72)};
  w.insert(w.end(), {{b0, b1}, {b1, b2}, {b2, b3}, {b3, b0}});
  return w;
}

// The front half of a noisy scan (a 180° lidar, as in the CARMEN logs).
std::vector<Point2> FrontScan(const std::vector<Segment>& walls, Pose2 pose, unsigned seed) {
  std::vector<Point2> front;
  for (const Point2& p : dpcr_test::SimulateScan(walls, pose, 720, 0.01f, seed)) {
    if (p.x > 0.0f) front.push_back(p);
  }
  return front;
}

struct Scene {
  GridFixture f;
  std::unique_ptr<dpcr::CoarseScoreGridStorage<144, 144>> grid = std::make_unique<dpcr::CoarseScoreGridStorage<144, 144>>();
  std::vector<Segment> walls = LRoom();
  Scene() {
    for (const Segment& w : walls) f.Draw(w);
    REQUIRE(f.Build() == dpcr::Status::kOk);
    grid->Build(*f.ref, dpcr::PoseSearchConfig{});
  }
};

}  // namespace

TEST_CASE("Coarse search recovers a scan rotated by 15 degrees and shifted, PLICP then refines it") {
  Scene s;
  REQUIRE_FALSE(s.grid->empty());
  const Pose2 truth{4.0f, 3.0f, 0.3f};
  const auto scan = FrontScan(s.walls, truth, 7);
  REQUIRE(scan.size() > 200);
  const Pose2 predicted{truth.x + 0.2f, truth.y - 0.1f, truth.theta - 15.0f * kDeg};
  const dpcr::PoseSearchResult r = dpcr::SearchPose(*s.grid, SpanOf(scan), predicted, dpcr::PoseSearchConfig{});
  INFO("search " << r.pose.x << " " << r.pose.y << " " << r.pose.theta / kDeg << " score " << r.score << " initial "
                 << r.initial_score);
  CHECK(r.moved);
  CHECK(r.score > r.initial_score + 0.2f);
  // Coarse: the score is flat within about half a 10 cm cell, and ties go towards the prediction.
  CHECK(std::fabs(dpcr::NormalizeAngle(r.pose.theta - truth.theta)) <= 2.5f * kDeg);
  CHECK(std::hypot(r.pose.x - truth.x, r.pose.y - truth.y) <= 0.15f);
  CHECK(r.evaluations == 41 * 49);
  const auto refined = dpcr::RegisterImproved(*s.f.ref, SpanOf(scan), r.pose, nullptr, dpcr::PlicpConfig{});
  CHECK(refined.verdict == dpcr::Status::kOk);
  CHECK(std::hypot(refined.pose.x - truth.x, refined.pose.y - truth.y) < 0.01f);
  CHECK(std::fabs(dpcr::NormalizeAngle(refined.pose.theta - truth.theta)) < 0.2f * kDeg);
}

TEST_CASE("Coarse search leaves a correctly predicted scan where it is") {
  Scene s;
  const Pose2 truth{4.0f, 3.0f, 0.3f};
  const auto scan = FrontScan(s.walls, truth, 8);
  const dpcr::PoseSearchResult r = dpcr::SearchPose(*s.grid, SpanOf(scan), truth, dpcr::PoseSearchConfig{});
  CHECK_FALSE(r.moved);
  CHECK(r.pose.x == truth.x);
  CHECK(r.pose.y == truth.y);
  CHECK(r.pose.theta == truth.theta);
  CHECK(r.score == r.initial_score);
  CHECK(r.score > 0.5f);
}

TEST_CASE("Coarse search on an empty reference changes nothing") {
  GridFixture f;
  REQUIRE(f.Build() == dpcr::Status::kOk);
  dpcr::CoarseScoreGridStorage<32, 32> grid;
  grid.Build(*f.ref, dpcr::PoseSearchConfig{});
  CHECK(grid.empty());
  const std::vector<Point2> scan = {{1.0f, 0.0f}, {0.0f, 1.0f}};
  const Pose2 p{1.0f, 2.0f, 0.5f};
  const auto r = dpcr::SearchPose(grid, SpanOf(scan), p, dpcr::PoseSearchConfig{});
  CHECK_FALSE(r.moved);
  CHECK(r.pose.theta == p.theta);
}

TEST_CASE("The first registration searches only when PLICP rejects, and then recovers") {
  Scene s;
  dpcr::FrontEndConfig config;
  std::vector<dpcr::Correspondence> scratch(1024);
  const dpcr::Span<dpcr::Correspondence> corr(scratch.data(), scratch.size());
  std::uint32_t grid_version = 0;
  dpcr::FirstRegistrationStats stats;
  const Pose2 truth{4.0f, 3.0f, 0.3f};
  const auto scan = FrontScan(s.walls, truth, 9);

  // A good prediction: PLICP accepts, no search.
  const Pose2 previous{3.8f, 3.0f, 0.25f};
  auto r = dpcr::RegisterFirst(*s.f.ref, s.grid.get(), &grid_version, 1, SpanOf(scan), previous,
                               Pose2{truth.x + 0.02f, truth.y, truth.theta + 1.0f * kDeg}, config, corr, &stats);
  CHECK(r.verdict == dpcr::Status::kOk);
  CHECK(stats.searches == 0);

  // A turn that odometry got 19° wrong (and 0.25 m): rejected first, then recovered from the search.
  r = dpcr::RegisterFirst(*s.f.ref, s.grid.get(), &grid_version, 1, SpanOf(scan), previous,
                          Pose2{truth.x + 0.2f, truth.y - 0.15f, truth.theta + 19.0f * kDeg}, config, corr, &stats);
  CHECK(stats.searches == 1);
  CHECK(stats.search_grid_builds == 1);
  CHECK(stats.search_recoveries == 1);
  CHECK(r.verdict == dpcr::Status::kOk);
  CHECK(std::hypot(r.pose.x - truth.x, r.pose.y - truth.y) < 0.01f);
  CHECK(std::fabs(dpcr::NormalizeAngle(r.pose.theta - truth.theta)) < 0.2f * kDeg);

  // Off: the rejection stands.
  config.search_on_rejection = false;
  r = dpcr::RegisterFirst(*s.f.ref, s.grid.get(), &grid_version, 1, SpanOf(scan), previous,
                          Pose2{truth.x + 0.2f, truth.y - 0.15f, truth.theta + 19.0f * kDeg}, config, corr, &stats);
  CHECK(stats.searches == 1);
}

TEST_CASE("The first registration trims above twice the lidar's range noise, only when the wheels measured the motion") {
  dpcr::MapperConfig config;
  const float configured = config.front_end.first_registration.trim_floor_m;  // 3 cm
  CHECK(dpcr::FirstRegistrationPlicp(config, true, false).trim_floor_m == configured);  // noise not known
  config.lidar.range_noise_m = 0.025f;  // an LD06 at 3 m
  CHECK(dpcr::FirstRegistrationPlicp(config, true, false).trim_floor_m == Approx(0.05f));
  CHECK(dpcr::FirstRegistrationPlicp(config, false, false).trim_floor_m == configured);  // a guessed de-skew: trimmed as before
  CHECK(dpcr::FirstRegistrationPlicp(config, true, false).huber_m == config.front_end.first_registration.huber_m);
  config.lidar.range_noise_m = 0.01f;  // a SICK: under the floor
  CHECK(dpcr::FirstRegistrationPlicp(config, true, false).trim_floor_m == configured);
  config.lidar.range_noise_m = 0.4f;  // never beyond the gate
  CHECK(dpcr::FirstRegistrationPlicp(config, true, false).trim_floor_m == config.front_end.first_registration.gate_m);
  REQUIRE(dpcr::Validate(config) == dpcr::Status::kOk);
}

TEST_CASE("A sparse scan is allowed a mean residual of twice the lidar range noise in its first registration") {
  dpcr::MapperConfig config;
  const float bound = config.front_end.first_registration.max_mean_residual_m;  // 4 cm
  // 150 of 360 readings (42 %) is sparse at the default share (45 %); 170 (47 %) is not.
  CHECK(dpcr::SparseScan(config.front_end, 150, 360));
  CHECK_FALSE(dpcr::SparseScan(config.front_end, 170, 360));
  CHECK_FALSE(dpcr::SparseScan(config.front_end, 0, 0));
  CHECK(dpcr::FirstRegistrationBase(config, true).max_mean_residual_m == bound);  // noise not known
  config.lidar.range_noise_m = 0.04f;  // an XV-11 at 3 m
  CHECK(dpcr::FirstRegistrationBase(config, true).max_mean_residual_m == Approx(0.08f));
  CHECK(dpcr::FirstRegistrationPlicp(config, false, true).max_mean_residual_m == Approx(0.08f));
  CHECK(dpcr::FirstRegistrationBase(config, false).max_mean_residual_m == bound);
  config.lidar.range_noise_m = 0.01f;  // a SICK: twice its noise is under the bound, which stays
  CHECK(dpcr::FirstRegistrationBase(config, true).max_mean_residual_m == bound);
  config.lidar.range_noise_m = 0.04f;
  config.front_end.sparse_scan_share = 0.0f;  // off
  CHECK_FALSE(dpcr::SparseScan(config.front_end, 10, 360));
  REQUIRE(dpcr::Validate(config) == dpcr::Status::kOk);
}
