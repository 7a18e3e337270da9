#include "core/back_end/correlative_search.hpp"

#include <cmath>
#include <cstdlib>

#include "core/back_end/square_sums.hpp"
#include "core/base/assert.hpp"
#include "core/grid/cell.hpp"
#include "core/grid/tile_pool.hpp"

namespace dpcr {
namespace {

// Chamfer weights (5 along an axis, 7 diagonally: 7/5 ~ sqrt 2); distances capped below 255.
constexpr int kAxis = 5;
constexpr int kDiagonal = 7;
constexpr int kFar = 250;

// Likelihood of a match cell at chamfer distance d (kAxis = one cell): a Gaussian of one cell's
// sigma, so a point one cell off a wall still scores 0.6 and three cells off nothing.
std::uint8_t LikelihoodOf(int d) {
  const float cells = static_cast<float>(d) / static_cast<float>(kAxis);
  return static_cast<std::uint8_t>(255.0f * std::exp(-0.5f * cells * cells) + 0.5f);
}

}  // namespace

MatchGrid::MatchGrid(Span<std::uint8_t> cells, Span<std::uint8_t> bounds, Span<std::uint8_t> coarse_bounds, int max_w,
                     int max_h)
    : cells_(cells), bounds_(bounds), coarse_bounds_(coarse_bounds), max_w_(max_w), max_h_(max_h) {
  DPCR_ASSERT(cells.size() >= static_cast<std::size_t>(max_w * max_h) && bounds.size() >= cells.size() &&
              coarse_bounds.size() >= cells.size());
}

void MatchGrid::Attach(Span<std::uint8_t> bytes) {
  const std::size_t n = static_cast<std::size_t>(max_w_ * max_h_);
  DPCR_ASSERT(bytes.size() >= 3 * n);
  cells_ = Span<std::uint8_t>(bytes.data(), n);
  bounds_ = Span<std::uint8_t>(bytes.data() + n, n);
  coarse_bounds_ = Span<std::uint8_t>(bytes.data() + 2 * n, n);
}

void MatchGrid::MaxOfFour(Span<const std::uint8_t> in, Span<std::uint8_t> out, int step) {
  // Rows first (into out), then columns in place: a cell's column reads only rows at or above it
  // before they are written, walking up from the bottom row.
  for (int y = 0; y < h_; ++y) {
    for (int x = 0; x < w_; ++x) {
      std::uint8_t m = 0;
      for (int k = 0; k < 4 && x + k * step < w_; ++k) {
        const std::uint8_t v = in[static_cast<std::size_t>(y * w_ + x + k * step)];
        m = v > m ? v : m;
      }
      out[static_cast<std::size_t>(y * w_ + x)] = m;
    }
  }
  for (int x = 0; x < w_; ++x) {
    for (int y = 0; y < h_; ++y) {
      std::uint8_t m = 0;
      for (int k = 0; k < 4 && y + k * step < h_; ++k) {
        const std::uint8_t v = out[static_cast<std::size_t>((y + k * step) * w_ + x)];
        m = v > m ? v : m;
      }
      out[static_cast<std::size_t>(y * w_ + x)] = m;  // rows below y are read before written
    }
  }
}

std::uint8_t MatchGrid::BoundAtClamped(int x, int y) const {
  // A block reaching in from the left or bottom edge: its cells inside start at 0.
  return bounds_[static_cast<std::size_t>((y < 0 ? 0 : y) * w_ + (x < 0 ? 0 : x))];
}

void MatchGrid::Build(const TiledGrid& grid, CellBox window, int coarsen, std::int16_t obstacle_threshold) {
  const int cw = (window.width() + coarsen - 1) / coarsen, ch = (window.height() + coarsen - 1) / coarsen;
  w_ = cw < max_w_ ? (cw > 0 ? cw : 0) : max_w_;
  h_ = ch < max_h_ ? (ch > 0 ? ch : 0) : max_h_;
  res_ = grid.resolution_m() * static_cast<float>(coarsen);
  origin_ = Point2{static_cast<float>(window.min.x) * grid.resolution_m(), static_cast<float>(window.min.y) * grid.resolution_m()};
  obstacles_ = 0;
  for (int i = 0; i < w_ * h_; ++i) cells_[static_cast<std::size_t>(i)] = kFar;
  ForEachTile(grid, [&](const std::int16_t* values, CellIndex corner) {
    for (int ly = 0; ly < kTileSide; ++ly) {
      const int gy = corner.y + ly - window.min.y;
      if (gy < 0) continue;
      const int y = gy / coarsen;
      if (y >= h_) break;
      for (int lx = 0; lx < kTileSide; ++lx) {
        if (values[ly * kTileSide + lx] <= obstacle_threshold) continue;  // kUnknownCell included
        const int gx = corner.x + lx - window.min.x;
        if (gx < 0) continue;
        const int x = gx / coarsen;
        if (x >= w_) break;
        std::uint8_t& c = cells_[static_cast<std::size_t>(y * w_ + x)];
        if (c != 0) ++obstacles_;
        c = 0;
      }
    }
  });
  DistanceTransform();
}

namespace {

// min(c, d): a relaxation of a chamfer pass (d may pass 255; c never does).
inline int Relaxed(int c, int d) { return d < c ? d : c; }

// One row of a chamfer pass: each cell relaxed from its neighbour before it along the row (`step`
// -1 forward, +1 backward, already done) and the three of the row done before (`prev`, null for
// the first row), in the pass's order. The edge cells have fewer neighbours; the interior reads
// them without bounds checks.
void ChamferRow(std::uint8_t* row, const std::uint8_t* prev, int w, int step, int axis, int diagonal) {
  const int first = step < 0 ? 0 : w - 1, last = step < 0 ? w - 1 : 0;
  for (int k = 0; k < w; ++k) {
    const int x = first - step * k;  // forward: 0, 1, ...; backward: w - 1, w - 2, ...
    int c = row[x];
    if (x != first) c = Relaxed(c, row[x + step] + axis);
    if (prev != nullptr) {
      c = Relaxed(c, prev[x] + axis);
      if (x != first) c = Relaxed(c, prev[x + step] + diagonal);
      if (x != last) c = Relaxed(c, prev[x - step] + diagonal);
    }
    row[x] = static_cast<std::uint8_t>(c);
  }
}

}  // namespace

void MatchGrid::DistanceTransform() {
  // Forward (rows up, left to right: from the left, below, below-left, below-right), then backward
  // (rows down, right to left, mirrored).
  std::uint8_t* cells = cells_.data();
  for (int y = 0; y < h_; ++y) {
    ChamferRow(cells + y * w_, y > 0 ? cells + (y - 1) * w_ : nullptr, w_, -1, kAxis, kDiagonal);
  }
  for (int y = h_ - 1; y >= 0; --y) {
    ChamferRow(cells + y * w_, y + 1 < h_ ? cells + (y + 1) * w_ : nullptr, w_, 1, kAxis, kDiagonal);
  }
  std::uint8_t lut[256];
  for (int d = 0; d < 256; ++d) lut[d] = LikelihoodOf(d);
  for (int i = 0; i < w_ * h_; ++i) cells_[static_cast<std::size_t>(i)] = lut[cells_[static_cast<std::size_t>(i)]];
  static_assert(kBlock == 4 && kCoarseBlock == 4 * kBlock, "each bound level is the max of 4 x 4 of the one below");
  MaxOfFour(Span<const std::uint8_t>(cells_.data(), cells_.size()), bounds_, 1);
  MaxOfFour(Span<const std::uint8_t>(bounds_.data(), bounds_.size()), coarse_bounds_, kBlock);
}

std::uint8_t MatchGrid::At(Point2 p) const {
  const float fx = (p.x - origin_.x) / res_, fy = (p.y - origin_.y) / res_;
  if (!(fx >= 0.0f && fy >= 0.0f)) return 0;
  return AtCell(static_cast<int>(fx), static_cast<int>(fy));
}

namespace {

using Peak = SearchPeak;

bool Excluded(const Peak* exclude, bool angle_far, int ox, int oy, int sep_cells) {
  return exclude != nullptr && !angle_far && std::abs(ox - exclude->ox) < sep_cells && std::abs(oy - exclude->oy) < sep_cells;
}

// A coordinate in match cells, clamped far outside any grid (no wrap-around of int16).
std::int16_t ToMatchCell(float cells) {
  constexpr float kFarOutside = 16000.0f;
  return static_cast<std::int16_t>(FloorToInt(std::fmax(-kFarOutside, std::fmin(kFarOutside, cells))));
}

// Angles from the guess outwards (0, +1, -1, +2, ...): a good pose found early prunes the rest.
int AngleAt(int k) { return (k % 2 == 1) ? (k + 1) / 2 : -(k / 2); }

// The box of the rotated cloud, in match cells: an offset that keeps it inside the grid needs no
// bounds check per point.
struct CloudExtent {
  bool known = false;
  int min_x = 0, min_y = 0, max_x = 0, max_y = 0;
  static CloudExtent Of(Span<const MatchCell> cells) {
    CloudExtent e;
    e.known = !cells.empty();
    if (!e.known) return e;
    e.min_x = e.max_x = cells[0].x;
    e.min_y = e.max_y = cells[0].y;
    for (const MatchCell& c : cells) {
      e.min_x = c.x < e.min_x ? c.x : e.min_x;
      e.max_x = c.x > e.max_x ? c.x : e.max_x;
      e.min_y = c.y < e.min_y ? c.y : e.min_y;
      e.max_y = c.y > e.max_y ? c.y : e.max_y;
    }
    return e;
  }
  // Every point's look-ups from (x, y) to (x + span_x, y + span_y), offset by (x0, y0), fall inside w x h.
  bool Inside(int x0, int y0, int span_x, int span_y, int w, int h) const {
    return known && min_x + x0 >= 0 && min_y + y0 >= 0 && max_x + x0 + span_x < w && max_y + y0 + span_y < h;
  }
};

// The sums over the cloud (offset by whole match cells) of a grid's likelihoods and of its bounds.
struct CloudScorer {
  const MatchGrid& grid;
  Span<const MatchCell> cells;  // the rotated cloud
  CloudExtent extent;
  std::uint32_t Score(int ox, int oy) const {
    std::uint32_t sum = 0;
    for (const MatchCell& c : cells) sum += grid.AtCell(c.x + ox, c.y + oy);
    return sum;
  }
  // The coarse bounds of `count` (<= kRowBatch) coarse blocks side by side from (bx, by), in one
  // pass over the cloud: out[i] is the bound of the block at (bx + kCoarseBlock i, by).
  static constexpr int kRowBatch = 8;
  void CoarseBounds(int bx, int by, int count, std::uint32_t* out) const {
    constexpr int kC = MatchGrid::kCoarseBlock;
    const int w = grid.width(), h = grid.height(), span = kC * (count - 1);
    const std::uint8_t* table = grid.coarse_bounds_data();
    std::uint32_t sums[kRowBatch] = {};
    if (extent.Inside(bx, by, span, 0, w, h)) {
      const int offset = by * w + bx;
      for (const MatchCell& c : cells) {
        const std::uint8_t* p = table + (c.y * w + c.x + offset);
        for (int i = 0; i < count; ++i) sums[i] += p[i * kC];
      }
      for (int i = 0; i < count; ++i) out[i] = sums[i];
      return;
    }
    for (const MatchCell& c : cells) {
      const int x = c.x + bx, y = c.y + by;
      if (x >= 0 && y >= 0 && x + span < w && y < h) {
        const std::uint8_t* p = table + (y * w + x);
        for (int i = 0; i < count; ++i) sums[i] += p[i * kC];
      } else if (x < w && y < h && x + span > -kC && y > -kC) {  // else all its look-ups read 0
        for (int i = 0; i < count; ++i) sums[i] += grid.CoarseBoundAt(x + i * kC, y);
      }
    }
    for (int i = 0; i < count; ++i) out[i] = sums[i];
  }
  // Sixteen sums in one pass over the cloud (core/back_end/square_sums.hpp): the scores of the
  // offsets of a block, or with kBounds the bounds of the blocks of a coarse block.
  template <bool kBounds>
  void Sixteen(int x0, int y0, std::uint32_t (&out)[16]) const {
    const int w = grid.width(), h = grid.height();
    if (kBounds) {
      constexpr int kSpan = 3 * MatchGrid::kBlock;
      SumBoundSquares(grid, cells, x0, y0, extent.Inside(x0, y0, kSpan + kBoundSquareSpareBytes, kSpan, w, h), out);
    } else {
      SumScoreSquares(grid, cells, x0, y0, extent.Inside(x0, y0, 3, 3, w, h), out);
    }
  }
};

// What one sweep keeps: the best pose, and (first sweep) the poses near it in score or (second
// sweep) the best pose to stay away from.
struct SweepState {
  Peak best;
  NearBestPeaks* near_best = nullptr;
  const Peak* exclude = nullptr;
  float ratio = 1.0f;      // max_second_ratio
  int sep_cells = 0;
  bool angle_far = true;   // this angle is far from `exclude`'s
  std::uint32_t evaluated = 0;

