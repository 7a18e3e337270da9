// The kept start scans (core/front_end/start_scans.hpp): kept during the run's first seconds,
// registered again at its end to place the start in the finished first map.
#include <cmath>

#include "core/front_end/first_registration.hpp"
#include "core/front_end/front_end.hpp"
#include "core/registration/pivot_frame.hpp"

namespace dpcr {

void FrontEnd::KeepStartScan(std::int64_t stamp_us, bool start_scan, std::size_t hits, bool accepted) {
  const StartScansConfig& c = config_.front_end.start_scans;
  float yaw = 0.0f;
  const bool have_yaw = odometry_.GyroYawAt(stamp_us, &yaw);
  if (start_scan) {
    const int map = regions_.current();
    if (map < 0) return;
    start_region_ = map;
    start_in_region_ = Between(regions_[map].anchor, pose());
    // Not for a loaded map (its frame is the saved one), nor without a gyro.
    if (!c.enabled || !have_yaw || !start_scans_.Begin(&regions_.pool(), stamp_us, yaw)) return;
    accepted = true;
  } else {
    start_scans_.Track(stamp_us, have_yaw, yaw, c);
  }
  // The maps come first: a pool that ran out takes the tiles back.
  if (start_scans_.holds_tiles() && counters_.updates_dropped_pool_full > 0) {
    start_scans_.Release(&regions_.pool());
    return;
  }
  if (accepted && regions_.current() == start_region_ && start_scans_.Due(regions_.pool(), stamp_us, c)) {
    start_scans_.Keep(&regions_.pool(), stamp_us, Between(regions_[start_region_].anchor, pose()), Span<const Point2>(s_.hits.data(), hits));
  }
}

StartRefinement FrontEnd::RefineStart() {
  StartRefinement out;
  out.kept = start_scans_.size();
  if (!std::isnan(start_offset_rad_)) {
    out.refined = true;
    out.offset_rad = start_offset_rad_;
    return out;
  }
  const StartScansConfig& c = config_.front_end.start_scans;
  if (out.kept < c.min_scans || start_region_ < 0 || start_region_ >= regions_.size()) {
    start_scans_.Release(&regions_.pool());
    return out;
  }
  if (back_end_.searching()) back_end_.CancelLoopClosure();
  const int maps[2] = {start_region_, -1};
  BuildRegionReference(maps, 1);
  InvalidateRegionReference();
  // Registered from where they were placed then; no prior: the finished map decides.
  const PlicpConfig plicp = FirstRegistrationBase(config_, false);
  float turns[StartScans::kMaxKept];
  for (int i = 0; i < out.kept; ++i) {
    const std::size_t n = start_scans_.Points(regions_.pool(), i, s_.target);
    const Point2 pivot = RecentreOnCentroid(Span<Point2>(s_.target.data(), n));
    const RegistrationResult r = RegisterImproved(*s_.region_reference, Span<const Point2>(s_.target.data(), n),
                                                  Pose2{pivot.x, pivot.y, 0.0f}, nullptr, plicp, s_.correspondences);
    turns[i] = r.verdict == Status::kOk ? r.pose.theta : NAN;
    if (r.verdict == Status::kOk) ++out.registered;
  }
  StartOffsetFit fit;
  const bool fitted = FitStartOffset(start_scans_, regions_.pool(), turns, start_in_region_.theta, c, &fit);
  out.offset_rad = fit.offset_rad;
  out.bias_rad_s = fit.bias_rad_s;
  out.offset_se_rad = fit.offset_se_rad;
  out.refined = fitted;
  if (out.refined) start_offset_rad_ = out.offset_rad;
  start_scans_.Release(&regions_.pool());
  return out;
}

}  // namespace dpcr
