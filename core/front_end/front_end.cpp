#include "core/front_end/front_end.hpp"

#include <cmath>

#include "core/base/assert.hpp"
#include "core/grid/ray_caster.hpp"

namespace dpcr {

Status FrontEnd::Init(const MapperConfig& config) {
  const Status v = Validate(config);
  if (v != Status::kOk) return v;
  if (static_cast<std::size_t>(config.front_end.second_registration_max_points) > s_.target.size()) {
    return Status::kInvalidArgument;
  }
  config_ = config;
  for (int i = 0; i < region_count_; ++i) s_.regions[static_cast<std::size_t>(i)].grid->Reset();
  s_.submap->Reset(config.grid, config.front_end.submap_scans, config.front_end.submap_miss_range_m);
  status_ = MapperStatus::kWaitingForData;
  counters_ = MapperCounters{};
  fe_counters_ = FrontEndCounters{};
  odometry_.Clear();
  pose_ = submap_pose_ = last_odom_ = Pose2::Identity();
  have_odom_ = have_scan_ = pool_full_ = weak_match_ = false;
  search_grid_version_ = 0;
  consecutive_rejections_ = 0;
  region_count_ = 0;
  current_region_ = previous_region_ = -1;
  reference_maps_[0] = reference_maps_[1] = -1;
  scans_since_submap_lines_ = scans_since_region_lines_ = scans_since_second_ = 0;
  stamp_ = 0;
  return Status::kOk;
}

void FrontEnd::AddOdometry(const OdometrySample& sample) {
  const std::uint32_t before = odometry_.steps_back();
  odometry_.Add(sample);
  // A stamp stepping back breaks interpolation, not the odometry frame: increments go on.
  if (odometry_.steps_back() != before) ++counters_.odometry_steps_back;
  ++counters_.odometry_samples;
}

Pose2 FrontEnd::Predict(std::int64_t stamp_us) {
  if (odometry_.empty()) {
    ++counters_.scans_without_odometry;
    return pose_;
  }
  const Pose2 odom = odometry_.PoseAt(stamp_us);
  const Pose2 predicted = have_odom_ ? pose_ * Between(last_odom_, odom) : pose_;
  last_odom_ = odom;
  have_odom_ = true;
  return predicted;
}

Status FrontEnd::AddScan(Span<const Beam> beams, std::int64_t stamp_us) {
  ++counters_.scans;
  if (++stamp_ == 0) stamp_ = 1;  // 0 means "no once-per-scan rule" to the grid
  // 1. Prediction and de-skew.
  const Pose2 predicted = Predict(stamp_us);
  const ProjectedScan projected = ProjectScan(beams, stamp_us, config_.lidar, odometry_, s_.hits, s_.free_ends);
  counters_.beams_invalid += static_cast<std::uint32_t>(projected.invalid);
  if (projected.hits == 0 && projected.free_ends == 0) {
    ++counters_.scans_rejected;
    pose_ = predicted;
    return Status::kNotEnoughData;
  }
  // 2. First registration against the submap (not for the very first scan: nothing to match).
  if (config_.front_end.enable_registration && s_.submap->size() > 0) {
    RebuildSubmapReferenceIfDue();
    RegisterScan(projected.hits, predicted);
  } else {
    pose_ = predicted;
  }
  // 4a. The submap takes every scan (its own ring decides what leaves).
  (void)s_.submap->Add(pose_, Span<const Point2>(s_.hits.data(), projected.hits));
  ++scans_since_submap_lines_;
  // 3. Regions, and the second registration.
  const Pose2 world = pose();
  if (!have_scan_) {
    tracker_.Start(Point2{world.x, world.y}, config_.front_end.region_width_m, config_.front_end.region_hysteresis_m);
    have_scan_ = true;
    EnterRegion(true);
  } else if (tracker_.Update(Point2{world.x, world.y})) {
    EnterRegion(false);
  } else if (config_.front_end.enable_registration &&
             ++scans_since_second_ >= static_cast<std::uint32_t>(config_.front_end.second_registration_period)) {
    SecondRegistration();
  }
  // 4b. Once into the current regional map.
  InsertIntoRegion(projected);
  UpdateStatus();
  return Status::kOk;
}

void FrontEnd::RebuildSubmapReferenceIfDue() {
  const FrontEndConfig& f = config_.front_end;
  // After a weak match, early (the scans since the last build hold what the reference lacks), but
  // not on every scan of a weak streak: line extraction costs about a registration.
  const bool early = weak_match_ && scans_since_submap_lines_ >= kMinScansBetweenEarlyBuilds;
  if (scans_since_submap_lines_ >= static_cast<std::uint32_t>(f.submap_line_period) || early ||
      fe_counters_.submap_line_builds == 0) {
    // A young submap cannot reach the threshold: ask for a hit in every scan it holds so far.
    ReferenceConfig reference = f.submap_reference;
    const int reachable = s_.submap->size() * config_.grid.hit_delta - 1;
    if (reachable < reference.obstacle_threshold) reference.obstacle_threshold = static_cast<std::int16_t>(reachable);
    if (early && f.weak_match_obstacle_threshold < reference.obstacle_threshold) {
      reference.obstacle_threshold = f.weak_match_obstacle_threshold;
      ++fe_counters_.submap_early_builds;
    }
    ReferenceBuildStats stats;
    const Status s = s_.submap_reference->Build(s_.submap->grid(), s_.submap->grid().box(), reference, &stats);
    if (s != Status::kOk) fe_counters_.reference_cells_dropped += static_cast<std::uint32_t>(stats.dropped_cells);
    if (f.submap_refit_gate_m > 0.0f) RefitSubmapLines();
    ++fe_counters_.submap_line_builds;
    scans_since_submap_lines_ = 0;
  }
}

void FrontEnd::RefitSubmapLines() {
  RegistrationReference& ref = *s_.submap_reference;
  ref.BeginPointRefit();
  for (int i = 0; i < s_.submap->size(); ++i) {
    const SubmapScanView scan = s_.submap->scan(i);
    const PointTransform to_submap(scan.pose);
    for (const Point2& p : scan.points) ref.AddRefitPoint(to_submap(p), config_.front_end.submap_refit_gate_m);
  }
  (void)ref.EndPointRefit(config_.front_end.submap_refit_min_points);
}

void FrontEnd::RegisterScan(std::size_t hits, const Pose2& predicted) {
  const FrontEndConfig& f = config_.front_end;
  const RegistrationResult r =
      // In a rejection streak the search runs on every other scan (each search that did not help
      // is followed by one PLICP-only attempt): the streak's cost stays bounded.
      RegisterFirst(*s_.submap_reference, consecutive_rejections_ % 2 == 0 ? s_.search_grid : nullptr, &search_grid_version_, fe_counters_.submap_line_builds,
                    Span<const Point2>(s_.hits.data(), hits), pose_, predicted, f, s_.correspondences, &fe_counters_.search);
  ++fe_counters_.first_registrations;
  weak_match_ = r.verdict != Status::kOk || r.inlier_ratio < f.weak_match_inlier_ratio;
  if (r.verdict == Status::kOk) {
    pose_ = r.pose;
    consecutive_rejections_ = 0;
  } else {
    // A rejected match is not fused: the pose falls back to the prediction.
    pose_ = predicted;
    ++fe_counters_.first_rejected;
    ++consecutive_rejections_;
  }
}

void FrontEnd::EnterRegion(bool first) {
  const RegionKey key = tracker_.current();
  for (int i = 0; i < region_count_; ++i) {
    if (s_.regions[static_cast<std::size_t>(i)].key == key) {
      if (current_region_ >= 0 && i != current_region_) previous_region_ = current_region_;
      current_region_ = i;
      // Re-entering a known region: align the submap to it at once (paper: on region entry).
      if (config_.front_end.enable_registration) SecondRegistration();
      return;
    }
  }
  if (static_cast<std::size_t>(region_count_) == s_.regions.size()) {
    // Evict nothing: the map stops growing; localisation goes on against the submap.
    ++counters_.region_pool_full;
    pool_full_ = true;
    if (current_region_ >= 0) previous_region_ = current_region_;  // still a reference (ReferenceRegion)
    current_region_ = -1;
    return;
  }
  RegionalMap& r = s_.regions[static_cast<std::size_t>(region_count_)];
  const Point2 c = tracker_.Centre(key);
  r.key = key;
  r.anchor = Pose2{c.x, c.y, 0.0f};
  r.scans_inserted = 0;
  const int half = r.grid->tiles_x() / 2;
  r.grid->set_resolution_m(config_.grid.resolution_m);
  r.grid->set_settle_at_bounds(config_.grid.settle_at_clamp);
  r.grid->Reset(CellIndex{-half, -half});
  previous_region_ = current_region_;
  current_region_ = region_count_++;
  ++counters_.regions_created;
  // A new regional map starts from the submap (paper §3.4: "the submap is directly used").
  if (!first) SeedRegionFromSubmap(r);
}

void FrontEnd::SeedRegionFromSubmap(RegionalMap& r) {
  // The newest scan is inserted by the caller; seed with the older ones.
  const Pose2 to_region = r.anchor.Inverse() * submap_pose_;
  for (int i = 0; i + 1 < s_.submap->size(); ++i) {
    const SubmapScanView scan = s_.submap->scan(i);
    const Pose2 p = to_region * scan.pose;
    const PointTransform to_region_frame(p);
    for (std::size_t k = 0; k < scan.points.size(); ++k) s_.free_ends[k] = to_region_frame(scan.points[k]);
    if (++stamp_ == 0) stamp_ = 1;
    const InsertionStats st = InsertRays(*r.grid, Point2{p.x, p.y}, Span<const Point2>(s_.free_ends.data(), scan.points.size()),
                                         Span<const Point2>(), config_.grid, stamp_, s_.scratch);
    counters_.updates_dropped_pool_full += static_cast<std::uint32_t>(st.dropped_pool_full);
    if (st.dropped_pool_full > 0) pool_full_ = true;
  }
  if (++stamp_ == 0) stamp_ = 1;  // the scan being added gets its own stamp
}

bool FrontEnd::WellInside(const RegionalMap& r) const {
  const Pose2 robot = pose();
  const Point2 local = r.anchor.Inverse().Apply(Point2{robot.x, robot.y});
  const CellBox box = r.grid->box();
  const float res = r.grid->resolution_m(), margin = config_.front_end.reference_inner_margin_m;
  return local.x >= static_cast<float>(box.min.x) * res + margin && local.y >= static_cast<float>(box.min.y) * res + margin &&
         local.x <= static_cast<float>(box.max.x) * res - margin && local.y <= static_cast<float>(box.max.y) * res - margin;
}

int FrontEnd::ReferenceMaps(int (&maps)[2]) const {
  const FrontEndConfig& f = config_.front_end;
  const auto scans = [&](int i) { return s_.regions[static_cast<std::size_t>(i)].scans_inserted; };
  int n = 0;
  // The current map, once it holds more than the submap it was seeded from.
  if (current_region_ >= 0 && scans(current_region_) >= static_cast<std::uint32_t>(f.submap_scans)) maps[n++] = current_region_;
  // With it, the mature map of the region the robot came from while the robot is well inside it:
  // walls seen from both regions then pull the new map towards the old one instead of letting each
  // keep its own heading (across a border, neighbouring maps disagreed by up to 0.7 deg). Only that
  // one: an older map seen again after a long loop may disagree with the drift accumulated since,
  // and reconciling them is the back end's job.
  if (previous_region_ >= 0 && scans(previous_region_) >= static_cast<std::uint32_t>(f.region_mature_scans) &&
      WellInside(s_.regions[static_cast<std::size_t>(previous_region_)])) {
    maps[n++] = previous_region_;
  }
  return n;
}

void FrontEnd::SecondRegistration() {
  scans_since_second_ = 0;
  int maps[2] = {-1, -1};
  const int n = ReferenceMaps(maps);
  if (n == 0) return;
  RegionalMap& r = s_.regions[static_cast<std::size_t>(maps[0])];
  const FrontEndConfig& f = config_.front_end;
  ++scans_since_region_lines_;
  const bool same_maps = maps[0] == reference_maps_[0] && maps[1] == reference_maps_[1];
  if (!same_maps || scans_since_region_lines_ * static_cast<std::uint32_t>(f.second_registration_period) >=
                        static_cast<std::uint32_t>(f.region_line_period)) {
    BuildRegionReference(maps, n);
    ++fe_counters_.region_line_builds;
    reference_maps_[0] = maps[0];
    reference_maps_[1] = maps[1];
    scans_since_region_lines_ = 0;
  }
  RegisterSubmap(r);
}

void FrontEnd::BuildRegionReference(const int (&maps)[2], int n) {
  // One reference over the maps, in the first one's frame. Regions are squares of one lattice
  // and their anchors are not rotated, so another map's cells are a whole number of cells away.
  const RegionalMap& r = s_.regions[static_cast<std::size_t>(maps[0])];
  const float res = r.grid->resolution_m();
  RegistrationReference& reference = *s_.region_reference;
  ReferenceBuildStats stats;
  reference.BeginBuild(r.grid->box(), res);
  for (int k = 0; k < n; ++k) {
    const RegionalMap& m = s_.regions[static_cast<std::size_t>(maps[k])];
    const CellIndex shift{static_cast<std::int32_t>(std::lround((m.anchor.x - r.anchor.x) / res)),
                          static_cast<std::int32_t>(std::lround((m.anchor.y - r.anchor.y) / res))};
    reference.AddGrid(*m.grid, shift, config_.front_end.region_reference, &stats);
  }
  if (reference.FinishBuild(config_.front_end.region_reference, &stats) != Status::kOk) {
    fe_counters_.reference_cells_dropped += static_cast<std::uint32_t>(stats.dropped_cells);
  }
}

void FrontEnd::RegisterSubmap(RegionalMap& r) {
  const FrontEndConfig& f = config_.front_end;
  // Target: the submap's obstacle cells (from its reference, rebuilt every K1 scans), evenly
  // thinned. Tried and dropped (docs/front-end-accuracy.md): the submap's raw points (noisier,
  // clutter included) and cell centres moved onto their refitted lines; both were less accurate.
  const RegistrationReference& sub = *s_.submap_reference;
  const std::size_t n = sub.cell_count();
  if (n == 0) return;
  const std::size_t max_points = static_cast<std::size_t>(f.second_registration_max_points);
  const std::size_t stride = (n + max_points - 1) / max_points;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; i += stride) s_.target[count++] = sub.CellCentre(static_cast<std::uint16_t>(i));
  const Pose2 initial = r.anchor.Inverse() * submap_pose_;
  const PosePrior prior{initial, f.prior_info_xy, f.prior_info_theta};
  const RegistrationResult res =
      RegisterImproved(*s_.region_reference, Span<const Point2>(s_.target.data(), count), initial, &prior,
                       f.second_registration, s_.correspondences);
  ++fe_counters_.second_registrations;
  if (res.verdict == Status::kOk) {
    submap_pose_ = r.anchor * res.pose;  // the submap, and the robot in it, move together
  } else {
    ++fe_counters_.second_rejected;
  }
}

