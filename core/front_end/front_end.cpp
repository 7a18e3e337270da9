#include "core/front_end/front_end.hpp"

#include <cmath>

#include "core/grid/ray_caster.hpp"

namespace dpcr {

Status FrontEnd::Init(const MapperConfig& config) {
  const Status v = Validate(config);
  if (v != Status::kOk) return v;
  if (static_cast<std::size_t>(config.front_end.second_registration_max_points) > s_.target.size()) {
    return Status::kInvalidArgument;
  }
  config_ = config;
  regions_.Reset(config.grid, config.front_end.region_miss_range_m);
  s_.submap->Reset(config.grid, config.front_end.submap_scans, config.front_end.submap_miss_range_m);
  status_ = MapperStatus::kWaitingForData;
  counters_ = MapperCounters{};
  fe_counters_ = FrontEndCounters{};
  odometry_.Clear();
  pose_ = submap_pose_ = last_odom_ = last_motion_ = Pose2::Identity();
  have_odom_ = have_scan_ = weak_match_ = have_gyro_yaw_ = false;
  last_gyro_yaw_ = 0.0f;
  search_grid_version_ = 0;
  consecutive_rejections_ = 0;
  last_stamp_us_ = -1;
  streak_us_ = 0;
  InvalidateRegionReference();
  scans_since_submap_lines_ = scans_since_second_ = second_registrations_since_region_lines_ = 0;
  scan_marker_.Reset();
  back_end_.Init(config.back_end, config.front_end.region_width_m, config.front_end.region_reference.obstacle_threshold);
  path_m_ = 0.0f;
  last_world_ = Pose2::Identity();
  last_scan_region_ = -1;
  last_scan_in_region_ = Pose2::Identity();
  anchor_region_ = -1;
  lost_in_region_ = false;
  scans_since_closure_try_ = 0;
  localiser_.Cancel();
  relocalising_ = restart_submap_ = may_be_near_ = false;
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
    return pose_ * last_motion_;  // constant velocity: the last scan-to-scan motion again
  }
  const Pose2 odom = odometry_.PoseAt(stamp_us);
  Pose2 step = Between(last_odom_, odom);
  // With a gyro (FrontEndConfig::gyro_heading): the wheels give the translation, the gyro the turn.
  float yaw = 0.0f;
  const bool use_gyro = config_.front_end.gyro_heading || !odometry_.newest().has_wheels;
  const bool gyro = use_gyro && odometry_.GyroYawAt(stamp_us, &yaw);
  if (gyro && have_gyro_yaw_) step.theta = NormalizeAngle(yaw - last_gyro_yaw_);
  // Without wheels (a gyro alone) the translation is the last scan-to-scan motion's (constant velocity).
  if (!odometry_.newest().has_wheels) {
    step.x = last_motion_.x;
    step.y = last_motion_.y;
  }
  have_gyro_yaw_ = gyro;
  last_gyro_yaw_ = yaw;
  const Pose2 predicted = have_odom_ ? pose_ * step : pose_;
  last_odom_ = odom;
  have_odom_ = true;
  return predicted;
}

