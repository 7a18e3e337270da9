#include "core/registration/plicp.hpp"

#include <cmath>

#include <Eigen/Cholesky>

namespace dpcr {
namespace {

// Residual histogram for the trimming percentiles in O(points). Linear bins of gate/256 (2 mm at
// the default gate) are fine enough: the threshold never goes below trim_floor_m (3 cm).
constexpr int kBins = 256;

struct Histogram {
  std::uint32_t count[kBins] = {};
  std::uint32_t total = 0;
  void Add(float r, float inv_bin) {
    int b = static_cast<int>(r * inv_bin);
    b = b >= kBins ? kBins - 1 : b;
    ++count[b];
    ++total;
  }
  float Percentile(float q, float bin_m) const {
    const auto want = static_cast<std::uint32_t>(q * static_cast<float>(total));
    std::uint32_t seen = 0;
    for (int b = 0; b < kBins; ++b) {
      seen += count[b];
      if (seen > want) return static_cast<float>(b + 1) * bin_m;
    }
    return static_cast<float>(kBins) * bin_m;
  }
};

// Upper triangle of Σ w JᵀJ and Σ w Jᵀr, accumulated in scalars (no 3x3 outer products).
struct NormalEquations {
  float h00 = 0, h01 = 0, h02 = 0, h11 = 0, h12 = 0, h22 = 0, g0 = 0, g1 = 0, g2 = 0;
  void Add(float w, float j0, float j1, float j2, float r) {
    h00 += w * j0 * j0, h01 += w * j0 * j1, h02 += w * j0 * j2;
    h11 += w * j1 * j1, h12 += w * j1 * j2, h22 += w * j2 * j2;
    g0 += w * j0 * r, g1 += w * j1 * r, g2 += w * j2 * r;
  }
  Eigen::Matrix3f H() const {
    Eigen::Matrix3f h;
    h << h00, h01, h02, h01, h11, h12, h02, h12, h22;
    return h;
  }
  Eigen::Vector3f g() const { return Eigen::Vector3f(g0, g1, g2); }
};

float Residual(const Correspondence& c, Point2 w) {
  if (c.point_to_point) return std::hypot(w.x - c.q.x, w.y - c.q.y);
  return std::fabs(c.normal.x * w.x + c.normal.y * w.y - c.offset);
}

}  // namespace

RegistrationResult RunPlicp(const RegistrationReference& ref, Span<const Point2> target, Pose2 initial,
                            const PosePrior* prior, const PlicpConfig& config, CorrespondenceFn find,
                            Span<Correspondence> scratch) {
  RegistrationResult result;
  const bool can_cache = scratch.size() >= target.size();
  Pose2 pose = initial;
  std::uint32_t last_hash = 0, older_hash = 0;  // correspondence sets of the last two iterations
  bool fine_phase = false;
  int inliers = 0;
  float residual_sum = 0.0f;
  Eigen::Matrix3f h_points = Eigen::Matrix3f::Zero();
  for (int iter = 0; iter < config.max_iterations; ++iter) {
    const float c = std::cos(pose.theta), s = std::sin(pose.theta);
    const auto to_world = [&](Point2 p) { return Point2{c * p.x - s * p.y + pose.x, s * p.x + c * p.y + pose.y}; };
    // Pass 1 (fine phase only): the residual distribution, for Censi's adaptive trim.
    // Trim only in the fine phase: while the pose still moves by centimetres, the residuals of a
    // correctly matched wall can all lie above 2 p70 (an offset along one axis shows only on the
    // walls across it), and trimming them would remove exactly the information needed.
    float threshold = config.gate_m;
    const bool cached = can_cache && config.trim && fine_phase;  // pass 1 fills scratch, pass 2 reads it
    if (config.trim && fine_phase) {
      Histogram hist;
      const float bin_m = config.gate_m / kBins, inv_bin = 1.0f / bin_m;
      for (std::size_t i = 0; i < target.size(); ++i) {
        Correspondence corr;
        const Point2 w = to_world(target[i]);
        const bool found = find(ref, w, config, &corr);
        if (cached) scratch[i] = found ? corr : Correspondence{};  // ref kNoCell: none
        if (!found) continue;
        const float r = Residual(corr, w);
        if (r <= config.gate_m) hist.Add(r, inv_bin);
      }
      if (hist.total > 0) {
        threshold = std::fmin(hist.Percentile(0.95f, bin_m), 2.0f * hist.Percentile(0.70f, bin_m));
        threshold = std::fmax(threshold, config.trim_floor_m);
      }
    }
    // Pass 2: the normal equations of the point-to-line (or point-to-point) residuals.
    NormalEquations ne;
    std::uint32_t hash = 0;
    inliers = 0;
    residual_sum = 0.0f;
    for (std::size_t i = 0; i < target.size(); ++i) {
      Correspondence corr;
      const Point2 w = to_world(target[i]);
      if (cached) {
        corr = scratch[i];
        if (corr.ref == kNoCell) continue;
      } else if (!find(ref, w, config, &corr)) {
        continue;
      }
      hash = hash * 31u + corr.ref + 1u;
      const float r_abs = Residual(corr, w);
      if (r_abs > threshold || r_abs > config.gate_m) continue;
      const float huber = r_abs <= config.huber_m ? 1.0f : config.huber_m / r_abs;
      const float weight = corr.weight * huber;
      const float rx = w.x - pose.x, ry = w.y - pose.y;  // d(w)/dθ = (-ry, rx)
      ++inliers;
      residual_sum += r_abs;
      if (corr.point_to_point) {
        ne.Add(weight, 1.0f, 0.0f, -ry, w.x - corr.q.x);
        ne.Add(weight, 0.0f, 1.0f, rx, w.y - corr.q.y);
      } else {
        ne.Add(weight, corr.normal.x, corr.normal.y, -corr.normal.x * ry + corr.normal.y * rx,
               corr.normal.x * w.x + corr.normal.y * w.y - corr.offset);
      }
    }
    Eigen::Matrix3f h = ne.H();
    Eigen::Vector3f g = ne.g();
    result.iterations = iter + 1;
    h_points = h;
    if (inliers < 3) break;
    if (prior != nullptr) {
      h(0, 0) += prior->info_xy;
      h(1, 1) += prior->info_xy;
      h(2, 2) += prior->info_theta;
      g(0) += prior->info_xy * (pose.x - prior->pose.x);
      g(1) += prior->info_xy * (pose.y - prior->pose.y);
      g(2) += prior->info_theta * NormalizeAngle(pose.theta - prior->pose.theta);
    }
    // A tiny Levenberg damping keeps a degenerate system (corridor without prior) solvable.
    h += Eigen::Matrix3f::Identity() * (1e-6f * h.trace() + 1e-9f);
    const Eigen::Vector3f step = h.ldlt().solve(-g);
    pose.x += step(0);
    pose.y += step(1);
    pose.theta = NormalizeAngle(pose.theta + step(2));
    const float dt = std::hypot(step(0), step(1)), da = std::fabs(step(2));
    const bool was_fine = fine_phase;
    fine_phase = dt < config.fine_phase_step_m && da < config.fine_phase_step_rad;
    if (!was_fine) {  // the stop tests below hold for the trimmed problem only
      older_hash = last_hash;
      last_hash = hash;
      continue;
    }
    if (dt < config.min_step_m && da < config.min_step_rad) break;
    // Same set as one or two iterations ago (a two-cycle between neighbouring cells): converged.
    const bool repeated = hash == last_hash || hash == older_hash;
    if (repeated && dt < 10.0f * config.min_step_m && da < 10.0f * config.min_step_rad) break;
    older_hash = last_hash;
    last_hash = hash;
  }

  // Verdict (DESIGN §3 acceptance): enough support, small residual, observable, plausible.
  result.pose = pose;
  result.hessian = h_points;
  result.inliers = inliers;
  result.inlier_ratio = target.empty() ? 0.0f : static_cast<float>(inliers) / static_cast<float>(target.size());
  result.mean_residual_m = inliers > 0 ? residual_sum / static_cast<float>(inliers) : 0.0f;
  if (inliers < config.min_correspondences) {
    result.verdict = Status::kNotEnoughData;
    return result;
  }
  // Smallest eigenvalue of the symmetric 2x2 translational block, closed form.
  const float a = h_points(0, 0), b = h_points(0, 1), d = h_points(1, 1);
  const float lambda_min = 0.5f * (a + d) - std::sqrt(0.25f * (a - d) * (a - d) + b * b);
  result.translation_information = lambda_min / static_cast<float>(inliers);
  result.degenerate = result.translation_information < config.min_translation_information;
  const Pose2 expected = prior != nullptr ? prior->pose : initial;
  const bool plausible = std::hypot(pose.x - expected.x, pose.y - expected.y) <= config.max_correction_m &&
                         std::fabs(NormalizeAngle(pose.theta - expected.theta)) <= config.max_correction_rad;
  const bool ok = result.inlier_ratio >= config.min_inlier_ratio &&
                  result.mean_residual_m <= config.max_mean_residual_m && plausible &&
                  (!result.degenerate || prior != nullptr);
  result.verdict = ok ? Status::kOk : Status::kRejected;
  return result;
}

namespace {

bool FindLineFeature(const RegistrationReference& ref, Point2 w, const PlicpConfig& config, Correspondence* out) {
  const std::uint16_t j = ref.Nearest(w);
  if (j == kNoCell) return false;
  const ObstacleCell& cell = ref.cell(j);
  out->ref = j;
  out->q = ref.CellCentre(j);
  if (cell.line != kNoLine) {  // the paper's term: distance to the owning line feature
    const LineFeature& l = ref.line(cell.line);
    out->normal = l.normal;
    out->offset = l.offset;
    out->weight = 1.0f;
  } else if (cell.nx != 0 || cell.ny != 0) {  // clutter with a direction: its local line
    const float nx = static_cast<float>(cell.nx), ny = static_cast<float>(cell.ny);
    const float inv = 1.0f / std::sqrt(nx * nx + ny * ny);
    out->normal = Point2{nx * inv, ny * inv};
    out->offset = out->normal.x * out->q.x + out->normal.y * out->q.y;
    out->weight = config.local_line_weight;
  } else {  // a chair leg: point-to-point
    out->point_to_point = true;
    out->weight = config.point_weight;
  }
  return true;
}

}  // namespace

RegistrationResult RegisterImproved(const RegistrationReference& ref, Span<const Point2> target, Pose2 initial,
                                    const PosePrior* prior, const PlicpConfig& config, Span<Correspondence> scratch) {
  return RunPlicp(ref, target, initial, prior, config, &FindLineFeature, scratch);
}

}  // namespace dpcr
