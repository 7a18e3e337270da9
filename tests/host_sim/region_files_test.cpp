// regions.tsv and graph.tsv (host_sim/output/region_files.hpp): each scan's map and pose in it,
// the final anchors and edges, read back as written.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "host_sim/output/region_files.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

std::vector<std::vector<std::string>> ReadRows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::vector<std::string> row;
    std::string f;
    while (std::getline(fields, f, '\t')) row.push_back(f);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST_CASE("regions.tsv holds each scan's map and pose in it and graph.tsv the final anchors and edges") {
  const dpcr::test::ScopedTempDir dir("region_files");
  dpcr::output::RunRecord run;
  run.estimate = {{1000000, dpcr::Pose2{0.0f, 0.0f, 0.0f}}, {1100000, dpcr::Pose2{4.5f, 0.25f, 0.1f}},
                  {1250000, dpcr::Pose2{7.0f, -1.0f, 3.0f}}};
  run.scan_region = {0, 1, -1};  // the last scan went into no map: its pose is the run's
  run.scan_in_region = {dpcr::Pose2{0.0f, 0.0f, 0.0f}, dpcr::Pose2{0.5f, 0.25f, 0.1f}, dpcr::Pose2{}};
  run.final_anchors = {dpcr::Pose2{0.0f, 0.0f, 0.0f}, dpcr::Pose2{4.0f, 0.0f, 0.0f}};
  run.final_edges = {{0, 1, 1, dpcr::Pose2{4.01f, -0.02f, 0.005f}}};
  dpcr::output::WriteRegionFiles(dir.str(), run);

  const auto regions = ReadRows(dir.str() + "/regions.tsv");
  REQUIRE(regions.size() == 3);
  CHECK(regions[1] == std::vector<std::string>{"1.100000", "1", "0.5", "0.25", "0.100000001"});
  CHECK(regions[2] == std::vector<std::string>{"1.250000", "-1", "7", "-1", "3"});

  const auto graph = ReadRows(dir.str() + "/graph.tsv");
  REQUIRE(graph.size() == 3);
  CHECK(graph[1] == std::vector<std::string>{"anchor", "1", "4", "0", "0"});
  CHECK(graph[2] == std::vector<std::string>{"edge", "0", "1", "map_match", "4.01000023", "-0.0199999996", "0.00499999989"});
}

TEST_CASE("Region files into a directory that does not exist fail naming the file") {
  const dpcr::test::ScopedTempDir dir("region_files_missing");
  dpcr::output::RunRecord run;
  CHECK_THROWS_WITH(dpcr::output::WriteRegionFiles(dir.str() + "/missing", run), Catch::Contains("missing/regions.tsv"));
}
