#include "host_sim/eval/relations_consistency.hpp"

#include <cmath>
#include <cstdint>
#include <map>

namespace dpcr::eval {

RelationsConsistency CheckRelationsConsistency(const std::vector<Relation>& relations) {
  // Each scan's neighbours, with the relation from the scan to them.
  std::map<std::int64_t, std::map<std::int64_t, Pose2>> graph;
  for (const Relation& r : relations) {
    if (r.t1_us == r.t2_us) continue;
    graph[r.t1_us][r.t2_us] = r.delta;
    graph[r.t2_us][r.t1_us] = r.delta.Inverse();
  }
  RelationsConsistency out;
  double trans_sum = 0.0, rot_sum = 0.0, trans_sq = 0.0, rot_sq = 0.0;
  // Each loop a < b < c once: walk a -> b -> c and back to a.
  for (const auto& [a, from_a] : graph) {
    for (auto ib = from_a.upper_bound(a); ib != from_a.end(); ++ib) {
      const auto& from_b = graph.at(ib->first);
      for (auto ic = from_b.upper_bound(ib->first); ic != from_b.end(); ++ic) {
        const auto back = from_a.find(ic->first);
        if (back == from_a.end()) continue;
        const Pose2 loop = ib->second * ic->second * back->second.Inverse();
        const double t2 = static_cast<double>(loop.x) * loop.x + static_cast<double>(loop.y) * loop.y;
        const double r = NormalizeAngle(loop.theta);
        ++out.loops;
        trans_sum += std::sqrt(t2);
        rot_sum += std::fabs(r);
        trans_sq += t2;
        rot_sq += r * r;
      }
    }
  }
  if (out.loops == 0) return out;
  const double n = static_cast<double>(out.loops), deg = 180.0 / static_cast<double>(kPi);
  out.loop_trans_mean_m = trans_sum / n;
  out.loop_rot_mean_deg = rot_sum / n * deg;
  out.relation_trans_rms_m = std::sqrt(trans_sq / n / 3.0);
  out.relation_rot_rms_deg = std::sqrt(rot_sq / n / 3.0) * deg;
  return out;
}

}  // namespace dpcr::eval
