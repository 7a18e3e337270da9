#include "host_sim/carmen/carmen_reader.hpp"

#include <charconv>
#include <cstdint>
#include <cmath>
#include <limits>
#include <system_error>

#include "host_sim/eval/stamp_text.hpp"

namespace dpcr::carmen {
namespace {

constexpr float kDegToRad = dpcr::kPi / 180.0f;

// ' ', or one of '\t' '\n' '\v' '\f' '\r' (9-13, contiguous): isspace in the "C" locale. A word's
// characters (digits, letters, '.', '-') lie above ' ': one comparison rules them out.
bool IsSpace(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u <= ' ' && (u == ' ' || static_cast<unsigned char>(u - '\t') <= static_cast<unsigned char>('\r' - '\t'));
}

bool IsDigit(char c) { return static_cast<unsigned char>(c - '0') <= 9u; }

// A range in metres to the centimetre with one or two whole digits ("1.23", "12.34"): nine words in
// ten of a laser log. Read at once: where the word ends and its value in centimetres, or nullptr.
const char* ReadCentimetres(const char* p, const char* last, std::uint64_t* centimetres) {
  if (last - p < 4 || !IsDigit(p[0])) return nullptr;
  std::uint64_t whole = static_cast<unsigned char>(p[0] - '0');
  const char* q = p + 1;
  if (IsDigit(*q)) whole = whole * 10u + static_cast<unsigned char>(*q++ - '0');
  if (last - q < 3 || q[0] != '.' || !IsDigit(q[1]) || !IsDigit(q[2])) return nullptr;
  if (q + 3 < last && !IsSpace(q[3])) return nullptr;
  *centimetres = whole * 100u + static_cast<unsigned char>(q[1] - '0') * 10u + static_cast<unsigned char>(q[2] - '0');
  return q + 3;
}

// Clinger's fast path: a plain decimal of at most 15 digits ("1.23", "-0.004", "17") is an exact
// integer over an exact power of ten, and one IEEE division rounds the quotient correctly: the
// double strtod and from_chars give, at a fraction of their cost (parsing was ~10 % of a replay).
// Read from `p` up to the next space or `last`: where the word ends, or nullptr when it is not such
// a decimal (the caller then parses the whole word). Parsed as it is read: one pass over a line.
const char* ReadShortDecimal(const char* p, const char* last, double* value) {
  const bool negative = p < last && *p == '-';
  if (p < last && (*p == '-' || *p == '+')) ++p;
  static constexpr double kPow10[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  std::uint64_t mantissa = 0;
  if (const char* const end = ReadCentimetres(p, last, &mantissa)) {  // the same division as below
    const double v = static_cast<double>(mantissa) / kPow10[2];
    *value = negative ? -v : v;
    return end;
  }
  const char* const first_digit = p;
  const char* point = nullptr;
  for (; p < last; ++p) {
    const unsigned digit = static_cast<unsigned char>(*p - '0');
    if (digit <= 9u) {
      mantissa = mantissa * 10u + digit;
    } else if (*p == '.' && point == nullptr) {
      point = p;
    } else if (IsSpace(*p)) {
      break;
    } else {
      return nullptr;
    }
  }
  // Every character is a digit but the point; more than 15 digits could overflow the mantissa
  // (it stops being exact past 2^53 anyway).
  const long digits = (p - first_digit) - (point != nullptr ? 1 : 0);
  if (digits == 0 || digits > 15) return nullptr;
  const long decimals = point != nullptr ? p - point - 1 : 0;
  const double v = static_cast<double>(mantissa) / kPow10[decimals];
  *value = negative ? -v : v;
  return p;
}

// The whitespace-separated words of one line, read in order as views into it (no copies).
class Tokens {
 public:
  Tokens(const std::string& text, long line) : p_(text.data()), end_(text.data() + text.size()), line_(line) {
    kind_ = NextWord();
  }
  std::string_view Kind() const { return kind_; }
  std::string_view Word(const char* what) {
    const std::string_view w = NextWord();
    if (w.empty()) throw CarmenError(line_, std::string("line ends before ") + what);
    last_ = w;
    return w;
  }
  // The line must end here: words left over mean its count or its fields were wrong (read on,
  // readings would have been taken for the pose and the time stamp).
  void End(const char* last_field) {
    std::size_t left = 0;
    while (!NextWord().empty()) ++left;
    if (left > 0) {
      throw CarmenError(line_, std::to_string(left) + " more words after the " + last_field +
                                   " (a wrong number of readings?)");
    }
  }
  // The whole word as a finite decimal number (correctly rounded, as strtod).
  double Number(const char* what) {
    SkipSpaces();
    double v = 0.0;
    const char* const word = p_;
    if (const char* const stop = ReadShortDecimal(word, end_, &v)) {  // the usual case, in one pass
      last_ = std::string_view(word, static_cast<std::size_t>(stop - word));
      p_ = stop;
      return v;
    }
    const std::string_view w = Word(what);
    if (!ParseNumber(w, &v)) throw CarmenError(line_, std::string("bad ") + what + " '" + std::string(w) + "'");
    return v;
  }
  // A number that must also fit a float: a finite double past FLT_MAX would become infinite.
  float Float(const char* what) {
    const double v = Number(what);
    if (std::fabs(v) > static_cast<double>(std::numeric_limits<float>::max())) {
      throw CarmenError(line_, std::string("bad ") + what + " '" + std::string(last_) + "': out of range");
    }
    return static_cast<float>(v);
  }
  long Count(const char* what, long max) {
    const double v = Number(what);
    if (v < 0 || v > static_cast<double>(max) || v != std::floor(v)) {
      throw CarmenError(line_, std::string("bad ") + what + " " + std::string(last_));
    }
    return static_cast<long>(v);
  }
  std::int64_t Stamp(const char* what) {
    const std::string_view w = Word(what);
    std::int64_t micros = 0;
    if (!dpcr::eval::ParseStamp(w, &micros)) throw CarmenError(line_, std::string("bad ") + what + " '" + std::string(w) + "'");
    return micros;
  }
  long line() const { return line_; }

 private:
  void SkipSpaces() {
    while (p_ < end_ && IsSpace(*p_)) ++p_;
  }
  // The next word; empty at the line's end.
  std::string_view NextWord() {
    SkipSpaces();
    const char* const word = p_;
    while (p_ < end_ && !IsSpace(*p_)) ++p_;
    return std::string_view(word, static_cast<std::size_t>(p_ - word));
  }
  const char* p_;
  const char* const end_;
  long line_;
  std::string_view kind_;  // the first word: the message name
  std::string_view last_;  // the last word read, for messages
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
  // One beam cannot span -90..+90 deg (its step would be 180 / 0).
  if (n < 2) throw CarmenError(t.line(), "FLASER line with one reading");
  // Beams span -90..+90 deg: 181/361 beams include both ends, 180/360 beams are 1/0.5 deg steps.
  const float step_deg = (n % 2 == 1) ? 180.0f / static_cast<float>(n - 1) : 180.0f / static_cast<float>(n);
  r->angle_min_rad = -90.0f * kDegToRad;
  r->angle_increment_rad = step_deg * kDegToRad;
  r->laser_pose = ReadPose(t, "laser pose");
  r->odom_pose = ReadPose(t, "odometry pose");
  r->stamp_us = t.Stamp("ipc_timestamp");
  t.Word("hostname");
  t.Number("logger_timestamp");
  t.End("logger_timestamp");
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
  r->stamp_us = t.Stamp("ipc_timestamp");
  t.Word("hostname");
  t.Number("logger_timestamp");
}

}  // namespace

CarmenError::CarmenError(long line, const std::string& reason)
    : std::runtime_error("line " + std::to_string(line) + ": " + reason), line_(line) {}

bool CarmenReader::Next(Record* out) {
  std::string& text = line_;  // reused: no allocation per line once it has grown
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
    const std::string_view kind = t.Kind();
    if (kind == "FLASER" || kind == "ROBOTLASER1") {
      out->kind = Record::Kind::kLaser;
      // Field by field, so that ranges_m keeps its capacity from record to record.
      LaserRecord& laser = out->laser;
      laser.line = line;
      laser.max_range_m = 0.0f;
      if (kind == "FLASER") {
        ParseFlaser(t, &laser);
      } else {
        ParseRobotLaser(t, &laser);
      }
      if (laser.stamp_us < last_laser_stamp_us_) ++counters_.laser_steps_back;
      last_laser_stamp_us_ = laser.stamp_us;
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
      out->odom.stamp_us = t.Stamp("ipc_timestamp");
      // The rest, so that a line cut short (inside its time stamp, say) is not taken for whole.
      t.Word("hostname");
      t.Number("logger_timestamp");
      t.End("logger_timestamp");
      ++counters_.odom_records;
      return true;
    }
    if (kind == "PARAM") {
      const std::string_view name = t.Word("parameter name");
      if (name == "robot_frontlaser_offset") front_laser_offset_m_ = t.Float("laser offset");
      continue;
    }
    if (kind.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") != std::string_view::npos) {
      throw CarmenError(line, "not a CARMEN message: '" + std::string(kind) + "'");
    }
    ++counters_.other_messages;
  }
  if (in_.bad()) throw CarmenError(counters_.lines, "read error");
  return false;
}

bool ParseNumber(std::string_view text, double* value) {
  const char* first = text.data();
  const char* const last = first + text.size();
  if (ReadShortDecimal(first, last, value) == last) return true;
  if (first < last && *first == '+') ++first;  // strtod's optional sign, which from_chars lacks
  double v = 0.0;
  const std::from_chars_result r = std::from_chars(first, last, v);
  if (r.ec != std::errc() || r.ptr != last || !std::isfinite(v)) return false;
  *value = v;
  return true;
}

}  // namespace dpcr::carmen
