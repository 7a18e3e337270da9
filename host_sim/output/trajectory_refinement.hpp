// The trajectory refined after the run: each scan registered again in its finished regional map.
//
// A scan's final pose is its map's final anchor times the pose it was registered at then, against
// the map as it was then. Where a robot comes back to a map many times, its visits disagree: on
// intel.clf one visit sits 0.4-2.0 degrees off the others of the same map (docs/back-end.md,
// "The trajectory registered again in the finished maps"). Registered again against the finished
// map, which holds every visit, each scan lands where that map places it. The robot cannot do this:
// it keeps no scans. The host apps keep each scan's returns as the mapper placed them (in the robot
// frame, de-skewed: Mapper::RecordScanPoints) and register them once more at the end, from the pose
// the run gave them, with the run's own first-registration prior and acceptance, against their own
// map and the map next to them (the other map whose centre is nearest): near a border the next
// map's walls place a scan too, as the run's second registration uses the map the robot came from.
// The maps are not touched: map.pgm is the same with or without it.
//
// Kept where the run placed them: the run's first recorded scan (the start: one registration's
// noise there would turn the whole start-aligned trajectory about it, and the start has its own
// refinement, Mapper::RefineStart); a scan in no map; one the registration refuses; one it moves
// farther than a scan's own noise explains (RefinementConfig: then it matched another wall).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/base/span.hpp"
#include "core/base/status.hpp"
#include "core/geometry/pose2.hpp"
#include "core/registration/plicp.hpp"

namespace dpcr::output {

struct RefinementConfig {
  // Gauss-Newton steps from the run's pose, which is a few millimetres and a tenth of a degree from
  // the finished map's: on intel.clf (own map alone) 1 / 2 / 3 / 30 steps gave 0.0176 / 0.0175 /
  // 0.0176 / 0.0177 m mean relation error, at 0.05 / 0.09 / 0.13 / 0.19 s for 13 631 scans.
  int max_iterations = 2;
  // A registration that moves a scan farther than this from where the run placed it has matched
  // another wall (a corridor's next door): the scan keeps its run pose.
  float max_move_m = 0.1f;
  float max_turn_rad = 0.05f;
};

// What RefineTrajectory did (metrics.json "trajectory_refinement").
struct RefinementStats {
  bool enabled = false;
  std::size_t recorded = 0;    // scans whose returns were recorded
  std::size_t registered = 0;  // moved to their pose in the finished map
  std::size_t refused = 0;     // the registration refused them: kept
  std::size_t too_far = 0;     // moved past the config's bounds: kept
  std::size_t stored_bytes = 0;  // the recorded returns (host memory)
  std::size_t points_not_stored = 0;  // returns past the record's reach (ScanPointRecord)
  double seconds = 0.0;
};

// Every scan's returns, as the mapper recorded them. Attach before the first scan; call AfterScan
// after each AddScan (a scan not recorded gets no points). Stored in millimetres (int16: 4 bytes a
// point, 9 MB for intel.clf's 13 631 scans) in blocks, so that the record never copies itself as it
// grows; a return farther than 32.767 m from the robot on either axis is not stored (counted).
class ScanPointRecord {
 public:
  template <class MapperType>
  void Attach(MapperType& mapper) {
    buffer_.assign(static_cast<std::size_t>(MapperType::ProfileType::kMaxBeams), Point2{});
    mapper.RecordScanPoints(Span<Point2>(buffer_.data(), buffer_.size()));
  }
  template <class MapperType>
  void AfterScan(const MapperType& mapper) { Append(Span<const Point2>(buffer_.data(), mapper.recorded_points())); }
  void Append(Span<const Point2> points);
  std::size_t scans() const { return begins_.size(); }
  std::size_t points(std::size_t scan) const { return End(scan) - begins_[scan]; }
  // Scan i's points into `out` (resized).
  void Scan(std::size_t i, std::vector<Point2>* out) const;
  std::size_t bytes() const { return blocks_.size() * kBlock * 2 * sizeof(std::int16_t) + begins_.size() * sizeof(std::size_t); }
  std::size_t points_not_stored() const { return not_stored_; }
  void Clear() {
    blocks_ = {};
    begins_ = {};
    size_ = 0;
  }

