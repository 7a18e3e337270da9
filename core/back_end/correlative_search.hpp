// Loop closure past the PLICP basin: an exhaustive correlative search (Olson 2009) of a point
// cloud over a window of poses, on a coarse likelihood grid of a regional map. It finds where the
// submap lies in a map it re-enters after a long drift (metres, degrees), for PLICP to refine.
// Only unambiguous answers count: a second peak, far from the best, that scores nearly as well
// (a twin room, a long corridor) makes the search answer kRejected.
// Size-erased: MatchGridStorage<W, H> owns the cells.
#pragma once

#include <cstdint>

#include "core/base/span.hpp"
#include "core/base/status.hpp"
#include "core/geometry/pose2.hpp"
#include "core/grid/tiled_grid.hpp"

namespace dpcr {

// A coarse grid of obstacle likelihoods, 0..255, over a window of one map's frame: 255 on an
// obstacle, falling with the distance to the nearest one (a chamfer distance transform).
class MatchGrid {
 public:
  // `bounds` and `coarse_bounds` (each as large as `cells`): for each cell the largest likelihood
  // of the kBlock x kBlock (kCoarseBlock x kCoarseBlock) cells from it up and right, the upper
  // bounds a two-level branch-and-bound search prunes by.
  MatchGrid(Span<std::uint8_t> cells, Span<std::uint8_t> bounds, Span<std::uint8_t> coarse_bounds, int max_w, int max_h);
  // Storage attached later (memory lent by another stage: RegistrationReference::LendTable).
  MatchGrid(int max_w, int max_h) : max_w_(max_w), max_h_(max_h) {}
  // Takes 3 * max_w * max_h bytes: the cells, then the two bound grids.
  void Attach(Span<std::uint8_t> bytes);
  static constexpr std::size_t BytesFor(int max_w, int max_h) { return 3u * static_cast<std::size_t>(max_w * max_h); }
  MatchGrid(const MatchGrid&) = delete;
  MatchGrid& operator=(const MatchGrid&) = delete;

  // Covers `window` (cells of `grid`, in its frame) at `coarsen` grid cells per match cell,
  // clipped to the capacity. A grid cell above `obstacle_threshold` marks its match cell.
  void Build(const TiledGrid& grid, CellBox window, int coarsen, std::int16_t obstacle_threshold);

  // Likelihood at a point of the map's frame (0 outside).
  std::uint8_t At(Point2 p) const;
  std::uint8_t AtCell(int x, int y) const {
    return (x < 0 || y < 0 || x >= w_ || y >= h_) ? 0 : cells_[static_cast<std::size_t>(y * w_ + x)];
  }
  // The largest likelihood of cells (x .. x + kBlock - 1, y .. y + kBlock - 1).
  std::uint8_t BoundAt(int x, int y) const {
    return (x <= -kBlock || y <= -kBlock || x >= w_ || y >= h_) ? 0 : BoundAtClamped(x, y);
  }
  // The largest likelihood of cells (x .. x + kCoarseBlock - 1, y .. y + kCoarseBlock - 1).
  std::uint8_t CoarseBoundAt(int x, int y) const {
    return (x <= -kCoarseBlock || y <= -kCoarseBlock || x >= w_ || y >= h_)
               ? 0
               : coarse_bounds_[static_cast<std::size_t>((y < 0 ? 0 : y) * w_ + (x < 0 ? 0 : x))];
  }
  // The rows of likelihoods and of kBlock bounds (width() bytes a row): the search reads them
  // directly where a point's look-ups all fall inside the grid (no bounds check per look-up).
  const std::uint8_t* cells_data() const { return cells_.data(); }
  const std::uint8_t* bounds_data() const { return bounds_.data(); }
  const std::uint8_t* coarse_bounds_data() const { return coarse_bounds_.data(); }
  static constexpr int kBlock = 4;
  static constexpr int kCoarseBlock = 4 * kBlock;
  float resolution_m() const { return res_; }
  Point2 origin() const { return origin_; }
  int width() const { return w_; }
  int height() const { return h_; }
  int obstacle_cells() const { return obstacles_; }

 private:
  void DistanceTransform();
  // out(x, y) = the largest of in(x + i * step, y + j * step), i, j < 4 (0 past the edges).
  void MaxOfFour(Span<const std::uint8_t> in, Span<std::uint8_t> out, int step);
  std::uint8_t BoundAtClamped(int x, int y) const;

  Span<std::uint8_t> cells_;
  Span<std::uint8_t> bounds_;
  Span<std::uint8_t> coarse_bounds_;
  int max_w_, max_h_;
  int w_ = 0, h_ = 0;
  int obstacles_ = 0;
  float res_ = 0.1f;
  Point2 origin_;
};

template <int kW, int kH>
class MatchGridStorage : public MatchGrid {
 public:
  MatchGridStorage()
      : MatchGrid(Span<std::uint8_t>(cells_, kW * kH), Span<std::uint8_t>(bounds_, kW * kH),
                  Span<std::uint8_t>(coarse_bounds_, kW * kH), kW, kH) {}

