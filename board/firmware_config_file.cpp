#include "board/firmware_config_file.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

namespace dpcr::board {
namespace {

using Json = nlohmann::json;

// One key's value, type-checked: "key: expected a number" etc.
struct Reader {
  const Json& j;
  std::string* error;
  bool ok = true;

  bool Fail(const std::string& key, const std::string& what) {
    if (ok) *error = key + ": " + what;
    ok = false;
    return false;
  }
  bool Number(const char* key, double* out) {
    if (!j.contains(key)) return false;
    if (!j[key].is_number()) return Fail(key, "expected a number, got " + j[key].dump());
    *out = j[key].get<double>();
    return true;
  }
  void Float(const char* key, float* out) {
    double v = 0.0;
    if (Number(key, &v)) *out = static_cast<float>(v);
  }
  void Int(const char* key, int* out) {
    double v = 0.0;
    if (!Number(key, &v)) return;
    if (v != std::floor(v) || std::fabs(v) > 2e9) {
      Fail(key, "expected a whole number, got " + j[key].dump());
      return;
    }
    *out = static_cast<int>(v);
  }
  bool String(const char* key, std::string* out) {
    if (!j.contains(key)) return false;
    if (!j[key].is_string()) return Fail(key, "expected a string, got " + j[key].dump());
    *out = j[key].get<std::string>();
    return true;
  }
};

// The keys of FILE (an object, every key known) into `j`; false with the reason in `error`.
bool ReadConfigObject(const std::string& path, Json* j, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = "cannot be read";
    return false;
  }
  try {
    *j = Json::parse(in);
  } catch (const Json::exception& e) {
    *error = std::string("not JSON: ") + e.what();
    return false;
  }
  if (!j->is_object()) {
    *error = "expected a JSON object";
    return false;
  }
  static const std::set<std::string> kKeys = {
      "uart", "baud", "lidar", "lidar_timing", "angle_sign", "max_range_m", "laser_offset_m", "can",
      "wheel_radius_m", "track_width_m", "ticks_per_rev", "max_accel_mps2", "heading", "profile", "map_dir", "autosave_s",
      "lidar_timeout_ms", "wheel_timeout_ms", "can_retry_ms", "status_period_s"};
  for (auto it = j->begin(); it != j->end(); ++it) {
    if (kKeys.count(it.key()) == 0) {
      *error = it.key() + ": unknown key";
      return false;
    }
  }
  if (!j->contains("ticks_per_rev")) {
    *error = "ticks_per_rev: required (the wheel encoders' ticks per wheel revolution)";
    return false;
  }
  return true;
}

// The lidar's keys: model, timing, direction, range, mount.
void ApplyLidarKeys(Reader& r, FirmwareConfig* c) {
  std::string text;
  if (r.String("lidar", &text)) {
    if (text == "ld06") {
      c->lidar = LidarKind::kLd06;
    } else if (text == "xv11") {
      c->lidar = LidarKind::kXv11;
      if (!r.j.contains("baud")) c->baud = 115200;
    } else {
      r.Fail("lidar", "\"" + text + "\" is not ld06 or xv11");
    }
  }
  if (r.String("lidar_timing", &text)) {
    if (text == "arrival") {
      c->lidar_timing = LidarTiming::kArrival;
    } else if (text == "device") {
      c->lidar_timing = LidarTiming::kDeviceClock;
    } else {
      r.Fail("lidar_timing", "\"" + text + "\" is not arrival or device");
    }
  }
  double sign = 0.0;
  if (r.Number("angle_sign", &sign)) {
    if (sign != 1.0 && sign != -1.0) r.Fail("angle_sign", "expected 1 or -1");
    c->angle_map.angle_sign = sign < 0.0 ? -1.0f : 1.0f;
  }
  r.Float("max_range_m", &c->max_range_m);
  r.Float("laser_offset_m", &c->laser_offset_m);
}

}  // namespace