  // A block whose bound cannot reach what this sweep still looks for.
  bool Prune(std::uint32_t bound) const {
    const float b = static_cast<float>(bound);
    return near_best != nullptr ? b < ratio * best.score : b <= best.score;
  }
  void Offer(const Peak& pose) {
    if (pose.score > best.score) best = pose;
    if (near_best != nullptr && pose.score >= ratio * best.score) near_best->Add(pose, ratio * best.score);
  }
};

// The offsets of one kBlock x kBlock block (clipped to the window), each scored.
void ScoreBlock(const CloudScorer& scorer, int bx, int by, int n, float dtheta, SweepState* st) {
  constexpr int kB = MatchGrid::kBlock;
  // A block wholly within the excluded square around the first best (second sweep) scores nothing.
  if (Excluded(st->exclude, st->angle_far, bx, by, st->sep_cells) &&
      Excluded(st->exclude, st->angle_far, bx + kB - 1, by + kB - 1, st->sep_cells)) {
    return;
  }
  std::uint32_t scores[16];
  scorer.Sixteen<false>(bx, by, scores);
  for (int j = 0; j < kB && by + j <= n; ++j) {
    const int oy = by + j;
    for (int i = 0; i < kB && bx + i <= n; ++i) {
      const int ox = bx + i;
      if (Excluded(st->exclude, st->angle_far, ox, oy, st->sep_cells)) continue;
      ++st->evaluated;
      st->Offer(Peak{static_cast<float>(scores[kB * j + i]), static_cast<std::int16_t>(ox), static_cast<std::int16_t>(oy), dtheta});
    }
  }
}

// One angle of a sweep starts: the cloud rotated by `dtheta` into whole match cells, and (first
// angle of the first sweep) the guess itself scored: a good score from the start prunes most blocks.
void BeginAngle(const MatchGrid& grid, Span<const Point2> points, Pose2 initial, float dtheta, bool first_angle,
                const CorrelativeSearchConfig& config, Span<MatchCell> rotated, SweepState* st) {
  const float inv_res = 1.0f / grid.resolution_m();
  st->angle_far = st->exclude == nullptr || std::fabs(dtheta - st->exclude->dtheta) >= config.peak_separation_rad;
  const PointTransform t(Pose2{initial.x, initial.y, initial.theta + dtheta});
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point2 w = t(points[i]);
    // Whole match cells: every offset below moves all points by whole cells.
    rotated[i] = MatchCell{ToMatchCell((w.x - grid.origin().x) * inv_res), ToMatchCell((w.y - grid.origin().y) * inv_res)};
  }
  if (first_angle && st->exclude == nullptr) {
    const CloudScorer scorer{grid, Span<const MatchCell>(rotated.data(), points.size()), CloudExtent{}};
    ++st->evaluated;
    st->Offer(Peak{static_cast<float>(scorer.Score(0, 0)), 0, 0, 0.0f});
  }
}

// One kCoarseBlock square of offsets (corner cx, cy) at the current angle: pruned by its bound,
// else the kBlock squares inside, each pruned by its bound or scored offset by offset. With
// `exclude` set, poses within the separation of it are skipped (the search for a second, separate
// peak); without, the poses within max_second_ratio of the best go to `near_best`, and only
// blocks that cannot reach that ratio are pruned.
void SweepCoarseBlock(const CloudScorer& scorer, int cx, int cy, int n, float dtheta, std::uint32_t coarse_bound,
                      SweepState* st) {
  constexpr int kB = MatchGrid::kBlock, kC = MatchGrid::kCoarseBlock;
  ++st->evaluated;
  if (st->Prune(coarse_bound)) return;
  static_assert(kC == 4 * kB, "a coarse block is 4 x 4 blocks");
  std::uint32_t bounds[16];
  scorer.Sixteen<true>(cx, cy, bounds);
  for (int j = 0; j < 4 && cy + j * kB <= n; ++j) {
    for (int i = 0; i < 4 && cx + i * kB <= n; ++i) {
      ++st->evaluated;
      if (!st->Prune(bounds[4 * j + i])) ScoreBlock(scorer, cx + i * kB, cy + j * kB, n, dtheta, st);
    }
  }
}

}  // namespace

