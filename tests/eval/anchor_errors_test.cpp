// The anchors' share of a run's error (DecomposeByAnchors) on runs built by hand: two square maps
// side by side, the robot driving a lap through both, one second per pose.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "host_sim/eval/accuracy.hpp"
#include "host_sim/eval/anchor_errors.hpp"

using dpcr::Pose2;
using dpcr::eval::MappedScan;
using dpcr::eval::StampedPose;
using dpcr::eval::Trajectory;

namespace {

struct HandRun {
  Trajectory truth;
  std::vector<Pose2> true_anchors{Pose2{0.0f, 0.0f, 0.0f}, Pose2{4.0f, 0.0f, 0.0f}};
  std::vector<int> region;
};

// 40 poses: a lap of an 8 m x 2 m loop; x < 4 m in map 0, beyond in map 1.
HandRun Lap() {
  HandRun run;
  for (int i = 0; i < 40; ++i) {
    const float s = static_cast<float>(i) / 40.0f * 20.0f;  // path length along the loop
    Pose2 p;
    if (s < 8.0f) p = Pose2{s, 0.0f, 0.0f};
    else if (s < 10.0f) p = Pose2{8.0f, s - 8.0f, dpcr::kPi / 2};
    else if (s < 18.0f) p = Pose2{18.0f - s, 2.0f, dpcr::kPi};
    else p = Pose2{0.0f, 20.0f - s, -dpcr::kPi / 2};
    run.truth.push_back({i * 1000000LL, p});
    run.region.push_back(p.x < 4.0f ? 0 : 1);
  }
  return run;
}

// The mapper's view: each pose in its map under the true anchors, disturbed by `in_map_error`,
// and the final pose under the anchors the back end ended with.
std::vector<MappedScan> Mapped(const HandRun& run, const std::vector<Pose2>& anchors, float in_map_error) {
  std::vector<MappedScan> scans;
  for (std::size_t i = 0; i < run.truth.size(); ++i) {
    const int r = run.region[i];
    Pose2 in_region = run.true_anchors[static_cast<std::size_t>(r)].Inverse() * run.truth[i].pose;
    if (i % 2 == 1) in_region.y += in_map_error;  // every other scan held 'in_map_error' off in its map
    scans.push_back({{run.truth[i].stamp_us, anchors[static_cast<std::size_t>(r)] * in_region}, r, in_region});
  }
  return scans;
}

}  // namespace

TEST_CASE("A perfect run has no error from anchors or maps") {
  const HandRun run = Lap();
  const auto d = dpcr::eval::DecomposeByAnchors(Mapped(run, run.true_anchors, 0.0f), run.true_anchors, run.truth);
  REQUIRE(d.loc_err_ave_m == Approx(0.0).margin(1e-5));
  REQUIRE(d.best_anchors_loc_err_ave_m == Approx(0.0).margin(1e-5));
  REQUIRE(d.regions.size() == 2);
}

TEST_CASE("A wrong anchor is the anchors' share, and its offset is reported") {
  const HandRun run = Lap();
  std::vector<Pose2> anchors = run.true_anchors;
  anchors[1] = Pose2{4.1f, 0.05f, 0.02f};  // map 1 placed 10 cm, 5 cm and 1.15 deg off
  const auto d = dpcr::eval::DecomposeByAnchors(Mapped(run, anchors, 0.0f), anchors, run.truth);
  REQUIRE(d.loc_err_ave_m > 0.1);
  REQUIRE(d.best_anchors_loc_err_ave_m == Approx(0.0).margin(1e-4));
  REQUIRE(d.regions[0].anchor_offset_m == Approx(0.0).margin(1e-4));
  REQUIRE(d.regions[1].anchor_offset_deg == Approx(0.02 * 180.0 / static_cast<double>(dpcr::kPi)).margin(1e-3));
  REQUIRE(d.regions[1].anchor_offset_m > 0.1);
  REQUIRE(d.regions[1].in_map_mean_m == Approx(0.0).margin(1e-4));
}

