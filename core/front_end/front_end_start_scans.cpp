// The kept start scans (core/front_end/start_scans.hpp): kept during the run's first seconds,
// registered again at its end to place the start in the finished first map; without wheels
// measuring the translation, the start scan searched for in that map too.
#include <cmath>

#include "core/front_end/first_registration.hpp"
#include "core/front_end/front_end.hpp"
#include "core/front_end/reference_for_noise.hpp"
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
  if (!std::isnan(start_offset_rad_) || StartMoved()) {
    // Done before: the same answer.
    out.refined = !std::isnan(start_offset_rad_);
    out.offset_rad = out.refined ? start_offset_rad_ : 0.0f;
    out.located = out.moved = StartMoved();
    out.shift = StartShift();
    return out;
  }
  const StartScansConfig& c = config_.front_end.start_scans;
  // Turns from wheels that measure the translation too err with the distance driven (a wheel's
  // radius), not with time: not a gyro's (as for the start heading's fit).
  const bool wheels = start_scans_.wheel_turns() && !wheel_check_.translation_ignored();
  const bool in_map = start_region_ >= 0 && start_region_ < regions_.size() && start_scans_.holds_tiles();
  const bool fit = in_map && out.kept >= c.min_scans && !wheels;
  // Only a start the wheels did not hold in place can have slid.
  const bool locate = in_map && out.kept >= 1 && c.locate && (!WheelsMeasured() || wheel_check_.translation_ignored());
  if (fit || locate) {
    if (back_end_.searching()) back_end_.CancelLoopClosure();
    if (fit) FitStartInMap(&out);
    if (locate) LocateStart(&out);
  }
  start_scans_.Release(&regions_.pool());
  return out;
}

void FrontEnd::FitStartInMap(StartRefinement* out) {
  const StartScansConfig& c = config_.front_end.start_scans;
  const int maps[2] = {start_region_, -1};
  BuildRegionReference(maps, 1);
  InvalidateRegionReference();
  // Registered from where they were placed then; no prior: the finished map decides.
  const PlicpConfig plicp = FirstRegistrationBase(config_, false);
  float turns[StartScans::kMaxKept];
  for (int i = 0; i < out->kept; ++i) {
    const std::size_t n = start_scans_.Points(regions_.pool(), i, s_.target);
    const Point2 pivot = RecentreOnCentroid(Span<Point2>(s_.target.data(), n));
    const RegistrationResult r = RegisterImproved(*s_.region_reference, Span<const Point2>(s_.target.data(), n),
                                                  Pose2{pivot.x, pivot.y, 0.0f}, nullptr, plicp, s_.correspondences);
    turns[i] = r.verdict == Status::kOk ? r.pose.theta : NAN;
    if (r.verdict == Status::kOk) ++out->registered;
  }
  StartOffsetFit fit;
  const bool fitted = FitStartOffset(start_scans_, regions_.pool(), turns, start_in_region_.theta, c, &fit);
  out->offset_rad = fit.offset_rad;
  out->bias_rad_s = fit.bias_rad_s;
  out->offset_se_rad = fit.offset_se_rad;
  out->refined = fitted;
  if (fitted) start_offset_rad_ = fit.offset_rad;
}

void FrontEnd::LocateStart(StartRefinement* out) {
  // The start scan (kept first), back in the robot's frame at its recorded pose.
  const std::size_t n = start_scans_.Points(regions_.pool(), 0, s_.target);
  const PointTransform to_robot(start_in_region_.Inverse());
  for (std::size_t i = 0; i < n; ++i) s_.target[i] = to_robot(s_.target[i]);
  const Span<const Point2> points(s_.target.data(), n);
  // Registered where it was recorded: a start that slid a little is found there.
  const int maps[2] = {start_region_, -1};
  BuildRegionReference(maps, 1);
  InvalidateRegionReference();
  const RegistrationResult here =
      RegisterImproved(*s_.region_reference, points, start_in_region_, nullptr, FirstRegistrationBase(config_, false), s_.correspondences);
  // Searched for around it (the global localiser's local round, run to its end): a start that slid
  // metres, with the heading sensor's heading.
  // Within 3 m of it (an XV-11's 6 m range, halved: a slide along a room it cannot see across).
  constexpr float kWindowM = 3.0f;
  constexpr float kHeadingWindowRad = 0.1f;
  localiser_.Cancel();
  localiser_.Drop();
  localiser_.BeginLocal(back_end_.storage(), points, config_.localisation, start_region_, start_in_region_, kWindowM);
  localiser_.LimitHeadings((regions_[start_region_].anchor * start_in_region_).theta, kHeadingWindowRad);
  constexpr int kMaxSteps = 1000;  // each step is bounded; a round over one map's window ends in a few
  const Span<const RegionalMap> regional(regions_.maps().data(), regions_.maps().size());
  const ReferenceConfig reference = ReferenceForNoise(config_.front_end.region_reference, config_);
  GlobalFix fix;
  Status st = Status::kNotEnoughData;
  for (int i = 0; i < kMaxSteps && st == Status::kNotEnoughData; ++i) {
    st = localiser_.Step(back_end_.storage(), regional, config_.front_end.region_width_m, reference, config_.localisation, config_.back_end, &fix);
  }
  localiser_.Cancel();
  InvalidateRegionReference();  // the search borrowed its table
  // The search's pose only when it explains clearly more of the scan than the recorded place does:
  // the map can hold a look-alike, and the recorded place is right unless the start slid.
  constexpr float kInlierMargin = 0.1f;
  const bool found = st == Status::kOk && fix.map == start_region_;
  const bool here_ok = here.verdict == Status::kOk;
  if (found && (!here_ok || fix.inlier_ratio >= here.inlier_ratio + kInlierMargin)) {
    out->shift = Between(start_in_region_, fix.in_map);
  } else if (here_ok) {
    out->shift = Between(start_in_region_, here.pose);
  } else {
    return;
  }
  out->located = true;
  const float shift_m = std::hypot(out->shift.x, out->shift.y);
  // Below this the placement's own error is as large (found within 5 mm where the start held).
  constexpr float kMinShiftM = 0.1f;
  if (shift_m < kMinShiftM || shift_m > kWindowM) return;
  out->moved = true;
  start_shift_mm_[0] = static_cast<std::int16_t>(std::lround(out->shift.x * 1000.0f));
  start_shift_mm_[1] = static_cast<std::int16_t>(std::lround(out->shift.y * 1000.0f));
}

}  // namespace dpcr
