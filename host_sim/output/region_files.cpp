#include "host_sim/output/region_files.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace dpcr::output {
namespace {

const char* EdgeKindName(int kind) {
  static const char* const kKinds[] = {"sequence", "map_match", "loop"};
  return kind >= 0 && kind < 3 ? kKinds[kind] : "unknown";
}

// "x y theta" at full float precision (the poses are floats: 9 significant digits round-trip).
std::string PoseText(const dpcr::Pose2& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.9g\t%.9g\t%.9g", static_cast<double>(p.x), static_cast<double>(p.y),
                static_cast<double>(p.theta));
  return buf;
}

std::string StampText(std::int64_t stamp_us) {
  const bool negative = stamp_us < 0;
  const unsigned long long us = negative ? 0ULL - static_cast<unsigned long long>(stamp_us) : static_cast<unsigned long long>(stamp_us);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%s%llu.%06llu", negative ? "-" : "", us / 1000000ULL, us % 1000000ULL);
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
    regions << StampText(run.estimate[i].stamp_us) << '\t' << r << '\t' << PoseText(pose) << '\n';
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
