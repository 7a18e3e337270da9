#include "host_sim/eval/accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "host_sim/eval/stamp_text.hpp"

namespace dpcr::eval {
namespace {

struct Vec2 {
  double x, y;
};

double Mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

double Std(const std::vector<double>& v, double mean) {
  double s = 0.0;
  for (double x : v) s += (x - mean) * (x - mean);
  return v.size() < 2 ? 0.0 : std::sqrt(s / static_cast<double>(v.size() - 1));
}

}  // namespace

long Nearest(const Trajectory& gt, std::int64_t t, std::int64_t tolerance_us) {
  auto it = std::lower_bound(gt.begin(), gt.end(), t,
                             [](const StampedPose& p, std::int64_t s) { return p.stamp_us < s; });
  long best = -1;
  std::int64_t best_dt = tolerance_us + 1;
  for (auto c : {it, it == gt.begin() ? it : it - 1}) {
    if (c == gt.end()) continue;
    const std::int64_t dt = std::llabs(c->stamp_us - t);
    if (dt < best_dt) {
      best_dt = dt;
      best = static_cast<long>(c - gt.begin());
    }
  }
  return best;
}

double MeanOfLargestTenth(std::vector<double> errors) {
  if (errors.empty()) return 0.0;
  std::sort(errors.begin(), errors.end(), std::greater<double>());
  const std::size_t k = std::max<std::size_t>(1, errors.size() / 10);
  double s = 0.0;
  for (std::size_t i = 0; i < k; ++i) s += errors[i];
  return s / static_cast<double>(k);
}

AccuracyResult EvaluateAgainstGroundTruth(const Trajectory& estimate, const Trajectory& ground_truth,
                                          double sample_period_s, std::int64_t tolerance_us) {
  AccuracyResult r;
  Trajectory gt = ground_truth;
  std::stable_sort(gt.begin(), gt.end(), [](const StampedPose& a, const StampedPose& b) { return a.stamp_us < b.stamp_us; });
  // Sample the estimate at the regular period.
  std::vector<std::pair<dpcr::Pose2, dpcr::Pose2>> pairs;  // (estimate, truth)
  const std::int64_t period_us = static_cast<std::int64_t>(sample_period_s * 1e6);
  std::int64_t next_us = INT64_MIN;
  for (const StampedPose& e : estimate) {
    if (e.stamp_us < next_us) continue;
    const long g = Nearest(gt, e.stamp_us, tolerance_us);
    if (g < 0) {
      ++r.unmatched;
      continue;
    }
    pairs.emplace_back(e.pose, gt[static_cast<std::size_t>(g)].pose);
    next_us = e.stamp_us + period_us;
  }
  r.samples = pairs.size();
  if (pairs.empty()) return r;

  // Start-aligned errors (the paper's LocErr_ave and the max error).
  const dpcr::Pose2 align = pairs.front().second * pairs.front().first.Inverse();
  std::vector<double> errors;
  for (const auto& [e, g] : pairs) {
    const dpcr::Point2 p = align.Apply(dpcr::Point2{e.x, e.y});
    errors.push_back(std::hypot(static_cast<double>(p.x - g.x), static_cast<double>(p.y - g.y)));
  }
  r.max_err_m = *std::max_element(errors.begin(), errors.end());
  r.loc_err_ave_m = MeanOfLargestTenth(errors);

  // ATE: closed-form least-squares rotation + translation in 2D.
  Vec2 me{0, 0}, mg{0, 0};
  for (const auto& [e, g] : pairs) {
    me.x += e.x; me.y += e.y; mg.x += g.x; mg.y += g.y;
  }
  const double n = static_cast<double>(pairs.size());
  me.x /= n; me.y /= n; mg.x /= n; mg.y /= n;
  double sxx = 0.0, sxy = 0.0;  // sum of dot and cross products of centred points
  for (const auto& [e, g] : pairs) {
    const double ex = e.x - me.x, ey = e.y - me.y, gx = g.x - mg.x, gy = g.y - mg.y;
    sxx += ex * gx + ey * gy;
    sxy += ex * gy - ey * gx;
  }
  const double th = std::atan2(sxy, sxx), c = std::cos(th), s = std::sin(th);
  double sq = 0.0;
  std::vector<double> rigid_errors;
  for (const auto& [e, g] : pairs) {
    const double ex = e.x - me.x, ey = e.y - me.y;
    const double dx = c * ex - s * ey + mg.x - g.x, dy = s * ex + c * ey + mg.y - g.y;
    sq += dx * dx + dy * dy;
    rigid_errors.push_back(std::hypot(dx, dy));
  }
  r.ate_rmse_m = std::sqrt(sq / n);
  r.rigid_loc_err_ave_m = MeanOfLargestTenth(rigid_errors);
  return r;
}

std::vector<Relation> ReadRelationsFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::vector<Relation> out;
  ForEachDataLine(in, [&](long line, const std::string& text) {
    std::istringstream s(text);
    std::string t1, t2;
    double x, y, z, roll, pitch, yaw;
    if (!(s >> t1 >> t2 >> x >> y >> z >> roll >> pitch >> yaw)) {
      throw std::runtime_error(path + ": line " + std::to_string(line) + ": expected 't1 t2 x y z roll pitch yaw'");
    }
    Relation r;
    if (!ParseStamp(t1, &r.t1_us) || !ParseStamp(t2, &r.t2_us)) {
      throw std::runtime_error(path + ": line " + std::to_string(line) + ": bad timestamp");
    }
    r.delta = dpcr::Pose2{static_cast<float>(x), static_cast<float>(y), static_cast<float>(yaw)};
    out.push_back(r);
  });
  return out;
}

RelationsResult EvaluateRelations(const Trajectory& estimate, const std::vector<Relation>& relations) {
  // Exact stamps: every relation stamp is a laser stamp, and we write one pose per laser line.
  // A stamp repeated in the log (intel.clf has a few) takes the last pose written for it.
  std::unordered_map<std::int64_t, dpcr::Pose2> by_stamp;
  for (const StampedPose& p : estimate) by_stamp[p.stamp_us] = p.pose;
  RelationsResult r;
  std::vector<double> trans, rot;
  for (const Relation& rel : relations) {
    const auto a = by_stamp.find(rel.t1_us);
    const auto b = by_stamp.find(rel.t2_us);
    if (a == by_stamp.end() || b == by_stamp.end()) {
      ++r.unmatched;
      continue;
    }
    // Error of the estimated relative motion against the relation, in double precision.
    const dpcr::Pose2& p1 = a->second;
    const dpcr::Pose2& p2 = b->second;
    const double c = std::cos(static_cast<double>(p1.theta)), s = std::sin(static_cast<double>(p1.theta));
    const double dx = static_cast<double>(p2.x) - p1.x, dy = static_cast<double>(p2.y) - p1.y;
    const double ex = c * dx + s * dy, ey = -s * dx + c * dy;
    double dth = static_cast<double>(p2.theta) - p1.theta - rel.delta.theta;
    dth = std::atan2(std::sin(dth), std::cos(dth));
    trans.push_back(std::hypot(ex - rel.delta.x, ey - rel.delta.y));
    rot.push_back(std::fabs(dth) * 180.0 / M_PI);
  }
  r.matched = trans.size();
  r.trans_mean_m = Mean(trans);
  r.trans_std_m = Std(trans, r.trans_mean_m);
  r.rot_mean_deg = Mean(rot);
  r.rot_std_deg = Std(rot, r.rot_mean_deg);
  return r;
}

}  // namespace dpcr::eval
