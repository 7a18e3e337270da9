// Do the wheels measure what the lidar sees the robot do? A recorder that turned its IMU's yaw
// into wheel ticks (real XV-11 recordings were converted so), a dead encoder, or a wheel board
// that sends counters that never move: the odometry then says "standing still" while the robot
// drives, the translation prior holds every registration back, and the run drifts by metres with
// every scan "tracked". A robot stuck on a rug's edge whose wheels spin on is the same the other
// way round. This check compares the wheels' net motion with the registered one over windows of
// clear motion and, when they disagree by 4x or more window after window, makes the
// front end treat them as a heading source at most (the gyro-only mode: translation from the
// constant velocity), or as nothing when they miss the turns too. Wheels that agree again are
// taken back. Real wheels agree within slip (a few per cent): the thresholds leave a wide margin.
#pragma once
#include <cstdint>
#include "core/front_end/odometry.hpp"
#include "core/geometry/pose2.hpp"

namespace dpcr {

class WheelCheck {
 public:
  // Every odometry sample as it arrives, before Filter.
  void AddOdometry(const OdometrySample& sample);
  // After each scan: `step` the registered motion since the last scan (in the last scan's frame),
  // `wheels` the wheel odometry's pose at the same stamp (OdometryBuffer::PoseAt: the newest sample
  // is a revolution later, and a turn window closed on it overstates the wheels' turn by 10 % and
  // more); `tracked` when its first registration was accepted and the robot was not lost (only
  // then does `step` say where the robot went). A step, not a pose: the front end's pose jumps
  // when the back end corrects its region or the submap's frame moves, and on intel.clf such
  // jumps of 0.3-0.5 m counted as lidar motion the wheels missed (21 windows in one replay, three
  // in a row with the robot standing: its wheels were set aside and the robot was lost for 690 s).
  // `clean_fit`: the registration fitted cleanly (FrontEnd::RegisterScan). A window in which
  // the wheels ran on while the lidar saw the robot stand counts as a miss only when every
  // registration in it fitted cleanly: a robot stuck on a rug's edge sees the same room scan after
  // scan, while a registration caught on the wrong wall fits it poorly (mit-csail.clf with 0.5 %
  // shorter steps, 25 m range: after a fast turn six registrations in a row held the robot back at
  // 3.1-3.8 cm mean residual, the wheels were set aside and the robot was lost for 190 of 420 s).
  void AddScan(const Pose2& step, const Pose2& wheels, std::int64_t stamp_us, bool tracked, bool clean_fit = true);
  // The sample the front end should use: unchanged while the wheels are trusted; otherwise a
  // sample without wheels whose yaw rate is the wheels' heading change (when the wheels see the
  // turns and no gyro rate came with it).
  OdometrySample Filter(const OdometrySample& sample) const;

  bool translation_ignored() const { return translation_.rejected; }
  // Registered turn over the wheels' turn, from the turns where both agree (1 until
  // kMinScaleEvidenceRad of them), clamped to [kAgreeRatio, 1 / kAgreeRatio]: a converter's or a
  // board's track width that is not the one the odometry assumes scales every turn. Applied,
  // when it is off by more than kScaleDeadBand, to the heading of wheels whose translation is
  // ignored (their turn rate). (Heading ticks through the device path decoded with a track width
  // 15 % short, seed 1: 0.148 -> 0.095 m; applied always, the estimate's noise cost 0.057 ->
  // 0.063 m on seeds 1-10 with the right one.)
  float heading_scale() const;
  // Ignored, or, while no window has yet shown the wheels right, on the way there: a window
  // already missed or the open one's wheels standing still so far (from kDoubtDistanceM on: the
  // scans before the switch build the first map). The registration then leans on the wheels'
  // translation as little as on a guess. Wheels once seen right are not doubted for standing
  // still (a logger's stall) until switched off, nor for running on where the lidar sees the
  // robot stand (intel.clf's odometry drifts by up to 0.25 m in turns on the spot: doubting it
  // there took all pairs from 0.025 to 0.049 m).
  bool translation_doubted() const {
    return translation_.rejected || (!translation_confirmed_ && (translation_.run > 0 || wheels_short_));
  }
  // The wheels' heading is presumed good until turns show otherwise (ticks made of an IMU's yaw
  // are good from the first sample; a dead encoder is found after kVotesToSwitch turns).
  bool heading_used() const { return !heading_.rejected; }
  // Windows in which the wheels missed most of the registered translation, and times the check
  // switched the wheels' translation off.
  std::uint32_t translation_misses() const { return translation_misses_; }
  std::uint32_t translation_switched_off() const { return switched_off_; }

