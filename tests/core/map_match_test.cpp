// A map-to-map registration repeated for a pair (BackEnd::OnRegionLeft's jobs) starts from the
// pair's previous measurement, not from the graph's estimate. In a corridor of look-alike doorways
// the registration ends near where it starts: started from a graph bent by a wrong closure, it
// measured the bend and held it in place (intel.clf: docs/back-end.md, "Map-to-map
// registrations that do not echo the graph").
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "tests/core/two_region_back_end.hpp"

using dpcr::Pose2;
using dpcr_test::Segment;

namespace {

// 12 m of corridor, 1.5 m wide, along x, with a doorway every metre in each wall (a 0.4 m gap
// between jambs 0.3 m deep): seen from anywhere it looks the same a whole metre further on.
std::vector<Segment> DoorwayCorridor() {
  std::vector<Segment> walls;
  for (int k = -6; k < 6; ++k) {
    const float x = static_cast<float>(k);
    for (const float y : {-0.75f, 0.75f}) {
      const float out = y < 0.0f ? -0.3f : 0.3f;
      walls.push_back({{x + 0.2f, y}, {x + 0.8f, y}});
      walls.push_back({{x + 0.8f, y}, {x + 0.8f, y + out}});
      walls.push_back({{x + 1.2f, y}, {x + 1.2f, y + out}});
    }
  }
  return walls;
}

// Two regions, 4 m apart along the corridor, whose maps hold the same corridor in their own frames
// (as they would: each is the corridor seen from its anchor, 4 doorways on).
struct Setup : dpcr_test::TwoRegionBackEnd {
  Setup() { Start(DoorwayCorridor(), Pose2{4.0f, 0.0f, 0.0f}); }

  // The robot leaves region 1: its map is registered to region 0's (two vertices: no optimisation,
  // the anchors stay where the test puts them).
  void LeaveRegion1() {
    back_end->OnRegionLeft(regions(), 1);
    for (int step = 0; step < 100 && back_end->busy(); ++step) (void)back_end->Step(regions());
    REQUIRE_FALSE(back_end->busy());
  }
  const dpcr::GraphEdge* MapMatch() const {
    const int k = graph->FindEdge(dpcr::EdgeKind::kMapMatch, 0, 1);
    return k >= 0 ? &graph->edge(k) : nullptr;
  }
};

}  // namespace

TEST_CASE("A map-to-map registration repeated for a pair does not measure the graph's bend") {
  Setup s;
  s.LeaveRegion1();
  REQUIRE(s.back_end->counters().map_match_edges == 1);
  const dpcr::GraphEdge* first = s.MapMatch();
  REQUIRE(first != nullptr);
  // The first registration starts from the graph's estimate, which is right here.
  CHECK(std::fabs(first->measurement.x - 4.0f) < 0.03f);
  CHECK(std::fabs(first->measurement.y) < 0.03f);
  CHECK(std::fabs(first->measurement.theta) < 0.01f);

  // A wrong closure elsewhere bent the graph: region 1 is believed 0.7 m further along, nearer the
  // next doorway than its own. The robot leaves region 1 again.
  s.maps[1].anchor = Pose2{4.7f, 0.0f, 0.0f};
  s.LeaveRegion1();
  REQUIRE(s.back_end->counters().map_match_edges == 2);  // measured again, and replaced
  const dpcr::GraphEdge* again = s.MapMatch();
  REQUIRE(again != nullptr);
  // Started from the bent estimate it ended 4.61 m along (checked with the graph's estimate as the
  // start): it measured the bend. Started from its previous measurement it finds the maps where
  // they were.
  CHECK(std::fabs(again->measurement.x - 4.0f) < 0.03f);
  CHECK(std::fabs(again->measurement.theta) < 0.01f);
}

TEST_CASE("The pose graph finds an edge by kind and vertices") {
  dpcr::PoseGraphStorage<3, 4> g;
  for (int i = 0; i < 3; ++i) REQUIRE(g.AddVertex(Pose2{static_cast<float>(i), 0.0f, 0.0f}) == dpcr::Status::kOk);
  dpcr::GraphEdge e;
  e.from = 0;
  e.to = 2;
  e.kind = dpcr::EdgeKind::kLoop;
  e.information = Eigen::Matrix3f::Identity();
  REQUIRE(g.AddOrReplaceEdge(e) == dpcr::Status::kOk);
  e.kind = dpcr::EdgeKind::kMapMatch;
  REQUIRE(g.AddOrReplaceEdge(e) == dpcr::Status::kOk);
  CHECK(g.FindEdge(dpcr::EdgeKind::kMapMatch, 0, 2) == 1);
  CHECK(g.FindEdge(dpcr::EdgeKind::kLoop, 0, 2) == 0);
  CHECK(g.FindEdge(dpcr::EdgeKind::kMapMatch, 2, 0) == -1);  // the direction counts
  CHECK(g.FindEdge(dpcr::EdgeKind::kSequence, 0, 2) == -1);
}
