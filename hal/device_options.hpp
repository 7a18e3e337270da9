// The robot's device options, one set for dpcr-firmware and dpcr-replay --uart (and written by
// dpcr-sim --emit-device into DIR/device.json): wheel geometry and encoder, the lidar's angle
// direction, its range limit and its mount. The defaults are the firmware's (an upright LD06,
// a typical vacuum drive); a recording made elsewhere describes itself in device.json.
#pragma once

#include <string_view>

#include "core/config.hpp"
#include "hal/diff_drive_odometry.hpp"
#include "hal/lidar_stream.hpp"
#include "hal/scan_assembler.hpp"

namespace dpcr {

struct DeviceOptions {
  DiffDriveConfig wheels;          // radius 0.035 m, track 0.235 m, 1000 ticks per revolution
  float angle_sign = -1.0f;        // -1: device angles clockwise (an upright LD06); +1: counter-clockwise
  float max_range_m = LidarConfig{}.max_range_m;  // returns farther than this are ignored
  float laser_offset_m = 0.0f;     // the lidar this far ahead of the robot centre, facing forward

  LidarAngleMap angle_map() const { return LidarAngleMap{angle_sign, 0.0f}; }
  void ApplyTo(LidarConfig* lidar) const {
    lidar->max_range_m = max_range_m;
    lidar->mount = Pose2{laser_offset_m, 0.0f, 0.0f};
  }
};

// What the mapper is told of a lidar model, the same in dpcr-firmware and dpcr-replay --uart: an
// XV-11's junk readings are dropped (LidarConfig::drop_isolated_returns), and each model's range
// noise at 3 m (LidarConfig::range_noise_m) is the simulator's model of it: an LD06 1 cm + 0.5 %
// of the range, an XV-11 1 cm + 1 % (host_sim/sim/sensors.hpp); both sit at a vacuum's ankle
// height, where near returns weigh less (LidarConfig::near_weight_range_m). An LD06's scans taken
// in a fast turn stay out of the regional maps (LidarConfig::map_max_turn_rate_rad_s; an XV-11's
// do not: measured, both in core/config.hpp). An XV-11's returns are smoothed along walls across
// its missing readings (LidarConfig::smoothing_max_gap_beams), an LD06's between adjacent beams.
inline void ApplyLidarModel(LidarKind kind, LidarConfig* lidar) {
  const bool xv11 = kind == LidarKind::kXv11;
  lidar->drop_isolated_returns = xv11;
  lidar->range_noise_m = xv11 ? 0.04f : 0.025f;
  lidar->smoothing_max_gap_beams = xv11 ? kXv11SmoothingMaxGapBeams : LidarConfig{}.smoothing_max_gap_beams;
  lidar->near_weight_range_m = kVacuumNearWeightRangeM;
  lidar->map_max_turn_rate_rad_s = xv11 ? 0.0f : kLd06MapMaxTurnRateRadS;
}

// The prediction's heading (FrontEndConfig::gyro_heading) when neither the command line nor a
// configuration names it: the gyro's for an XV-11, the wheels' for an LD06. A 5 Hz lidar's sparse
// scans leave more of the wheels' heading error uncorrected: apartment seeds 1-10, XV-11 with
// wheels and a gyro, 35 min: LocErr_ave 0.071 m with the wheels' heading, 0.031 m with the
// gyro's; with half the readings at 3.5-5 Hz (10 min, seeds 1-60) 4 runs over 0.2 m against none.
// An LD06 corrects it scan by scan: 0.020 m with the wheels', 0.022 m with the gyro's. Without
// gyro frames the wheels' heading is used anyway (FrontEndConfig::gyro_heading).
inline bool ModelGyroHeading(LidarKind kind) { return kind == LidarKind::kXv11; }

// Whether `choice` names a heading source: model, wheels or gyro.
inline bool IsHeadingChoice(std::string_view choice) { return choice == "model" || choice == "wheels" || choice == "gyro"; }

// A --heading choice (model, wheels or gyro) for this lidar: whether the gyro's heading is used.
inline bool GyroHeadingFor(std::string_view choice, LidarKind kind) {
  return choice == "gyro" || (choice == "model" && ModelGyroHeading(kind));
}

}  // namespace dpcr
