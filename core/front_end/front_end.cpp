#include "core/front_end/front_end.hpp"

#include <cmath>
#include <utility>

#include "core/front_end/acceleration_limit.hpp"
#include "core/front_end/forward_step.hpp"
#include "core/front_end/reference_for_noise.hpp"
#include "core/front_end/return_share.hpp"
#include "core/registration/weak_direction_hold.hpp"
#include "core/geometry/wall_direction.hpp"
#include "core/grid/ray_caster.hpp"
#include "core/registration/pivot_frame.hpp"

namespace dpcr {
namespace {

// Odometry poses farther than this from the odometry origin are corrupt samples, not motion: past
// any floor a vacuum or a research robot drives, and short of where float positions fail.
constexpr float kMaxOdometryCoordinateM = 100000.0f;

// A scan this long after the one before it (or this far before it) follows a clock jump, or a
// sleep of the robot: nothing measured per second (the constant velocity, a turn rate, a
// rejection streak's time) is carried across it. Longer than any lidar dropout a run survives.
constexpr std::int64_t kMaxScanGapUs = 600 * 1000000LL;

// A yaw rate past any gyro's range (vacuums' saturate at 35 rad/s): a rate of 1e30 integrated to
// an infinite heading once.
constexpr float kMaxGyroRateRadS = 100.0f;

bool PlausibleOdometry(const OdometrySample& s) {
  // Written so that NaN fails every test.
  const bool position = std::fabs(s.pose.x) <= kMaxOdometryCoordinateM && std::fabs(s.pose.y) <= kMaxOdometryCoordinateM;
  return position && std::isfinite(s.pose.theta) && (!s.has_gyro || std::fabs(s.gyro_yaw_rate) <= kMaxGyroRateRadS) &&
         PlausibleStamp(s.stamp_us);
}

}  // namespace

Status FrontEnd::Init(const MapperConfig& config) {
  const Status v = Validate(config);
  if (v != Status::kOk) return v;
  if (static_cast<std::size_t>(config.front_end.second_registration_max_points) > s_.target.size()) {
    return Status::kInvalidArgument;
  }
  config_ = config;
  // Hit means only behind a lidar that declares its range noise: measured to help there (the
  // simulated LD06 and XV-11), and to hurt intel.clf's loop closures (docs/back-end.md, "Walls
  // fitted where the returns fell").
  GridConfig regional = config.grid;
  regional.hit_means = HitMeans();
  regions_.Reset(regional, config.front_end.region_miss_range_m);
  s_.submap->Reset(config.grid, config.front_end.submap_scans, config.front_end.submap_miss_range_m);
  status_ = MapperStatus::kWaitingForData;
  counters_ = MapperCounters{};
  fe_counters_ = FrontEndCounters{};
  odometry_.Clear();
  wheel_check_ = WheelCheck{};
  calibration_.Reset();
  stall_.Reset();
  wheel_step_ = Pose2::Identity();
  wheel_step_valid_ = false;
  pose_ = submap_pose_ = last_odom_ = last_motion_ = Pose2::Identity();
  last_motion_us_ = 0;
  have_odom_ = have_scan_ = weak_match_ = have_gyro_yaw_ = last_degenerate_ = false;
  last_gyro_yaw_ = 0.0f;
  search_grid_version_ = 0;
  consecutive_rejections_ = consecutive_second_rejections_ = 0;
  restart_pending_ = bent_ = false;
  grid_turn_pending_ = true;
  grid_turn_stamp_us_ = 0;
  start_pending_ = true;
  step_turn_measured_ = step_turn_from_wheels_ = start_wheel_turns_ = false;
  start_heading_.Reset();
  start_scans_.Reset(&regions_.pool());
  start_offset_rad_ = NAN;
  start_shift_mm_[0] = start_shift_mm_[1] = 0;
  start_region_ = -1;
  bent_kept_out_ = 0;
  last_stamp_us_ = -1;
  streak_us_ = 0;
  InvalidateRegionReference();
  scans_since_submap_lines_ = scans_since_second_ = second_registrations_since_region_lines_ = 0;
  scan_marker_.Reset();
  back_end_.Init(config_.back_end, config.front_end.region_width_m, ReferenceForNoise(config.front_end.region_reference, config));
  path_m_ = 0.0f;
  last_world_ = Pose2::Identity();
  last_scan_region_ = -1;
  last_scan_in_region_ = Pose2::Identity();
  anchor_region_ = -1;
  lost_in_region_ = false;
  scans_since_closure_try_ = 0;
  localiser_.Cancel();
  localiser_.Drop();
  relocalising_ = restart_submap_ = may_be_near_ = near_failed_ = false;
  lost_since_us_ = 0;
  pending_ = PendingScan{};
  bent_against_single_ = false;
  return Status::kOk;
}

bool FrontEnd::AddOdometry(const OdometrySample& sample) {
  // A CARMEN pose of 1e6 m once opened a region 1000 km away: such a sample is counted and dropped,
  // the prediction comes from the samples around it.
  if (!PlausibleOdometry(sample)) {
    ++counters_.odometry_rejected;
    return false;
  }
  // A heading is an angle however many turns its source counts: two samples at -3.4e38 and
  // 3.4e38 rad (finite) once differed by infinity, and the de-skew's pose became NaN.
  OdometrySample wrapped = sample;
  if (std::fabs(wrapped.pose.theta) > kPi) wrapped.pose.theta = NormalizeAngle(wrapped.pose.theta);
  const std::uint32_t before = odometry_.steps_back();
  wheel_check_.AddOdometry(wrapped);
  const OdometrySample used = wheel_check_.Filter(wrapped);
  if (used.has_wheels != wrapped.has_wheels) ++counters_.odometry_without_wheel_translation;
  odometry_.Add(used);
  // A stamp stepping back breaks interpolation, not the odometry frame: increments go on.
  if (odometry_.steps_back() != before) ++counters_.odometry_steps_back;
  ++counters_.odometry_samples;
  return true;
}

Pose2 FrontEnd::ConstantVelocity(std::int64_t dt_us) const {
  if (last_motion_us_ <= 0 || dt_us <= 0) return last_motion_;
  // A lidar's revolution time varies (an XV-11: 3.5-5 Hz); past a gap, twice the last motion at most.
  float f = static_cast<float>(dt_us) / static_cast<float>(last_motion_us_);
  if (f > kMaxVelocityScale) f = kMaxVelocityScale;
  return Pose2{last_motion_.x * f, last_motion_.y * f, last_motion_.theta * f};
}

void FrontEnd::FadeConstantVelocity() {
  // In a rejection streak the constant velocity fades (halves each scan): a turn carried on at
  // its last rate long after the robot stopped would spin the pose away (no wheels to say so).
  // The translation is held for the streak's first seconds when it is the constant velocity's
  // (no wheels measure it) and a heading sensor (a gyro, the wheels' heading) keeps the turn: a
  // robot crossing a long room at a steady speed, whose far wall is out of the lidar's reach,
  // keeps going while the scans slide along the room and are rejected; a faded guess stopped it
  // within two scans, the rejected scans then fell ever further ahead of it, and the submap
  // restarted there (XV-11 at 5 Hz without wheel translation: 0.4 m off in a room it then mapped
  // twice; docs/front-end-accuracy.md). Without any sensor the heading is a guess too, and
  // carrying the translation along it hurt (lidar alone: 0.061 m -> 0.195 m); with wheels their
  // prediction is used, and holding the constant velocity's (the guess tried when the wheels are
  // doubted) doubled mit-csail's central hall: both fade as before.
  const float xy = HoldsVelocity() ? 1.0f : 0.5f;
  last_motion_ = Pose2{xy * last_motion_.x, xy * last_motion_.y, 0.5f * last_motion_.theta};
}

Pose2 FrontEnd::Predict(std::int64_t stamp_us, std::int64_t dt_us) {
  const Pose2 constant_velocity = ConstantVelocity(dt_us);
  step_turn_measured_ = false;
  if (odometry_.empty()) {
    ++counters_.scans_without_odometry;
    return pose_ * constant_velocity;
  }
  const Pose2 odom = odometry_.PoseAt(stamp_us);
  // With a gyro (FrontEndConfig::gyro_heading): the wheels give the translation, the gyro the turn.
  float yaw = 0.0f;
  const bool wheels = odometry_.newest().has_wheels;
  const bool use_gyro = config_.front_end.gyro_heading || !wheels;
  const bool gyro = use_gyro && odometry_.GyroYawAt(stamp_us, &yaw);
  Pose2 step = WheelStep(odom, wheels, constant_velocity);
  if (gyro && have_gyro_yaw_) {
    step.theta = NormalizeAngle(yaw - last_gyro_yaw_);
  } else if (!wheels) {
    step.theta = constant_velocity.theta;  // neither wheels nor a gyro yaw yet
  }
  // Without wheels (a gyro alone) the translation is the constant velocity's.
  if (!wheels) {
    step.x = constant_velocity.x;
    step.y = constant_velocity.y;
  }
  step_turn_ = step.theta;
  step_turn_from_wheels_ = !(gyro && have_gyro_yaw_) && wheels;
  step_turn_measured_ = have_odom_ && (step_turn_from_wheels_ || (gyro && have_gyro_yaw_));
  have_gyro_yaw_ = gyro;
  last_gyro_yaw_ = yaw;
  const Pose2 predicted = have_odom_ ? pose_ * step : pose_;
  last_odom_ = odom;
  have_odom_ = true;
  return predicted;
}

Pose2 FrontEnd::WheelStep(const Pose2& odom, bool wheels, const Pose2& constant_velocity) {
  const Pose2 measured = Between(last_odom_, odom);
  wheel_step_ = measured;
  wheel_step_valid_ = have_odom_ && wheels;
  if (!wheel_step_valid_) return measured;
  const Pose2 calibrated = config_.front_end.calibrate_odometry ? calibration_.Apply(measured) : measured;
  const bool still = odom.x == last_odom_.x && odom.y == last_odom_.y && odom.theta == last_odom_.theta;
  bool caught_up = false;
  const Pose2 step = stall_.Step(calibrated, still, constant_velocity, &caught_up);
  if (caught_up) {
    ++fe_counters_.odometry_stalls;
    wheel_step_valid_ = false;  // no measure of the wheels over one scan
  }
  return step;
}

void FrontEnd::AfterWheelStep(const Pose2& registered_step, std::int64_t stamp_us, bool registered, bool keep_out,
                              bool clean_fit) {
  wheel_check_.AddScan(registered_step, last_odom_, stamp_us, registered && consecutive_rejections_ == 0, clean_fit);
  stall_.AddRegistered(registered_step);
  // The calibration takes only a clean measure of the wheels: accepted, not degenerate (along a
  // corridor the registration returns the prediction), the wheels trusted.
  if (!registered || keep_out || consecutive_rejections_ != 0 || last_degenerate_ || !wheel_step_valid_ ||
      wheel_check_.translation_doubted()) {
    return;
  }
  calibration_.Add(registered_step, wheel_step_);
}

void FrontEnd::WheelsUnmeasured(std::int64_t stamp_us) {
  // A lost robot's scan says nothing of where it went: the wheel check's windows close, and what
  // was registered while the wheels stalled is forgotten.
  wheel_check_.AddScan(Pose2::Identity(), Pose2::Identity(), stamp_us, false);
  stall_.Reset();
}

Pose2 FrontEnd::GuessedVelocityStep(const Pose2& step, std::int64_t dt_us) const {
  // Only where the constant velocity is the translation's guess and a heading sensor keeps the
  // turn. The lidar alone (its turn a guess too) was worse with the limit: 10 min, seeds 1-60, two
  // runs over 0.2 m against none (docs/back-end.md, "A correction is not a speed").
  if (!HeadingMeasured() || (WheelsMeasured() && !wheel_check_.translation_doubted())) return step;
  const Pose2 limited = LimitAcceleration(last_motion_, last_motion_us_, step, dt_us, config_.front_end.max_acceleration_mps2);
  return last_degenerate_ && config_.front_end.degenerate_guess_forward ? ForwardStep(limited) : limited;
}

Pose2 FrontEnd::VelocityPerSecond() const {
  if (last_motion_us_ <= 0) return Pose2::Identity();
  const float f = 1e6f / static_cast<float>(last_motion_us_);
  return Pose2{last_motion_.x * f, last_motion_.y * f, last_motion_.theta * f};
}

std::int64_t FrontEnd::ScanInterval(std::int64_t stamp_us) {
  std::int64_t since_last_us = last_stamp_us_ >= 0 ? stamp_us - last_stamp_us_ : 0;
  if (since_last_us > kMaxScanGapUs || since_last_us < -kMaxScanGapUs) {
    ++counters_.scan_stamp_jumps;
    since_last_us = 0;
  }
  last_stamp_us_ = stamp_us;
  return since_last_us;
}

Status FrontEnd::AddScan(Span<const Beam> beams, std::int64_t stamp_us) {
  ++counters_.scans;
  if (!PlausibleStamp(stamp_us)) {
    ++counters_.scans_bad_stamp;  // nothing else changes: the next scan is measured from the last good one
    return Status::kInvalidArgument;
  }
  BeginScan();
  // 1. Prediction and de-skew.
  Pose2 previous = pose_;
  const std::int64_t since_last_us = ScanInterval(stamp_us);
  Pose2 predicted = Predict(stamp_us, since_last_us);
  const ScanMotion motion(odometry_, config_.front_end.gyro_heading, VelocityPerSecond(), stamp_us);
  ProjectedScan projected = ProjectScan(beams, config_.lidar, motion, s_.hits, s_.free_ends);
  counters_.beams_invalid += static_cast<std::uint32_t>(projected.invalid);
  counters_.beams_isolated += static_cast<std::uint32_t>(projected.isolated);
  fe_counters_.return_share = UpdateReturnShare(fe_counters_.return_share, projected);
  if (SkipScan(projected, predicted)) return Status::kNotEnoughData;
  // The first scan not skipped may turn the grid (not an XV-11's spin-up; ScanWorldPose turns that).
  const bool may_turn_grid = std::exchange(grid_turn_pending_, false);
  const bool start_scan = std::exchange(start_pending_, false);  // the run's first scan not skipped
  // 0. Lost (wheels lifted, a long rejection streak, an unknown start): the scan goes into no
  // map; it tracks locally and searches the maps (front_end_relocalise.cpp).
  if (LostNow()) {
    StopStartFits();
    pending_.active = false;  // a lost robot maps nothing: the waiting scan is dropped
    RelocaliseScan(beams, motion, since_last_us, &projected, predicted);
    WheelsUnmeasured(stamp_us);
    last_motion_ = GuessedVelocityStep(Between(previous, pose_), since_last_us);
    last_motion_us_ = static_cast<std::int32_t>(since_last_us);
    FinishScan(since_last_us);
    return Status::kOk;
  }
  if (may_turn_grid) TurnFrameFromWalls(stamp_us, Span<const Point2>(s_.hits.data(), projected.hits), &previous, &predicted);
  // 2. First registration against the submap (not for the very first scan: nothing to match).
  bool keep_out = false, bent = false, clean_fit = false;
  const bool first = s_.submap->size() == 0;
  const std::uint32_t restarts = counters_.submap_restarts;
  const bool registered = config_.front_end.enable_registration && s_.submap->size() > 0;
  if (registered) {
    RebuildSubmapReferenceIfDue();
    const bool uncertain = UncertainPrediction(predicted);
    clean_fit = RegisterScan(beams, motion, since_last_us, &projected, predicted);
    keep_out = AfterFirstRegistration(uncertain, since_last_us, projected.hits);
    if (!keep_out) keep_out = bent = KeepOutBent(projected.hits);
  } else {
    pose_ = predicted;
  }
  AfterWheelStep(Between(previous, pose_), stamp_us, registered, keep_out, clean_fit);
  last_motion_ = GuessedVelocityStep(Between(previous, pose_), since_last_us);
  if (consecutive_rejections_ > 0) FadeConstantVelocity();
  last_motion_us_ = static_cast<std::int32_t>(since_last_us);
  if (FixedLag()) {
    FlushPendingScan(beams, stamp_us, previous, since_last_us, projected, keep_out, bent, first,
                     counters_.submap_restarts != restarts);
    StepBackEnd();
    FinishScan(since_last_us);
    return Status::kOk;
  }
  pending_.active = false;  // wheels or a gyro from now on: a waiting scan is dropped
  // 4a. The submap takes every scan (its own ring decides what leaves), but not a rejected one
  // placed by an uncertain prediction.
  if (!keep_out) {
    (void)s_.submap->Add(pose_, Span<const Point2>(s_.hits.data(), projected.hits));
    ++scans_since_submap_lines_;
  }
  // 3. Regions, and the second registration.
  TrackRegions();
  const bool accepted = registered && !keep_out && consecutive_rejections_ == 0;
  KeepScanPoints(stamp_us, start_scan, projected.hits, accepted);  // before the map takes the points into its frame
  // 4b. Once into a regional map (InsertIntoMaps); if not, its pose is still known in the anchor region's frame.
  if (!InsertIntoMaps(projected, pose(), keep_out, TurningFast())) {
    last_scan_region_ = anchor_region_ >= 0 ? anchor_region_ : regions_.current();
    if (last_scan_region_ >= 0) last_scan_in_region_ = Between(regions_[last_scan_region_].anchor, pose());
  }
  FitStartHeading(stamp_us, start_scan, accepted);
  // 5. Back end: at most one queued job.
  StepBackEnd();
  FinishScan(since_last_us);
  return Status::kOk;
}

bool FrontEnd::FixedLag() const {
  return config_.front_end.lidar_only_fixed_lag && config_.front_end.enable_registration && !HeadingMeasured();
}

Pose2 FrontEnd::PendingVelocity(std::int64_t stamp_us) const {
  const float after_s = static_cast<float>(stamp_us - pending_.stamp_us) * 1e-6f;
  const Pose2 after = Between(pending_.pose, pose_);
  const Pose2 v{after.x / after_s, after.y / after_s, after.theta / after_s};
  if (pending_.first) return Pose2{0.5f * v.x, 0.5f * v.y, 0.5f * v.theta};  // from a standstill
  const float before_s = static_cast<float>(pending_.since_before_us) * 1e-6f;
  if (pending_.since_before_us <= 0 || before_s > 2.0f * after_s) return v;
  // The step before, turned from the earlier scan's frame into this one's.
  const Pose2 b = Between(pending_.before, pending_.pose);
  const float c = std::cos(b.theta), s = std::sin(b.theta);
  const Pose2 u{(c * b.x + s * b.y) / before_s, (c * b.y - s * b.x) / before_s, b.theta / before_s};
  return Pose2{0.5f * (u.x + v.x), 0.5f * (u.y + v.y), 0.5f * (u.theta + v.theta)};
}

void FrontEnd::FlushPendingScan(Span<const Beam> beams, std::int64_t stamp_us, const Pose2& previous,
                                std::int64_t since_last_us, const ProjectedScan& current, bool keep_out, bool bent,
                                bool first, bool restarted) {
  const FrontEndConfig& f = config_.front_end;
  start_heading_.Abort();  // no heading sensor: nothing to fit the start with
  bool flushed = false, into_maps = false;
  Pose2 at;
  ProjectedScan projected;
  if (first) {
    // The run's first scan goes into the submap at once, projected with no motion known (the
    // next scan needs something to match); it is projected again once that scan is registered.
    (void)s_.submap->Add(pose_, Span<const Point2>(s_.hits.data(), current.hits));
    ++scans_since_submap_lines_;
  } else if (pending_.active) {
    // The current scan's points are no longer needed: the waiting scan's take their place.
    const ScanMotion motion(odometry_, f.gyro_heading, PendingVelocity(stamp_us), pending_.stamp_us);
    projected = ProjectScan(Span<const PackedBeam>(s_.pending_beams.data(), pending_.beams), config_.lidar, motion,
                            s_.hits, s_.free_ends);
    at = pending_.pose;
    // Registered again from where it was placed (not after a rejection: that pose is a guess).
    bool registered = false;
    if (!pending_.rejected && !pending_.first) {
      const PlicpConfig plicp = FirstRegistrationBase(config_, SparseScan(f, projected.hits, pending_.beams));
      const RegistrationResult r =
          RegisterFirst(*s_.submap_reference, nullptr, &search_grid_version_, fe_counters_.submap_line_builds,
                        Span<const Point2>(s_.hits.data(), projected.hits),
                        pending_.since_before_us > 0 ? pending_.before : pending_.pose, pending_.pose, f,
                        s_.correspondences, &fe_counters_.search, kPriorXyWithoutWheels, kPriorThetaWithoutHeading, &plicp);
      if (r.verdict == Status::kOk) {
        at = r.pose;
        registered = true;
        ++fe_counters_.lag_reregistered;
      }
    }
    // Kept out as bent, it is straight now if it registers again close to where it was placed.
    const Pose2 moved = Between(pending_.pose, at);
    const bool straight = pending_.bent && registered && std::hypot(moved.x, moved.y) <= kLagBentMaxMoveM &&
                          std::fabs(moved.theta) <= kLagBentMaxMoveRad;
    if (straight) ++fe_counters_.lag_bent_taken;
    if (pending_.first || (bent_against_single_ && !pending_.rejected && !straight)) {
      // The submap's lone scan (this one, or an older one while a turn starts) gives way to
      // this one, de-skewed from both sides.
      if (!restarted && s_.submap->size() == 1) {
        s_.submap->Reset(config_.grid, f.submap_scans, f.submap_miss_range_m);
        (void)s_.submap->Add(at, Span<const Point2>(s_.hits.data(), projected.hits));
        scans_since_submap_lines_ = static_cast<std::uint32_t>(f.submap_line_period);  // rebuild next scan
      }
    } else if ((!pending_.kept_out || straight) && !restarted) {
      (void)s_.submap->Add(at, Span<const Point2>(s_.hits.data(), projected.hits));
      ++scans_since_submap_lines_;
    }
    flushed = true;
    into_maps = !pending_.kept_out || straight;
  }
  TrackRegions();
  if (flushed) (void)InsertIntoMaps(projected, submap_pose_ * at, !into_maps, pending_.turning);
  // The current scan's pose is known in its map's frame now; the scan itself waits.
  last_scan_region_ = (keep_out || lost_in_region_) && anchor_region_ >= 0 ? anchor_region_ : regions_.current();
  if (last_scan_region_ >= 0) last_scan_in_region_ = Between(regions_[last_scan_region_].anchor, pose());
  // Only beams that can be packed faithfully wait (an implausible one would come back plausible).
  std::size_t n = 0;
  for (std::size_t i = 0; i < beams.size() && n < s_.pending_beams.size(); ++i) {
    if (PlausibleBeam(beams[i])) s_.pending_beams[n++] = PackedBeam::Pack(beams[i]);
  }
  pending_.active = true;
  pending_.first = first;
  pending_.kept_out = keep_out;
  pending_.bent = bent;
  pending_.rejected = consecutive_rejections_ > 0;
  pending_.turning = TurningFast();
  pending_.beams = static_cast<std::uint16_t>(n);
  pending_.stamp_us = stamp_us;
  pending_.since_before_us = first ? 0 : since_last_us;
  pending_.pose = pose_;
  pending_.before = previous;
}

void FrontEnd::TrackRegions() {
  const Pose2 world = pose();
  if (have_scan_) path_m_ += std::hypot(world.x - last_world_.x, world.y - last_world_.y);
  if (!have_scan_) {
    tracker_.Start(Point2{world.x, world.y}, config_.front_end.region_width_m, config_.front_end.region_hysteresis_m);
    have_scan_ = true;
    EnterRegion(true);
  } else if (tracker_.Update(Point2{world.x, world.y})) {
    EnterRegion(false);
  } else if (!back_end_.searching()) {
    // Not placed in the current map yet: retry once the robot has moved on enough to see
    // something new; meanwhile it keeps registering to (and mapping into) its anchor map. While
    // a search runs, the region reference's table is the search's: no second registration.
    if (lost_in_region_ && ++scans_since_closure_try_ >= static_cast<std::uint32_t>(config_.back_end.loop_retry_scans) &&
        path_m_ - path_at_closure_try_ >= config_.back_end.loop_retry_path_m) {
      scans_since_closure_try_ = 0;
      BeginLoopClosure(anchor_region_);
    } else if (config_.front_end.enable_registration &&
               ++scans_since_second_ >= static_cast<std::uint32_t>(config_.front_end.second_registration_period)) {
      const int current = regions_.current();
      const bool mature = current >= 0 && regions_[current].scans_inserted >= static_cast<std::uint32_t>(config_.front_end.region_mature_scans);
      consecutive_second_rejections_ = !SecondRegistration() && mature ? consecutive_second_rejections_ + 1 : 0;
    }
  }
}

void FrontEnd::FinishScan(std::int64_t since_last_us) {
  last_world_ = pose();
  UpdateStatus();
  if (status_ == MapperStatus::kLost) {
    ++counters_.lost_scans;
    counters_.lost_us += since_last_us;
  }
}

bool FrontEnd::KeepOutBent(std::size_t hits) {
  if (!bent_ || consecutive_rejections_ > 0 || bent_kept_out_ >= kMaxBentKeptOut) {
    bent_kept_out_ = 0;
    return false;
  }
  ++counters_.scans_kept_out_bent;
  if (s_.submap->size() == 1 && FixedLag()) {
    bent_against_single_ = true;  // FlushPendingScan puts the waiting scan in its place
    return true;
  }
  if (s_.submap->size() == 1) {
    // A submap of one scan (a run that starts in a turn: that scan was de-skewed with no motion
    // known) is that scan: this one, de-skewed with the motion just found, is less bent.
    const FrontEndConfig& f = config_.front_end;
    s_.submap->Reset(config_.grid, f.submap_scans, f.submap_miss_range_m);
    (void)s_.submap->Add(pose_, Span<const Point2>(s_.hits.data(), hits));
    scans_since_submap_lines_ = static_cast<std::uint32_t>(f.submap_line_period);  // rebuild next scan
    ++counters_.submap_restarts;
    return true;
  }
  ++bent_kept_out_;
  return true;
}

void FrontEnd::TurnFrameFromWalls(std::int64_t stamp_us, Span<const Point2> hits, Pose2* previous, Pose2* predicted) {
  grid_turn_stamp_us_ = stamp_us;  // scans skipped before this one were reported in the frame before any turn
  const FrontEndConfig& f = config_.front_end;
  // Only for a lidar that declares its range noise: the bands of cells are the noise's (with exact
  // ranges, walls along the rows map better, and a log's lidar says nothing of its noise).
  if (f.grid_turn_rad <= 0.0f || !(config_.lidar.range_noise_m > 0.0f) || s_.submap->size() != 0 || regions_.size() != 0) {
    return;
  }
  const WallDirection walls = DominantWallDirection(hits, WallDirectionConfig{});
  if (!walls.found) return;
  fe_counters_.first_wall_direction_rad = walls.angle_rad;
  if (std::fabs(walls.angle_rad) >= f.grid_turn_band_rad) return;
  // The robot's heading in the turned frame puts its walls grid_turn_rad off the axes. The submap
  // is empty and its frame the world's: the robot's poses in it turn with the frame.
  fe_counters_.grid_turn_rad = NormalizeAngle(f.grid_turn_rad - walls.angle_rad - pose().theta);
  const Pose2 turn{0.0f, 0.0f, fe_counters_.grid_turn_rad};
  pose_ = turn * pose_;
  *previous = turn * *previous;
  *predicted = turn * *predicted;
}

void FrontEnd::FitStartHeading(std::int64_t stamp_us, bool start_scan, bool accepted) {
  const StartHeadingConfig& h = config_.front_end.start_heading;
  if (start_scan) {
    // The start's map and pose in it were recorded before the insertion (KeepStartScan).
    if (h.window_s > 0.0f && last_scan_region_ >= 0) start_heading_.Begin(stamp_us, pose().theta);
    return;
  }
  FeedStartHeading(accepted);
}

void FrontEnd::StopStartFits() {
  start_heading_.Abort();
  start_scans_.Stop();  // what they kept stays good: placed before the robot lost itself
}

void FrontEnd::FeedStartHeading(bool accepted) {
  if (step_turn_measured_ && step_turn_from_wheels_) start_wheel_turns_ = true;
  // Wheels whose translation the check set aside are an IMU's heading made into ticks: a gyro's.
  const bool wheels = start_wheel_turns_ && !wheel_check_.translation_ignored();
  const StartHeadingFit::Step step{last_stamp_us_, pose().theta, step_turn_, step_turn_measured_, accepted};
  (void)start_heading_.AddScan(step, wheels, config_.front_end.start_heading);
}

Pose2 FrontEnd::ScanWorldPose(std::int64_t stamp_us, int region, const Pose2& in_region, const Pose2& online) const {
  Pose2 world = region >= 0 && region < regions_.size() ? regions_[region].anchor * in_region : online;
  // A scan skipped before the grid turned was reported in the frame before the turn.
  if (region < 0 && stamp_us < grid_turn_stamp_us_ && fe_counters_.grid_turn_rad != 0.0f) {
    world = Pose2{0.0f, 0.0f, fe_counters_.grid_turn_rad} * world;
  }
  const bool refined = !std::isnan(start_offset_rad_);
  const bool moved = StartMoved();
  const bool fitted = start_heading_.outcome() == StartHeadingFit::Outcome::kApplied;
  const std::int64_t start_us = refined || moved ? start_scans_.start_stamp_us() : start_heading_.start_stamp_us();
  if ((!refined && !moved && !fitted) || stamp_us > start_us || start_region_ < 0 || start_region_ >= regions_.size()) {
    return world;
  }
  // Moved and turned about the start: the start lands where the later scans place it.
  const Pose2 start = regions_[start_region_].anchor * start_in_region_;
  const float turn = refined ? start_offset_rad_ : (fitted ? start_heading_.offset_rad() : 0.0f);
  Pose2 correction = StartShift();  // the move, then the turn about the start
  correction.theta = turn;
  return start * correction * start.Inverse() * world;
}

bool FrontEnd::SkipScan(const ProjectedScan& projected, const Pose2& predicted) {
  const bool empty = projected.hits == 0 && projected.free_ends == 0;
  // A lidar's spin-up revolution (an XV-11: 7-17 returns of 360) must not become the submap's
  // only scan: every later scan would be registered against it and rejected.
  const bool sparse_start =
      s_.submap->size() == 0 && projected.hits < static_cast<std::size_t>(config_.front_end.min_start_hits);
  if (!empty && !sparse_start) return false;
  ++counters_.scans_rejected;
  ++(empty ? counters_.scans_empty : counters_.scans_too_sparse);
  pose_ = predicted;
  FeedStartHeading(false);  // its turn, as predicted
  return true;
}

bool FrontEnd::UncertainPrediction(const Pose2& predicted) const {
  return !WheelsMeasured() || consecutive_rejections_ > 0 ||
         std::fabs(NormalizeAngle(predicted.theta - pose_.theta)) > config_.front_end.uncertain_turn_rad;
}

bool FrontEnd::AfterFirstRegistration(bool uncertain, std::int64_t since_last_us, std::size_t hits) {
  if (consecutive_rejections_ == 0) {
    streak_us_ = 0;
    restart_pending_ = false;
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
  // Not from a sparse scan (FrontEndConfig::min_start_hits): then from the next one that is not.
  const FrontEndConfig& f = config_.front_end;
  if (consecutive_rejections_ % f.submap_restart_after_rejections == 0) restart_pending_ = true;
  if (restart_pending_ && hits >= static_cast<std::size_t>(f.min_start_hits)) {
    restart_pending_ = false;
    RestartSubmap(hits);
  }
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
    // A young submap cannot reach the threshold: ask for a hit in half the scans it holds so far
    // (not in all of them: a low-cost lidar returns only 40-80 % of its beams).
    // The line fits tolerate the lidar's noise only behind wheels (as the first registration's
    // trim floor, FirstRegistrationPlicp): without them a wide band of cells is as likely a scan
    // de-skewed by a wrong guess, and fitting it as a wall locks the registration onto the smear
    // (XV-11, gyro only, seeds 1-10: 0.049 m with the clean tolerance, 0.227 m with the wider one).
    const bool wheels = WheelsMeasured();
    ReferenceConfig reference = wheels ? ReferenceForNoise(f.submap_reference, config_) : f.submap_reference;
    // A lidar that loses many of its readings gives its walls fewer hits (return_share.hpp).
    reference = ReferenceForReturnShare(reference, fe_counters_.return_share, f.sparse_reference_full_share);
    if (reference.obstacle_threshold < f.submap_reference.obstacle_threshold) ++fe_counters_.submap_sparse_builds;
    const int reachable = (s_.submap->size() + 1) / 2 * config_.grid.hit_delta - 1;
    if (reachable < reference.obstacle_threshold) reference.obstacle_threshold = static_cast<std::int16_t>(reachable);
    // Lowered to one hit only behind wheels: without them a weak match more likely means a
    // misplaced scan (a turn the constant velocity missed) than a new wall, and one hit would put
    // that scan's copy of the walls into the reference.
    if (early && wheels && f.weak_match_obstacle_threshold < reference.obstacle_threshold) {
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
    ref.AddRefitPoints(Span<const Point2>(scan.points.data(), scan.points.size()), to_submap,
                       config_.front_end.submap_refit_gate_m);
  }
  (void)ref.EndPointRefit(config_.front_end.submap_refit_min_points);
}

bool FrontEnd::RegisterScan(Span<const Beam> beams, const ScanMotion& motion, std::int64_t dt_us, ProjectedScan* projected,
                            const Pose2& predicted) {
  const FrontEndConfig& f = config_.front_end;
  const bool sparse = SparseScan(f, projected->hits, beams.size());
  const PlicpConfig plicp = FirstRegistrationPlicp(config_, motion.wheels(), sparse);
  RegistrationResult r =
      // In a rejection streak the search runs on every other scan (each search that did not help
      // is followed by one PLICP-only attempt): the streak's cost stays bounded.
      RegisterFirst(*s_.submap_reference, consecutive_rejections_ % 2 == 0 ? s_.search_grid : nullptr, &search_grid_version_, fe_counters_.submap_line_builds,
                    Span<const Point2>(s_.hits.data(), projected->hits), pose_, predicted, f, s_.correspondences, &fe_counters_.search,
                    PriorXyScale(motion, dt_us), PriorThetaScale(motion), &plicp);
  bent_ = false;
  if (!motion.wheels() && dt_us > 0 && !beams.empty()) r = RegisterRedeskewed(beams, motion, dt_us, sparse, projected, r);
  if (r.verdict != Status::kOk && motion.wheels() && !motion.gyro()) r = RegisterFromConstantVelocity(projected->hits, sparse, dt_us, predicted, r);
  if (r.verdict == Status::kOk && ImplausibleWithoutWheels(r.pose, predicted, motion, dt_us)) r.verdict = Status::kRejected;
  if (r.verdict == Status::kOk && GuessHoldsWeakDirections(motion, dt_us)) {
    const float dt_s = static_cast<float>(dt_us) * 1e-6f;
    const float max_deviation_m = f.max_acceleration_mps2 * dt_s * dt_s;
    if (HoldWeakDirections(r.hessian, r.inliers, predicted, f.weak_direction_information, max_deviation_m, &r.pose)) {
      ++fe_counters_.weak_direction_holds;
    }
  }
  ++fe_counters_.first_registrations;
  weak_match_ = r.verdict != Status::kOk || r.inlier_ratio < f.weak_match_inlier_ratio;
  last_degenerate_ = r.verdict == Status::kOk && r.degenerate;
  if (r.verdict == Status::kOk) {
    pose_ = r.pose;
    consecutive_rejections_ = 0;
  } else {
    // A rejected match is not fused: the pose falls back to the prediction.
    pose_ = predicted;
    ++fe_counters_.first_rejected;
    ++consecutive_rejections_;
  }
  return r.verdict == Status::kOk && FitsCleanly(r, plicp);
}

bool FrontEnd::ImplausibleWithoutWheels(const Pose2& registered, const Pose2& predicted, const ScanMotion& motion,
                                         std::int64_t dt_us) const {
  // Only a guess with no wheels behind it, and only while tracking or the streak holds the
  // velocity (FadeConstantVelocity): once it has faded the registration must be free to catch up.
  if (WheelsTranslate(motion) || (consecutive_rejections_ > 0 && !HoldsVelocity())) return false;
  if (std::hypot(registered.x - predicted.x, registered.y - predicted.y) > kMaxLeapWithoutWheelsM) return true;
  // The speed only with a heading sensor: the lidar alone mis-turns now and then, and a speed cap
  // then kept out the registrations that found it again (seed 1: 0.218 -> 1.82 m).
  const float step_m = std::hypot(registered.x - pose_.x, registered.y - pose_.y);
  return motion.gyro() && dt_us > 0 && step_m > kMaxSpeedWithoutWheelsMps * static_cast<float>(dt_us) * 1e-6f;
}

bool FrontEnd::GuessHoldsWeakDirections(const ScanMotion& motion, std::int64_t dt_us) const {
  // As ImplausibleWithoutWheels: only while the constant velocity is held (a faded guess says
  // nothing along the way either).
  const FrontEndConfig& f = config_.front_end;
  return f.weak_direction_information > 0.0f && f.max_acceleration_mps2 > 0.0f && dt_us > 0 && !WheelsTranslate(motion) &&
         (consecutive_rejections_ == 0 || HoldsVelocity());
}

RegistrationResult FrontEnd::RegisterRedeskewed(Span<const Beam> beams, const ScanMotion& motion, std::int64_t dt_us, bool sparse,
                                                ProjectedScan* projected, const RegistrationResult& first) {
  const FrontEndConfig& f = config_.front_end;
  // The motion the registration found, per second, against the one the de-skew assumed; the
  // difference they make by the revolution's last beam. (Tried and dropped: also that motion plus
  // its change since the last interval, a turn still speeding up, the lower residual winning: on
  // apartment seed 1 without odometry it won with wrong poses, 0.2 -> 9 % rejected.)
  const Pose2 step = Between(pose_, first.pose);
  const float per_s = 1e6f / static_cast<float>(dt_us);
  const Pose2& assumed = motion.velocity();
  const Pose2 found{step.x * per_s, step.y * per_s, step.theta * per_s};
  const float revolution_s = static_cast<float>(beams[beams.size() - 1].offset_us) * 1e-6f;
  const float bend_m = std::hypot(found.x - assumed.x, found.y - assumed.y) * revolution_s;
  const float bend_rad = motion.gyro() ? 0.0f : std::fabs(found.theta - assumed.theta) * revolution_s;
  bent_ = bend_m >= 2.0f * f.redeskew_min_m || bend_rad >= 2.0f * f.redeskew_min_rad;
  if (bend_m < f.redeskew_min_m && bend_rad < f.redeskew_min_rad) return first;
  ++fe_counters_.redeskews;
  const PlicpConfig plicp = FirstRegistrationBase(config_, sparse);
  const ScanMotion again(odometry_, f.gyro_heading, found, motion.stamp_us());
  *projected = ProjectScan(beams, config_.lidar, again, s_.hits, s_.free_ends);
  const RegistrationResult second =
      RegisterFirst(*s_.submap_reference, nullptr, &search_grid_version_, fe_counters_.submap_line_builds,
                    Span<const Point2>(s_.hits.data(), projected->hits), pose_, first.pose, f, s_.correspondences, &fe_counters_.search,
                    PriorXyScale(motion, dt_us), PriorThetaScale(motion), &plicp);
  if (second.verdict == Status::kOk) return second;
  if (first.verdict != Status::kOk) return bent_ ? TrackBent(second, first.pose) : second;
  // Only the first one was accepted: its points back.
  *projected = ProjectScan(beams, config_.lidar, motion, s_.hits, s_.free_ends);
  return first;
}

RegistrationResult FrontEnd::RegisterFromConstantVelocity(std::size_t hits, bool sparse, std::int64_t dt_us, const Pose2& predicted,
                                                          const RegistrationResult& rejected) {
  const FrontEndConfig& f = config_.front_end;
  const Pose2 guess = pose_ * ConstantVelocity(dt_us);
  const Pose2 apart = Between(predicted, guess);
  const bool doubt_m = f.odometry_doubt_m > 0.0f && std::hypot(apart.x, apart.y) > f.odometry_doubt_m;
  const bool doubt_rad = f.odometry_doubt_rad > 0.0f && std::fabs(apart.theta) > f.odometry_doubt_rad;
  if (!doubt_m && !doubt_rad) return rejected;
  ++fe_counters_.odometry_doubted;
  const PlicpConfig plicp = FirstRegistrationBase(config_, sparse);
  const RegistrationResult again =
      RegisterFirst(*s_.submap_reference, nullptr, &search_grid_version_, fe_counters_.submap_line_builds,
                    Span<const Point2>(s_.hits.data(), hits), pose_, guess, f, s_.correspondences, &fe_counters_.search, 1.0f, 1.0f,
                    &plicp);
  if (again.verdict != Status::kOk) return rejected;
  ++fe_counters_.odometry_overruled;
  return again;
}

RegistrationResult FrontEnd::TrackBent(RegistrationResult r, const Pose2& from) {
  // A bent scan cannot fit straight walls as closely as the residual bound asks; its pose still
  // tracks the turn when everything else holds. The scan itself stays out of the maps (KeepOutBent).
  const PlicpConfig& c = config_.front_end.first_registration;
  const Pose2 moved = Between(from, r.pose);
  if (r.inliers >= c.min_correspondences && r.inlier_ratio >= c.min_inlier_ratio && !r.degenerate &&
      r.mean_residual_m <= 2.0f * c.max_mean_residual_m && std::hypot(moved.x, moved.y) <= c.max_correction_m &&
      std::fabs(moved.theta) <= c.max_correction_rad) {
    r.verdict = Status::kOk;
    ++fe_counters_.bent_tracked;
  }
  return r;
}

void FrontEnd::EnterRegion(bool first) {
  // A search for the map the robot just left has lost its point.
  if (back_end_.searching()) back_end_.CancelLoopClosure();
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

int FrontEnd::ReferenceMaps(int (&maps)[2], bool loop_entry) const {
  const FrontEndConfig& f = config_.front_end;
  const auto scans = [&](int i) { return regions_[i].scans_inserted; };
  const bool in_anchor = lost_in_region_ && !loop_entry && anchor_region_ >= 0;
  const int current = in_anchor ? anchor_region_ : regions_.current(), previous = regions_.previous();
  const bool map_alone = loop_entry || in_anchor;
  int n = 0;
  // The current map, once it holds more than the submap it was seeded from.
  if (current >= 0 && scans(current) >= static_cast<std::uint32_t>(f.submap_scans)) maps[n++] = current;
  // With it, the mature map of the region the robot came from while the robot is well inside it:
  // walls seen from both regions then pull the new map towards the old one instead of letting each
  // keep its own heading (across a border, neighbouring maps disagreed by up to 0.7 deg). Only that
  // one: an older map seen again after a long loop may disagree with the drift accumulated since,
  // and reconciling them is the back end's job.
  if (!map_alone && previous >= 0 && previous != current && scans(previous) >= static_cast<std::uint32_t>(f.region_mature_scans) &&
      WellInside(regions_[previous])) {
    maps[n++] = previous;
  }
  return n;
}

bool FrontEnd::SecondRegistration(RegistrationResult* result, int* region, bool loop_entry) {
  scans_since_second_ = 0;
  int maps[2] = {-1, -1};
  const int n = ReferenceMaps(maps, loop_entry);
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
  const ReferenceConfig config = ReferenceForNoise(config_.front_end.region_reference, config_);
  ReferenceBuildStats stats;
  reference.BeginBuild(r.grid->box(), res);
  for (int k = 0; k < n; ++k) {
    const RegionalMap& m = regions_[maps[k]];
    reference.AddPlacedGrid(*m.grid, Between(r.anchor, m.anchor), config, &stats);
  }
  if (reference.FinishBuild(config, &stats) != Status::kOk) {
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
  const Pose2 initial = PivotPose(r.anchor.Inverse() * submap_pose_, target_pivot_);
  const PosePrior prior{initial, f.prior_info_xy, f.prior_info_theta};
  const RegistrationResult res =
      FrameResult(RegisterImproved(*s_.region_reference, Span<const Point2>(s_.target.data(), count), initial, &prior,
                                   f.second_registration, s_.correspondences),
                  target_pivot_);
  ++fe_counters_.second_registrations;
  if (res.verdict == Status::kOk) {
    submap_pose_ = r.anchor * res.pose;  // the submap, and the robot in it, move together
  } else {
    ++fe_counters_.second_rejected;
  }
  return res;
}

bool FrontEnd::TurningFast() const {
  const float max_rate = config_.lidar.map_max_turn_rate_rad_s;
  if (max_rate <= 0.0f || last_motion_us_ <= 0) return false;
  return std::fabs(last_motion_.theta) * 1e6f > max_rate * static_cast<float>(last_motion_us_);
}

bool FrontEnd::InsertIntoMaps(const ProjectedScan& projected, const Pose2& world, bool keep_out, bool turning) {
  if (keep_out || turning || config_.localisation.localise_only) {
    ++counters_.scans_not_inserted;
    if (turning && !keep_out && !config_.localisation.localise_only) ++counters_.scans_turning_not_mapped;
    return false;
  }
  if (lost_in_region_ && anchor_region_ >= 0) {
    ++counters_.scans_into_anchor_map;
    InsertIntoRegion(projected, anchor_region_, world);
  } else {
    InsertIntoRegion(projected, regions_.current(), world);
  }
  return true;
}

void FrontEnd::InsertIntoRegion(const ProjectedScan& projected, int index, const Pose2& world) {
  last_scan_region_ = index;
  if (last_scan_region_ >= 0) {
    RegionalMap& r = regions_[last_scan_region_];
    last_scan_in_region_ = Between(r.anchor, world);
    r.path_at_last_scan_m = path_m_;
  }
  // A map that holds enough scans learns slowly (FrontEndConfig::region_slow_learning_scans).
  const FrontEndConfig& f = config_.front_end;
  const bool slow = index >= 0 && regions_[index].scans_inserted >= static_cast<std::uint32_t>(f.region_slow_learning_scans);
  // The submap already copied the robot-frame points: they may move into the region's frame.
  const InsertionStats st = regions_.InsertScan(world, Span<Point2>(s_.hits.data(), projected.hits),
                                                Span<Point2>(s_.free_ends.data(), projected.free_ends),
                                                scan_marker_.current(), index, slow ? f.region_slow_learning_rate : 1.0f);
  counters_.updates_out_of_box += static_cast<std::uint32_t>(st.out_of_box);
  counters_.updates_dropped_pool_full += static_cast<std::uint32_t>(st.dropped_pool_full);
}

void FrontEnd::EnterKnownRegion() {
  const int region = regions_.current();
  const float absence = path_m_ - regions_[region].path_at_last_scan_m;
  const bool loop = absence >= config_.back_end.loop_min_path_m && anchor_region_ >= 0 && config_.back_end.enable;
  // Align the submap to the map at once (paper: on region entry); after a loop to that map alone:
  // the map the robot drifted in holds the walls near the border too, and with it in the
  // reference the registration confirms the drift instead of measuring it.
  const Pose2 submap_before = submap_pose_;
  RegistrationResult result;
  int frame = -1;
  bool aligned = SecondRegistration(&result, &frame, loop);
  if (!loop) {
    anchor_region_ = region;  // back after a short detour
    lost_in_region_ = false;
    return;
  }
  // Back after a loop. Aligned to this map alone: that is a closure for the graph too. Otherwise
  // the drift may be past the PLICP basin: a search. Without either, the robot does not know
  // where it is in this map, and its scans stay out of it until a retry succeeds or it reaches a
  // new region.
  // Only a small correction is trusted from PLICP alone (the search's base window); a larger
  // one may be a neighbouring minimum (a wall one doorway over), and the search verifies it.
  if (aligned && frame == region) {
    const Pose2 correction =
        ChangeAboutPivot(Between(regions_[region].anchor.Inverse() * submap_before, result.pose), target_pivot_);
    if (!WithinSearchBaseWindow(config_.back_end, correction)) {
      submap_pose_ = submap_before;
      aligned = false;
    }
  }
  if (aligned && frame == region) {
    if (back_end_.AddClosure(regions_.maps(), region, anchor_region_, result, submap_before)) {
      submap_pose_ = regions_[region].anchor * result.pose;
      InvalidateRegionReference();
    }
    anchor_region_ = region;
    lost_in_region_ = false;
    return;
  }
  // Until the search (in slices, StepBackEnd) places the robot in this map, it is not placed.
  lost_in_region_ = true;
  BeginLoopClosure(anchor_region_);
  scans_since_closure_try_ = 0;
}

void FrontEnd::BeginScan() {
  (void)scan_marker_.Next();
  recorded_points_ = 0;
  bent_against_single_ = false;
}

void FrontEnd::KeepScanPoints(std::int64_t stamp_us, bool start_scan, std::size_t hits, bool accepted) {
  KeepStartScan(stamp_us, start_scan, hits, accepted);
  recorded_points_ = hits < s_.recorded.size() ? hits : s_.recorded.size();
  for (std::size_t i = 0; i < recorded_points_; ++i) s_.recorded[i] = s_.hits[i];
}

bool FrontEnd::BeginMapRegistration(int region, int other) {
  if (region < 0 || region >= regions_.size() || other < -1 || other >= regions_.size() || other == region) return false;
  if (back_end_.searching()) back_end_.CancelLoopClosure();  // the search grid shares the reference's table
  const int maps[2] = {region, other};
  BuildRegionReference(maps, other >= 0 ? 2 : 1);
  InvalidateRegionReference();  // not the pair the second registration expects
  return true;
}

RegistrationResult FrontEnd::RegisterInMap(Span<const Point2> robot_points, const Pose2& in_region, int max_iterations) {
  PlicpConfig plicp = FirstRegistrationBase(config_, false);
  plicp.max_iterations = max_iterations;
  const FrontEndConfig& f = config_.front_end;
  const PosePrior prior{in_region, f.prior_info_xy, f.prior_info_theta};
  return RegisterImproved(*s_.region_reference, robot_points, in_region, &prior, plicp, s_.correspondences);
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
  // Against lines fitted to hit means, a wall's cells are taken where its line runs (the submap's
  // lines are refitted to raw points): a cell centre is up to half a cell off the wall, and the
  // maps' lines no longer share that error (docs/back-end.md, "Walls fitted where the returns fell").
  const bool onto_lines = HitMeans();
  for (std::size_t i = 0; i < n; i += stride) {
    const std::uint16_t k = static_cast<std::uint16_t>(i);
    Point2 p = sub.ObstaclePoint(k);
    const std::uint16_t line = sub.cell(k).line;
    if (onto_lines && line != kNoLine) {
      const LineFeature& l = sub.line(line);
      const float d = l.normal.x * p.x + l.normal.y * p.y - l.offset;
      p = Point2{p.x - d * l.normal.x, p.y - d * l.normal.y};
    }
    s_.target[count++] = p;
  }
  // Registered about their centroid, not the submap frame's far origin (pivot_frame.hpp).
  target_pivot_ = RecentreOnCentroid(Span<Point2>(s_.target.data(), count));
  return count;
}

void FrontEnd::BeginLoopClosure(int from) {
  const int region = regions_.current();
  if (region < 0) return;
  path_at_closure_try_ = path_m_;
  const std::size_t n = SubmapTarget();
  const float path = path_m_ - regions_[region].path_at_last_scan_m;
  if (back_end_.BeginLoopClosure(regions_.maps(), region, from, Span<const Point2>(s_.target.data(), n),
                                 PivotPose(submap_pose_, target_pivot_),
                                 path)) {
    InvalidateRegionReference();  // its table holds the search grid now
  }
}

void FrontEnd::FinishLoopClosure() {
  const int region = back_end_.search_region();
  const std::size_t n = SubmapTarget();
  const LoopClosureResult r =
      back_end_.FinishLoopClosure(regions_.maps(), Span<const Point2>(s_.target.data(), n),
                                  PivotPose(submap_pose_, target_pivot_));
  InvalidateRegionReference();
  if (r.verdict != Status::kOk) return;
  // The anchors have moved (the graph took the closure); the submap belongs where it was found.
  submap_pose_ = FramePose(regions_[region].anchor * r.submap_in_region, target_pivot_);
  anchor_region_ = region;
  lost_in_region_ = false;
}

void FrontEnd::StepBackEnd() {
  // The robot's pose is known in the anchor region's frame (the current one, unless the robot
  // could not place itself in the map it entered): it moves with that vertex.
  const int followed = anchor_region_ >= 0 ? anchor_region_ : regions_.current();
  const Pose2 before = followed >= 0 ? regions_[followed].anchor : Pose2::Identity();
  const BackEnd::StepResult r = back_end_.Step(regions_.maps());
  if (r.used_reference || r.anchors_moved) InvalidateRegionReference();
  if (r.anchors_moved && followed >= 0) submap_pose_ = regions_[followed].anchor * before.Inverse() * submap_pose_;
  if (r.loop_search_done) FinishLoopClosure();
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
