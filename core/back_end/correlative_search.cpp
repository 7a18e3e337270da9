#include "core/back_end/correlative_search.hpp"

#include <cmath>

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

MatchGrid::MatchGrid(Span<std::uint8_t> cells, Span<std::uint8_t> bounds, int max_w, int max_h)
    : cells_(cells), bounds_(bounds), max_w_(max_w), max_h_(max_h) {
  DPCR_ASSERT(cells.size() >= static_cast<std::size_t>(max_w * max_h) && bounds.size() >= cells.size());
}

void MatchGrid::Attach(Span<std::uint8_t> bytes) {
  const std::size_t n = static_cast<std::size_t>(max_w_ * max_h_);
  DPCR_ASSERT(bytes.size() >= 2 * n);
  cells_ = Span<std::uint8_t>(bytes.data(), n);
  bounds_ = Span<std::uint8_t>(bytes.data() + n, n);
}

void MatchGrid::BuildBounds() {
  // Rows first (max over x .. x + kBlock - 1), then columns, each a short sliding window.
  for (int y = 0; y < h_; ++y) {
    for (int x = 0; x < w_; ++x) {
      std::uint8_t m = 0;
      for (int k = 0; k < kBlock && x + k < w_; ++k) {
        const std::uint8_t v = cells_[static_cast<std::size_t>(y * w_ + x + k)];
        m = v > m ? v : m;
      }
      bounds_[static_cast<std::size_t>(y * w_ + x)] = m;
    }
  }
  for (int x = 0; x < w_; ++x) {
    for (int y = 0; y < h_; ++y) {
      std::uint8_t m = 0;
      for (int k = 0; k < kBlock && y + k < h_; ++k) {
        const std::uint8_t v = bounds_[static_cast<std::size_t>((y + k) * w_ + x)];
        m = v > m ? v : m;
      }
      bounds_[static_cast<std::size_t>(y * w_ + x)] = m;  // rows below y are read before written
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

void MatchGrid::DistanceTransform() {
  const auto relax = [&](int x, int y, int dx, int dy, int weight) {
    const int nx = x + dx, ny = y + dy;
    if (nx < 0 || ny < 0 || nx >= w_ || ny >= h_) return;
    std::uint8_t& c = cells_[static_cast<std::size_t>(y * w_ + x)];
    const int d = cells_[static_cast<std::size_t>(ny * w_ + nx)] + weight;
    if (d < c) c = static_cast<std::uint8_t>(d);
  };
  for (int y = 0; y < h_; ++y) {
    for (int x = 0; x < w_; ++x) {
      relax(x, y, -1, 0, kAxis);
      relax(x, y, 0, -1, kAxis);
      relax(x, y, -1, -1, kDiagonal);
      relax(x, y, 1, -1, kDiagonal);
    }
  }
  for (int y = h_ - 1; y >= 0; --y) {
    for (int x = w_ - 1; x >= 0; --x) {
      relax(x, y, 1, 0, kAxis);
      relax(x, y, 0, 1, kAxis);
      relax(x, y, 1, 1, kDiagonal);
      relax(x, y, -1, 1, kDiagonal);
    }
  }
  std::uint8_t lut[256];
  for (int d = 0; d < 256; ++d) lut[d] = LikelihoodOf(d);
  for (int i = 0; i < w_ * h_; ++i) cells_[static_cast<std::size_t>(i)] = lut[cells_[static_cast<std::size_t>(i)]];
  BuildBounds();
}

std::uint8_t MatchGrid::At(Point2 p) const {
  const float fx = (p.x - origin_.x) / res_, fy = (p.y - origin_.y) / res_;
  if (!(fx >= 0.0f && fy >= 0.0f)) return 0;
  return AtCell(static_cast<int>(fx), static_cast<int>(fy));
}

namespace {

struct Peak {
  float score = -1.0f;
  int ox = 0, oy = 0;
  float dtheta = 0.0f;
};

bool Excluded(const Peak* exclude, bool angle_far, int ox, int oy, int sep_cells) {
  return exclude != nullptr && !angle_far && std::abs(ox - exclude->ox) < sep_cells && std::abs(oy - exclude->oy) < sep_cells;
}

// One sweep over the window. With `exclude` set, poses within the separation of it are skipped
// (the search for a second, separate peak).
Peak Sweep(const MatchGrid& grid, Span<const Point2> points, Pose2 initial, int n_offsets, int n_angles, float step,
           const Peak* exclude, const CorrelativeSearchConfig& config, Span<Point2> rotated,
           std::uint32_t* evaluated) {
  Peak best;
  const float inv_res = 1.0f / grid.resolution_m();
  const int sep_cells = static_cast<int>(config.peak_separation_m * inv_res);
  constexpr int kB = MatchGrid::kBlock;
  for (int a = -n_angles; a <= n_angles; ++a) {
    const float dtheta = static_cast<float>(a) * step;
    const bool angle_far = exclude == nullptr || std::fabs(dtheta - exclude->dtheta) >= config.peak_separation_rad;
    const PointTransform t(Pose2{initial.x, initial.y, initial.theta + dtheta});
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Point2 w = t(points[i]);
      // Whole match cells: every offset below moves all points by whole cells.
      rotated[i] = Point2{static_cast<float>(FloorToInt((w.x - grid.origin().x) * inv_res)),
                          static_cast<float>(FloorToInt((w.y - grid.origin().y) * inv_res))};
    }
    for (int by = -n_offsets; by <= n_offsets; by += kB) {
      for (int bx = -n_offsets; bx <= n_offsets; bx += kB) {
        // Upper bound of every offset in the block [bx, bx + kB) x [by, by + kB).
        std::uint32_t bound = 0;
        for (std::size_t i = 0; i < points.size(); ++i) {
          bound += grid.BoundAt(static_cast<int>(rotated[i].x) + bx, static_cast<int>(rotated[i].y) + by);
        }
        ++*evaluated;
        if (static_cast<float>(bound) <= best.score) continue;
        for (int oy = by; oy < by + kB && oy <= n_offsets; ++oy) {
          for (int ox = bx; ox < bx + kB && ox <= n_offsets; ++ox) {
            if (Excluded(exclude, angle_far, ox, oy, sep_cells)) continue;
            std::uint32_t sum = 0;
            for (std::size_t i = 0; i < points.size(); ++i) {
              sum += grid.AtCell(static_cast<int>(rotated[i].x) + ox, static_cast<int>(rotated[i].y) + oy);
            }
            ++*evaluated;
            if (static_cast<float>(sum) > best.score) best = Peak{static_cast<float>(sum), ox, oy, dtheta};
          }
        }
      }
    }
  }
  return best;
}

}  // namespace

CorrelativeSearchResult CorrelativeSearch(const MatchGrid& grid, Span<const Point2> points, Pose2 initial,
                                          float window_m, float window_rad, const CorrelativeSearchConfig& config,
                                          Span<Point2> rotated) {
  CorrelativeSearchResult result;
  result.pose = initial;
  if (points.size() < 10 || grid.width() == 0 || rotated.size() < points.size()) return result;
  float max_range = 0.0f;
  for (const Point2& p : points) max_range = std::fmax(max_range, std::sqrt(p.x * p.x + p.y * p.y));
  float step = grid.resolution_m() / std::fmax(max_range, 1.0f);
  step = std::fmin(std::fmax(step, config.min_angle_step_rad), config.max_angle_step_rad);
  const int n_angles = static_cast<int>(window_rad / step);
  const int n_offsets = static_cast<int>(window_m / grid.resolution_m());
  const Peak best = Sweep(grid, points, initial, n_offsets, n_angles, step, nullptr, config, rotated, &result.poses_evaluated);
  const Peak second = Sweep(grid, points, initial, n_offsets, n_angles, step, &best, config, rotated, &result.poses_evaluated);
  const float norm = 1.0f / (255.0f * static_cast<float>(points.size()));
  result.score = best.score * norm;
  result.second_score = second.score > 0.0f ? second.score * norm : 0.0f;
  result.pose = Pose2{initial.x + static_cast<float>(best.ox) * grid.resolution_m(),
                      initial.y + static_cast<float>(best.oy) * grid.resolution_m(), NormalizeAngle(initial.theta + best.dtheta)};
  const bool strong = result.score >= config.min_score;
  const bool unique = result.second_score < config.max_second_ratio * result.score;
  result.verdict = strong && unique ? Status::kOk : Status::kRejected;
  return result;
}

}  // namespace dpcr