void NearBestPeaks::Add(const SearchPeak& p, float floor) {
  if (size_ == kCapacity) Drop(floor);
  if (size_ == kCapacity) {
    overflow_ = true;
    return;
  }
  peaks_[size_++] = p;
}

float NearBestPeaks::BestSeparated(const SearchPeak& best, float separation_rad, int sep_cells) const {
  float out = -1.0f;
  for (int i = 0; i < size_; ++i) {
    const SearchPeak& p = peaks_[i];
    const bool angle_far = std::fabs(p.dtheta - best.dtheta) >= separation_rad;
    if (!Excluded(&best, angle_far, p.ox, p.oy, sep_cells) && p.score > out) out = p.score;
  }
  return out;
}

void NearBestPeaks::Drop(float floor) {
  int kept = 0;
  for (int i = 0; i < size_; ++i) {
    if (peaks_[i].score >= floor) peaks_[kept++] = peaks_[i];
  }
  size_ = kept;
}

void CorrelativeSearchRun::Begin(const MatchGrid& grid, Span<const Point2> points, Pose2 initial, float window_m,
                                 float window_rad, const CorrelativeSearchConfig& config) {
  result_ = CorrelativeSearchResult{};
  result_.pose = initial;
  phase_ = Phase::kDone;
  if (points.size() < 10 || grid.width() == 0) return;
  float max_range = 0.0f;
  for (const Point2& p : points) max_range = std::fmax(max_range, std::sqrt(p.x * p.x + p.y * p.y));
  float step = grid.resolution_m() / std::fmax(max_range, 1.0f);
  step = std::fmin(std::fmax(step, config.min_angle_step_rad), config.max_angle_step_rad);
  initial_ = initial;
  n_offsets_ = static_cast<int>(window_m / grid.resolution_m());
  n_angles_ = static_cast<int>(window_rad / step);
  step_ = step;
  next_angle_ = 0;
  next_block_ = 0;
  best_ = SearchPeak{};
  near_best_.Clear();
  phase_ = Phase::kFirstSweep;
}

