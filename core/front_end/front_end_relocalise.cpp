// FrontEnd's lost handling (front_end.hpp): a robot that does not know where it is puts no scan
// into any map; it tracks locally against a fresh submap and searches the regional maps for
// itself (GlobalLocaliser, one bounded step per scan), then resumes in the same world frame.
#include "core/front_end/front_end.hpp"

#include <cmath>

#include "core/front_end/reference_for_noise.hpp"

namespace dpcr {

bool FrontEnd::LostNow() {
  if (relocalising_) return true;
  if (!config_.localisation.relocalise || !config_.front_end.enable_registration || regions_.size() == 0) return false;
  // Carried (wheels lifted), or the registrations have failed for a while: the pose is unknown.
  const bool lifted = !odometry_.empty() && odometry_.newest().lifted;
  // A streak without a lift may be a robot that only lost track nearby: the second registration
  // may still find it where it thinks it is (as before the global search existed).
  // Without wheels measuring the translation, a submap the regional map keeps rejecting has slipped
  // (FrontEndConfig::lidar_only_lost_after_second_rejections); it may still be near where it believes.
  const int slipped_after = config_.front_end.lidar_only_lost_after_second_rejections;
  const bool slipped = slipped_after > 0 && !WheelsMeasured() && consecutive_second_rejections_ >= slipped_after;
  if (lifted || slipped || consecutive_rejections_ >= config_.front_end.lost_after_rejections) StartRelocalisation(!lifted);
  return relocalising_;
}

void FrontEnd::StartRelocalisation(bool may_be_near) {
  relocalising_ = true;
  may_be_near_ = may_be_near;
  restart_submap_ = true;  // what the submap holds may be of another place
  lost_since_us_ = last_stamp_us_ - streak_us_;
  near_failed_ = false;
  consecutive_rejections_ = consecutive_second_rejections_ = 0;
  localiser_.Cancel();
  localiser_.Drop();
  // A loop-closure search under way is void: the global search takes its grid (the lent table),
  // and the submap it placed is gone.
  if (back_end_.searching()) back_end_.CancelLoopClosure();
  ++counters_.lost_events;
  status_ = MapperStatus::kLost;
}

void FrontEnd::RelocaliseScan(Span<const Beam> beams, const ScanMotion& motion, std::int64_t dt_us,
                              ProjectedScan* projected, const Pose2& predicted) {
  std::size_t hits = projected->hits;
  ++counters_.scans_not_inserted;
  last_scan_region_ = -1;  // in no map: its pose is not known in any
  if (!odometry_.empty() && odometry_.newest().lifted) {
    // Carried: nothing to track, nothing to search with.
    ++counters_.lifted_scans;
    pose_ = predicted;
    localiser_.Cancel();
    localiser_.Drop();
    restart_submap_ = true;
    return;
  }
  if (restart_submap_ || s_.submap->size() == 0) {
    // A fresh submap from the first scan on the floor; the search starts from it at once.
    pose_ = predicted;
    RestartSubmap(hits);
    restart_submap_ = false;
    localiser_.Cancel();
    localiser_.Drop();
    StepRelocalisation(hits);
    return;
  }
  // Local tracking: the search's answer is carried from its frozen scan to the current one.
  RebuildSubmapReferenceIfDue();
  (void)RegisterScan(beams, motion, dt_us, projected, predicted);
  hits = projected->hits;  // a re-deskewed scan was projected again
  if (consecutive_rejections_ > 0) {
    localiser_.Cancel();  // the frozen scan's place in the submap is no longer known
    localiser_.Drop();    // nor the held fix's
    if (consecutive_rejections_ % config_.front_end.submap_restart_after_rejections == 0) RestartSubmap(hits);
    return;
  }
  (void)s_.submap->Add(pose_, Span<const Point2>(s_.hits.data(), hits));
  ++scans_since_submap_lines_;
  // Without a heading sensor the dead-reckoned pose may be far off: the local round instead.
  const bool near_search = !HeadingMeasured() && config_.localisation.near_window_m > 0.0f;
  if (may_be_near_ && !near_search && regions_.current() >= 0 &&
      ++scans_since_second_ >= static_cast<std::uint32_t>(config_.front_end.second_registration_period)) {
    // Aligned to the map it was in, where it believes it is: found again without a search.
    const bool aligned = SecondRegistration();
    localiser_.ForgetGrid();  // the registration rebuilt the reference the search grid borrows
    if (aligned) {
      localiser_.Cancel();
      relocalising_ = false;
      ++counters_.relocalisations;
      Rejoin(regions_.current());
      return;
    }
  }
  StepRelocalisation(hits);
}

void FrontEnd::StepRelocalisation(std::size_t hits) {
  if (!localiser_.active()) {
    const float window = NearWindow();
    const int map = regions_.current();
    if (window > 0.0f) {
      const Pose2 centre = regions_[map].anchor.Inverse() * pose();
      localiser_.BeginLocal(back_end_.storage(), Span<const Point2>(s_.hits.data(), hits), config_.localisation, map, centre, window);
    } else {
      localiser_.Begin(back_end_.storage(), Span<const Point2>(s_.hits.data(), hits), config_.localisation);
    }
    localiser_.LimitHeadings(pose().theta, HeadingWindow());
    frozen_in_submap_ = pose_;
  }
  GlobalFix fix;
  const Status st = localiser_.Step(back_end_.storage(), Span<const RegionalMap>(regions_.maps().data(), regions_.maps().size()), config_.front_end.region_width_m,
                                    ReferenceForNoise(config_.front_end.region_reference, config_), config_.localisation, config_.back_end, &fix);
  // The search used the regional reference (its table, then a build).
  InvalidateRegionReference();
  if (st == Status::kOk && TakeFix(fix)) ResumeAt(fix);
  if (st != Status::kRejected) return;
  ++counters_.relocalisation_failures;
  if (localiser_.local()) {
    near_failed_ = true;  // not near, or not for sure: the global search next
    return;
  }
  if (localiser_.holding()) {
    // Without a heading sensor a verified fix is waiting for a second one: one more round before
    // the fallback below (which would trust the dead-reckoned pose over it).
    localiser_.Drop();
    return;
  }
  if (may_be_near_) {
    // Not carried, and not found anywhere for sure (a symmetric room, a place outside the maps):
    // back to tracking from the dead-reckoned pose, as without the search (the submap restarted;
    // never smear still keeps rejected scans out). A new streak searches again.
    relocalising_ = false;
    InvalidateRegionReference();
  }
}

float FrontEnd::LostSeconds() const {
  const float lost_s = static_cast<float>(last_stamp_us_ - lost_since_us_) * 1e-6f;
  return lost_s > 0.0f ? lost_s : 0.0f;
}

float FrontEnd::NearDistance() const {
  const LocalisationConfig& c = config_.localisation;
  return c.near_window_m + c.near_window_mps * LostSeconds();
}

float FrontEnd::NearWindow() const {
  const LocalisationConfig& c = config_.localisation;
  if (!may_be_near_ || near_failed_ || HeadingMeasured() || !(c.near_window_m > 0.0f) || regions_.current() < 0) return 0.0f;
  const float window = NearDistance();
  // Past the map's square and margin the local round would be the global one's work on one map.
  return window < 0.5f * config_.front_end.region_width_m + c.window_margin_m ? window : 0.0f;
}

float FrontEnd::HeadingWindow() const {
  const LocalisationConfig& c = config_.localisation;
  if (!may_be_near_ || !HeadingMeasured() || !(c.heading_window_rad > 0.0f)) return 0.0f;
  return c.heading_window_rad + c.heading_window_rad_s * LostSeconds();
}

bool FrontEnd::TakeFix(const GlobalFix& fix) {
  const LocalisationConfig& c = config_.localisation;
  if (HeadingMeasured() && !PastNearWindow(fix)) return true;
  if (fix.score >= c.clear_min_score && fix.second_score <= c.clear_max_ratio * fix.score) return true;
  // Where the robot would be now by this fix and by the held one (each places the submap frame).
  const Pose2 frame = SubmapFrameOf(fix);
  Pose2 held;
  if (localiser_.Held(back_end_.storage(), &held)) {
    const Pose2 apart = Between(held * pose_, frame * pose_);
    const CorrelativeSearchConfig& sep = config_.back_end.search;
    if (std::hypot(apart.x, apart.y) < 0.5f * sep.peak_separation_m &&
        std::fabs(apart.theta) < 0.5f * sep.peak_separation_rad) {
      localiser_.Drop();
      return true;
    }
  }
  localiser_.Hold(back_end_.storage(), frame);
  return false;
}

bool FrontEnd::PastNearWindow(const GlobalFix& fix) const {
  const LocalisationConfig& c = config_.localisation;
  if (!may_be_near_ || !(c.near_window_m > 0.0f)) return false;
  const Pose2 by_fix = SubmapFrameOf(fix) * pose_;
  const Pose2 believed = pose();
  return std::hypot(by_fix.x - believed.x, by_fix.y - believed.y) > NearDistance();
}

Pose2 FrontEnd::SubmapFrameOf(const GlobalFix& fix) const {
  // The frozen scan was at fix.in_map in the map; the submap frame follows, and the robot in it.
  return regions_[fix.map].anchor * fix.in_map * frozen_in_submap_.Inverse();
}

void FrontEnd::ResumeAt(const GlobalFix& fix) {
  submap_pose_ = SubmapFrameOf(fix);
  relocalising_ = false;
  ++counters_.relocalisations;
  Rejoin(fix.map);
}

void FrontEnd::Rejoin(int found) {
  consecutive_rejections_ = 0;
  last_degenerate_ = false;
  const Pose2 world = pose();
  last_world_ = world;
  const FrontEndConfig& f = config_.front_end;
  tracker_.Restore(region_origin(), f.region_width_m, f.region_hysteresis_m, Point2{world.x, world.y});
  anchor_region_ = found;
  lost_in_region_ = false;
  const RegionKey key = tracker_.current();
  if (config_.localisation.localise_only && regions_.Find(key) < 0) {
    // Maps frozen: the map the robot was found in stays its reference.
    const RegionKey found_key = regions_[found].key;
    if (regions_.current() != found) (void)regions_.Enter(found_key, tracker_.Centre(found_key));
  } else {
    // A region without a map yet, found through a neighbour's margin: chained to that map.
    EnterRegionChainedTo(key, found);
  }
  InvalidateRegionReference();
  // The second registration aligns the submap to the map at the next scan.
  scans_since_second_ = static_cast<std::uint32_t>(f.second_registration_period);
}

void FrontEnd::EnterFrozenRegion() {
  const RegionKey key = tracker_.current();
  if (regions_.Find(key) < 0) return;  // no map there: the current one stays the reference
  (void)regions_.Enter(key, tracker_.Centre(key));
  anchor_region_ = regions_.current();
  lost_in_region_ = false;
  if (config_.front_end.enable_registration) (void)SecondRegistration();
}

}  // namespace dpcr
