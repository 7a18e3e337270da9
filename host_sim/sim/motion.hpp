// The robot's true motion: a differential-drive base following a waypoint tour by turning in
// place and driving straight, each move with a time-optimal trapezoidal velocity profile under
// speed and acceleration limits. The pose is an exact function of time (no integration error),
// so the ground truth, the lidar's per-beam poses and the wheel travel all agree.
#pragma once

#include <vector>

#include "host_sim/sim/geometry.hpp"

namespace dpcr::sim {

struct MotionLimits {
  double max_speed_mps = 0.30;
  double max_accel_mps2 = 0.50;
  double max_yaw_rate_rps = 1.50;
  double max_yaw_accel_rps2 = 3.00;
  // In-place spins (a vacuum's spot cleaning, an escape): after every spin_every_waypoints-th
  // waypoint reached (0 = never), one full turn on the spot at spin_yaw_rate_rps (120°/s),
  // accelerating at spin_yaw_accel_rps2; the direction alternates.
  int spin_every_waypoints = 0;
  double spin_yaw_rate_rps = 2.0943951;
  double spin_yaw_accel_rps2 = 6.0;
};

class PlanFollower {
 public:
  // `tour` is a closed list of waypoints (it repeats); the robot starts at tour[0] facing start_theta.
  PlanFollower(std::vector<Vec2> tour, double start_theta, const MotionLimits& limits);

  // Moves time forward to t_s (never backwards).
  void AdvanceTo(double t_s);
  // The robot put down at `pose` (a kidnap), at the current time: it resumes the tour from
  // tour[waypoint] on. The wheel travel does not change (the wheels were lifted).
  void Relocate(const Pose2d& pose, std::size_t waypoint);
  double time_s() const { return t_; }
  const Pose2d& pose() const { return pose_; }
  // Cumulative signed distance driven and cumulative (unwrapped) rotation since the start: the
  // wheels' true travel is distance -/+ track/2 * rotation.
  double distance_m() const { return distance_; }
  double rotation_rad() const { return rotation_; }
  int tours_completed() const { return tours_; }
  // True while the robot is in one of the in-place spins (MotionLimits::spin_every_waypoints).
  bool spinning() const { return move_.spin && t_ >= move_.start_t && t_ < move_.start_t + move_.duration; }

 private:
  struct Move {
    bool rotate = false;
    bool spin = false;  // an in-place spin, not a turn towards a waypoint
    double amount = 0.0;   // signed metres or radians
    double start_t = 0.0;
    double duration = 0.0;
    double vmax = 0.0, accel = 0.0, t_acc = 0.0, v_peak = 0.0;
    Pose2d start_pose;
    double start_distance = 0.0, start_rotation = 0.0;
  };
  void NextMove();
  double Progress(const Move& m, double dt) const;  // unsigned progress after dt in the move
  void Evaluate(double t);

  std::vector<Vec2> tour_;
  MotionLimits limits_;
  std::size_t next_waypoint_ = 1;
  Move move_;
  double t_ = 0.0;
  Pose2d pose_;
  double distance_ = 0.0;
  double rotation_ = 0.0;
  int tours_ = 0;
  int arrivals_ = 0;          // waypoints reached
  bool spin_due_ = false;     // the next move is a spin
  double spin_direction_ = 1.0;
};

}  // namespace dpcr::sim
