// Coarse pose search before PLICP, for when the prediction may be outside PLICP's basin (a fast
// turn, an odometry glitch, no odometry): correlative scan matching (Olson 2009) on a coarse
// score grid built from a registration reference's obstacle cells. Every rotation in a window
// (±20° at 1° by default) is tried with every translation in a window (±0.3 m at the grid's
// 10 cm); the best-scoring pose seeds PLICP, which refines it and gives the verdict.
// Fixed capacity, no heap: CoarseScoreGridStorage<W, H> owns the cells (Mapper<Profile> holds one).
#pragma once

#include <cstdint>

#include "core/base/span.hpp"
#include "core/geometry/pose2.hpp"
#include "core/registration/registration_reference.hpp"

namespace dpcr {

struct PoseSearchConfig {
  float resolution_m = 0.10f;  // score grid cell, and the translation step
  float sigma_m = 0.10f;       // score = exp(-d²/2σ²) of the distance to the nearest obstacle cell
  int kernel_radius_cells = 2;  // score 0 beyond this many cells
  float angle_window_rad = 0.35f;   // ±20°
  float angle_step_rad = 0.0175f;   // 1°: at 6 m a step moves a point by 10 cm, one grid cell
  float xy_window_m = 0.3f;         // ±, in steps of resolution_m
  int max_points = 100;             // the scan is thinned evenly to this many points
  // Ties go to the pose nearest the initial one: each angle or translation step away from it
  // costs this fraction of a perfect point's score, summed over the points.
  float step_penalty = 0.002f;
  // The best pose replaces the initial one only if its mean score per point (0..1) is higher by
  // this much: a prediction that scores about as well is kept (a flat score, e.g. along a corridor,
  // says nothing).
  float min_gain = 0.05f;
};

struct PoseSearchResult {
  Pose2 pose;                 // best pose (== initial when nothing scored better)
  float score = 0.0f;         // mean score per point of the best pose, 0..1
  float initial_score = 0.0f; // the same at the initial pose
  bool moved = false;         // pose != initial
  int evaluations = 0;        // poses scored
};

// SearchPose's working arrays (kept with the grid, not on the stack: a Cortex-M7 task stack is
// small, and core functions stay under 1 KiB of stack).
struct PoseSearchScratch {
  static constexpr int kMaxPoints = 256;
  static constexpr int kMaxOffsets = 31;  // translation steps per axis (+-15)
  Point2 points[kMaxPoints];
  int cx[kMaxPoints];
  int cy[kMaxPoints];
  std::uint32_t sums[kMaxOffsets * kMaxOffsets];
};

// Score grid: one byte per cell, 255 on an obstacle cell, decaying with the distance to the
// nearest one; the window follows the reference's obstacle cells (clipped to the capacity).
class CoarseScoreGrid {
 public:
  CoarseScoreGrid(Span<std::uint8_t> cells, PoseSearchScratch* scratch, int max_w, int max_h)
      : cells_(cells), scratch_(scratch), max_w_(max_w), max_h_(max_h) {}
  CoarseScoreGrid(const CoarseScoreGrid&) = delete;
  CoarseScoreGrid& operator=(const CoarseScoreGrid&) = delete;

  void Build(const RegistrationReference& ref, const PoseSearchConfig& config);
  bool empty() const { return w_ == 0; }
  int width() const { return w_; }
  int height() const { return h_; }
  float resolution_m() const { return res_; }
  Point2 origin() const { return origin_; }
  // Score of grid cell (x, y), 0 outside.
  std::uint8_t At(int x, int y) const {
    return x >= 0 && y >= 0 && x < w_ && y < h_ ? cells_[static_cast<std::size_t>(y * w_ + x)] : 0;
  }
  // Row y (0 <= y < height()), width() cells.
  const std::uint8_t* Row(int y) const { return cells_.data() + static_cast<std::size_t>(y * w_); }
  // SearchPose's scratch (single-threaded use, like the reference's nearest-obstacle cache).
  PoseSearchScratch& scratch() const { return *scratch_; }

 private:
  Span<std::uint8_t> cells_;
  PoseSearchScratch* scratch_;
  int max_w_, max_h_;
  int w_ = 0, h_ = 0;
  float res_ = 0.1f;
  Point2 origin_;
};

template <int kW, int kH>
class CoarseScoreGridStorage : public CoarseScoreGrid {
 public:
  CoarseScoreGridStorage() : CoarseScoreGrid(Span<std::uint8_t>(cells_, kW * kH), &scratch_, kW, kH) {}

 private:
  std::uint8_t cells_[kW * kH];
  PoseSearchScratch scratch_;
};

// The best pose of `points` (target frame) on `grid` within the windows around `initial`.
PoseSearchResult SearchPose(const CoarseScoreGrid& grid, Span<const Point2> points, Pose2 initial,
                            const PoseSearchConfig& config);

}  // namespace dpcr
