#include "host_sim/sim/motion.hpp"

#include <cmath>

namespace dpcr::sim {

PlanFollower::PlanFollower(std::vector<Vec2> tour, double start_theta, const MotionLimits& limits)
    : tour_(std::move(tour)), limits_(limits) {
  if (tour_.empty()) tour_.push_back(Vec2{});
  pose_ = Pose2d{tour_[0].x, tour_[0].y, WrapAngle(start_theta)};
  move_.start_pose = pose_;  // an empty move at t = 0
  NextMove();
}

void PlanFollower::NextMove() {
  const Move done = move_;
  Move m;
  m.start_t = done.start_t + done.duration;
  m.start_pose = pose_;
  m.start_distance = distance_;
  m.start_rotation = rotation_;
  if (spin_due_) {
    spin_due_ = false;
    m.rotate = m.spin = true;
    m.amount = spin_direction_ * 2.0 * kPiD;
    m.vmax = limits_.spin_yaw_rate_rps;
    m.accel = limits_.spin_yaw_accel_rps2;
    spin_direction_ = -spin_direction_;
  }
  // Find the next waypoint that needs motion; a tour with no motion at all leaves the robot parked.
  for (std::size_t tries = 0; tries < tour_.size() + 1 && !m.spin; ++tries) {
    if (tour_.size() < 2) break;
    const Vec2 target = tour_[next_waypoint_];
    const Vec2 d = target - Vec2{pose_.x, pose_.y};
    const double dist = Norm(d);
    if (dist > 1e-9) {
      const double turn = WrapAngle(std::atan2(d.y, d.x) - pose_.theta);
      if (std::fabs(turn) > 1e-9) {
        m.rotate = true;
        m.amount = turn;
        m.vmax = limits_.max_yaw_rate_rps;
        m.accel = limits_.max_yaw_accel_rps2;
      } else {
        m.rotate = false;
        m.amount = dist;
        m.vmax = limits_.max_speed_mps;
        m.accel = limits_.max_accel_mps2;
      }
      break;
    }
    next_waypoint_ = (next_waypoint_ + 1) % tour_.size();
    if (next_waypoint_ == 0) ++tours_;
  }
  const double a = std::fabs(m.amount);
  if (a > 0.0) {
    if (a >= m.vmax * m.vmax / m.accel) {
      m.v_peak = m.vmax;
      m.t_acc = m.vmax / m.accel;
      m.duration = 2.0 * m.t_acc + (a - m.vmax * m.vmax / m.accel) / m.vmax;
    } else {
      m.v_peak = std::sqrt(a * m.accel);
      m.t_acc = m.v_peak / m.accel;
      m.duration = 2.0 * m.t_acc;
    }
  } else {
    m.duration = 1e9;  // parked
  }
  move_ = m;
}

double PlanFollower::Progress(const Move& m, double dt) const {
  const double a = std::fabs(m.amount);
  if (dt <= 0.0) return 0.0;
  if (dt >= m.duration) return a;
  if (dt < m.t_acc) return 0.5 * m.accel * dt * dt;
  const double rest = m.duration - dt;
  if (rest < m.t_acc) return a - 0.5 * m.accel * rest * rest;
  return 0.5 * m.accel * m.t_acc * m.t_acc + m.v_peak * (dt - m.t_acc);
}

void PlanFollower::Evaluate(double t) {
  const Move& m = move_;
  const double s = std::copysign(Progress(m, t - m.start_t), m.amount);
  if (m.rotate) {
    pose_ = Pose2d{m.start_pose.x, m.start_pose.y, WrapAngle(m.start_pose.theta + s)};
    rotation_ = m.start_rotation + s;
    distance_ = m.start_distance;
  } else {
    const double c = std::cos(m.start_pose.theta), sn = std::sin(m.start_pose.theta);
    pose_ = Pose2d{m.start_pose.x + s * c, m.start_pose.y + s * sn, m.start_pose.theta};
    distance_ = m.start_distance + s;
    rotation_ = m.start_rotation;
  }
}

void PlanFollower::AdvanceTo(double t_s) {
  if (t_s < t_) t_s = t_;
  while (t_s >= move_.start_t + move_.duration) {
    Evaluate(move_.start_t + move_.duration);
    if (!move_.rotate && std::fabs(move_.amount) > 0.0) {
      // Arrived: land exactly on the waypoint so float error never accumulates along the tour.
      pose_.x = tour_[next_waypoint_].x;
      pose_.y = tour_[next_waypoint_].y;
      next_waypoint_ = (next_waypoint_ + 1) % tour_.size();
      if (next_waypoint_ == 0) ++tours_;
      ++arrivals_;
      if (limits_.spin_every_waypoints > 0 && arrivals_ % limits_.spin_every_waypoints == 0) spin_due_ = true;
    }
    NextMove();
  }
  Evaluate(t_s);
  t_ = t_s;
}

void PlanFollower::Relocate(const Pose2d& pose, std::size_t waypoint) {
  pose_ = pose;
  next_waypoint_ = tour_.empty() ? 0 : waypoint % tour_.size();
  Move here;
  here.start_t = t_;
  here.start_pose = pose_;
  here.start_distance = distance_;
  here.start_rotation = rotation_;
  move_ = here;  // an empty move ending now
  NextMove();
}

}  // namespace dpcr::sim
