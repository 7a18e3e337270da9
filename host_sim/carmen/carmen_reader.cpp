#include "host_sim/carmen/carmen_reader.hpp"

#include <cmath>
#include <sstream>

namespace dpcr::carmen {
namespace {

constexpr float kDegToRad = dpcr::kPi / 180.0f;

class Tokens {
 public:
  Tokens(const std::string& text, long line) : line_(line) {
    std::istringstream s(text);
    std::string t;
    while (s >> t) tokens_.push_back(t);
  }
  std::size_t size() const { return tokens_.size(); }
  std::size_t remaining() const { return tokens_.size() - next_; }
  const std::string& Word(const char* what) {
    if (next_ >= tokens_.size()) throw CarmenError(line_, std::string("line ends before ") + what);
    return tokens_[next_++];
  }
  double Number(const char* what) {
    const std::string& w = Word(what);
    try {
      std::size_t used = 0;
      const double v = std::stod(w, &used);
      if (used != w.size() || !std::isfinite(v)) throw std::invalid_argument(w);
      return v;
    } catch (const std::exception&) {
      throw CarmenError(line_, std::string("bad ") + what + " '" + w + "'");
    }
  }
  float Float(const char* what) { return static_cast<float>(Number(what)); }
  long Count(const char* what, long max) {
    const double v = Number(what);
    if (v < 0 || v > static_cast<double>(max) || v != std::floor(v)) {
      throw CarmenError(line_, std::string("bad ") + what + " " + tokens_[next_ - 1]);
    }
    return static_cast<long>(v);
  }
  std::int64_t Stamp(const char* what, std::string* text) {
    const std::string& w = Word(what);
    try {
      *text = w;
      return ParseStampMicros(w);
    } catch (const std::exception&) {
      throw CarmenError(line_, std::string("bad ") + what + " '" + w + "'");
    }
  }
  long line() const { return line_; }

 private:
  std::vector<std::string> tokens_;
  std::size_t next_ = 1;  // token 0 is the message name
  long line_;
};

dpcr::Pose2 ReadPose(Tokens& t, const char* what) {
  dpcr::Pose2 p;
  p.x = t.Float(what);
  p.y = t.Float(what);
  p.theta = dpcr::NormalizeAngle(t.Float(what));
  return p;
}

void ReadRanges(Tokens& t, LaserRecord* r) {
  const long n = t.Count("number of readings", 100000);
  if (n == 0) throw CarmenError(t.line(), "laser line with no readings");
  r->ranges_m.resize(static_cast<std::size_t>(n));
  for (float& range : r->ranges_m) range = t.Float("range reading");
}

// FLASER n r1..rn x y theta odom_x odom_y odom_theta ipc_timestamp hostname logger_timestamp
void ParseFlaser(Tokens& t, LaserRecord* r) {
  ReadRanges(t, r);
  const std::size_t n = r->ranges_m.size();
  // Beams span -90..+90 deg: 181/361 beams include both ends, 180/360 beams are 1/0.5 deg steps.
  const float step_deg = (n % 2 == 1) ? 180.0f / static_cast<float>(n - 1) : 180.0f / static_cast<float>(n);
  r->angle_min_rad = -90.0f * kDegToRad;
  r->angle_increment_rad = step_deg * kDegToRad;
  r->laser_pose = ReadPose(t, "laser pose");
  r->odom_pose = ReadPose(t, "odometry pose");
  r->stamp_us = t.Stamp("ipc_timestamp", &r->stamp_text);
  t.Word("hostname");
  t.Number("logger_timestamp");
}

// ROBOTLASER1 type start_angle fov resolution max_range accuracy remission_mode n r1..rn
//   m v1..vm laser_x laser_y laser_theta robot_x robot_y robot_theta tv rv forward_safety
//   side_safety turn_axis ipc_timestamp hostname logger_timestamp
void ParseRobotLaser(Tokens& t, LaserRecord* r) {
  t.Number("laser type");
  r->angle_min_rad = t.Float("start angle");
  t.Number("field of view");
  r->angle_increment_rad = t.Float("angular resolution");
  r->max_range_m = t.Float("maximum range");
  t.Number("accuracy");
  t.Number("remission mode");
  ReadRanges(t, r);
  const long m = t.Count("number of remissions", 100000);
  for (long i = 0; i < m; ++i) t.Number("remission");
  r->laser_pose = ReadPose(t, "laser pose");
  r->odom_pose = ReadPose(t, "robot pose");
  for (const char* what : {"tv", "rv", "forward safety distance", "side safety distance", "turn axis"}) t.Number(what);
  r->stamp_us = t.Stamp("ipc_timestamp", &r->stamp_text);
  t.Word("hostname");
  t.Number("logger_timestamp");
}

}  // namespace

CarmenError::CarmenError(long line, const std::string& reason)
    : std::runtime_error("line " + std::to_string(line) + ": " + reason), line_(line) {}

std::int64_t ParseStampMicros(const std::string& text) {
  const std::size_t dot = text.find('.');
  const std::string whole = text.substr(0, dot);
  std::string frac = dot == std::string::npos ? "" : text.substr(dot + 1);
  if (whole.empty() || whole.find_first_not_of("0123456789") != std::string::npos ||
      frac.find_first_not_of("0123456789") != std::string::npos || frac.size() > 9) {
    throw std::invalid_argument("not a timestamp: " + text);
  }
  // Round to the microsecond (logs give 6 decimals; more are tolerated).
  while (frac.size() < 7) frac += '0';
  std::int64_t micros = std::stoll(frac.substr(0, 6));
  if (frac[6] >= '5') ++micros;
  return std::stoll(whole) * 1000000 + micros;
}

bool CarmenReader::Next(Record* out) {
  std::string text;
  while (std::getline(in_, text)) {
    const long line = ++counters_.lines;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    const std::size_t first = text.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    if (text[first] == '#') {
      ++counters_.comments;
      continue;
    }
    Tokens t(text, line);
    std::istringstream head(text);
    std::string kind;
    head >> kind;
    if (kind == "FLASER" || kind == "ROBOTLASER1") {
      out->kind = Record::Kind::kLaser;
      out->laser = LaserRecord{};
      out->laser.line = line;
      if (kind == "FLASER") {
        ParseFlaser(t, &out->laser);
      } else {
        ParseRobotLaser(t, &out->laser);
      }
      if (out->laser.stamp_us < last_laser_stamp_us_) ++counters_.laser_steps_back;
      last_laser_stamp_us_ = out->laser.stamp_us;
      ++counters_.laser_records;
      return true;
    }
    if (kind == "ODOM") {
      // ODOM x y theta tv rv accel ipc_timestamp hostname logger_timestamp
      out->kind = Record::Kind::kOdom;
      out->odom = OdomRecord{};
      out->odom.line = line;
      out->odom.pose = ReadPose(t, "odometry pose");
      for (const char* what : {"tv", "rv", "accel"}) t.Number(what);
      std::string stamp_text;
      out->odom.stamp_us = t.Stamp("ipc_timestamp", &stamp_text);
      ++counters_.odom_records;
      return true;
    }
    if (kind == "PARAM") {
      const std::string& name = t.Word("parameter name");
      if (name == "robot_frontlaser_offset") front_laser_offset_m_ = t.Float("laser offset");
      continue;
    }
    if (kind.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") != std::string::npos) {
      throw CarmenError(line, "not a CARMEN message: '" + kind + "'");
    }
    ++counters_.other_messages;
  }
  if (in_.bad()) throw CarmenError(counters_.lines, "read error");
  return false;
}

}  // namespace dpcr::carmen