void FrontEnd::InsertIntoRegion(const ProjectedScan& projected) {
  if (current_region_ < 0) return;
  RegionalMap& r = s_.regions[static_cast<std::size_t>(current_region_)];
  const Pose2 to_region = r.anchor.Inverse() * pose();
  // hits/free_ends are robot-frame; move them into the region's frame in place (the submap
  // already copied the robot-frame points).
  const PointTransform into_region(to_region);
  for (std::size_t i = 0; i < projected.hits; ++i) s_.hits[i] = into_region(s_.hits[i]);
  for (std::size_t i = 0; i < projected.free_ends; ++i) s_.free_ends[i] = into_region(s_.free_ends[i]);
  const InsertionStats st = InsertRays(*r.grid, Point2{to_region.x, to_region.y}, Span<const Point2>(s_.hits.data(), projected.hits),
                                       Span<const Point2>(s_.free_ends.data(), projected.free_ends), config_.grid, stamp_, s_.scratch,
                                       config_.front_end.region_miss_range_m);
  ++r.scans_inserted;
  counters_.updates_out_of_box += static_cast<std::uint32_t>(st.out_of_box);
  counters_.updates_dropped_pool_full += static_cast<std::uint32_t>(st.dropped_pool_full);
  if (st.dropped_pool_full > 0) pool_full_ = true;
}

void FrontEnd::UpdateStatus() {
  if (pool_full_) {
    status_ = MapperStatus::kPoolFull;
  } else if (consecutive_rejections_ >= config_.front_end.lost_after_rejections) {
    status_ = MapperStatus::kLost;
  } else {
    status_ = MapperStatus::kTracking;
  }
}

}  // namespace dpcr
