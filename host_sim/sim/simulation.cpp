#include "host_sim/sim/simulation.hpp"

#include <cmath>

namespace dpcr::sim {
namespace {
// Separate random streams, so changing one model's settings does not reshuffle the others.
constexpr std::uint64_t kLidarStream = 0x9E3779B97F4A7C15ull;
constexpr std::uint64_t kOdometryStream = 0xC2B2AE3D27D4EB4Full;
constexpr std::uint64_t kPlanStream = 0x165667B19E3779F9ull;
constexpr std::uint64_t kRateStream = 0x27D4EB2F165667C5ull;
constexpr std::uint64_t kKidnapStream = 0x165667B19E3779F9ull;
constexpr std::uint64_t kPeopleStream = 0x85EBCA77C2B2AE63ull;
constexpr std::uint64_t kDoorStream = 0x94D049BB133111EBull;

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
  if (std::isfinite(config.start_heading_rad)) start.theta = config.start_heading_rad;
  start_ = start;
  plan_ = PlanCoverage(caster_, planner, Vec2{start.x, start.y});
  if (plan_.waypoints.empty()) throw WorldError(world.name + ": no free space for the robot near the start pose");
  follower_ = std::make_unique<PlanFollower>(plan_.waypoints, start.theta, config.motion);
  end_us_ = static_cast<std::int64_t>(std::llround(config.duration_min * 60e6));
  period_us_ = static_cast<std::int64_t>(std::llround(1e6 / config.lidar.rate_hz));
  rate_hz_ = config.lidar.rate_hz;
  odom_period_us_ = static_cast<std::int64_t>(std::llround(1e6 / config.odometry.rate_hz));
  // A robot does not drive before its lidar is up to speed: the plan waits out a spin-up
  // revolution (no odometry could tell the mapper a turn made while the lidar saw nothing).
  if (config.lidar.spin_up_valid_probability < 1.0) plan_paused_s_ = static_cast<double>(period_us_) * 1e-6;
  pending_scan_.type = SimEventType::kScan;
  pose_ = follower_->pose();
  ScheduleKidnaps();
  people_ = People(config.people, plan_.waypoints, config.seed ^ kPeopleStream, static_cast<double>(end_us_) * 1e-6);
  doors_ = Doors(config.doors, world_, config.seed ^ kDoorStream, static_cast<double>(end_us_) * 1e-6);
  door_rng_.seed(config.seed ^ kDoorStream ^ kLidarStream);
}

void Simulation::ScheduleKidnaps() {
  const KidnapConfig& k = config_.kidnaps;
  if (k.count <= 0) return;
  if (!(k.from_min >= 0.0) || !(k.carry_min_s > 0.0) || !(k.carry_max_s >= k.carry_min_s)) {
    throw WorldError("kidnaps: from_min must not be negative and 0 < carry_min_s <= carry_max_s");
  }
  const double from_s = k.from_min * 60.0, end_s = static_cast<double>(end_us_) * 1e-6;
  const double spacing = (end_s - from_s) / k.count;
  if (!(spacing > k.carry_max_s + 1.0)) {
    throw WorldError("kidnaps: " + std::to_string(k.count) + " do not fit between minute " + std::to_string(k.from_min) +
                     " and the end of the run (each needs more than the longest carry)");
  }
  std::mt19937_64 rng(config_.seed ^ kKidnapStream);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < k.count; ++i) {
    PlannedKidnap p;
    const double carry = k.carry_min_s + unit(rng) * (k.carry_max_s - k.carry_min_s);
    // Anywhere in the first part of its slot, so that the robot has time to recover before the next.
    const double lift = from_s + spacing * (i + 0.5 * unit(rng) * (1.0 - (carry + 1.0) / spacing));
    p.lift_us = static_cast<std::int64_t>(std::llround(lift * 1e6));
    p.down_us = p.lift_us + static_cast<std::int64_t>(std::llround(carry * 1e6));
    p.waypoint = std::uniform_int_distribution<std::size_t>(0, plan_.waypoints.size() - 1)(rng);
    p.theta = (2.0 * unit(rng) - 1.0) * kPiD;
    planned_.push_back(p);
  }
}