Status FrontEnd::AddScan(Span<const Beam> beams, std::int64_t stamp_us) {
  ++counters_.scans;
  (void)scan_marker_.Next();
  // 1. Prediction and de-skew.
  const Pose2 previous = pose_;
  const Pose2 predicted = Predict(stamp_us);
  const ProjectedScan projected = ProjectScan(beams, stamp_us, config_.lidar, odometry_, s_.hits, s_.free_ends);
  counters_.beams_invalid += static_cast<std::uint32_t>(projected.invalid);
  if (projected.hits == 0 && projected.free_ends == 0) {
    ++counters_.scans_rejected;
    ++counters_.scans_empty;
    pose_ = predicted;
    return Status::kNotEnoughData;
  }
  // 2. First registration against the submap (not for the very first scan: nothing to match).
  bool keep_out = false;
  const std::int64_t since_last_us = last_stamp_us_ >= 0 ? stamp_us - last_stamp_us_ : 0;
  last_stamp_us_ = stamp_us;
  // 0. Lost (wheels lifted, a long rejection streak, an unknown start): the scan goes into no
  // map; it tracks locally and searches the maps (front_end_relocalise.cpp).
  if (LostNow()) {
    RelocaliseScan(projected.hits, predicted);
    last_motion_ = Between(previous, pose_);
    FinishScan(since_last_us);
    return Status::kOk;
  }
  if (config_.front_end.enable_registration && s_.submap->size() > 0) {
    RebuildSubmapReferenceIfDue();
    const bool uncertain = UncertainPrediction(predicted);
    RegisterScan(projected.hits, predicted);
    keep_out = AfterFirstRegistration(uncertain, since_last_us, projected.hits);
  } else {
    pose_ = predicted;
  }
  last_motion_ = Between(previous, pose_);
  // 4a. The submap takes every scan (its own ring decides what leaves), but not a rejected one
  // placed by an uncertain prediction.
  if (!keep_out) {
    (void)s_.submap->Add(pose_, Span<const Point2>(s_.hits.data(), projected.hits));
    ++scans_since_submap_lines_;
  }
  // 3. Regions, and the second registration.
  const Pose2 world = pose();
  if (have_scan_) path_m_ += std::hypot(world.x - last_world_.x, world.y - last_world_.y);
  if (!have_scan_) {
    tracker_.Start(Point2{world.x, world.y}, config_.front_end.region_width_m, config_.front_end.region_hysteresis_m);
    have_scan_ = true;
    EnterRegion(true);
  } else if (tracker_.Update(Point2{world.x, world.y})) {
    EnterRegion(false);
  } else if (lost_in_region_) {
    // Retry once the robot has moved on enough to see something new.
    if (++scans_since_closure_try_ >= static_cast<std::uint32_t>(config_.back_end.loop_retry_scans) &&
        path_m_ - path_at_closure_try_ >= config_.back_end.loop_retry_path_m) {
      scans_since_closure_try_ = 0;
      lost_in_region_ = !TryLoopClosure(anchor_region_);
      if (!lost_in_region_) anchor_region_ = regions_.current();
    }
  } else if (config_.front_end.enable_registration &&
             ++scans_since_second_ >= static_cast<std::uint32_t>(config_.front_end.second_registration_period)) {
    SecondRegistration();
  }
  // 4b. Once into the current regional map (not while the robot cannot place itself in it, nor
  // a scan kept out above).
  if (lost_in_region_ || keep_out || config_.localisation.localise_only) {
    ++counters_.scans_not_inserted;
    // Its pose is still known in the anchor region's frame.
    last_scan_region_ = anchor_region_ >= 0 ? anchor_region_ : regions_.current();
    if (last_scan_region_ >= 0) last_scan_in_region_ = Between(regions_[last_scan_region_].anchor, pose());
  } else {
    InsertIntoRegion(projected);
  }
  // 5. Back end: at most one queued job.
  StepBackEnd();
  FinishScan(since_last_us);
  return Status::kOk;
}

void FrontEnd::FinishScan(std::int64_t since_last_us) {
  last_world_ = pose();
  UpdateStatus();
  if (status_ == MapperStatus::kLost) {
    ++counters_.lost_scans;
    counters_.lost_us += since_last_us;
  }
}

bool FrontEnd::UncertainPrediction(const Pose2& predicted) const {
  return odometry_.empty() || !odometry_.newest().has_wheels || consecutive_rejections_ > 0 ||
         std::fabs(NormalizeAngle(predicted.theta - pose_.theta)) > config_.front_end.uncertain_turn_rad;
}

bool FrontEnd::AfterFirstRegistration(bool uncertain, std::int64_t since_last_us, std::size_t hits) {
  if (consecutive_rejections_ == 0) {
    streak_us_ = 0;
    return false;
  }
  ++counters_.scans_rejected;
  ++counters_.streak_scans;
  counters_.streak_us += since_last_us;
  streak_us_ += since_last_us;
  const std::uint32_t streak = static_cast<std::uint32_t>(consecutive_rejections_);
  if (streak > counters_.longest_streak_scans) counters_.longest_streak_scans = streak;
  if (streak_us_ > counters_.longest_streak_us) counters_.longest_streak_us = streak_us_;
  if (!uncertain) {
    ++counters_.scans_fused_at_prediction;
    return false;
  }
  ++counters_.scans_kept_out_rejected;
  // Kept out of everything, the submap would never track again: every so many rejections in a
  // row, a fresh submap starts from this scan at the predicted pose (regional maps untouched; the
  // scan stays out of them).
  if (consecutive_rejections_ % config_.front_end.submap_restart_after_rejections == 0) RestartSubmap(hits);
  return true;
}