bool CorrelativeSearchRun::Continue(const MatchGrid& grid, Span<const Point2> points, const CorrelativeSearchConfig& config,
                                    Span<MatchCell> rotated, std::uint32_t max_evaluations) {
  if (phase_ == Phase::kDone) return true;
  if (rotated.size() < points.size()) {
    phase_ = Phase::kDone;
    return true;
  }
  // The first sweep finds the best pose and keeps the poses close to it in score; only when too
  // many are (a ridge) does a second sweep look for the best pose away from the best.
  const bool second = phase_ == Phase::kSecondSweep;
  SweepState st;
  st.best = best_;
  st.near_best = second ? nullptr : &near_best_;
  st.exclude = second ? &first_best_ : nullptr;
  st.ratio = config.max_second_ratio;
  st.sep_cells = static_cast<int>(config.peak_separation_m / grid.resolution_m());
  st.angle_far = angle_far_;
  constexpr int kC = MatchGrid::kCoarseBlock;
  const int n = n_offsets_, last = 2 * n_angles_;
  const int per_row = (2 * n) / kC + 1, blocks = per_row * per_row;
  // Evaluations of one coarse block when nothing is pruned: a slice stops before one that might
  // not fit (but always does one).
  constexpr std::uint32_t kWorstBlock = kC * kC + (kC / MatchGrid::kBlock) * (kC / MatchGrid::kBlock) + 1;
  // The coarse bounds of the blocks ahead in the row, computed together (CloudScorer::CoarseBounds):
  // bounds[k] is block batch_start + k's at the current angle; a slice that stops mid-batch drops the rest.
  std::uint32_t bounds[CloudScorer::kRowBatch];
  int batch_start = 0, batch_size = 0;
  CloudExtent extent;
  bool first = true;
  while (next_angle_ <= last && (first || st.evaluated + kWorstBlock <= max_evaluations)) {
    first = false;
    const float dtheta = static_cast<float>(AngleAt(next_angle_)) * step_;
    if (next_block_ == 0) {
      BeginAngle(grid, points, initial_, dtheta, next_angle_ == 0, config, rotated, &st);
      batch_size = 0;
    }
    const Span<const MatchCell> cloud(rotated.data(), points.size());
    if (batch_size == 0) extent = CloudExtent::Of(cloud);  // a new angle, or a slice starting mid-angle
    const CloudScorer scorer{grid, cloud, extent};
    const int col = next_block_ % per_row, row = next_block_ / per_row;
    if (next_block_ < batch_start || next_block_ >= batch_start + batch_size) {
      const int left = per_row - col;
      batch_start = next_block_;
      batch_size = left < CloudScorer::kRowBatch ? left : CloudScorer::kRowBatch;
      scorer.CoarseBounds(-n + col * kC, -n + row * kC, batch_size, bounds);
    }
    SweepCoarseBlock(scorer, -n + col * kC, -n + row * kC, n, dtheta, bounds[next_block_ - batch_start], &st);
    if (++next_block_ == blocks) {
      next_block_ = 0;
      ++next_angle_;
    }
  }
  best_ = st.best;
  angle_far_ = st.angle_far;
  result_.poses_evaluated += st.evaluated;
  if (next_angle_ <= last) return false;
  if (!second && near_best_.overflow()) {
    first_best_ = best_;
    best_ = SearchPeak{};
    next_angle_ = 0;
    phase_ = Phase::kSecondSweep;
    return false;
  }
  const int sep_cells = static_cast<int>(config.peak_separation_m / grid.resolution_m());
  if (second) {
    const float second_score = best_.score;
    best_ = first_best_;
    Finish(grid, points, config, second_score);
  } else {
    Finish(grid, points, config, near_best_.BestSeparated(best_, config.peak_separation_rad, sep_cells));
  }
  return true;
}

