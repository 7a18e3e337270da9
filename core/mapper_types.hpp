// What the Mapper reports: its state and its counters (metrics.json reads these).
#pragma once

#include <cstdint>

namespace dpcr {

enum class MapperStatus : std::uint8_t {
  kWaitingForData,  // no scan yet
  kTracking,
  kLost,      // repeated rejected registrations: poses come from odometry alone
  kPoolFull,  // a region or tile pool is exhausted: the map stops growing, localisation goes on
};

const char* ToString(MapperStatus status);

struct MapperCounters {
  std::uint32_t scans = 0;
  // Scans whose pose came from no registration: empty ones (scans_empty) and rejected first
  // registrations (FrontEndCounters::first_rejected); each of the latter is either fused at the
  // predicted pose (scans_fused_at_prediction) or kept out (scans_kept_out_rejected).
  std::uint32_t scans_rejected = 0;
  std::uint32_t scans_empty = 0;             // no usable beam: the pose is the prediction
  // Fewer returns than FrontEndConfig::min_start_hits while the submap was empty (a lidar's
  // spin-up): no submap starts from them; the pose is the prediction.
  std::uint32_t scans_too_sparse = 0;
  std::uint32_t scans_fused_at_prediction = 0;  // rejected, prediction certain: inserted there
  std::uint32_t scans_kept_out_rejected = 0;  // rejected, prediction uncertain: inserted nowhere
  std::uint32_t scans_kept_out_bent = 0;      // registered, de-skew doubtful: inserted nowhere (FrontEnd::KeepOutBent)
  std::uint32_t scans_without_odometry = 0;  // no odometry sample yet: constant-velocity prediction
  std::uint32_t odometry_samples = 0;
  std::uint32_t odometry_steps_back = 0;     // samples stamped earlier than their predecessor
  std::uint32_t odometry_rejected = 0;       // not finite, past any floor or gyro, a bad stamp: dropped (FrontEnd::AddOdometry)
  std::uint32_t beams_invalid = 0;           // no return, or outside [min, max] range
  std::uint32_t beams_isolated = 0;          // returns dropped as junk (LidarConfig::drop_isolated_returns)
  std::uint32_t regions_created = 0;
  std::uint32_t region_pool_full = 0;        // scans that wanted a new region and got none
  std::uint32_t updates_out_of_box = 0;      // cell updates past a regional map's box
  std::uint32_t updates_dropped_pool_full = 0;
  // Scans kept out of the regional maps (no smeared copy of the room): scans_kept_out_rejected.
  std::uint32_t scans_not_inserted = 0;
  // Scans mapped into the anchor map (the one the robot's pose is known in) while it could not
  // yet place itself in the map of the region it re-entered after a loop.
  std::uint32_t scans_into_anchor_map = 0;
  // Of scans_not_inserted: those taken while turning fast (LidarConfig::map_max_turn_rate_rad_s).
  std::uint32_t scans_turning_not_mapped = 0;
  std::uint32_t submap_restarts = 0;         // after a long rejection streak (FrontEndConfig)
  // Rejection streaks (consecutive rejected first registrations): the scans in them, the time
  // they covered (each scan counts the time since the previous scan), the longest one.
  std::uint32_t streak_scans = 0;
  std::int64_t streak_us = 0;
  std::uint32_t longest_streak_scans = 0;
  // Relocalisation (core/back_end/global_localiser.hpp; each counter sits where the layout had
  // padding): times the robot got lost (a rejection streak, the wheels lifted, an unknown start),
  // recoveries (placed in the maps again), global search rounds that ended without a verified
  // pose, scans taken with the wheels lifted (kept out of every map).
  std::uint32_t lost_events = 0;
  std::int64_t longest_streak_us = 0;
  // Scans after which the status was kLost, and the time they covered.
  std::uint32_t lost_scans = 0;
  std::uint32_t relocalisations = 0;
  std::int64_t lost_us = 0;
  std::uint32_t relocalisation_failures = 0;
  std::uint32_t lifted_scans = 0;
  // Odometry samples whose wheel translation was left out: the wheels missed the motion the lidar
  // registered, window after window (FrontEnd's WheelCheck: ticks made of an IMU's yaw, a dead
  // encoder); the front end then predicted like a robot without wheels.
  std::uint32_t odometry_without_wheel_translation = 0;
  // Scans stamped before 1970 or past 2^56 us: refused (Status::kInvalidArgument), nothing changed.
  std::uint32_t scans_bad_stamp = 0;
  // Scans stamped more than 10 minutes after or before the previous one (a clock jump, a sleep):
  // used, with no time measured across the jump (FrontEnd::AddScan).
  std::uint32_t scan_stamp_jumps = 0;
};

}  // namespace dpcr
