#include "host_sim/sim/simulation.hpp"

#include <cmath>

namespace dpcr::sim {
namespace {
// Separate random streams, so changing one model's settings does not reshuffle the others.
constexpr std::uint64_t kLidarStream = 0x9E3779B97F4A7C15ull;
constexpr std::uint64_t kOdometryStream = 0xC2B2AE3D27D4EB4Full;
constexpr std::uint64_t kPlanStream = 0x165667B19E3779F9ull;
constexpr std::uint64_t kRateStream = 0x27D4EB2F165667C5ull;

// A start pose drawn from the seed: a random waypoint of the canonical plan (so reachable from
// everywhere the plan goes, never inside a closed cabinet), facing anywhere.
Pose2d RandomStart(const CoveragePlan& canonical, std::mt19937_64* rng) {
  const std::size_t n = canonical.waypoints.size();
  const Vec2 p = canonical.waypoints[std::uniform_int_distribution<std::size_t>(0, n - 1)(*rng)];
  const double theta = std::uniform_real_distribution<double>(-1.0, 1.0)(*rng) * 3.14159265358979323846;
  return Pose2d{p.x, p.y, theta};
}
}  // namespace

Simulation::Simulation(const World& world, const SimConfig& config)
    : config_(config),
      world_(world),
      caster_(world_),
      odometry_(config.odometry, config.seed ^ kOdometryStream),
      lidar_rng_(config.seed ^ kLidarStream),
      rate_rng_(config.seed ^ kRateStream) {
  if (config.lidar.beams_per_revolution < 1 ||
      config.lidar.beams_per_revolution > static_cast<int>(SimScan{}.beams.capacity())) {
    throw WorldError("lidar beams_per_revolution must be in [1, " + std::to_string(SimScan{}.beams.capacity()) + "]");
  }
  if (!(config.lidar.rate_hz > 0.0) || !(config.odometry.rate_hz > 0.0) || !(config.duration_min >= 0.0)) {
    throw WorldError("lidar and odometry rates must be positive and the duration not negative");
  }
  Pose2d start = world.start;
  if (!world.has_start) {
    // No start given (PGM plans): the free point nearest the first room's centre.
    const Room& r = world.rooms.empty() ? Room{} : world.rooms.front();
    Vec2 p;
    if (!FindFreePoint(caster_, config.planner, Vec2{0.5 * (r.xmin + r.xmax), 0.5 * (r.ymin + r.ymax)}, &p)) {
      throw WorldError(world.name + ": no free space for the robot");
    }
    start = Pose2d{p.x, p.y, 0.0};
  }
  PlannerConfig planner = config.planner;
  if (config.vary_plan) {
    const CoveragePlan canonical = PlanCoverage(caster_, planner, Vec2{start.x, start.y});
    if (!canonical.waypoints.empty()) {
      std::mt19937_64 rng(config.seed ^ kPlanStream);
      start = RandomStart(canonical, &rng);
      planner.variation = rng() | 1u;  // never 0, the canonical plan
    }
  }
  start_ = start;
  plan_ = PlanCoverage(caster_, planner, Vec2{start.x, start.y});
  if (plan_.waypoints.empty()) throw WorldError(world.name + ": no free space for the robot near the start pose");
  follower_ = std::make_unique<PlanFollower>(plan_.waypoints, start.theta, config.motion);
  end_us_ = static_cast<std::int64_t>(std::llround(config.duration_min * 60e6));
  period_us_ = static_cast<std::int64_t>(std::llround(1e6 / config.lidar.rate_hz));
  rate_hz_ = config.lidar.rate_hz;
  odom_period_us_ = static_cast<std::int64_t>(std::llround(1e6 / config.odometry.rate_hz));
  pending_scan_.type = SimEventType::kScan;
}

Simulation::~Simulation() = default;

std::int64_t Simulation::BeamTime(std::int64_t i) const {
  return revolution_us_ + i * period_us_ / config_.lidar.beams_per_revolution;
}

std::int64_t Simulation::NextPeriodUs() {
  const LidarConfig& lidar = config_.lidar;
  if (lidar.rate_min_hz > 0.0 && lidar.rate_min_hz < lidar.rate_hz) {
    rate_hz_ += std::normal_distribution<double>(0.0, lidar.rate_step_hz)(rate_rng_);
    if (rate_hz_ > lidar.rate_hz) rate_hz_ = 2.0 * lidar.rate_hz - rate_hz_;
    if (rate_hz_ < lidar.rate_min_hz) rate_hz_ = 2.0 * lidar.rate_min_hz - rate_hz_;
    if (rate_hz_ > lidar.rate_hz || rate_hz_ < lidar.rate_min_hz) rate_hz_ = lidar.rate_hz;  // a step past both
  }
  return static_cast<std::int64_t>(std::llround(1e6 / rate_hz_));
}

bool Simulation::Step(SimEvent* out) {
  const LidarConfig& lidar = config_.lidar;
  const std::int64_t n = lidar.beams_per_revolution;
  for (;;) {
    const std::int64_t beam_us = BeamTime(next_beam_ % n);
    if (next_odom_us_ <= beam_us) {
      if (next_odom_us_ > end_us_) return false;
      const std::int64_t t = next_odom_us_;
      next_odom_us_ += odom_period_us_;
      follower_->AdvanceTo(static_cast<double>(t) * 1e-6);
      const double half_track = 0.5 * config_.odometry.track_m;
      const double d = follower_->distance_m(), r = follower_->rotation_rad();
      const double yaw_rate = (r - last_rotation_) * config_.odometry.rate_hz;
      last_rotation_ = r;
      out->type = SimEventType::kOdometry;
      out->time_us = t;
      odometry_.Sample(t, d - half_track * r, d + half_track * r, t == 0 ? 0.0 : yaw_rate, &out->odometry, &out->ticks);
      out->truth = follower_->pose();
      out->sensor_truth = out->truth * lidar.mount;
      return true;
    }
    if (beam_us > end_us_) return false;
    const std::int64_t i = next_beam_ % n;
    ++next_beam_;
    follower_->AdvanceTo(static_cast<double>(beam_us) * 1e-6);
    const Pose2d sensor = follower_->pose() * lidar.mount;
    SimScan& scan = pending_scan_.scan;
    if (i == 0) {
      scan.beams.clear();
      scan.stamp_us = beam_us;
      pending_scan_.truth = follower_->pose();
      pending_scan_.sensor_truth = sensor;
      pending_scan_.spinning = false;
    }
    pending_scan_.spinning = pending_scan_.spinning || follower_->spinning();
    const double angle = 2.0 * kPiD * static_cast<double>(i) / static_cast<double>(n);
    Beam beam;
    beam.angle_rad = NormalizeAngle(static_cast<float>(angle));
    beam.range_m = SimulateBeam(caster_, lidar, sensor, angle, &lidar_rng_);
    if (lidar.invalid_probability > 0.0 || lidar.junk_probability > 0.0 || lidar.spin_up_valid_probability < 1.0) {
      beam.range_m = DegradeBeam(beam.range_m, lidar, next_beam_ <= n, &lidar_rng_);
    }
    beam.offset_us = static_cast<std::int32_t>(beam_us - scan.stamp_us);
    (void)scan.beams.push_back(beam);  // capacity checked in the constructor
    if (i == n - 1) {
      revolution_us_ += period_us_;
      period_us_ = NextPeriodUs();
      pending_scan_.time_us = beam_us;
      *out = pending_scan_;
      return true;
    }
  }
}

::dpcr::LidarConfig MapperLidarConfig(const SimConfig& config) {
  ::dpcr::LidarConfig lidar;
  lidar.max_range_m = static_cast<float>(config.lidar.max_range_m);
  lidar.mount = config.lidar.mount.ToPose2();
  return lidar;
}

}  // namespace dpcr::sim
