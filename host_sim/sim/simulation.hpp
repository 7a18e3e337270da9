// The simulator the apps drive: a robot covering a World, producing a time-ordered stream of
// events — 100 Hz wheel odometry (+ raw ticks, + gyro) and 10 Hz lidar revolutions whose beams
// are each cast from the pose at the beam's own time — each with its ground-truth pose.
// Deterministic: the same World, SimConfig and seed give the same stream.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "core/capacity.hpp"
#include "core/config.hpp"
#include "core/geometry/scan.hpp"
#include "host_sim/sim/coverage_planner.hpp"
#include "host_sim/sim/doors.hpp"
#include "host_sim/sim/motion.hpp"
#include "host_sim/sim/people.hpp"
#include "host_sim/sim/sensors.hpp"

namespace dpcr::sim {

// Kidnaps: `count` times the robot is lifted (the wheels' lift flag set, the wheels still), held
// where it was for half the carry, then held at a random waypoint of its plan (any heading) for
// the other half, and put down there; it resumes its plan from that waypoint. The kidnaps are
// spread evenly (with jitter) from `from_min` to the end of the run.
struct KidnapConfig {
  int count = 0;
  double from_min = 0.0;
  double carry_min_s = 3.0;
  double carry_max_s = 6.0;
};

// One kidnap as it happened.
struct KidnapEvent {
  std::int64_t lift_us = 0;
  std::int64_t down_us = 0;
  Pose2d from;
  Pose2d to;
};

struct SimConfig {
  std::uint64_t seed = 1;
  // true: the seed also varies the cleaning plan (start pose, room order, lane axis and side, wall
  // direction), as one home's cleanings differ; false: the world's start pose and canonical plan.
  bool vary_plan = true;
  // The robot's heading at the start in the world frame (NaN: the world's or the seed's). 0 on a
  // world drawn with its walls along the axes starts the robot square to them, as from a dock.
  double start_heading_rad = std::numeric_limits<double>::quiet_NaN();
  double duration_min = 35.0;
  PlannerConfig planner;
  MotionLimits motion;
  LidarConfig lidar;
  OdometryConfig odometry;
  KidnapConfig kidnaps;
  PeopleConfig people;  // people walking through the home, seen by the lidar
  DoorsConfig doors;    // doors that open and close (the world's doors with a leaf)
};

using SimScan = Scan<VacuumProfile::kMaxBeams>;

// The mapper's lidar settings for this simulation's sensor (maximum range, mount pose, range noise).
::dpcr::LidarConfig MapperLidarConfig(const SimConfig& config);

enum class SimEventType { kOdometry, kScan };

struct SimEvent {
  SimEventType type = SimEventType::kOdometry;
  std::int64_t time_us = 0;  // when the event becomes available (a scan: its last beam's time)
  // kOdometry: stamp == time_us; ground truth is the robot pose at the stamp.
  OdometrySample odometry;
  WheelTicks ticks;
  // kScan: stamp = first beam's time; beams in the sensor frame, range 0 = no return.
  SimScan scan;
  Pose2d truth;         // robot pose in the world at the odometry stamp / scan stamp
  Pose2d sensor_truth;  // the sensor's pose at the same time (truth * mount)
  bool spinning = false;  // kScan: the robot was in an in-place spin during the revolution
};

class Simulation {
 public:
  // Copies the world. Throws WorldError if the config is unusable (e.g. more beams than a Scan holds).
  Simulation(const World& world, const SimConfig& config);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // Next event in time order; false once the duration is over.
  bool Step(SimEvent* out);

  const CoveragePlan& plan() const { return plan_; }
  // Where the robot started, in the world frame (the seed's draw, or the world's start pose).
  const Pose2d& start_pose() const { return start_; }
  const WheelCalibration& believed_calibration() const { return odometry_.believed(); }
  int slip_events() const { return odometry_.slip_events(); }
  int tours_completed() const { return follower_->tours_completed(); }
  // The robot pose at the current simulation time (after the last Step).
  const Pose2d& current_pose() const { return pose_; }
  // The kidnaps so far (those whose carry has begun; down_us is 0 until put down).
  const std::vector<KidnapEvent>& kidnaps() const { return kidnaps_; }
  // The people walking and the doors opening and closing (both empty unless configured).
  const People& people() const { return people_; }
  const Doors& doors() const { return doors_; }

 private:
  // The time of beam `i` of the current revolution.
  std::int64_t BeamTime(std::int64_t i) const;
  // The next revolution's period (LidarConfig::rate_min_hz: a wandering motor speed).
  std::int64_t NextPeriodUs();
  // Moves the robot to time t: along its plan, or carried (pose_, lifted_).
  void AdvanceRobot(std::int64_t t_us);
  void ScheduleKidnaps();

  struct PlannedKidnap {
    std::int64_t lift_us = 0;
    std::int64_t down_us = 0;
    std::size_t waypoint = 0;
    double theta = 0.0;
  };
  std::vector<PlannedKidnap> planned_;
  std::vector<KidnapEvent> kidnaps_;
  std::size_t next_kidnap_ = 0;
  bool lifted_ = false;
  double plan_paused_s_ = 0.0;  // the plan's clock stood still this long: carried, or waiting for the lidar
  Pose2d pose_;             // the robot's true pose now
  People people_;
  Doors doors_;
  std::mt19937_64 door_rng_;  // the range noise of returns from doors

  SimConfig config_;
  World world_;  // a copy: the caster points into it, so temporaries are safe to pass
  WorldRayCaster caster_;
  Pose2d start_;
  CoveragePlan plan_;
  std::unique_ptr<PlanFollower> follower_;
  WheelOdometryModel odometry_;
  std::mt19937_64 lidar_rng_;
  std::mt19937_64 rate_rng_;
  double rate_hz_ = 0.0;          // the current revolution's rate
  std::int64_t revolution_us_ = 0;  // the current revolution's first beam time
  std::int64_t end_us_ = 0;
  std::int64_t period_us_ = 0;
  std::int64_t odom_period_us_ = 0;
  std::int64_t next_odom_us_ = 0;
  std::int64_t next_beam_ = 0;  // global beam index
  double last_rotation_ = 0.0;
  SimEvent pending_scan_;       // the revolution being built
};

}  // namespace dpcr::sim