 private:
  std::uint8_t cells_[kW * kH];
  std::uint8_t bounds_[kW * kH];
  std::uint8_t coarse_bounds_[kW * kH];
};

struct CorrelativeSearchConfig {
  // Angular step: the rotation that moves the farthest point by about one match cell.
  float min_angle_step_rad = 0.005f;
  float max_angle_step_rad = 0.035f;
  // The best pose must reach this mean likelihood over the points (0..1).
  float min_score = 0.55f;
  // Ambiguity: a peak at least `peak_separation_m` (or `peak_separation_rad`) from the best that
  // scores above `max_second_ratio` of it rejects the search.
  float max_second_ratio = 0.95f;
  float peak_separation_m = 0.5f;
  float peak_separation_rad = 0.14f;
};

struct CorrelativeSearchResult {
  Pose2 pose;                // best pose of the cloud's frame in the map's frame
  float score = 0.0f;        // mean likelihood of the best pose, 0..1
  // The best score of a separate peak when one reaches max_second_ratio of the best (what decides);
  // below that, the best separate pose the sweep happened to score (0 if none).
  float second_score = 0.0f;
  std::uint32_t poses_evaluated = 0;
  bool on_border = false;    // the best pose lies on the window's border (then rejected)
  Status verdict = Status::kNotEnoughData;  // kOk, kRejected (weak, ambiguous, on the border), kNotEnoughData
};

// A point of the rotated cloud in whole match cells of the grid (the search's scratch: half the
// bytes of a Point2, and no float-to-int conversion per look-up).
struct MatchCell {
  std::int16_t x = 0;
  std::int16_t y = 0;
};

// One pose of a search: its summed likelihood, its offset in match cells, its rotation.
struct SearchPeak {
  float score = -1.0f;
  std::int16_t ox = 0, oy = 0;
  float dtheta = 0.0f;
};

// The poses that scored within max_second_ratio of the best so far: the only ones that can be the
// separate peak that makes a search ambiguous. Bounded; when it overflows (a long ridge of near-
// best poses, e.g. a corridor) the search takes a second sweep instead.
class NearBestPeaks {
 public:
  void Clear() { size_ = 0; overflow_ = false; }
  void Add(const SearchPeak& p, float floor);
  bool overflow() const { return overflow_; }
  // The best score among the poses separated from `best` (the second sweep's rule), -1 if none.
  float BestSeparated(const SearchPeak& best, float separation_rad, int sep_cells) const;

 private:
  void Drop(float floor);
  static constexpr int kCapacity = 24;
  SearchPeak peaks_[kCapacity];
  int size_ = 0;
  bool overflow_ = false;
};

// A search in bounded steps, so that a wide window (metres, tenths of a radian: up to ~10^8
// instructions) does not stall the scan loop: Begin plans it, each Continue sweeps blocks of
// offsets (kCoarseBlock squares, angle by angle) until it has evaluated about a given number of
// poses and bounds, and the answer is the same as CorrelativeSearch's. The grid and the points must not change between Begin and done().
class CorrelativeSearchRun {
 public:
  void Begin(const MatchGrid& grid, Span<const Point2> points, Pose2 initial, float window_m, float window_rad,
             const CorrelativeSearchConfig& config);
  // True once the search is done (at once when there is nothing to search).
  bool Continue(const MatchGrid& grid, Span<const Point2> points, const CorrelativeSearchConfig& config,
                Span<MatchCell> rotated, std::uint32_t max_evaluations);
  bool done() const { return phase_ == Phase::kDone; }
  // Valid once done().
  const CorrelativeSearchResult& result() const { return result_; }

 private:
  enum class Phase : std::uint8_t { kDone, kFirstSweep, kSecondSweep };
  void Finish(const MatchGrid& grid, Span<const Point2> points, const CorrelativeSearchConfig& config, float second);

  Phase phase_ = Phase::kDone;
  Pose2 initial_;
  int n_offsets_ = 0, n_angles_ = 0;
  float step_ = 0.0f;
  int next_angle_ = 0;          // index into the sweep order (0, +1, -1, +2, ...)
  int next_block_ = 0;          // the next coarse block of offsets at that angle, row by row
  bool angle_far_ = true;       // that angle is far from the first sweep's best (second sweep)
  SearchPeak best_;             // of the sweep under way
  SearchPeak first_best_;       // the first sweep's, excluded by the second
  NearBestPeaks near_best_;
  CorrelativeSearchResult result_;
};

// Searches poses within +-window_m (x, y) and +-window_rad around `initial` for the cloud
// `points` (in its own frame): every angle, translations by branch and bound (blocks of
// kBlock x kBlock offsets scored by their upper bound first; only blocks that could beat the best
// so far are scored cell by cell), the same answer as scoring every pose. `rotated` is scratch for the rotated cloud in match-cell units
// (at least points.size() entries).
CorrelativeSearchResult CorrelativeSearch(const MatchGrid& grid, Span<const Point2> points, Pose2 initial,
                                          float window_m, float window_rad, const CorrelativeSearchConfig& config,
                                          Span<MatchCell> rotated);

}  // namespace dpcr
