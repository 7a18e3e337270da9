// Sensor models: an LD06/LD19-like 360-degree lidar (range noise growing with distance, dropouts
// by surface material) and wheel encoders with differential-drive odometry integrated from ticks
// with mis-calibrated parameters, tick quantisation, slip events and an optional noisy gyro.
#pragma once

#include <cstdint>
#include <random>

#include "core/front_end/odometry.hpp"
#include "host_sim/sim/world_ray_caster.hpp"

namespace dpcr::sim {

struct LidarConfig {
  int beams_per_revolution = 450;  // LD06 at 10 Hz: 4500 samples/s
  double rate_hz = 10.0;
  // A motor whose speed wanders (an XV-11's: 3.5-5 Hz): each revolution's rate is the last one's
  // plus a normal step of rate_step_hz, reflected into [rate_min_hz, rate_hz]; rate_min_hz 0 or
  // >= rate_hz: every revolution at rate_hz.
  double rate_min_hz = 0.0;
  double rate_step_hz = 0.05;
  double min_range_m = 0.02;
  double max_range_m = 12.0;
  double noise_base_m = 0.01;     // range sigma = base + fraction * range
  double noise_fraction = 0.005;
  bool dropouts = true;           // apply the materials' return probabilities
  Pose2d mount;                   // sensor pose in the robot frame
  // Low-cost lidar faults (0 / 1: off, the LD06 model; DegradeBeam): a return is lost (invalid
  // flag) with invalid_probability, replaced by a junk range uniform in [min, max] with
  // junk_probability; in the first revolution (spin-up) only spin_up_valid_probability of the
  // returns come.
  double invalid_probability = 0.0;
  double junk_probability = 0.0;
  double spin_up_valid_probability = 1.0;
};

// A Neato XV-11: 4.5-5 Hz (rate_min_hz 3.5 for a slower motor), 360 readings at 1 degree, 0.15-6 m, 30 % of the returns invalid, 1 % junk,
// a spin-up revolution with 10 % of its returns.
LidarConfig Xv11LidarConfig();

// The faults above applied to one simulated range (draws the same random numbers whatever happens).
float DegradeBeam(float range_m, const LidarConfig& config, bool spin_up, std::mt19937_64* rng);

// Range of one beam from the sensor pose in the world; 0 = no return.
float SimulateBeam(const WorldRayCaster& caster, const LidarConfig& config, const Pose2d& sensor_pose,
                   double beam_angle_rad, std::mt19937_64* rng);

struct WheelTicks {
  std::int64_t stamp_us = 0;
  std::int32_t left = 0;   // free-running counters, wrap like hardware ones
  std::int32_t right = 0;
};

struct OdometryConfig {
  int ticks_per_revolution = 4096;
  double wheel_radius_m = 0.035;
  double track_m = 0.23;
  double rate_hz = 100.0;
  // Systematic error: each believed parameter (left radius, right radius, track) is off by a
  // seeded random fraction in [min, max] with a random sign.
  bool systematic_error = true;
  double calibration_error_min = 0.01;
  double calibration_error_max = 0.02;
  // Slip: a wheel's ticks scaled by a random factor for a short time.
  double slips_per_minute = 0.5;
  double slip_duration_min_s = 0.1;
  double slip_duration_max_s = 0.4;
  double slip_factor_min = 0.8;
  double slip_factor_max = 1.2;
  bool gyro = true;
  double gyro_noise_rps = 0.005;  // white noise sigma per sample
  double gyro_bias_rps = 0.002;
};

struct WheelCalibration {
  double left_radius_m = 0.0;
  double right_radius_m = 0.0;
  double track_m = 0.0;
};

class WheelOdometryModel {
 public:
  WheelOdometryModel(const OdometryConfig& config, std::uint64_t seed);

  // Takes the true cumulative wheel travel (metres) at `stamp_us` and the true mean yaw rate over
  // the last interval; produces the tick counters and the odometry integrated from them.
  void Sample(std::int64_t stamp_us, double left_travel_m, double right_travel_m, double yaw_rate_rps,
              OdometrySample* odometry, WheelTicks* ticks);

  const WheelCalibration& believed() const { return believed_; }
  int slip_events() const { return slip_events_; }

 private:
  OdometryConfig config_;
  WheelCalibration believed_;
  std::mt19937_64 rng_;
  double encoder_rad_[2] = {0.0, 0.0};
  double last_travel_[2] = {0.0, 0.0};
  std::int64_t last_ticks_[2] = {0, 0};
  double slip_until_s_ = -1.0;
  int slip_wheel_ = 0;
  double slip_factor_ = 1.0;
  int slip_events_ = 0;
  bool first_ = true;
  double x_ = 0.0, y_ = 0.0, theta_ = 0.0;
};

}  // namespace dpcr::sim
