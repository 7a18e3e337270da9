#include "core/front_end/region_set.hpp"

namespace dpcr {

void RegionSet::Reset(const GridConfig& grid, float miss_range_m) {
  for (int i = 0; i < size_; ++i) (*this)[i].grid->Reset();
  grid_ = grid;
  miss_range_m_ = miss_range_m;
  size_ = 0;
  current_ = previous_ = -1;
  pool_full_ = false;
}

int RegionSet::Find(RegionKey key) const {
  for (int i = 0; i < size_; ++i) {
    if ((*this)[i].key == key) return i;
  }
  return -1;
}

RegionSet::Entry RegionSet::Enter(RegionKey key, Point2 centre) {
  const int known = Find(key);
  if (known >= 0) {
    if (current_ >= 0 && known != current_) previous_ = current_;
    current_ = known;
    return Entry::kKnown;
  }
  if (static_cast<std::size_t>(size_) == maps_.size()) {
    pool_full_ = true;
    if (current_ >= 0) previous_ = current_;
    current_ = -1;
    return Entry::kPoolFull;
  }
  RegionalMap& r = (*this)[size_];
  r.key = key;
  r.anchor = Pose2{centre.x, centre.y, 0.0f};
  r.scans_inserted = 0;
  // The anchor at the box centre: the region's square and its margin all round.
  const int half = r.grid->tiles_x() / 2;
  r.grid->set_resolution_m(grid_.resolution_m);
  r.grid->set_settle_rule(grid_.settle_at_clamp, grid_.unsettle_occupied_after, grid_.unsettle_free_after);
  r.grid->set_hit_means(grid_.hit_means && grid_.settle_at_clamp ? grid_.clamp_max : std::int16_t{0});
  r.grid->Reset(CellIndex{-half, -half});
  previous_ = current_;
  current_ = size_++;
  return Entry::kCreated;
}

RegionalMap* RegionSet::Restore(RegionKey key, const Pose2& anchor, std::uint32_t scans_inserted) {
  if (static_cast<std::size_t>(size_) == maps_.size()) return nullptr;
  RegionalMap& r = (*this)[size_++];
  r.key = key;
  r.anchor = anchor;
  r.scans_inserted = scans_inserted;
  r.path_at_last_scan_m = 0.0f;
  // The box as Enter places it: the anchor at its centre.
  const int half = r.grid->tiles_x() / 2;
  r.grid->set_resolution_m(grid_.resolution_m);
  r.grid->set_settle_rule(grid_.settle_at_clamp, grid_.unsettle_occupied_after, grid_.unsettle_free_after);
  r.grid->set_hit_means(grid_.hit_means && grid_.settle_at_clamp ? grid_.clamp_max : std::int16_t{0});
  r.grid->Reset(CellIndex{-half, -half});
  return &r;
}

int RegionSet::SeedFromSubmap(const Submap& submap, const Pose2& submap_pose, Span<Point2> points,
                              ScanMarker& marker) {
  RegionalMap& r = (*this)[current_];
  const Pose2 to_region = r.anchor.Inverse() * submap_pose;
  int dropped = 0;
  for (int i = 0; i + 1 < submap.size(); ++i) {
    const SubmapScanView scan = submap.scan(i);
    const Pose2 p = to_region * scan.pose;
    const PointTransform to_region_frame(p);
    for (std::size_t k = 0; k < scan.points.size(); ++k) points[k] = to_region_frame(scan.points[k]);
    const InsertionStats st = InsertRays(*r.grid, Point2{p.x, p.y}, Span<const Point2>(points.data(), scan.points.size()),
                                         Span<const Point2>(), grid_, marker.Next(), scratch_);
    dropped += st.dropped_pool_full;
  }
  (void)marker.Next();  // the scan being added gets its own marker
  if (dropped > 0) pool_full_ = true;
  return dropped;
}

InsertionStats RegionSet::InsertScan(const Pose2& robot, Span<Point2> hits, Span<Point2> free_ends,
                                     std::uint32_t marker, int index, float learning_rate) {
  if (index < 0) index = current_;
  if (index < 0 || index >= size_) return InsertionStats{};
  RegionalMap& r = (*this)[index];
  const Pose2 to_region = r.anchor.Inverse() * robot;
  const PointTransform into_region(to_region);
  for (Point2& p : hits) p = into_region(p);
  for (Point2& p : free_ends) p = into_region(p);
  const GridConfig learning = learning_rate < 1.0f ? ScaledLearning(grid_, learning_rate) : grid_;
  const InsertionStats st = InsertRays(*r.grid, Point2{to_region.x, to_region.y}, Span<const Point2>(hits.data(), hits.size()),
                                       Span<const Point2>(free_ends.data(), free_ends.size()), learning, marker, scratch_,
                                       miss_range_m_);
  r.grid->AddHitMeans(Span<const Point2>(hits.data(), hits.size()), marker);
  ++r.scans_inserted;
  if (st.dropped_pool_full > 0) pool_full_ = true;
  return st;
}

}  // namespace dpcr
