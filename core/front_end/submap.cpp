#include "core/front_end/submap.hpp"

#include <cmath>

#include "core/base/assert.hpp"

namespace dpcr {

Submap::Submap(TiledGrid* grid, Span<Point2> point_store, Span<Pose2> poses, Span<std::uint16_t> counts,
               Span<Point2> transformed, Span<CellIndex> scratch, int max_beams)
    : grid_(grid),
      point_store_(point_store),
      poses_(poses),
      counts_(counts),
      transformed_(transformed),
      scratch_(scratch),
      max_beams_(max_beams) {}

void Submap::Reset(const GridConfig& grid_config, int scans, float miss_range_m) {
  DPCR_ASSERT(scans > 0 && static_cast<std::size_t>(scans) <= poses_.size());
  capacity_ = scans;
  miss_range_m_ = miss_range_m;
  head_ = 0;
  size_ = 0;
  // Unclamped sums (see header): the clamp is only a guard at the ends of the int16 range.
  add_config_ = grid_config;
  add_config_.clamp_max = INT16_MAX - 1;
  add_config_.clamp_min = INT16_MIN + 1;
  remove_config_ = add_config_;
  remove_config_.hit_delta = static_cast<std::int16_t>(-grid_config.hit_delta);
  remove_config_.miss_delta = static_cast<std::int16_t>(-grid_config.miss_delta);
  grid_->set_resolution_m(grid_config.resolution_m);
  RecentreOn(Point2{0.0f, 0.0f});
  recentres_ = 0;
}

SubmapScanView Submap::scan(int i) const {
  const int slot = Slot(i);
  return SubmapScanView{poses_[static_cast<std::size_t>(slot)],
                        Span<Point2>(point_store_.data() + static_cast<std::size_t>(slot) * static_cast<std::size_t>(max_beams_),
                                     counts_[static_cast<std::size_t>(slot)])};
}

InsertionStats Submap::Insert(const Pose2& pose, Span<const Point2> points, const GridConfig& config) {
  // The same float operations on the same inputs give the same cells, so a removal visits
  // exactly the cells its insertion did.
  const PointTransform to_submap(pose);
  for (std::size_t i = 0; i < points.size(); ++i) transformed_[i] = to_submap(points[i]);
  return InsertRays(*grid_, Point2{pose.x, pose.y}, Span<const Point2>(transformed_.data(), points.size()),
                    Span<const Point2>(), config, scan_marker_.Next(), scratch_, miss_range_m_);
}

void Submap::RecentreOn(Point2 p) {
  const int side = grid_->tiles_x();
  const CellIndex c = CellOf(p.x, p.y, grid_->resolution_m());
  const auto floor_div = [](std::int32_t a, std::int32_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
  grid_->Reset(CellIndex{floor_div(c.x, kTileSide) - side / 2, floor_div(c.y, kTileSide) - side / 2});
  for (int i = 0; i < size_; ++i) {
    const SubmapScanView s = scan(i);
    (void)Insert(s.pose, Span<const Point2>(s.points.data(), s.points.size()), add_config_);
  }
  ++recentres_;
}

InsertionStats Submap::Add(const Pose2& pose, Span<const Point2> points) {
  DPCR_ASSERT(capacity_ > 0 && points.size() <= static_cast<std::size_t>(max_beams_));
  if (size_ == capacity_) {
    const SubmapScanView oldest = scan(0);
    (void)Insert(oldest.pose, Span<const Point2>(oldest.points.data(), oldest.points.size()), remove_config_);
    head_ = Slot(1);
    --size_;
  }
  const int slot = Slot(size_);
  Point2* store = point_store_.data() + static_cast<std::size_t>(slot) * static_cast<std::size_t>(max_beams_);
  for (std::size_t i = 0; i < points.size(); ++i) store[i] = points[i];
  poses_[static_cast<std::size_t>(slot)] = pose;
  counts_[static_cast<std::size_t>(slot)] = static_cast<std::uint16_t>(points.size());
  ++size_;
  // A robot near the box edge would see its scans cut off: re-place the box around it.
  const float half = static_cast<float>(grid_->tiles_x() * kTileSide) * grid_->resolution_m() / 2.0f;
  const CellBox box = grid_->box();
  const float cx = static_cast<float>(box.min.x) * grid_->resolution_m() + half;
  const float cy = static_cast<float>(box.min.y) * grid_->resolution_m() + half;
  if (std::fabs(pose.x - cx) > kRecentreDistanceM || std::fabs(pose.y - cy) > kRecentreDistanceM) {
    RecentreOn(Point2{pose.x, pose.y});  // re-inserts the ring, the new scan included
    return InsertionStats{};
  }
  return Insert(pose, Span<const Point2>(store, points.size()), add_config_);
}

}  // namespace dpcr