bool LoadFirmwareConfigFile(const std::string& path, FirmwareConfig* c, std::string* error) {
  Json j;
  std::string local_error;
  if (!ReadConfigObject(path, &j, &local_error)) {
    *error = path + ": " + local_error;
    return false;
  }
  Reader r{j, &local_error};
  r.String("uart", &c->uart_device);
  r.Int("baud", &c->baud);
  ApplyLidarKeys(r, c);
  r.String("can", &c->can_interface);
  r.Float("wheel_radius_m", &c->wheels.wheel_radius_m);
  r.Float("track_width_m", &c->wheels.track_width_m);
  r.Float("ticks_per_rev", &c->wheels.ticks_per_rev);
  r.Float("max_accel_mps2", &c->max_accel_mps2);
  std::string text;
  if (r.String("heading", &text)) {
    if (!IsHeadingChoice(text)) r.Fail("heading", "\"" + text + "\" is not model, wheels or gyro");
    c->heading = text;
  }
  if (r.String("profile", &text) && text != "vacuum") {
    r.Fail("profile", "\"" + text + "\": this firmware is built for the vacuum profile");
  }
  r.String("map_dir", &c->map_dir);
  r.Int("autosave_s", &c->autosave_s);
  r.Int("lidar_timeout_ms", &c->lidar_timeout_ms);
  r.Int("wheel_timeout_ms", &c->wheel_timeout_ms);
  r.Int("can_retry_ms", &c->can_retry_ms);
  int status_s = c->status_period_ms / 1000;
  r.Int("status_period_s", &status_s);
  c->status_period_ms = status_s * 1000;
  if (!r.ok || !ValidateFirmwareConfig(*c, &local_error)) {
    *error = path + ": " + local_error;
    return false;
  }
  return true;
}

bool ValidateFirmwareConfig(const FirmwareConfig& c, std::string* error) {
  const auto in = [](float v, float lo, float hi) { return std::isfinite(v) && v >= lo && v <= hi; };
  if (c.uart_device.empty()) {
    *error = "uart: empty";
  } else if (c.baud != 115200 && c.baud != 230400) {
    *error = "baud: " + std::to_string(c.baud) + " (115200 for the XV-11, 230400 for the LD06)";
  } else if (c.can_interface.empty() && c.can_fd < 0) {
    *error = "can: empty";
  } else if (!(c.wheels.ticks_per_rev > 0.0f)) {
    *error = "ticks_per_rev: not stated (the wheel encoders' ticks per wheel revolution; dpcr-sim's device files: 4096)";
  } else if (!in(c.wheels.ticks_per_rev, 1.0f, 1e7f)) {
    *error = "ticks_per_rev: out of range (1 .. 1e7)";
  } else if (!in(c.wheels.wheel_radius_m, 0.005f, 0.5f)) {
    *error = "wheel_radius_m: out of range (0.005 .. 0.5 m)";
  } else if (!in(c.wheels.track_width_m, 0.05f, 2.0f)) {
    *error = "track_width_m: out of range (0.05 .. 2 m)";
  } else if (!in(c.max_range_m, 0.5f, 100.0f)) {
    *error = "max_range_m: out of range (0.5 .. 100 m)";
  } else if (!in(c.laser_offset_m, -1.0f, 1.0f)) {
    *error = "laser_offset_m: out of range (-1 .. 1 m)";
  } else if (!in(c.max_accel_mps2, 0.0f, 100.0f)) {
    *error = "max_accel_mps2: out of range (0 .. 100 m/s^2; 0: no limit)";
  } else if (!IsHeadingChoice(c.heading)) {
    *error = "heading: \"" + c.heading + "\" is not model, wheels or gyro";
  } else if (c.map_dir.empty()) {
    *error = "map_dir: empty";
  } else if (c.autosave_s < 0) {
    *error = "autosave_s: negative";
  } else if (c.lidar_timeout_ms <= 0) {
    *error = "lidar_timeout_ms: must be positive";
  } else if (c.wheel_timeout_ms <= 0) {
    *error = "wheel_timeout_ms: must be positive";
  } else if (c.can_retry_ms <= 0) {
    *error = "can_retry_ms: must be positive";
  } else if (c.status_period_ms <= 0) {
    *error = "status_period_s: must be positive";
  } else {
    return true;
  }
  return false;
}

}  // namespace dpcr::board
