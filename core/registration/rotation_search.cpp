#include "core/registration/rotation_search.hpp"

#include <cmath>

namespace dpcr {
namespace {

constexpr int kMaxKernelRadius = 6;
constexpr int kMaxSearchPoints = PoseSearchScratch::kMaxPoints;
constexpr int kMaxOffsets = PoseSearchScratch::kMaxOffsets;

int FloorCell(float v) { return static_cast<int>(std::floor(v)); }

}  // namespace

void CoarseScoreGrid::Build(const RegistrationReference& ref, const PoseSearchConfig& config) {
  w_ = h_ = 0;
  res_ = config.resolution_m;
  const std::size_t n = ref.cell_count();
  if (n == 0) return;
  Point2 lo = ref.ObstaclePoint(0), hi = lo;
  for (std::size_t i = 1; i < n; ++i) {
    const Point2 c = ref.ObstaclePoint(static_cast<std::uint16_t>(i));
    lo.x = std::fmin(lo.x, c.x), lo.y = std::fmin(lo.y, c.y);
    hi.x = std::fmax(hi.x, c.x), hi.y = std::fmax(hi.y, c.y);
  }
  const int radius = config.kernel_radius_cells < kMaxKernelRadius ? config.kernel_radius_cells : kMaxKernelRadius;
  const float margin = static_cast<float>(radius + 1) * res_;
  origin_ = Point2{lo.x - margin, lo.y - margin};
  const int w = static_cast<int>(std::ceil((hi.x - lo.x + 2.0f * margin) / res_)) + 1;
  const int h = static_cast<int>(std::ceil((hi.y - lo.y + 2.0f * margin) / res_)) + 1;
  w_ = w < max_w_ ? w : max_w_;
  h_ = h < max_h_ ? h : max_h_;
  const std::size_t total = static_cast<std::size_t>(w_ * h_);
  for (std::size_t i = 0; i < total; ++i) cells_[i] = 0;
  // Each obstacle cell raises the coarse cells around it to its score at their centres, from the
  // exact distance (not the distance in coarse cells: a wall on a coarse cell border would
  // otherwise pull the best pose half a cell towards one side).
  constexpr int kTable = 64;
  std::uint8_t table[kTable + 1];  // score by d² in steps of reach²/kTable
  const float reach = static_cast<float>(radius) * res_;
  const float reach2 = reach * reach, to_index = static_cast<float>(kTable) / reach2;
  for (int i = 0; i <= kTable; ++i) {
    const float d2 = static_cast<float>(i) / to_index;
    table[i] = static_cast<std::uint8_t>(255.0f * std::exp(-d2 / (2.0f * config.sigma_m * config.sigma_m)) + 0.5f);
  }
  const float inv = 1.0f / res_;
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 c = ref.ObstaclePoint(static_cast<std::uint16_t>(i));
    const float fx = (c.x - origin_.x) * inv, fy = (c.y - origin_.y) * inv;
    const int x = FloorCell(fx), y = FloorCell(fy);
    const int y0 = y - radius < 0 ? 0 : y - radius, y1 = y + radius >= h_ ? h_ - 1 : y + radius;
    const int x0 = x - radius < 0 ? 0 : x - radius, x1 = x + radius >= w_ ? w_ - 1 : x + radius;
    for (int yy = y0; yy <= y1; ++yy) {
      std::uint8_t* row = cells_.data() + static_cast<std::size_t>(yy * w_);
      const float dy = (static_cast<float>(yy) + 0.5f - fy) * res_;
      for (int xx = x0; xx <= x1; ++xx) {
        const float dx = (static_cast<float>(xx) + 0.5f - fx) * res_;
        const float d2 = dx * dx + dy * dy;
        if (d2 >= reach2) continue;
        const std::uint8_t v = table[static_cast<int>(d2 * to_index + 0.5f)];
        if (row[xx] < v) row[xx] = v;
      }
    }
  }
}