void Simulation::AdvanceRobot(std::int64_t t_us) {
  if (!lifted_ && next_kidnap_ < planned_.size() && t_us >= planned_[next_kidnap_].lift_us) {
    const PlannedKidnap& p = planned_[next_kidnap_];
    follower_->AdvanceTo(static_cast<double>(p.lift_us) * 1e-6 - plan_paused_s_);
    const Vec2 w = plan_.waypoints[p.waypoint];
    kidnaps_.push_back(KidnapEvent{p.lift_us, 0, follower_->pose(), Pose2d{w.x, w.y, p.theta}});
    lifted_ = true;
  }
  if (lifted_) {
    const PlannedKidnap& p = planned_[next_kidnap_];
    KidnapEvent& e = kidnaps_.back();
    if (t_us < p.down_us) {
      // Held where it was lifted, then where it will be put down (the carry between is not modelled).
      pose_ = 2 * (t_us - p.lift_us) < p.down_us - p.lift_us ? e.from : e.to;
      return;
    }
    plan_paused_s_ += static_cast<double>(p.down_us - p.lift_us) * 1e-6;
    follower_->Relocate(e.to, p.waypoint);
    e.down_us = p.down_us;
    lifted_ = false;
    ++next_kidnap_;
  }
  follower_->AdvanceTo(static_cast<double>(t_us) * 1e-6 - plan_paused_s_);
  pose_ = follower_->pose();
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
      AdvanceRobot(t);
      const double half_track = 0.5 * config_.odometry.track_m;
      const double d = follower_->distance_m(), r = follower_->rotation_rad();
      const double yaw_rate = (r - last_rotation_) * config_.odometry.rate_hz;
      last_rotation_ = r;
      out->type = SimEventType::kOdometry;
      out->time_us = t;
      odometry_.Sample(t, d - half_track * r, d + half_track * r, t == 0 ? 0.0 : yaw_rate, &out->odometry, &out->ticks);
      out->odometry.lifted = lifted_;
      out->truth = pose_;
      out->sensor_truth = out->truth * lidar.mount;
      return true;
    }
    if (beam_us > end_us_) return false;
    const std::int64_t i = next_beam_ % n;
    ++next_beam_;
    AdvanceRobot(beam_us);
    const Pose2d sensor = pose_ * lidar.mount;
    SimScan& scan = pending_scan_.scan;
    if (i == 0) {
      scan.beams.clear();
      scan.stamp_us = beam_us;
      pending_scan_.truth = pose_;
      pending_scan_.sensor_truth = sensor;
      pending_scan_.spinning = false;
    }
    pending_scan_.spinning = pending_scan_.spinning || follower_->spinning();
    const double angle = 2.0 * kPiD * static_cast<double>(i) / static_cast<double>(n);
    Beam beam;
    beam.angle_rad = NormalizeAngle(static_cast<float>(angle));
    beam.range_m = SimulateBeam(caster_, lidar, sensor, angle, &lidar_rng_);
    if (people_.size() > 0) {
      // A person in front of the wall: the beam returns from their legs.
      const double d = people_.Cast(Vec2{sensor.x, sensor.y}, sensor.theta + angle, static_cast<double>(beam_us) * 1e-6,
                                    lidar.max_range_m, Vec2{pose_.x, pose_.y});
      if (d >= lidar.min_range_m && (beam.range_m <= 0.0f || d < static_cast<double>(beam.range_m))) beam.range_m = static_cast<float>(d);
    }
    if (doors_.size() > 0) {
      // A closed door in front of what the beam reached: it returns from the door, with the
      // lidar's range noise (its own stream: the other beams' draws do not move).
      const double d = doors_.Cast(Vec2{sensor.x, sensor.y}, sensor.theta + angle, static_cast<double>(beam_us) * 1e-6,
                                   Vec2{pose_.x, pose_.y}, lidar.max_range_m);
      if (d >= lidar.min_range_m && (beam.range_m <= 0.0f || d < static_cast<double>(beam.range_m))) {
        const double r = d + std::normal_distribution<double>(0.0, 1.0)(door_rng_) * (lidar.noise_base_m + lidar.noise_fraction * d);
        beam.range_m = r >= lidar.min_range_m && r <= lidar.max_range_m ? static_cast<float>(r) : 0.0f;
      }
    }
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
  lidar.range_noise_m = static_cast<float>(config.lidar.noise_base_m + 3.0 * config.lidar.noise_fraction);
  lidar.near_weight_range_m = kVacuumNearWeightRangeM;  // both models are a vacuum's lidar
  return lidar;
}

}  // namespace dpcr::sim