void CorrelativeSearchRun::Finish(const MatchGrid& grid, Span<const Point2> points, const CorrelativeSearchConfig& config,
                                  float second) {
  const float norm = 1.0f / (255.0f * static_cast<float>(points.size()));
  result_.score = best_.score * norm;
  result_.second_score = second > 0.0f ? second * norm : 0.0f;
  result_.pose = Pose2{initial_.x + static_cast<float>(best_.ox) * grid.resolution_m(),
                       initial_.y + static_cast<float>(best_.oy) * grid.resolution_m(),
                       NormalizeAngle(initial_.theta + best_.dtheta)};
  const bool strong = result_.score >= config.min_score;
  const bool unique = result_.second_score < config.max_second_ratio * result_.score;
  // A best pose on the window's border is not a peak the search saw whole: the true one may lie
  // outside, and what scored best is the nearest look-alike (a doorway one metre off).
  const bool inside = (n_offsets_ == 0 || (std::abs(best_.ox) < n_offsets_ && std::abs(best_.oy) < n_offsets_)) &&
                      (n_angles_ == 0 || std::fabs(best_.dtheta) < (static_cast<float>(n_angles_) - 0.5f) * step_);
  result_.on_border = !inside;
  result_.verdict = strong && unique && inside ? Status::kOk : Status::kRejected;
  phase_ = Phase::kDone;
}

CorrelativeSearchResult CorrelativeSearch(const MatchGrid& grid, Span<const Point2> points, Pose2 initial,
                                          float window_m, float window_rad, const CorrelativeSearchConfig& config,
                                          Span<MatchCell> rotated) {
  CorrelativeSearchRun run;
  run.Begin(grid, points, initial, window_m, window_rad, config);
  while (!run.Continue(grid, points, config, rotated, 0xFFFFFFFFu)) {
  }
  return run.result();
}

}  // namespace dpcr
