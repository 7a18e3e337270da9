// The recorded scans of the trajectory's refinement (host_sim/output/trajectory_refinement.hpp): they
// read back to the millimetre, across the record's blocks, and a return out of its reach is counted,
// not stored.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "host_sim/output/trajectory_refinement.hpp"

using dpcr::Point2;
using dpcr::output::ScanPointRecord;

namespace {

std::vector<Point2> Scan(int n, float seed) {
  std::vector<Point2> points;
  for (int i = 0; i < n; ++i) {
    const float a = seed + 0.01f * static_cast<float>(i);
    points.push_back(Point2{12.0f * std::cos(a), -7.5f * std::sin(3.0f * a)});
  }
  return points;
}

}  // namespace

TEST_CASE("Recorded scans read back to the millimetre across the blocks of the record") {
  ScanPointRecord record;
  std::vector<std::vector<Point2>> scans;
  // 200 scans of 450 returns: 90 000 points, past the first block of 65 536.
  for (int s = 0; s < 200; ++s) {
    scans.push_back(s % 50 == 7 ? std::vector<Point2>() : Scan(450, 0.37f * static_cast<float>(s)));
    record.Append(dpcr::Span<const Point2>(scans.back().data(), scans.back().size()));
  }
  REQUIRE(record.scans() == 200);
  CHECK(record.points_not_stored() == 0);
  std::vector<Point2> out;
  for (std::size_t s = 0; s < scans.size(); ++s) {
    record.Scan(s, &out);
    REQUIRE(out.size() == scans[s].size());
    REQUIRE(record.points(s) == scans[s].size());
    for (std::size_t i = 0; i < out.size(); ++i) {
      CHECK(std::fabs(out[i].x - scans[s][i].x) <= 0.00051f);
      CHECK(std::fabs(out[i].y - scans[s][i].y) <= 0.00051f);
    }
  }
}

TEST_CASE("A return out of reach of the record is counted and left out of its scan") {
  ScanPointRecord record;
  const std::vector<Point2> scan = {{1.0f, 2.0f}, {40.0f, 0.0f}, {-3.0f, -32.9f}, {NAN, 1.0f}, {-32.0f, 32.0f}};
  record.Append(dpcr::Span<const Point2>(scan.data(), scan.size()));
  CHECK(record.points_not_stored() == 3);
  std::vector<Point2> out;
  record.Scan(0, &out);
  REQUIRE(out.size() == 2);
  CHECK(out[0].x == Approx(1.0f));
  CHECK(out[1].x == Approx(-32.0f));
  CHECK(out[1].y == Approx(32.0f));
}
