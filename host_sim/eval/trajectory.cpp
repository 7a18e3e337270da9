#include "host_sim/eval/trajectory.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dpcr::eval {

void WriteTum(std::ostream& out, const Trajectory& trajectory) {
  char buf[160];
  for (const StampedPose& p : trajectory) {
    const double half = 0.5 * static_cast<double>(p.pose.theta);
    std::snprintf(buf, sizeof(buf), " %.6f %.6f 0 0 0 %.9f %.9f\n", static_cast<double>(p.pose.x),
                  static_cast<double>(p.pose.y), std::sin(half), std::cos(half));
    out << FormatStamp(p.stamp_us) << buf;
  }
}

Trajectory ReadTum(std::istream& in) {
  Trajectory out;
  ForEachDataLine(in, [&out](long line, const std::string& text) {
    std::istringstream s(text);
    std::string stamp;
    double x, y, z, qx, qy, qz, qw;
    if (!(s >> stamp >> x >> y >> z >> qx >> qy >> qz >> qw)) {
      throw std::runtime_error("line " + std::to_string(line) + ": expected 't x y z qx qy qz qw'");
    }
    StampedPose p;
    if (!ParseStamp(stamp, &p.stamp_us)) {
      throw std::runtime_error("line " + std::to_string(line) + ": bad timestamp '" + stamp + "'");
    }
    p.pose.x = static_cast<float>(x);
    p.pose.y = static_cast<float>(y);
    // Yaw of a quaternion; roll and pitch are ignored (a 2D trajectory has none).
    p.pose.theta = static_cast<float>(std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz)));
    out.push_back(p);
  });
  return out;
}

Trajectory ReadTumFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  try {
    return ReadTum(in);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace dpcr::eval
