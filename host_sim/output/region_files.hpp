// regions.tsv and graph.tsv (dpcr-sim / dpcr-replay --write-regions): what trajectory.tum is made
// of, for analysis outside the run. trajectory.tum holds each scan at its map's final anchor
// times its pose in that map; these two files hold the factors: each scan's map and pose in it,
// and the final anchors and region-graph edges. With them a scan's error splits into its map's
// anchor and its place in the map, and a jump between two scans into the two maps' disagreement.
//
// regions.tsv, one line per scan:  stamp_s  region  x  y  theta
//   region -1: the scan went into no map (kept out, lost); x y theta are then its pose as the run
//   gave it (world frame), else its pose in the map's frame.
// graph.tsv:  anchor  region  x  y  theta      (the map's frame in the world, at the end)
//             edge  from  to  kind  x  y  theta  (kind: sequence, map_match, loop; `to`'s anchor
//                                                 in `from`'s frame as measured)
#pragma once

#include <string>

#include "host_sim/output/run_report.hpp"

namespace dpcr::output {

// Throws std::runtime_error naming the file on I/O errors.
void WriteRegionFiles(const std::string& dir, const RunRecord& run);

}  // namespace dpcr::output
