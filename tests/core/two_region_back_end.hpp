// A back end over two regional maps that share one drawn grid, for tests that drive BackEnd
// directly (a loop closure, a map-to-map registration) without a front end.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/back_end/back_end.hpp"
#include "core/back_end/back_end_config.hpp"
#include "tests/core/registration_fixtures.hpp"

namespace dpcr_test {

struct TwoRegionBackEnd {
  GridFixture fixture;
  std::unique_ptr<dpcr::MatchGrid> match_grid = std::make_unique<dpcr::MatchGrid>(128, 128);
  std::unique_ptr<dpcr::PoseGraphStorage<4, 8>> graph = std::make_unique<dpcr::PoseGraphStorage<4, 8>>();
  std::vector<dpcr::Point2> cloud = std::vector<dpcr::Point2>(400);
  std::vector<dpcr::MatchCell> rotated = std::vector<dpcr::MatchCell>(512);
  std::vector<dpcr::Correspondence> correspondences = std::vector<dpcr::Correspondence>(512);
  std::vector<std::int32_t> jobs = std::vector<std::int32_t>(8);
  dpcr::RegionalMap maps[2];
  dpcr::BackEndConfig config;  // set before Start
  std::unique_ptr<dpcr::BackEnd> back_end;

  // Draws `walls` into the grid (its box from -6.4 m to 6.4 m), which both maps hold as their own
  // (1000 scans each); region 0's anchor is the origin, region 1's `anchor1`, created from region 0.
  void Start(const std::vector<Segment>& walls, const dpcr::Pose2& anchor1) {
    fixture.grid->Reset(dpcr::CellIndex{-4, -4});
    for (const Segment& s : walls) fixture.Draw(s);
    for (dpcr::RegionalMap& m : maps) {
      m.grid = fixture.grid.get();
      m.scans_inserted = 1000;
    }
    maps[1].anchor = anchor1;
    dpcr::BackEndStorage storage;
    storage.graph = graph.get();
    storage.match_grid = match_grid.get();
    storage.reference = fixture.ref.get();
    storage.cloud = dpcr::Span<dpcr::Point2>(cloud.data(), cloud.size());
    storage.rotated = dpcr::Span<dpcr::MatchCell>(rotated.data(), rotated.size());
    storage.correspondences = dpcr::Span<dpcr::Correspondence>(correspondences.data(), correspondences.size());
    storage.jobs = dpcr::Span<std::int32_t>(jobs.data(), jobs.size());
    back_end = std::make_unique<dpcr::BackEnd>(storage);
    back_end->Init(config, 4.0f, dpcr::ReferenceConfig{});
    back_end->AddRegion(regions(), 0, -1);
    back_end->AddRegion(regions(), 1, 0);
  }
  dpcr::Span<dpcr::RegionalMap> regions() { return dpcr::Span<dpcr::RegionalMap>(maps, 2); }
};

}  // namespace dpcr_test