void FrontEnd::RestartSubmap(std::size_t hits) {
  const FrontEndConfig& f = config_.front_end;
  s_.submap->Reset(config_.grid, f.submap_scans, f.submap_miss_range_m);
  (void)s_.submap->Add(pose_, Span<const Point2>(s_.hits.data(), hits));
  scans_since_submap_lines_ = static_cast<std::uint32_t>(f.submap_line_period);  // rebuild next scan
  ++counters_.submap_restarts;
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
  if (config_.localisation.localise_only) {
    EnterFrozenRegion();
    return;
  }
  const RegionKey key = tracker_.current();
  const int left = regions_.current();
  switch (regions_.Enter(key, tracker_.Centre(key))) {
    case RegionSet::Entry::kKnown:
      OnRegionLeft(left);
      if (config_.front_end.enable_registration) EnterKnownRegion();
      break;
    case RegionSet::Entry::kCreated:
      ++counters_.regions_created;
      OnRegionLeft(left);
      // Chained to the map the robot's pose is known in (the region left, unless the robot came
      // through a map it could not place itself in).
      back_end_.AddRegion(regions_.maps(), regions_.current(), anchor_region_);
      anchor_region_ = regions_.current();
      lost_in_region_ = false;
      // A new regional map starts from the submap (paper §3.4: "the submap is directly used").
      if (!first) {
        const int dropped = regions_.SeedFromSubmap(*s_.submap, submap_pose_, s_.free_ends, scan_marker_);
        counters_.updates_dropped_pool_full += static_cast<std::uint32_t>(dropped);
      }
      break;
    case RegionSet::Entry::kPoolFull:
      lost_in_region_ = false;
      // Evict nothing: the map stops growing; localisation goes on against the submap.
      ++counters_.region_pool_full;
      break;
  }
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
  const auto scans = [&](int i) { return regions_[i].scans_inserted; };
  const int current = regions_.current(), previous = regions_.previous();
  int n = 0;
  // The current map, once it holds more than the submap it was seeded from.
  if (current >= 0 && scans(current) >= static_cast<std::uint32_t>(f.submap_scans)) maps[n++] = current;
  // With it, the mature map of the region the robot came from while the robot is well inside it:
  // walls seen from both regions then pull the new map towards the old one instead of letting each
  // keep its own heading (across a border, neighbouring maps disagreed by up to 0.7 deg). Only that
  // one: an older map seen again after a long loop may disagree with the drift accumulated since,
  // and reconciling them is the back end's job.
  if (previous >= 0 && scans(previous) >= static_cast<std::uint32_t>(f.region_mature_scans) &&
      WellInside(regions_[previous])) {
    maps[n++] = previous;
  }
  return n;
}

bool FrontEnd::SecondRegistration(RegistrationResult* result, int* region) {
  scans_since_second_ = 0;
  int maps[2] = {-1, -1};
  const int n = ReferenceMaps(maps);
  if (n == 0) return false;
  RegionalMap& r = regions_[maps[0]];
  const FrontEndConfig& f = config_.front_end;
  ++second_registrations_since_region_lines_;
  const bool same_maps = maps[0] == reference_maps_[0] && maps[1] == reference_maps_[1];
  if (!same_maps || second_registrations_since_region_lines_ * static_cast<std::uint32_t>(f.second_registration_period) >=
                        static_cast<std::uint32_t>(f.region_line_period)) {
    BuildRegionReference(maps, n);
    ++fe_counters_.region_line_builds;
    reference_maps_[0] = maps[0];
    reference_maps_[1] = maps[1];
    second_registrations_since_region_lines_ = 0;
  }
  const RegistrationResult res = RegisterSubmap(r);
  if (result != nullptr) *result = res;
  if (region != nullptr) *region = maps[0];
  return res.verdict == Status::kOk;
}

void FrontEnd::BuildRegionReference(const int (&maps)[2], int n) {
  // One reference over the maps, in the first one's frame. Until the back end moves anchors,
  // regions are squares of one lattice and another map's cells are a whole number of cells away
  // (AddPlacedGrid takes the exact shift); after, they are carried cell by cell.
  const RegionalMap& r = regions_[maps[0]];
  const float res = r.grid->resolution_m();
  RegistrationReference& reference = *s_.region_reference;
  ReferenceBuildStats stats;
  reference.BeginBuild(r.grid->box(), res);
  for (int k = 0; k < n; ++k) {
    const RegionalMap& m = regions_[maps[k]];
    reference.AddPlacedGrid(*m.grid, Between(r.anchor, m.anchor), config_.front_end.region_reference, &stats);
  }
  if (reference.FinishBuild(config_.front_end.region_reference, &stats) != Status::kOk) {
    fe_counters_.reference_cells_dropped += static_cast<std::uint32_t>(stats.dropped_cells);
  }
}

RegistrationResult FrontEnd::RegisterSubmap(RegionalMap& r) {
  const FrontEndConfig& f = config_.front_end;
  // Target: the submap's obstacle cells (from its reference, rebuilt every K1 scans), evenly
  // thinned. Tried and dropped (docs/front-end-accuracy.md): the submap's raw points (noisier,
  // clutter included) and cell centres moved onto their refitted lines; both were less accurate.
  const std::size_t count = SubmapTarget();
  if (count == 0) return RegistrationResult{};
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
  return res;
}

