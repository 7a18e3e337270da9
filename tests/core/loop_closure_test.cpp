// A loop closure in a featureless corridor (BackEnd::BeginLoopClosure / FinishLoopClosure): the
// map cannot fix the submap along the corridor, so the search is ambiguous and PLICP refines from
// the graph's guess. Without a prior that refinement is degenerate and rejected (the corridor's
// block of the map stayed off on intel.clf); with BackEndConfig::closure_prior_info it is kept,
// corrects what the walls do measure (across the corridor, the heading) and stays at the guess
// along it.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "tests/core/two_region_back_end.hpp"

using dpcr::Point2;
using dpcr::Pose2;
using dpcr_test::Segment;

namespace {

// 12 m of corridor, 1.55 m wide, along the x axis of region 0's frame (its anchor at the origin);
// the walls run through cell centres (5 cm cells), so the map holds them where they are.
std::vector<Segment> Corridor() { return {{{-6.0f, -0.775f}, {6.0f, -0.775f}}, {{-6.0f, 0.775f}, {6.0f, 0.775f}}}; }

// Region 0 holds the corridor; region 1, where the robot's pose is known, is its neighbour along
// it (its map plays no part in a closure into region 0).
struct Setup : dpcr_test::TwoRegionBackEnd {
  explicit Setup(float closure_prior_info) {
    config.closure_prior_info = closure_prior_info;
    Start(Corridor(), Pose2{4.0f, 0.0f, 0.0f});
  }

  // The robot re-enters region 0 from region 1 with its submap (here one scan, in its own frame)
  // believed at `believed`; the search runs in slices to its end, then the closure is decided.
  dpcr::LoopClosureResult Close(const std::vector<Point2>& submap, const Pose2& believed) {
    const dpcr::Span<const Point2> points(submap.data(), submap.size());
    REQUIRE(back_end->BeginLoopClosure(regions(), 0, 1, points, believed, 10.0f));
    for (int step = 0; step < 1000; ++step) {
      if (back_end->Step(regions()).loop_search_done) return back_end->FinishLoopClosure(regions(), points, believed);
    }
    FAIL("the search did not end");
    return {};
  }
};

// Truly at 1.0 m along the corridor, 0.1 m left of its middle; believed 0.12 m further left and
// 1.7 degrees off: within what PLICP alone is trusted with (BackEndConfig::search_base_m, _rad).
const Pose2 kTruth{1.0f, 0.1f, 0.05f};
const Pose2 kBelieved{1.0f, 0.22f, 0.08f};

}  // namespace

TEST_CASE("A corridor re-entry closes with the closure prior and is refused as degenerate without it") {
  const std::vector<Point2> scan = dpcr_test::SimulateScan(Corridor(), kTruth, 360, 0.01f, 5);
  REQUIRE(scan.size() > 300);

  Setup without(0.0f);
  const dpcr::LoopClosureResult refused = without.Close(scan, kBelieved);
  CHECK(refused.verdict == dpcr::Status::kRejected);
  CHECK(without.back_end->last_closure().refinement == dpcr::Status::kRejected);
  CHECK(without.back_end->counters().loop_closures_accepted == 0);

  Setup with(10.0f);
  const dpcr::LoopClosureResult closed = with.Close(scan, kBelieved);
  REQUIRE(closed.verdict == dpcr::Status::kOk);
  CHECK(with.back_end->counters().loop_closures_accepted == 1);
  // The search could not fix the submap along the corridor (the guess was refined)...
  CHECK(with.back_end->last_closure().search.verdict != dpcr::Status::kOk);
  // ...the walls fix it across the corridor and in heading, the prior holds it along it.
  const Pose2& in_region = closed.submap_in_region;
  CHECK(std::fabs(in_region.y - kTruth.y) < 0.02f);
  CHECK(std::fabs(dpcr::NormalizeAngle(in_region.theta - kTruth.theta)) < 0.005f);
  CHECK(std::fabs(in_region.x - kBelieved.x) < 0.03f);
}