TEST_CASE("Error inside a map stays with the map: the best anchor only takes its mean") {
  // Every other scan 3 cm off: no anchor removes that; the best one sits half-way (1.5 cm).
  const HandRun run = Lap();
  const auto d = dpcr::eval::DecomposeByAnchors(Mapped(run, run.true_anchors, 0.03f), run.true_anchors, run.truth);
  REQUIRE(d.loc_err_ave_m == Approx(0.03).margin(1e-4));
  REQUIRE(d.best_anchors_loc_err_ave_m == Approx(0.015).margin(0.002));
  for (const auto& r : d.regions) {
    REQUIRE(r.in_map_mean_m == Approx(0.015).margin(0.002));
    REQUIRE(r.anchor_offset_m == Approx(0.015).margin(0.002));
  }
}

TEST_CASE("Scans in no map keep their pose, and the run's own figure matches EvaluateAgainstGroundTruth") {
  const HandRun run = Lap();
  std::vector<Pose2> anchors = run.true_anchors;
  anchors[0] = Pose2{0.0f, 0.2f, 0.0f};
  std::vector<MappedScan> scans = Mapped(run, anchors, 0.0f);
  scans[5].region = -1;  // lost: its online pose, 0.5 m off, is all there is
  scans[5].estimate.pose.x += 0.5f;
  Trajectory estimate;
  for (const auto& s : scans) estimate.push_back(s.estimate);
  const auto d = dpcr::eval::DecomposeByAnchors(scans, anchors, run.truth);
  const auto a = dpcr::eval::EvaluateAgainstGroundTruth(estimate, run.truth);
  REQUIRE(d.loc_err_ave_m == Approx(a.loc_err_ave_m).margin(1e-6));
  // The first sample is scan 0, in map 0 whose anchor is 0.2 m off: start-aligned, map 0 is
  // right and map 1 is 0.2 m off; with the best anchors only the lost scan keeps an error.
  REQUIRE(d.best_anchors_loc_err_ave_m > 0.0);
  REQUIRE(d.best_anchors_loc_err_ave_m < d.loc_err_ave_m);
  std::size_t in_map0 = 0;
  for (const auto& s : scans) in_map0 += s.region == 0 ? 1 : 0;
  REQUIRE(d.regions[0].scans == in_map0);  // scan 5 left out of map 0's fit
}

TEST_CASE("An edge is checked against the best anchors' relation and against the final anchors") {
  // Map 1 ends 2 cm and 0.01 rad off; one edge measured the truth, one what the graph ended with,
  // one between a map and a map that holds no scan (skipped).
  const HandRun run = Lap();
  std::vector<Pose2> anchors = run.true_anchors;
  anchors[1] = Pose2{4.02f, 0.0f, 0.01f};
  anchors.push_back(Pose2{8.0f, 0.0f, 0.0f});
  const Pose2 truth = run.true_anchors[0].Inverse() * run.true_anchors[1];
  const Pose2 graph = anchors[0].Inverse() * anchors[1];
  const std::vector<dpcr::eval::AnchorEdge> edges = {{0, 1, 1, truth}, {0, 1, 2, graph}, {1, 2, 0, truth}};
  const auto d = dpcr::eval::DecomposeByAnchors(Mapped(run, anchors, 0.0f), anchors, run.truth, 1.0, 10000, edges);
  REQUIRE(d.edges.size() == 2);
  REQUIRE(d.edges[0].edge.kind == 1);
  REQUIRE(d.edges[0].truth_m == Approx(0.0).margin(1e-4));
  REQUIRE(d.edges[0].truth_deg == Approx(0.0).margin(1e-3));
  REQUIRE(d.edges[0].final_m == Approx(0.02).margin(1e-4));
  REQUIRE(d.edges[0].final_deg == Approx(0.01 * 180.0 / static_cast<double>(dpcr::kPi)).margin(1e-3));
  REQUIRE(d.edges[1].truth_m == Approx(0.02).margin(1e-4));
  REQUIRE(d.edges[1].truth_deg == Approx(0.01 * 180.0 / static_cast<double>(dpcr::kPi)).margin(1e-3));
  REQUIRE(d.edges[1].final_m == Approx(0.0).margin(1e-4));
}