void FrontEnd::InsertIntoRegion(const ProjectedScan& projected) {
  last_scan_region_ = regions_.current();
  if (last_scan_region_ >= 0) {
    RegionalMap& r = regions_[last_scan_region_];
    last_scan_in_region_ = Between(r.anchor, pose());
    r.path_at_last_scan_m = path_m_;
  }
  // The submap already copied the robot-frame points: they may move into the region's frame.
  const InsertionStats st = regions_.InsertScan(pose(), Span<Point2>(s_.hits.data(), projected.hits),
                                                Span<Point2>(s_.free_ends.data(), projected.free_ends),
                                                scan_marker_.current());
  counters_.updates_out_of_box += static_cast<std::uint32_t>(st.out_of_box);
  counters_.updates_dropped_pool_full += static_cast<std::uint32_t>(st.dropped_pool_full);
}

void FrontEnd::EnterKnownRegion() {
  const int region = regions_.current();
  const float absence = path_m_ - regions_[region].path_at_last_scan_m;
  // Align the submap to the map at once (paper: on region entry).
  const Pose2 submap_before = submap_pose_;
  RegistrationResult result;
  int frame = -1;
  const bool aligned = SecondRegistration(&result, &frame);
  if (absence < config_.back_end.loop_min_path_m || anchor_region_ < 0 || !config_.back_end.enable) {
    anchor_region_ = region;  // back after a short detour
    lost_in_region_ = false;
    return;
  }
  // Back after a loop. Aligned to this map alone: that is a closure for the graph too. Otherwise
  // the drift may be past the PLICP basin: a search. Without either, the robot does not know
  // where it is in this map, and its scans stay out of it until a retry succeeds or it reaches a
  // new region.
  if (aligned && frame == region) {
    if (back_end_.AddClosure(regions_.maps(), region, anchor_region_, result, submap_before)) {
      submap_pose_ = regions_[region].anchor * result.pose;
      InvalidateRegionReference();
    }
    anchor_region_ = region;
    lost_in_region_ = false;
    return;
  }
  lost_in_region_ = !TryLoopClosure(anchor_region_);
  if (!lost_in_region_) anchor_region_ = region;
  scans_since_closure_try_ = 0;
}

void FrontEnd::InvalidateRegionReference() { reference_maps_[0] = reference_maps_[1] = -1; }

void FrontEnd::OnRegionLeft(int left) {
  if (left >= 0 && left != regions_.current()) back_end_.OnRegionLeft(regions_.maps(), left);
}

std::size_t FrontEnd::SubmapTarget() {
  const RegistrationReference& sub = *s_.submap_reference;
  const std::size_t n = sub.cell_count();
  if (n == 0) return 0;
  const std::size_t max_points = static_cast<std::size_t>(config_.front_end.second_registration_max_points);
  const std::size_t stride = (n + max_points - 1) / max_points;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; i += stride) s_.target[count++] = sub.CellCentre(static_cast<std::uint16_t>(i));
  return count;
}

bool FrontEnd::TryLoopClosure(int from) {
  const int region = regions_.current();
  if (region < 0) return false;
  path_at_closure_try_ = path_m_;
  const std::size_t n = SubmapTarget();
  const float path = path_m_ - regions_[region].path_at_last_scan_m;
  const LoopClosureResult r =
      back_end_.TryLoopClosure(regions_.maps(), region, from, Span<const Point2>(s_.target.data(), n), submap_pose_, path);
  if (r.used_reference) InvalidateRegionReference();
  if (r.verdict != Status::kOk) return false;
  // The anchors have moved (the graph took the closure); the submap belongs where it was found.
  submap_pose_ = regions_[region].anchor * r.submap_in_region;
  InvalidateRegionReference();
  return true;
}

void FrontEnd::StepBackEnd() {
  // The robot's pose is known in the anchor region's frame (the current one, unless the robot
  // could not place itself in the map it entered): it moves with that vertex.
  const int followed = anchor_region_ >= 0 ? anchor_region_ : regions_.current();
  const Pose2 before = followed >= 0 ? regions_[followed].anchor : Pose2::Identity();
  const BackEnd::StepResult r = back_end_.Step(regions_.maps());
  if (r.used_reference || r.anchors_moved) InvalidateRegionReference();
  if (r.anchors_moved && followed >= 0) submap_pose_ = regions_[followed].anchor * before.Inverse() * submap_pose_;
}

void FrontEnd::UpdateStatus() {
  if (relocalising_) {
    status_ = MapperStatus::kLost;
  } else if (regions_.pool_full()) {
    status_ = MapperStatus::kPoolFull;
  } else if (consecutive_rejections_ >= config_.front_end.lost_after_rejections) {
    status_ = MapperStatus::kLost;
  } else {
    status_ = MapperStatus::kTracking;
  }
}

}  // namespace dpcr
