// The kept start scans (core/front_end/start_scans.hpp): kept during the run's first seconds,
// registered again at its end to place the start in the finished first map.
#include <cmath>

#include "core/front_end/first_registration.hpp"
#include "core/front_end/front_end.hpp"
#include "core/registration/pivot_frame.hpp"

namespace dpcr {

void FrontEnd::KeepStartScan(std::int64_t stamp_us, bool start_scan, std::size_t hits, bool accepted) {
  const StartScansConfig& c = config_.front_end.start_scans;
  // The maps come first: a pool that ran out takes the tiles back (and lends none).
  const bool pool_ran_out = counters_.updates_dropped_pool_full > 0;
  if (pool_ran_out && start_scans_.holds_tiles()) start_scans_.Release(&regions_.pool());
  if (!start_scan && !start_scans_.keeping()) return;  // past the window: no yaw to look up
  // The gyro's yaw; without a gyro, the wheels' heading, kept in case the wheel check finds the
  // ticks to carry only an IMU's heading (as real recordings were converted).
  float yaw = 0.0f;
  const bool gyro = start_scan ? StartGyroYaw(stamp_us, &yaw) : !start_scans_.wheel_turns() && odometry_.GyroYawAt(stamp_us, &yaw);
  const bool wheel_turns = start_scan ? !gyro : start_scans_.wheel_turns();
  const bool have_yaw = wheel_turns ? have_odom_ && WheelsMeasured() : gyro;
  if (wheel_turns) yaw = NormalizeAngle(last_odom_.theta);
  if (start_scan) {
    const int map = regions_.current();
    if (map < 0) return;
    start_region_ = map;
    start_in_region_ = Between(regions_[map].anchor, pose());
    // Nothing without a heading sensor. (A loaded map has no start scan: its frame is the saved one.)
    if (!c.enabled || pool_ran_out || !have_yaw || !start_scans_.Begin(&regions_.pool(), stamp_us, yaw, wheel_turns)) return;
    accepted = true;
  } else {
    start_scans_.Track(stamp_us, have_yaw, yaw, c);
  }
  if (accepted && regions_.current() == start_region_ && start_scans_.Due(regions_.pool(), stamp_us, c)) {
    start_scans_.Keep(&regions_.pool(), stamp_us, Between(regions_[start_region_].anchor, pose()), Span<const Point2>(s_.hits.data(), hits));
  }
}

bool FrontEnd::StartGyroYaw(std::int64_t stamp_us, float* yaw) const {
  if (odometry_.GyroYawAt(stamp_us, yaw)) return true;
  // A device's first revolution can be stamped before the first wheel frame it waited for (the
  // bus's latency): the gyro's yaw at its first sample, the robot barely moved in between.
  return !odometry_.empty() && stamp_us < odometry_.oldest().stamp_us && odometry_.GyroYawAt(odometry_.oldest().stamp_us, yaw);
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
  // Turns from wheels that measure the translation too err with the distance driven (a wheel's
  // radius), not with time: not a gyro's (as for the start heading's fit).
  const bool wheels = start_scans_.wheel_turns() && !wheel_check_.translation_ignored();
  if (out.kept < c.min_scans || wheels || start_region_ < 0 || start_region_ >= regions_.size()) {
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
