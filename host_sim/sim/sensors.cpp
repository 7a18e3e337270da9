#include "host_sim/sim/sensors.hpp"

#include <cmath>

namespace dpcr::sim {

float SimulateBeam(const WorldRayCaster& caster, const LidarConfig& config, const Pose2d& sensor_pose,
                   double beam_angle_rad, std::mt19937_64* rng) {
  const RayHit hit = caster.Cast(Vec2{sensor_pose.x, sensor_pose.y}, sensor_pose.theta + beam_angle_rad,
                                 config.max_range_m);
  // Draw the same random numbers whatever happens, so one beam's outcome never shifts the others'.
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double u = uniform(*rng);
  const double n = normal(*rng);
  if (!hit.hit || hit.range_m < config.min_range_m) return 0.0f;
  const double p = caster.world().materials[static_cast<std::size_t>(hit.material)].return_probability;
  if (config.dropouts && u >= p) return 0.0f;
  const double r = hit.range_m + n * (config.noise_base_m + config.noise_fraction * hit.range_m);
  if (r < config.min_range_m || r > config.max_range_m) return 0.0f;
  return static_cast<float>(r);
}

LidarConfig Xv11LidarConfig() {
  LidarConfig c;
  c.beams_per_revolution = 360;
  c.rate_hz = 5.0;
  c.rate_min_hz = 4.5;
  c.min_range_m = 0.15;
  c.max_range_m = 6.0;
  c.noise_base_m = 0.01;
  c.noise_fraction = 0.01;
  c.invalid_probability = 0.3;
  c.junk_probability = 0.01;
  c.spin_up_valid_probability = 0.1;
  return c;
}

float DegradeBeam(float range_m, const LidarConfig& config, bool spin_up, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double u_junk = uniform(*rng), junk = uniform(*rng), u_valid = uniform(*rng);
  if (u_junk < config.junk_probability) {
    return static_cast<float>(config.min_range_m + junk * (config.max_range_m - config.min_range_m));
  }
  const double keep = (1.0 - config.invalid_probability) * (spin_up ? config.spin_up_valid_probability : 1.0);
  return u_valid < keep ? range_m : 0.0f;
}

WheelOdometryModel::WheelOdometryModel(const OdometryConfig& config, std::uint64_t seed)
    : config_(config), rng_(seed) {
  believed_ = WheelCalibration{config.wheel_radius_m, config.wheel_radius_m, config.track_m};
  if (config.systematic_error) {
    std::uniform_real_distribution<double> magnitude(config.calibration_error_min, config.calibration_error_max);
    std::bernoulli_distribution sign(0.5);
    auto off = [&](double v) { return v * (1.0 + (sign(rng_) ? 1.0 : -1.0) * magnitude(rng_)); };
    believed_.left_radius_m = off(believed_.left_radius_m);
    believed_.right_radius_m = off(believed_.right_radius_m);
    believed_.track_m = off(believed_.track_m);
  }
}

void WheelOdometryModel::Sample(std::int64_t stamp_us, double left_travel_m, double right_travel_m,
                                double yaw_rate_rps, OdometrySample* odometry, WheelTicks* ticks) {
  const double t = static_cast<double>(stamp_us) * 1e-6;
  const double dt = 1.0 / config_.rate_hz;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double slip_draw = uniform(rng_);
  const double slip_wheel = uniform(rng_);
  const double slip_len = uniform(rng_);
  const double slip_factor = uniform(rng_);
  const double gyro_noise = normal(rng_);
  if (t >= slip_until_s_ && slip_draw < config_.slips_per_minute / 60.0 * dt) {
    ++slip_events_;
    slip_wheel_ = slip_wheel < 0.5 ? 0 : 1;
    slip_until_s_ = t + config_.slip_duration_min_s + slip_len * (config_.slip_duration_max_s - config_.slip_duration_min_s);
    slip_factor_ = config_.slip_factor_min + slip_factor * (config_.slip_factor_max - config_.slip_factor_min);
  }
  const double travel[2] = {left_travel_m, right_travel_m};
  std::int64_t now_ticks[2];
  for (int w = 0; w < 2; ++w) {
    const double step = first_ ? 0.0 : travel[w] - last_travel_[w];
    const double factor = (t < slip_until_s_ && w == slip_wheel_) ? slip_factor_ : 1.0;
    encoder_rad_[w] += step / config_.wheel_radius_m * factor;
    last_travel_[w] = travel[w];
    now_ticks[w] = static_cast<std::int64_t>(std::floor(encoder_rad_[w] * config_.ticks_per_revolution / (2.0 * kPiD)));
  }
  // Integrate the tick increments with the believed calibration (midpoint rule).
  const double per_tick = 2.0 * kPiD / config_.ticks_per_revolution;
  const double dl = static_cast<double>(now_ticks[0] - last_ticks_[0]) * per_tick * believed_.left_radius_m;
  const double dr = static_cast<double>(now_ticks[1] - last_ticks_[1]) * per_tick * believed_.right_radius_m;
  const double ds = 0.5 * (dl + dr);
  const double dtheta = (dr - dl) / believed_.track_m;
  x_ += ds * std::cos(theta_ + 0.5 * dtheta);
  y_ += ds * std::sin(theta_ + 0.5 * dtheta);
  theta_ = WrapAngle(theta_ + dtheta);
  last_ticks_[0] = now_ticks[0];
  last_ticks_[1] = now_ticks[1];
  first_ = false;

  odometry->stamp_us = stamp_us;
  odometry->pose = Pose2d{x_, y_, theta_}.ToPose2();
  odometry->has_gyro = config_.gyro;
  odometry->gyro_yaw_rate =
      config_.gyro ? static_cast<float>(yaw_rate_rps + config_.gyro_bias_rps + config_.gyro_noise_rps * gyro_noise) : 0.0f;
  ticks->stamp_us = stamp_us;
  // Two's-complement wrap of the 64-bit count, as a 32-bit hardware counter would.
  ticks->left = static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::uint64_t>(now_ticks[0])));
  ticks->right = static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::uint64_t>(now_ticks[1])));
}

}  // namespace dpcr::sim
