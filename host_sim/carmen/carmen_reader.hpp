// Reads CARMEN logs (the Freiburg/Radish public 2D lidar benchmarks): FLASER, ROBOTLASER1 and
// ODOM lines, PARAM robot_frontlaser_offset. Lines are returned in file order: the file order is
// the physical one (intel.clf steps back in time 631 times), so nothing is sorted.
// Malformed lines raise CarmenError with the line number and the reason.
#pragma once

#include <cstdint>
#include <istream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/geometry/pose2.hpp"

namespace dpcr::carmen {

class CarmenError : public std::runtime_error {
 public:
  CarmenError(long line, const std::string& reason);
  long line() const { return line_; }

 private:
  long line_;
};

struct LaserRecord {
  long line = 0;
  std::int64_t stamp_us = 0;       // ipc_timestamp, to the microsecond (relations use it)
  float angle_min_rad = 0.0f;
  float angle_increment_rad = 0.0f;
  float max_range_m = 0.0f;        // 0 when the line does not say
  std::vector<float> ranges_m;
  dpcr::Pose2 laser_pose;          // the pose fields as logged (laser or robot pose, see offset)
  dpcr::Pose2 odom_pose;           // robot odometry pose as logged
};

struct OdomRecord {
  long line = 0;
  std::int64_t stamp_us = 0;
  dpcr::Pose2 pose;
};

struct Record {
  enum class Kind { kLaser, kOdom } kind = Kind::kLaser;
  LaserRecord laser;
  OdomRecord odom;
};

struct ReaderCounters {
  long lines = 0;
  long comments = 0;
  long other_messages = 0;   // message types we do not use (SYNC, RLASER, TRUEPOS...)
  long laser_records = 0;
  long odom_records = 0;
  long laser_steps_back = 0;  // laser stamps earlier than the previous laser stamp
};

class CarmenReader {
 public:
  explicit CarmenReader(std::istream& in) : in_(in) {}

  // The next laser or odometry record; false at end of file. Throws CarmenError.
  bool Next(Record* out);

  const ReaderCounters& counters() const { return counters_; }
  // PARAM robot_frontlaser_offset (m along the robot's x axis), if the log gave one.
  float front_laser_offset_m() const { return front_laser_offset_m_; }

 private:
  std::istream& in_;
  ReaderCounters counters_;
  float front_laser_offset_m_ = 0.0f;
  std::int64_t last_laser_stamp_us_ = INT64_MIN;
  // Reused from line to line (parsing allocates nothing once it has grown).
  std::string line_;
};

// A whole word as a finite decimal number: the double strtod gives; false on anything else.
bool ParseNumber(std::string_view text, double* value);

}  // namespace dpcr::carmen
