// Which part of a run's error the back end's anchors carry and which lies inside the regional
// maps. A scan's final pose is its map's anchor times its pose in that map (FinalizeTrajectory).
// Replacing each map's anchor by the one that fits the ground truth of that map's scans best
// gives the error a perfect back end would leave (the maps as the front end built them); the
// difference to the run's own error is the back end's share.
#pragma once

#include <cstdint>
#include <vector>

#include "host_sim/eval/trajectory.hpp"

namespace dpcr::eval {

// One scan as the mapper left it: its final pose, the regional map it went into (-1: none) and
// its pose in that map's frame.
struct MappedScan {
  StampedPose estimate;
  int region = -1;
  dpcr::Pose2 in_region;
};

struct RegionAnchorError {
  int region = -1;
  std::size_t scans = 0;           // with ground truth
  double anchor_offset_m = 0.0;    // anchor against the best-fitting one, at the map's scans' centroid
  double anchor_offset_deg = 0.0;
  double in_map_mean_m = 0.0;      // mean position error of the map's scans with the best anchor
};

// One graph edge (a relative pose between two maps' anchors, measured by the mapper).
struct AnchorEdge {
  int from = 0;
  int to = 0;
  int kind = 0;  // dpcr::EdgeKind
  dpcr::Pose2 measurement;  // `to`'s anchor in `from`'s frame
};

// An edge's measurement against the relative pose of the two maps' best anchors (what a perfect
// measurement would say) and against their final anchors (what the graph made of it).
struct EdgeError {
  AnchorEdge edge;
  double truth_m = 0.0, truth_deg = 0.0;  // at `to`'s anchor, in metres and degrees
  double final_m = 0.0, final_deg = 0.0;
};

struct AnchorDecomposition {
  double loc_err_ave_m = 0.0;               // the run's own (as EvaluateAgainstGroundTruth)
  double best_anchors_loc_err_ave_m = 0.0;  // every map at its best-fitting anchor
  std::vector<RegionAnchorError> regions;   // the maps holding scans with ground truth, by index
  std::vector<EdgeError> edges;             // those between two such maps
};

// `anchors[r]`: map r's final anchor. The best anchor of a map takes the mean heading offset of
// its scans against the truth, then the mean position offset (closed form; a map whose scans all
// stand in one spot still gets a heading). LocErr_ave is sampled and start-aligned as in
// EvaluateAgainstGroundTruth; scans in no map keep their pose in both figures.
// `edges` (optional): the graph's edges, each checked against the best anchors.
AnchorDecomposition DecomposeByAnchors(const std::vector<MappedScan>& scans, const std::vector<dpcr::Pose2>& anchors,
                                       const Trajectory& ground_truth, double sample_period_s = 1.0,
                                       std::int64_t tolerance_us = 10000, const std::vector<AnchorEdge>& edges = {});

}  // namespace dpcr::eval