  // A translation window closes once the robot has moved this far (net, as registered or as the
  // wheels say); a heading window once it has turned this much. Windows that take longer are
  // restarted. kDoubtDistanceM: from here on an open window counts (translation_doubted).
  static constexpr float kWindowDistanceM = 0.3f;
  static constexpr float kWindowTurnRad = 0.5f;
  static constexpr float kDoubtDistanceM = 0.1f;
  static constexpr std::int64_t kWindowMaxUs = 10000000;
  // The shorter of the two translations under this share of the longer: a miss; at least kAgree
  // of it: the wheels agree. (Heading: the wheels' turn against the registered one.)
  static constexpr float kMissRatio = 0.25f;
  static constexpr float kAgreeRatio = 0.5f;
  // Consecutive windows that switch the wheels' translation (heading) off, or back on.
  static constexpr int kVotesToSwitch = 3;
  static constexpr float kMinScaleEvidenceRad = 3.0f;
  static constexpr float kScaleDeadBand = 0.05f;
  // Each agreeing turn window's sums decay by this, so that the scale follows a change.
  static constexpr float kScaleMemory = 0.98f;

 private:
  // Consecutive votes of one quantity: `rejected` flips after kVotesToSwitch in a row.
  struct Verdict {
    bool rejected = false;
    std::uint8_t run = 0;  // consecutive votes against the current state
    bool Vote(bool agrees);  // true when the state flipped
  };
  void RestartWindows(const Pose2& wheels, std::int64_t stamp_us);
  void CheckTranslation(const Pose2& wheels, std::int64_t stamp_us);
  void CheckHeading(const Pose2& step, const Pose2& wheels, std::int64_t stamp_us);

  // (Ordered by size: the vacuum profile's static RAM is counted to the byte.)
  std::int64_t wheel_stamp_us_ = 0;
  // The open windows: when they started.
  std::int64_t translation_start_us_ = 0;
  std::int64_t turn_start_us_ = 0;
  float wheel_theta_ = 0.0f;      // the newest wheel heading received
  float wheel_turn_rate_ = 0.0f;  // rad/s between the two newest wheel samples
  // The registered steps summed since the translation window started (in a frame of the check's
  // own: `registered_heading_` is the registered turns summed), and where the wheels were then; the wheels'
  // last heading and the signed turns summed since the turn window started.
  Point2 moved_xy_;
  Point2 start_wheels_xy_;
  float registered_heading_ = 0.0f;
  float previous_wheels_theta_ = 0.0f;
  float turned_ = 0.0f;
  float wheels_turned_ = 0.0f;
  // Decayed sums of |registered turn| and |wheels' turn| over the agreeing turn windows.
  float scale_registered_rad_ = 0.0f;
  float scale_wheels_rad_ = 0.0f;
  std::uint32_t translation_misses_ = 0;
  std::uint32_t switched_off_ = 0;
  Verdict translation_;
  Verdict heading_;
  bool have_wheels_ = false;
  bool window_open_ = false;
  // The open translation window so far: the wheels under kMissRatio of the registered translation.
  bool wheels_short_ = false;
  bool translation_confirmed_ = false;  // a window has shown the wheels' translation right
  bool miss_wheels_long_ = false;  // the last missed window: the wheels went the farther
  bool window_unclean_ = false;  // a registration in the open translation window did not fit cleanly
};

}  // namespace dpcr
