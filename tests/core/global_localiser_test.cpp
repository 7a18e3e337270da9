// The global search that finds a lost robot in its maps, and its local round (a robot without a
// heading sensor, searched for around where it believes it is: LocalisationConfig::near_window_m).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "core/back_end/back_end.hpp"
#include "core/back_end/back_end_config.hpp"
#include "core/back_end/global_localiser.hpp"
#include "tests/core/registration_fixtures.hpp"

using dpcr::Point2;
using dpcr::Pose2;
using dpcr_test::Segment;

namespace {

// An L-shaped room with a table and a cupboard (no symmetry), around the map frame's origin: the
// global round searches the region's square (the anchor at its centre) and a margin.
std::vector<Segment> Room() {
  std::vector<Segment> walls = {{{1, 1}, {9, 1}}, {{9, 1}, {9, 5}}, {{9, 5}, {5, 5}}, {{5, 5}, {5, 9}}, {{5, 9}, {1, 9}},
                                {{1, 9}, {1, 1}}, {{2.5f, 3}, {3.5f, 3}}, {{3.5f, 3}, {3.5f, 3.6f}}, {{7, 2}, {7.8f, 2}}};
  for (Segment& w : walls) {
    w.a = Point2{w.a.x - 5.0f, w.a.y - 5.0f};
    w.b = Point2{w.b.x - 5.0f, w.b.y - 5.0f};
  }
  return walls;
}

// A bare 6 m x 3 m room: every pose has a twin turned half a turn about the room's centre.
std::vector<Segment> SymmetricRoom() {
  return {{{-3, -1.5f}, {3, -1.5f}}, {{3, -1.5f}, {3, 1.5f}}, {{3, 1.5f}, {-3, 1.5f}}, {{-3, 1.5f}, {-3, -1.5f}}};
}

// Two closed rooms alike, side by side: every pose in one has a twin 2.6 m along x, same heading.
std::vector<Segment> TwinRooms() {
  std::vector<Segment> walls;
  for (float dx : {-1.3f, 1.3f}) {
    const std::vector<Segment> room = {{{-1.1f, -1.2f}, {1.1f, -1.2f}}, {{1.1f, -1.2f}, {1.1f, 1.2f}},
                                       {{1.1f, 1.2f}, {-1.1f, 1.2f}}, {{-1.1f, 1.2f}, {-1.1f, -1.2f}},
                                       {{0.3f, 0.5f}, {0.8f, 0.5f}}, {{0.8f, 0.5f}, {0.8f, 0.9f}}};
    for (Segment w : room) {
      w.a.x += dx;
      w.b.x += dx;
      walls.push_back(w);
    }
  }
  return walls;
}

// One regional map of the room (anchor at the origin) and the back end's scratch the search uses.
struct Setup {
  dpcr_test::GridFixture fixture;
  std::unique_ptr<dpcr::MatchGrid> match_grid = std::make_unique<dpcr::MatchGrid>(128, 128);
  std::vector<Point2> cloud = std::vector<Point2>(400);
  std::vector<dpcr::MatchCell> rotated = std::vector<dpcr::MatchCell>(512);
  std::vector<dpcr::Correspondence> correspondences = std::vector<dpcr::Correspondence>(512);
  dpcr::RegionalMap map;
  dpcr::BackEndStorage storage;
  dpcr::LocalisationConfig config;
  dpcr::BackEndConfig back_end;
  explicit Setup(const std::vector<Segment>& walls = Room()) {
    fixture.grid->Reset(dpcr::CellIndex{-4, -4});  // the box from -6.4 m to 6.4 m
    for (const Segment& s : walls) fixture.Draw(s);
    map.grid = fixture.grid.get();
    map.scans_inserted = 1000;
    storage.match_grid = match_grid.get();
    storage.reference = fixture.ref.get();
    storage.cloud = dpcr::Span<Point2>(cloud.data(), cloud.size());
    storage.rotated = dpcr::Span<dpcr::MatchCell>(rotated.data(), rotated.size());
    storage.correspondences = dpcr::Span<dpcr::Correspondence>(correspondences.data(), correspondences.size());
  }
  // Steps a round to its end (each step bounded); the status and the fix.
  dpcr::Status Run(dpcr::GlobalLocaliser* localiser, dpcr::GlobalFix* fix) {
    for (int step = 0; step < 500; ++step) {
      const dpcr::Status st = localiser->Step(storage, dpcr::Span<const dpcr::RegionalMap>(&map, 1), 4.0f, dpcr::ReferenceConfig{},
                                              config, back_end, fix);
      if (st != dpcr::Status::kNotEnoughData) return st;
    }
    return dpcr::Status::kNotEnoughData;
  }
};

const Pose2 kTruth{1.2f, -1.9f, -0.3f};

std::vector<Point2> ScanAt(Pose2 at) { return dpcr_test::SimulateScan(Room(), at, 360, 0.01f, 3); }

}  // namespace

