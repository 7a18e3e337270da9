#include "core/registration/plicp.hpp"

#include <cmath>
#include <cstdint>

#include <Eigen/Cholesky>

#include "core/base/assert.hpp"

namespace dpcr {
namespace {

// Residual histogram for the trimming percentiles in O(points). Linear bins of gate/256 (2 mm at
// the default gate) are fine enough: the threshold never goes below trim_floor_m (3 cm).
// 16-bit counts (targets have fewer than 2^16 points): 512 bytes of stack.
constexpr int kBins = 256;

struct Histogram {
  std::uint16_t count[kBins] = {};
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

// Upper triangle of Σ w JᵀJ and Σ w Jᵀr, accumulated in scalars (no 3x3 outer products), eight
// of the nine four at a time with the compiler's vector types (SSE2, NEON): lane by lane the same
// products ((w j_a) j_b) and sums as one by one, so the same floats.
struct NormalEquations {
  using Float4 = float __attribute__((vector_size(16)));
  Float4 h = {0, 0, 0, 0};       // h00, h01, h02, h11
  Float4 hg = {0, 0, 0, 0};      // h12, h22, g0, g1
  float g2 = 0;
  void Add(float w, float j0, float j1, float j2, float r) {
    const float wj0 = w * j0, wj1 = w * j1, wj2 = w * j2;
    h += Float4{wj0, wj0, wj0, wj1} * Float4{j0, j1, j2, j1};
    hg += Float4{wj1, wj2, wj0, wj1} * Float4{j2, j2, r, r};
    g2 += wj2 * r;
  }
  Eigen::Matrix3f H() const {
    Eigen::Matrix3f m;
    m << h[0], h[1], h[2], h[1], h[3], hg[0], h[2], hg[0], hg[1];
    return m;
  }
  Eigen::Vector3f g() const { return Eigen::Vector3f(hg[2], hg[3], g2); }
};

float Residual(const Correspondence& c, Point2 w) {
  if (c.point_to_point) return std::hypot(w.x - c.q.x, w.y - c.q.y);
  return std::fabs(c.normal.x * w.x + c.normal.y * w.y - c.offset);
}

// Pass 1 of a fine-phase iteration: Censi's adaptive trim threshold, min(p95, 2 p70) of the
// gated residuals, not below trim_floor_m (gate_m if nothing matched). With a non-empty `cache`
// each point's correspondence is kept there for pass 2 (ref kNoCell: none).
template <typename Find>
float TrimThreshold(const RegistrationReference& ref, Span<const Point2> target, const PointTransform& to_world,
                    const PlicpConfig& config, Find find, Span<Correspondence> cache) {
  DPCR_ASSERT(target.size() <= UINT16_MAX);
  Histogram hist;
  const float bin_m = config.gate_m / kBins, inv_bin = 1.0f / bin_m;
  for (std::size_t i = 0; i < target.size(); ++i) {
    Correspondence corr;
    const Point2 w = to_world(target[i]);
    const bool found = find(ref, w, config, &corr);
    if (!cache.empty()) cache[i] = found ? corr : Correspondence{};
    if (!found) continue;
    const float r = Residual(corr, w);
    if (r <= config.gate_m) hist.Add(r, inv_bin);
  }
  if (hist.total == 0) return config.gate_m;
  const float threshold = std::fmin(hist.Percentile(0.95f, bin_m), 2.0f * hist.Percentile(0.70f, bin_m));
  return std::fmax(threshold, config.trim_floor_m);
}

// A target point's share by its distance from the target frame's origin (PlicpConfig::
// near_weight_range_m): 1 beyond `range_m` (or with range_m 0), falling linearly to 0 at the origin.
struct NearWeight {
  explicit NearWeight(float r) : range_m(r), range2(r * r) {}  // the square once per pass, not per point
  float operator()(Point2 p) const {
    const float d2 = p.x * p.x + p.y * p.y;
    return d2 >= range2 ? 1.0f : std::sqrt(d2) / range_m;
  }
  float range_m;
  float range2;
};

// What pass 2 found at one pose.
struct Linearisation {
  NormalEquations ne;
  std::uint32_t hash = 0;  // of the correspondence set, for the two-cycle stop
  int inliers = 0;
  float residual_sum = 0.0f;
};

// Pass 2: the normal equations of the point-to-line (or point-to-point) residuals below
// `threshold`, Huber-weighted. Correspondences come from `cache` when it is non-empty.
template <typename Find>
Linearisation Linearise(const RegistrationReference& ref, Span<const Point2> target, const Pose2& pose,
                        float threshold, const PlicpConfig& config, Find find,
                        Span<const Correspondence> cache) {
  const PointTransform to_world(pose);
  // Local accumulators, not the returned struct's: `find` is an opaque call, and sums kept in the
  // return slot would be stored and reloaded around every call.
  NormalEquations ne;
  std::uint32_t hash = 0;
  int inliers = 0;
  float residual_sum = 0.0f;
  const NearWeight near_weight(config.near_weight_range_m);
  for (std::size_t i = 0; i < target.size(); ++i) {
    Correspondence corr;
    const Point2 w = to_world(target[i]);
    if (!cache.empty()) {
      corr = cache[i];
      if (corr.ref == kNoCell) continue;
    } else if (!find(ref, w, config, &corr)) {
      continue;
    }
    hash = hash * 31u + corr.ref + 1u;
    const float r_abs = Residual(corr, w);
    if (r_abs > threshold || r_abs > config.gate_m) continue;
    const float huber = r_abs <= config.huber_m ? 1.0f : config.huber_m / r_abs;
    const float weight = corr.weight * huber * near_weight(target[i]);
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
  return Linearisation{ne, hash, inliers, residual_sum};
}

// The Gauss–Newton step from `pose`: the points' normal equations `h`, `g` plus the prior's.
Eigen::Vector3f SolveStep(Eigen::Matrix3f h, Eigen::Vector3f g, const Pose2& pose, const PosePrior* prior) {
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
  return h.ldlt().solve(-g);
}

// A scan that sees much the reference does not (a robot turning into a corridor, a door opening
// onto a room not yet seen) has few inliers for its size, and a match on what does overlap is
// rejected for the ratio alone. Its pose then fell back to the prediction, and a vacuum's or a
// logger's odometry that under-reports a fast turn by a few degrees a scan left the scans mapped
// rotated, the next ones matching worse: in a replay of mit-csail.clf a turn of 120° in 2.5 s
// into a corridor went from one scan at 47.5 % inliers to five rejected and a heading 15° off for
// the rest of the log. A fit is taken when the part that overlaps is large in its own right and fits as closely
// as the walls' noise allows: at least 70 % of the inlier ratio asked, five times the inliers
// asked, and half the mean residual allowed.
bool PartialOverlapFits(const RegistrationResult& r, const PlicpConfig& config) {
  return r.inlier_ratio >= 0.7f * config.min_inlier_ratio && r.inliers >= 5 * config.min_correspondences &&
         FitsCleanly(r, config);
}

// The verdict: enough support, small residual, observable, plausible.
// `result` holds the pose, Hessian and inlier statistics.
Status Verdict(RegistrationResult* result, const Pose2& initial, const PosePrior* prior, const PlicpConfig& config) {
  if (result->inliers < config.min_correspondences) return Status::kNotEnoughData;
  // Smallest eigenvalue of the symmetric 2x2 translational block, closed form.
  const Eigen::Matrix3f& h = result->hessian;
  const float a = h(0, 0), b = h(0, 1), d = h(1, 1);
  const float lambda_min = 0.5f * (a + d) - std::sqrt(0.25f * (a - d) * (a - d) + b * b);
  result->translation_information = lambda_min / static_cast<float>(result->inliers);
  result->degenerate = result->translation_information < config.min_translation_information;
  const Pose2& pose = result->pose;
  const Pose2 expected = prior != nullptr ? prior->pose : initial;
  const bool plausible = std::hypot(pose.x - expected.x, pose.y - expected.y) <= config.max_correction_m &&
                         std::fabs(NormalizeAngle(pose.theta - expected.theta)) <= config.max_correction_rad;
  const bool enough_inliers = result->inlier_ratio >= config.min_inlier_ratio ||
                              (config.accept_partial_overlap && PartialOverlapFits(*result, config));
  const bool ok = enough_inliers &&
                  result->mean_residual_m <= config.max_mean_residual_m && plausible &&
                  (!result->degenerate || prior != nullptr);
  return ok ? Status::kOk : Status::kRejected;
}

// The solver for a correspondence finder `find` (a function or a function object, which the
// passes then inline: registration spends most of its time on correspondences).
template <typename Find>
RegistrationResult RunPlicpWith(const RegistrationReference& ref, Span<const Point2> target, Pose2 initial,
                                const PosePrior* prior, const PlicpConfig& config, Find find,
                                Span<Correspondence> scratch) {
  RegistrationResult result;
  // The trimmed iterations keep pass 1's correspondences for pass 2 when scratch can hold them.
  const Span<Correspondence> cache = scratch.size() >= target.size() ? Span<Correspondence>(scratch.data(), target.size())
                                                                       : Span<Correspondence>();
  Pose2 pose = initial;
  std::uint32_t last_hash = 0, older_hash = 0;  // correspondence sets of the last two iterations
  bool fine_phase = false;
  Linearisation lin;
  for (int iter = 0; iter < config.max_iterations; ++iter) {
    // Trim only in the fine phase: while the pose still moves by centimetres, the residuals of a
    // correctly matched wall can all lie above 2 p70 (an offset along one axis shows only on the
    // walls across it), and trimming them would remove exactly the information needed.
    const bool trimmed = config.trim && fine_phase;
    const Span<Correspondence> pass_cache = trimmed ? cache : Span<Correspondence>();
    const float threshold =
        trimmed ? TrimThreshold(ref, target, PointTransform(pose), config, find, pass_cache) : config.gate_m;
    lin = Linearise(ref, target, pose, threshold, config, find,
                    Span<const Correspondence>(pass_cache.data(), pass_cache.size()));
    result.iterations = iter + 1;
    result.hessian = lin.ne.H();
    if (lin.inliers < 3) break;
    const Eigen::Vector3f step = SolveStep(result.hessian, lin.ne.g(), pose, prior);
    pose.x += step(0);
    pose.y += step(1);
    pose.theta = NormalizeAngle(pose.theta + step(2));
    const float dt = std::hypot(step(0), step(1)), da = std::fabs(step(2));
    const bool was_fine = fine_phase;
    fine_phase = dt < config.fine_phase_step_m && da < config.fine_phase_step_rad;
    if (was_fine) {  // the stop tests hold for the trimmed problem only
      if (dt < config.min_step_m && da < config.min_step_rad) break;
      // Same set as one or two iterations ago (a two-cycle between neighbouring cells): converged.
      const bool repeated = lin.hash == last_hash || lin.hash == older_hash;
      if (repeated && dt < 10.0f * config.min_step_m && da < 10.0f * config.min_step_rad) break;
    }
    older_hash = last_hash;
    last_hash = lin.hash;
  }
  result.pose = pose;
  result.inliers = lin.inliers;
  result.inlier_ratio = target.empty() ? 0.0f : static_cast<float>(lin.inliers) / static_cast<float>(target.size());
  result.mean_residual_m = lin.inliers > 0 ? lin.residual_sum / static_cast<float>(lin.inliers) : 0.0f;
  result.verdict = Verdict(&result, initial, prior, config);
  return result;
}

}  // namespace

RegistrationResult RunPlicp(const RegistrationReference& ref, Span<const Point2> target, Pose2 initial,
                            const PosePrior* prior, const PlicpConfig& config, CorrespondenceFn find,
                            Span<Correspondence> scratch) {
  return RunPlicpWith(ref, target, initial, prior, config, find, scratch);
}

namespace {

struct FindLineFeature {
  // A function object, so that RunPlicpWith inlines it.
  bool operator()(const RegistrationReference& ref, Point2 w, const PlicpConfig& config, Correspondence* out) const {
    const std::uint16_t j = ref.Nearest(w);
    if (j == kNoCell) return false;
    const ObstacleCell& cell = ref.cell(j);
    out->ref = j;
    if (cell.line != kNoLine) {  // the paper's term: distance to the owning line feature
      // No q: a line's residual never reads it, and most correspondences are lines.
      const LineFeature& l = ref.line(cell.line);
      out->normal = l.normal;
      out->offset = l.offset;
      out->weight = 1.0f;
      return true;
    }
    out->q = ref.ObstaclePoint(j);
    if (cell.nx != 0 || cell.ny != 0) {  // clutter with a direction: its local line
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
};

}  // namespace

RegistrationResult RegisterImproved(const RegistrationReference& ref, Span<const Point2> target, Pose2 initial,
                                    const PosePrior* prior, const PlicpConfig& config, Span<Correspondence> scratch) {
  return RunPlicpWith(ref, target, initial, prior, config, FindLineFeature{}, scratch);
}

}  // namespace dpcr