 private:
  static constexpr std::size_t kBlock = 1 << 16;  // points
  std::size_t End(std::size_t scan) const { return scan + 1 < begins_.size() ? begins_[scan + 1] : size_; }
  std::vector<Point2> buffer_;  // the mapper writes each scan's returns here
  std::vector<std::vector<std::int16_t>> blocks_;  // x, y in mm, kBlock points each
  std::vector<std::size_t> begins_;  // each scan's first point
  std::size_t size_ = 0;
  std::size_t not_stored_ = 0;
};

// The map other than `own` whose centre is nearest to `robot` (-1: none).
template <class MapperType>
int NearestOtherMap(const MapperType& mapper, int own, const Pose2& robot) {
  int best = -1;
  float best_d = 0.0f;
  for (int r = 0; r < mapper.region_count(); ++r) {
    if (r == own) continue;
    const Point2 c = mapper.region_centre(r);
    const float d = std::hypot(c.x - robot.x, c.y - robot.y);
    if (best < 0 || d < best_d) {
      best = r;
      best_d = d;
    }
  }
  return best;
}

// Each recorded scan i in map region[i] gets in_region[i] replaced by its pose in that map as the
// map is now (see the file comment for those kept). Call at the end of the run, once the back end
// has done its work: it builds each map's reference in the mapper's storage.
template <class MapperType>
RefinementStats RefineTrajectory(MapperType& mapper, const ScanPointRecord& record, const std::vector<int>& region,
                                 std::vector<Pose2>* in_region, const RefinementConfig& config = RefinementConfig()) {
  const auto t0 = std::chrono::steady_clock::now();
  RefinementStats stats;
  stats.enabled = true;
  stats.stored_bytes = record.bytes();
  stats.points_not_stored = record.points_not_stored();
  const std::size_t n = record.scans() < region.size() ? record.scans() : region.size();
  std::size_t start = 0;
  while (start < n && record.points(start) == 0) ++start;
  // Each scan's reference: its own map and the other map whose centre is nearest to it (two maps,
  // as the run's own second registration uses). Sorted by that pair: one reference build each.
  const std::size_t maps = static_cast<std::size_t>(mapper.region_count());
  std::vector<std::pair<std::size_t, std::size_t>> jobs;  // (own * (maps + 1) + next, scan); next = maps: none
  for (std::size_t i = 0; i < n; ++i) {
    if (record.points(i) == 0) continue;
    ++stats.recorded;
    if (i == start || region[i] < 0 || static_cast<std::size_t>(region[i]) >= maps) continue;
    const int next = NearestOtherMap(mapper, region[i], mapper.region_anchor(region[i]) * (*in_region)[i]);
    jobs.emplace_back(static_cast<std::size_t>(region[i]) * (maps + 1) + (next >= 0 ? static_cast<std::size_t>(next) : maps), i);
  }
  std::stable_sort(jobs.begin(), jobs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Point2> points;
  bool built = false;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    const std::size_t key = jobs[k].first;
    if (k == 0 || key != jobs[k - 1].first) {
      const std::size_t own = key / (maps + 1), next = key % (maps + 1);
      built = mapper.BeginMapRegistration(static_cast<int>(own), next < maps ? static_cast<int>(next) : -1);
    }
    if (!built) continue;
    const std::size_t i = jobs[k].second;
    Pose2& pose = (*in_region)[i];
    record.Scan(i, &points);
    const RegistrationResult r = mapper.RegisterInMap(Span<const Point2>(points.data(), points.size()), pose, config.max_iterations);
    if (r.verdict != Status::kOk) {
      ++stats.refused;
    } else if (std::hypot(r.pose.x - pose.x, r.pose.y - pose.y) > config.max_move_m ||
               std::abs(NormalizeAngle(r.pose.theta - pose.theta)) > config.max_turn_rad) {
      ++stats.too_far;
    } else {
      pose = r.pose;
      ++stats.registered;
    }
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return stats;
}

}  // namespace dpcr::output