PoseSearchResult SearchPose(const CoarseScoreGrid& grid, Span<const Point2> points, Pose2 initial,
                            const PoseSearchConfig& config) {
  PoseSearchResult result;
  result.pose = initial;
  if (grid.empty() || points.empty()) return result;
  // Evenly thinned points.
  int max_points = config.max_points < kMaxSearchPoints ? config.max_points : kMaxSearchPoints;
  if (max_points < 1) max_points = 1;
  const std::size_t stride = (points.size() + static_cast<std::size_t>(max_points) - 1) / static_cast<std::size_t>(max_points);
  PoseSearchScratch& scratch = grid.scratch();
  Point2* pts = scratch.points;
  int n = 0;
  for (std::size_t i = 0; i < points.size() && n < kMaxSearchPoints; i += stride) pts[n++] = points[i];

  const float res = grid.resolution_m(), inv = 1.0f / res;
  int t = static_cast<int>(config.xy_window_m / res + 0.5f);
  if (t > kMaxOffsets / 2) t = kMaxOffsets / 2;
  const int side = 2 * t + 1;
  const int steps = config.angle_step_rad > 0.0f ? static_cast<int>(config.angle_window_rad / config.angle_step_rad + 0.5f) : 0;
  const float penalty = config.step_penalty * 255.0f * static_cast<float>(n);
  const Point2 origin = grid.origin();
  int* cx = scratch.cx;
  int* cy = scratch.cy;
  std::uint32_t* sums = scratch.sums;
  float best = -1.0f;
  std::uint32_t best_sum = 0, initial_sum = 0;
  for (int a = -steps; a <= steps; ++a) {
    const float theta = initial.theta + static_cast<float>(a) * config.angle_step_rad;
    const float c = std::cos(theta), s = std::sin(theta);
    for (int i = 0; i < n; ++i) {
      cx[i] = FloorCell((c * pts[i].x - s * pts[i].y + initial.x - origin.x) * inv);
      cy[i] = FloorCell((s * pts[i].x + c * pts[i].y + initial.y - origin.y) * inv);
    }
    for (int k = 0; k < side * side; ++k) sums[k] = 0;
    for (int i = 0; i < n; ++i) {
      const bool inside = cx[i] - t >= 0 && cy[i] - t >= 0 && cx[i] + t < grid.width() && cy[i] + t < grid.height();
      for (int dy = -t; dy <= t; ++dy) {
        std::uint32_t* row_sums = sums + (dy + t) * side;
        if (inside) {
          const std::uint8_t* row = grid.Row(cy[i] + dy) + cx[i] - t;
          for (int k = 0; k < side; ++k) row_sums[k] += row[k];
        } else {
          for (int dx = -t; dx <= t; ++dx) row_sums[dx + t] += grid.At(cx[i] + dx, cy[i] + dy);
        }
      }
    }
    const int abs_a = a < 0 ? -a : a;
    for (int dy = -t; dy <= t; ++dy) {
      for (int dx = -t; dx <= t; ++dx) {
        const std::uint32_t sum = sums[(dy + t) * side + dx + t];
        const int steps_away = abs_a + (dx < 0 ? -dx : dx) + (dy < 0 ? -dy : dy);
        const float score = static_cast<float>(sum) - penalty * static_cast<float>(steps_away);
        if (a == 0 && dx == 0 && dy == 0) initial_sum = sum;
        ++result.evaluations;
        if (score > best) {
          best = score;
          best_sum = sum;
          result.moved = steps_away != 0;
          result.pose = result.moved ? Pose2{initial.x + static_cast<float>(dx) * res,
                                             initial.y + static_cast<float>(dy) * res, NormalizeAngle(theta)}
                                     : initial;
        }
      }
    }
  }
  const float norm = 1.0f / (255.0f * static_cast<float>(n));
  result.score = static_cast<float>(best_sum) * norm;
  result.initial_score = static_cast<float>(initial_sum) * norm;
  if (result.moved && result.score < result.initial_score + config.min_gain) {
    result.pose = initial;
    result.score = result.initial_score;
    result.moved = false;
  }
  return result;
}

}  // namespace dpcr
