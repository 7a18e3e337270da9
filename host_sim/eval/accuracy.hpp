// Accuracy figures of an estimated trajectory against ground truth.
//  - LocErr_ave (Cao et al. 2025, Eq. 17): poses sampled at a regular period, the estimate
//    aligned to the ground truth at the start pose; the mean of the largest 10 % of the
//    position errors. max_err_m is the largest of those errors.
//  - ATE RMSE: the RMS position error after the least-squares rigid alignment (Horn/Umeyama in 2D).
//  - rigid_loc_err_ave_m: LocErr_ave's statistic on the errors after that alignment instead of the
//    start pose's. A diagnostic, not the paper's figure: the difference is the part of the error
//    that one rigid motion of the whole estimate removes (a turn common to the maps, whatever made it).
//  - Relations (Kümmerle et al. 2009): for each relation (t1, t2, Z), the error of the estimated
//    relative pose Between(x(t1), x(t2)) against Z: mean and std of |translation| (m) and |angle| (deg).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "host_sim/eval/trajectory.hpp"

namespace dpcr::eval {

struct AccuracyResult {
  std::size_t samples = 0;
  std::size_t unmatched = 0;  // samples with no ground truth within the tolerance
  double loc_err_ave_m = 0.0;
  double ate_rmse_m = 0.0;
  double rigid_loc_err_ave_m = 0.0;
  double max_err_m = 0.0;
};

// Poses are matched by timestamp (nearest ground truth within `tolerance_us`).
AccuracyResult EvaluateAgainstGroundTruth(const Trajectory& estimate, const Trajectory& ground_truth,
                                          double sample_period_s = 1.0, std::int64_t tolerance_us = 10000);

// Index of the pose of `gt` (sorted by stamp) nearest in time to `t`, or -1 beyond the tolerance.
long Nearest(const Trajectory& gt, std::int64_t t, std::int64_t tolerance_us);

// The mean of the largest 10 % of `errors` (at least one); 0 for none.
double MeanOfLargestTenth(std::vector<double> errors);

struct Relation {
  std::int64_t t1_us = 0;
  std::int64_t t2_us = 0;
  dpcr::Pose2 delta;
};

// Reads `t1 t2 x y z roll pitch yaw` lines; throws std::runtime_error("path: line N: ...").
std::vector<Relation> ReadRelationsFile(const std::string& path);

struct RelationsResult {
  std::size_t matched = 0;
  std::size_t unmatched = 0;  // relations whose t1 or t2 is not in the trajectory (exact stamp)
  double trans_mean_m = 0.0;
  double trans_std_m = 0.0;
  double rot_mean_deg = 0.0;
  double rot_std_deg = 0.0;
};

RelationsResult EvaluateRelations(const Trajectory& estimate, const std::vector<Relation>& relations);

}  // namespace dpcr::eval
