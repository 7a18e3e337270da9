#include "host_sim/eval/relations_consistency.hpp"

#include <cmath>
#include <cstdint>
#include <map>

namespace dpcr::eval {
namespace {

// A relation as a pose in double precision (loop errors are millimetres over metres).
struct Delta {
  double x = 0.0, y = 0.0, theta = 0.0;
};

Delta Compose(const Delta& a, const Delta& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  return Delta{a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, a.theta + b.theta};
}

Delta Invert(const Delta& a) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  return Delta{-c * a.x - s * a.y, s * a.x - c * a.y, -a.theta};
}

double Wrap(double a) { return std::remainder(a, 2.0 * 3.14159265358979323846); }

}  // namespace

RelationsConsistency CheckRelationsConsistency(const std::vector<Relation>& relations) {
  // Each scan's neighbours, with the relation from the scan to them.
  std::map<std::int64_t, std::map<std::int64_t, Delta>> graph;
  for (const Relation& r : relations) {
    if (r.t1_us == r.t2_us) continue;
    const Delta d{r.delta.x, r.delta.y, r.delta.theta};
    graph[r.t1_us][r.t2_us] = d;
    graph[r.t2_us][r.t1_us] = Invert(d);
  }
  RelationsConsistency out;
  double trans_sum = 0.0, rot_sum = 0.0, trans_sq = 0.0, rot_sq = 0.0;
  // Each loop a < b < c once: walk a -> b -> c and back to a.
  for (const auto& [a, from_a] : graph) {
    for (auto ib = from_a.upper_bound(a); ib != from_a.end(); ++ib) {
      const std::int64_t b = ib->first;
      const auto& from_b = graph.at(b);
      for (auto ic = from_b.upper_bound(b); ic != from_b.end(); ++ic) {
        const auto back = from_a.find(ic->first);
        if (back == from_a.end()) continue;
        const Delta loop = Compose(Compose(ib->second, ic->second), Invert(back->second));
        const double t2 = loop.x * loop.x + loop.y * loop.y, r = Wrap(loop.theta);
        ++out.loops;
        trans_sum += std::sqrt(t2);
        rot_sum += std::fabs(r);
        trans_sq += t2;
        rot_sq += r * r;
      }
    }
  }
  if (out.loops == 0) return out;
  const double n = static_cast<double>(out.loops), deg = 180.0 / 3.14159265358979323846;
  out.loop_trans_mean_m = trans_sum / n;
  out.loop_rot_mean_deg = rot_sum / n * deg;
  out.relation_trans_rms_m = std::sqrt(trans_sq / n / 3.0);
  out.relation_rot_rms_deg = std::sqrt(rot_sq / n / 3.0) * deg;
  return out;
}

}  // namespace dpcr::eval