TEST_CASE("A local round finds the robot within its window around the believed pose, at any heading") {
  Setup s;
  const auto scan = ScanAt(kTruth);
  dpcr::GlobalLocaliser localiser;
  // Believed 0.5 m and 0.6 rad off: a second registration from there would not converge.
  const Pose2 believed = kTruth * Pose2{0.4f, -0.3f, 0.6f};
  localiser.BeginLocal(s.storage, dpcr::Span<const Point2>(scan.data(), scan.size()), s.config, 0, believed, 0.8f);
  REQUIRE(localiser.local());
  dpcr::GlobalFix fix;
  REQUIRE(s.Run(&localiser, &fix) == dpcr::Status::kOk);
  CHECK(fix.map == 0);
  CHECK(std::hypot(fix.in_map.x - kTruth.x, fix.in_map.y - kTruth.y) < 0.05f);
  CHECK(std::fabs(dpcr::NormalizeAngle(fix.in_map.theta - kTruth.theta)) < 0.03f);
}

TEST_CASE("A local round whose window misses the robot finds nothing, and guesses nothing") {
  Setup s;
  const auto scan = ScanAt(kTruth);
  dpcr::GlobalLocaliser localiser;
  // Believed in the other leg of the L, 5 m away, with a 0.6 m window.
  localiser.BeginLocal(s.storage, dpcr::Span<const Point2>(scan.data(), scan.size()), s.config, 0, Pose2{-2.0f, 2.0f, 0.0f}, 0.6f);
  dpcr::GlobalFix fix;
  const dpcr::Status st = s.Run(&localiser, &fix);
  INFO("fix at " << fix.in_map.x << ", " << fix.in_map.y << " score " << fix.score);
  CHECK(st == dpcr::Status::kRejected);
  // The global round over the whole map finds it.
  localiser.Begin(s.storage, dpcr::Span<const Point2>(scan.data(), scan.size()), s.config);
  REQUIRE(!localiser.local());
  REQUIRE(s.Run(&localiser, &fix) == dpcr::Status::kOk);
  CHECK(std::hypot(fix.in_map.x - kTruth.x, fix.in_map.y - kTruth.y) < 0.05f);
}

TEST_CASE("A held fix is kept across rounds until dropped") {
  Setup s;
  dpcr::GlobalLocaliser localiser;
  Pose2 held;
  CHECK_FALSE(localiser.Held(s.storage, &held));
  localiser.Hold(s.storage, Pose2{1.5f, -2.0f, 0.25f});
  const auto scan = ScanAt(kTruth);
  // A new round fills the cloud's front; the held pose sits past it.
  localiser.BeginLocal(s.storage, dpcr::Span<const Point2>(scan.data(), scan.size()), s.config, 0, kTruth, 0.4f);
  REQUIRE(localiser.Held(s.storage, &held));
  CHECK(held.x == 1.5f);
  CHECK(held.y == -2.0f);
  CHECK(held.theta == 0.25f);
  localiser.Drop();
  CHECK_FALSE(localiser.Held(s.storage, &held));
}

TEST_CASE("A round limited to the believed heading tells a room from its half-turned twin") {
  Setup s(SymmetricRoom());
  const Pose2 truth{1.0f, 0.5f, 0.2f};
  const auto scan = dpcr_test::SimulateScan(SymmetricRoom(), truth, 360, 0.01f, 5);
  const dpcr::Span<const Point2> cloud(scan.data(), scan.size());
  dpcr::GlobalLocaliser localiser;
  dpcr::GlobalFix fix;
  // Every heading: the twin at (-1.0, -0.5, 0.2 + pi) scores as well; the answer is ambiguous.
  localiser.Begin(s.storage, cloud, s.config);
  CHECK(s.Run(&localiser, &fix) == dpcr::Status::kRejected);
  CHECK(fix.second_score >= s.config.max_second_ratio * fix.score);
  // Within 0.35 rad of a heading believed 0.1 rad off: the twin is not searched.
  localiser.Begin(s.storage, cloud, s.config);
  localiser.LimitHeadings(truth.theta + 0.1f, 0.35f);
  REQUIRE(s.Run(&localiser, &fix) == dpcr::Status::kOk);
  CHECK(std::hypot(fix.in_map.x - truth.x, fix.in_map.y - truth.y) < 0.05f);
  CHECK(std::fabs(dpcr::NormalizeAngle(fix.in_map.theta - truth.theta)) < 0.03f);
}

TEST_CASE("A round limited to the believed heading still finds a look-alike at that heading ambiguous") {
  Setup s(TwinRooms());
  const Pose2 truth{-1.0f, -0.4f, 0.3f};
  const auto scan = dpcr_test::SimulateScan(TwinRooms(), truth, 360, 0.01f, 6);
  dpcr::GlobalLocaliser localiser;
  localiser.Begin(s.storage, dpcr::Span<const Point2>(scan.data(), scan.size()), s.config);
  localiser.LimitHeadings(truth.theta, 0.35f);
  dpcr::GlobalFix fix;
  // The map's square is searched in parts that each give a candidate: the twin room's pose
  // competes with the true one instead of being dropped as the lesser pose of one search.
  CHECK(s.Run(&localiser, &fix) == dpcr::Status::kRejected);
  INFO("best " << fix.score << " second " << fix.second_score);
  CHECK(fix.second_score >= s.config.max_second_ratio * fix.score);
}
