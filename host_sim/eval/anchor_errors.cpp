#include "host_sim/eval/anchor_errors.hpp"

#include <algorithm>
#include <cmath>

#include "host_sim/eval/accuracy.hpp"

namespace dpcr::eval {
namespace {

// A rigid 2D transform in doubles (the figures are differences of centimetres over metres).
struct Rigid {
  double x = 0.0, y = 0.0, theta = 0.0;

  static Rigid Of(const dpcr::Pose2& p) {
    return {static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.theta)};
  }
  Rigid operator*(const Rigid& b) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * b.x - s * b.y, y + s * b.x + c * b.y, theta + b.theta};
  }
  Rigid Inverse() const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-c * x - s * y, s * x - c * y, -theta};
  }
};

double Distance(const Rigid& a, const Rigid& b) { return std::hypot(a.x - b.x, a.y - b.y); }

constexpr double kPi = 3.14159265358979323846;

double WrappedDegrees(double rad) { return std::remainder(rad, 2.0 * kPi) * 180.0 / kPi; }

// The anchor B that best maps the scans' poses in the map onto their truth (B * in_region ~ truth).
struct AnchorFit {
  double sin_sum = 0.0, cos_sum = 0.0;
  std::vector<std::pair<Rigid, Rigid>> pairs;  // (in region, truth)

  void Add(const Rigid& in_region, const Rigid& truth) {
    sin_sum += std::sin(truth.theta - in_region.theta);
    cos_sum += std::cos(truth.theta - in_region.theta);
    pairs.emplace_back(in_region, truth);
  }
  Rigid Best() const {
    Rigid b;
    b.theta = std::atan2(sin_sum, cos_sum);
    const double c = std::cos(b.theta), s = std::sin(b.theta), n = static_cast<double>(pairs.size());
    for (const auto& [p, g] : pairs) {
      b.x += (g.x - (c * p.x - s * p.y)) / n;
      b.y += (g.y - (s * p.x + c * p.y)) / n;
    }
    return b;
  }
};

}  // namespace

AnchorDecomposition DecomposeByAnchors(const std::vector<MappedScan>& scans, const std::vector<dpcr::Pose2>& anchors,
                                       const Trajectory& ground_truth, double sample_period_s, std::int64_t tolerance_us,
                                       const std::vector<AnchorEdge>& edges) {
  AnchorDecomposition out;
  Trajectory gt = ground_truth;
  std::stable_sort(gt.begin(), gt.end(), [](const StampedPose& a, const StampedPose& b) { return a.stamp_us < b.stamp_us; });
  const auto in_map = [&](int r) { return r >= 0 && static_cast<std::size_t>(r) < anchors.size(); };

  // Each scan's truth, and the regular samples LocErr_ave takes.
  std::vector<long> truth(scans.size(), -1);
  std::vector<std::size_t> samples;
  const std::int64_t period_us = static_cast<std::int64_t>(sample_period_s * 1e6);
  std::int64_t next_us = INT64_MIN;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    truth[i] = Nearest(gt, scans[i].estimate.stamp_us, tolerance_us);
    if (truth[i] < 0 || scans[i].estimate.stamp_us < next_us) continue;
    samples.push_back(i);
    next_us = scans[i].estimate.stamp_us + period_us;
  }
  if (samples.empty()) return out;
  const auto truth_of = [&](std::size_t i) { return Rigid::Of(gt[static_cast<std::size_t>(truth[i])].pose); };
  // Start-aligned: the estimate carried into the truth's frame at the first sample.
  const Rigid align = truth_of(samples.front()) * Rigid::Of(scans[samples.front()].estimate.pose).Inverse();

  std::vector<AnchorFit> fits(anchors.size());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    if (truth[i] >= 0 && in_map(scans[i].region)) {
      fits[static_cast<std::size_t>(scans[i].region)].Add(Rigid::Of(scans[i].in_region), truth_of(i));
    }
  }
  const auto fitted = [&](int r) { return in_map(r) && !fits[static_cast<std::size_t>(r)].pairs.empty(); };
  std::vector<Rigid> best(anchors.size());
  for (std::size_t r = 0; r < anchors.size(); ++r) {
    if (fits[r].pairs.empty()) continue;
    best[r] = fits[r].Best();
    RegionAnchorError e;
    e.region = static_cast<int>(r);
    e.scans = fits[r].pairs.size();
    Rigid centroid;
    double in_map_sum = 0.0;
    for (const auto& [p, g] : fits[r].pairs) {
      centroid.x += p.x / static_cast<double>(e.scans);
      centroid.y += p.y / static_cast<double>(e.scans);
      in_map_sum += Distance(best[r] * p, g);
    }
    const Rigid actual = align * Rigid::Of(anchors[r]);
    e.anchor_offset_m = Distance(actual * centroid, best[r] * centroid);
    e.anchor_offset_deg = WrappedDegrees(actual.theta - best[r].theta);
    e.in_map_mean_m = in_map_sum / static_cast<double>(e.scans);
    out.regions.push_back(e);
  }

  std::vector<double> own, with_best;
  for (std::size_t i : samples) {
    const Rigid g = truth_of(i);
    const Rigid estimate = align * Rigid::Of(scans[i].estimate.pose);
    own.push_back(Distance(estimate, g));
    const int r = scans[i].region;
    with_best.push_back(fitted(r) ? Distance(best[static_cast<std::size_t>(r)] * Rigid::Of(scans[i].in_region), g) : own.back());
  }
  for (const auto& e : edges) {
    if (!fitted(e.from) || !fitted(e.to)) continue;
    const Rigid measured = Rigid::Of(e.measurement);
    const Rigid relation = best[static_cast<std::size_t>(e.from)].Inverse() * best[static_cast<std::size_t>(e.to)];
    const Rigid final = Rigid::Of(anchors[static_cast<std::size_t>(e.from)]).Inverse() * Rigid::Of(anchors[static_cast<std::size_t>(e.to)]);
    out.edges.push_back({e, Distance(measured, relation), std::fabs(WrappedDegrees(measured.theta - relation.theta)),
                         Distance(measured, final), std::fabs(WrappedDegrees(measured.theta - final.theta))});
  }
  out.loc_err_ave_m = MeanOfLargestTenth(own);
  out.best_anchors_loc_err_ave_m = MeanOfLargestTenth(with_best);
  return out;
}

}  // namespace dpcr::eval
