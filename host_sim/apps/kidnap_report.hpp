// dpcr-sim's relocalisation figures (metrics.json "relocalisation"): for each simulated kidnap,
// whether and when the mapper placed itself in its maps again after the robot was put down, and
// how far from the truth; and for a start at an unknown pose in a saved map, the same for the
// first fix. Errors are taken at the scan of the fix (the pose the mapper gave then), against the
// ground truth carried into the map's frame.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/geometry/pose2.hpp"
#include "host_sim/eval/accuracy.hpp"
#include "host_sim/sim/simulation.hpp"

namespace dpcr::apps {

// A scan after which the mapper's relocalisation counter rose: the pose it gave and the truth
// (world frame of the simulation).
struct Recovery {
  std::int64_t stamp_us = 0;
  dpcr::Pose2 estimate;
  dpcr::Pose2 truth;
};

struct FixError {
  double position_m = 0.0;
  double heading_deg = 0.0;
};

inline FixError ErrorOf(const Recovery& r, const dpcr::Pose2& align) {
  const dpcr::Pose2 truth = align * r.truth;
  return FixError{std::hypot(static_cast<double>(r.estimate.x - truth.x), static_cast<double>(r.estimate.y - truth.y)),
                  std::fabs(static_cast<double>(dpcr::NormalizeAngle(r.estimate.theta - truth.theta))) * 180.0 / 3.14159265358979};
}

// The fixes' errors so far: the worst ones, and how many were farther off than `max_error_m`.
struct FixTally {
  double max_error_m = 0.0;
  int wrong = 0;
  double worst_m = 0.0, worst_deg = 0.0;
  void Add(const FixError& err) {
    if (err.position_m > max_error_m) ++wrong;
    worst_m = std::max(worst_m, err.position_m);
    worst_deg = std::max(worst_deg, err.heading_deg);
  }
};

inline double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5))];
}

// `align`: world -> map frame. `within_s`: the recovery target (3 s of motion after put-down;
// the simulated robot drives on at once). `max_error_m`: a fix farther off counts as wrong.
inline nlohmann::json KidnapMetrics(const std::vector<dpcr::sim::KidnapEvent>& kidnaps, const std::vector<Recovery>& recoveries,
                                    const dpcr::Pose2& align, double within_s, double max_error_m) {
  int put_down = 0, recovered = 0, in_time = 0;
  std::vector<double> times;
  FixTally tally{max_error_m};
  nlohmann::json each = nlohmann::json::array();
  for (std::size_t k = 0; k < kidnaps.size(); ++k) {
    const auto& e = kidnaps[k];
    if (e.down_us == 0) continue;  // still carried when the run ended
    ++put_down;
    const std::int64_t next_lift = k + 1 < kidnaps.size() ? kidnaps[k + 1].lift_us : INT64_MAX;
    const auto it = std::find_if(recoveries.begin(), recoveries.end(),
                                 [&](const Recovery& r) { return r.stamp_us >= e.down_us && r.stamp_us < next_lift; });
    nlohmann::json j = {{"lift_s", static_cast<double>(e.lift_us) * 1e-6}, {"down_s", static_cast<double>(e.down_us) * 1e-6}};
    if (it != recoveries.end()) {
      const double t = static_cast<double>(it->stamp_us - e.down_us) * 1e-6;
      const FixError err = ErrorOf(*it, align);
      ++recovered;
      if (t <= within_s) ++in_time;
      tally.Add(err);
      times.push_back(t);
      j["time_to_recover_s"] = t;
      j["error_m"] = err.position_m;
      j["error_deg"] = err.heading_deg;
    }
    each.push_back(j);
  }
  return {{"kidnaps", put_down},
          {"recovered", recovered},
          {"recovered_within_s", within_s},
          {"recovered_in_time", in_time},
          {"recovered_in_time_fraction", put_down > 0 ? static_cast<double>(in_time) / put_down : 0.0},
          {"time_to_recover_s", {{"median", Quantile(times, 0.5)}, {"p95", Quantile(times, 0.95)}, {"max", Quantile(times, 1.0)}}},
          {"max_error_m", tally.worst_m},
          {"max_error_deg", tally.worst_deg},
          {"wrong_fixes", tally.wrong},
          {"wrong_fix_threshold_m", max_error_m},
          {"each", each}};
}

// Every fix of the run, whatever lost the robot (a kidnap, a rejection streak, a slip without
// odometry): its error, and how many were wrong (farther off than `max_error_m`).
inline nlohmann::json FixMetrics(const std::vector<Recovery>& recoveries, const dpcr::Pose2& align, double max_error_m) {
  FixTally tally{max_error_m};
  nlohmann::json each = nlohmann::json::array();
  for (const Recovery& r : recoveries) {
    const FixError err = ErrorOf(r, align);
    tally.Add(err);
    each.push_back({{"t_s", static_cast<double>(r.stamp_us) * 1e-6}, {"error_m", err.position_m}, {"error_deg", err.heading_deg}});
  }
  return {{"fixes", recoveries.size()}, {"wrong_fixes", tally.wrong}, {"wrong_fix_threshold_m", max_error_m},
          {"max_error_m", tally.worst_m}, {"max_error_deg", tally.worst_deg}, {"each", each}};
}

// A start at an unknown pose: the first fix after `start_us`.
inline nlohmann::json UnknownStartMetrics(std::int64_t start_us, const std::vector<Recovery>& recoveries, const dpcr::Pose2& align) {
  if (recoveries.empty()) return {{"recovered", false}};
  const Recovery& r = recoveries.front();
  const FixError err = ErrorOf(r, align);
  return {{"recovered", true}, {"time_to_fix_s", static_cast<double>(r.stamp_us - start_us) * 1e-6},
          {"error_m", err.position_m}, {"error_deg", err.heading_deg}};
}

// The accuracy of the scans the mapper placed (not `lost`; while lost its pose is a guess, and
// says so), against the truth already in the map's frame. LocErr_ave is start-aligned: here at the
// first placed scan, whose fix error it then carries along; the mean error in the map's own frame
// (known: a fresh session, or dpcr-sim --map-origin) is the fairer figure of a loaded session.
inline nlohmann::json PlacedAccuracy(const dpcr::eval::Trajectory& estimate, const dpcr::eval::Trajectory& truth_in_map,
                                     const std::vector<bool>& lost) {
  dpcr::eval::Trajectory placed, truth;
  double sum = 0.0;
  for (std::size_t i = 0; i < estimate.size() && i < truth_in_map.size() && i < lost.size(); ++i) {
    if (lost[i]) continue;
    placed.push_back(estimate[i]);
    truth.push_back(truth_in_map[i]);
    sum += std::hypot(static_cast<double>(estimate[i].pose.x - truth_in_map[i].pose.x),
                      static_cast<double>(estimate[i].pose.y - truth_in_map[i].pose.y));
  }
  const auto a = dpcr::eval::EvaluateAgainstGroundTruth(placed, truth);
  return {{"loc_err_ave_m", a.loc_err_ave_m}, {"ate_rmse_m", a.ate_rmse_m}, {"max_err_m", a.max_err_m}, {"samples", a.samples},
          {"mean_err_in_map_frame_m", placed.empty() ? 0.0 : sum / static_cast<double>(placed.size())}};
}

}  // namespace dpcr::apps
