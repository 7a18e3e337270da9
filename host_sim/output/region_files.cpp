#include "host_sim/output/region_files.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "host_sim/eval/stamp_text.hpp"

namespace dpcr::output {
namespace {

// "x y theta" at full float precision (the poses are floats: 9 significant digits round-trip).
std::string PoseText(const dpcr::Pose2& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.9g\t%.9g\t%.9g", static_cast<double>(p.x), static_cast<double>(p.y),
                static_cast<double>(p.theta));
  return buf;
}

void Check(const std::ofstream& out, const std::string& path) {
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace

void WriteRegionFiles(const std::string& dir, const RunRecord& run) {
  const std::string regions_path = dir + "/regions.tsv";
  std::ofstream regions(regions_path);
  regions << "# stamp_s\tregion\tx\ty\ttheta  (region -1: in no map, pose in the world frame; else in the map's frame)\n";
  for (std::size_t i = 0; i < run.scan_region.size() && i < run.scan_in_region.size() && i < run.estimate.size(); ++i) {
    const int r = run.scan_region[i];
    const dpcr::Pose2& pose = r >= 0 ? run.scan_in_region[i] : run.estimate[i].pose;
    regions << dpcr::eval::FormatStamp(run.estimate[i].stamp_us) << '\t' << r << '\t' << PoseText(pose) << '\n';
  }
  regions.close();
  Check(regions, regions_path);

  const std::string graph_path = dir + "/graph.tsv";
  std::ofstream graph(graph_path);
  graph << "# anchor\tregion\tx\ty\ttheta  |  edge\tfrom\tto\tkind\tx\ty\ttheta  (to's anchor in from's frame)\n";
  for (std::size_t r = 0; r < run.final_anchors.size(); ++r) graph << "anchor\t" << r << '\t' << PoseText(run.final_anchors[r]) << '\n';
  for (const auto& e : run.final_edges) {
    graph << "edge\t" << e.from << '\t' << e.to << '\t' << EdgeKindName(e.kind) << '\t' << PoseText(e.measurement) << '\n';
  }
  graph.close();
  Check(graph, graph_path);
}

}  // namespace dpcr::output
