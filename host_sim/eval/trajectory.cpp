#include "host_sim/eval/trajectory.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dpcr::eval {

namespace {

// `v` in fixed notation with `decimals` digits, then `tail`: the text printf's "%.Nf" gives (both
// round the exact binary value correctly), at a fraction of printf's cost (a long trajectory's
// file took ~1 % of a replay).
char* PutFixed(char* at, char* end, double v, int decimals, char tail) {
  const std::to_chars_result r = std::to_chars(at, end, v, std::chars_format::fixed, decimals);
  *r.ptr = tail;
  return r.ptr + 1;
}

}  // namespace

void WriteTum(std::ostream& out, const Trajectory& trajectory) {
  char buf[192];  // a finite float in fixed notation has at most 39 integer digits
  char* const end = buf + sizeof(buf);
  for (const StampedPose& p : trajectory) {
    const double half = 0.5 * static_cast<double>(p.pose.theta);
    char* at = buf;
    *at++ = ' ';
    at = PutFixed(at, end, static_cast<double>(p.pose.x), 6, ' ');
    at = PutFixed(at, end, static_cast<double>(p.pose.y), 6, ' ');
    for (const char c : {'0', ' ', '0', ' ', '0', ' '}) *at++ = c;
    at = PutFixed(at, end, std::sin(half), 9, ' ');
    at = PutFixed(at, end, std::cos(half), 9, '\n');
    out << FormatStamp(p.stamp_us);
    out.write(buf, at - buf);
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
