// dpcr-firmware: the mapper on a Linux vacuum SoC (lidar on a UART, wheel encoders on CAN).
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "board/firmware_config_file.hpp"
#include "board/firmware_loop.hpp"

namespace {

void Usage() {
  std::fprintf(stderr,
               "usage: dpcr-firmware [--config FILE] [--uart DEV] [--baud N] [--lidar ld06|xv11] [--can IFACE]\n"
               "                     [--map-dir DIR] [--autosave S] [--lidar-timeout-ms MS] [--wheel-timeout-ms MS]\n"
               "                     [--status-period S] [--angle-sign 1|-1] [--wheel-radius M] [--track-width M]\n"
               "                     --ticks-per-rev N (or ticks_per_rev in --config: required)\n"
               "                     [--max-range M] [--laser-offset M] [--heading model|wheels|gyro]\n"
               "                     [--max-accel A] (the robot's largest acceleration, m/s^2; 0: no limit)\n"
               "                     [--can-fd FD]   (an open fd carrying struct can_frame, for tests)\n"
               "                     [--lidar-timing arrival|device] (LD06: stamp packets by their own clock)\n"
               "                     [--trajectory FILE] (TUM, written at exit) [--record DIR] (received streams)\n"
               "--config FILE: the robot's parameters as JSON (board/firmware_config_file.hpp, docs/board.md);\n"
               "the command line overrides it.\n");
}

bool ParseDouble(const char* option, const char* text, double* out) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || errno == ERANGE || !std::isfinite(v)) {
    std::fprintf(stderr, "dpcr-firmware: error: %s: '%s' is not a number\n", option, text);
    return false;
  }
  *out = v;
  return true;
}

bool ParseInt(const char* option, const char* text, int* out) {
  double v = 0.0;
  if (!ParseDouble(option, text, &v)) return false;
  if (v != std::floor(v) || std::fabs(v) > 2e9) {
    std::fprintf(stderr, "dpcr-firmware: error: %s: '%s' is not a whole number\n", option, text);
    return false;
  }
  *out = static_cast<int>(v);
  return true;
}

bool ParseFloat(const char* option, const char* text, float* out) {
  double v = 0.0;
  if (!ParseDouble(option, text, &v)) return false;
  *out = static_cast<float>(v);
  return true;
}

// Choice options: false (with the error printed) for a value not among the choices.
bool ApplyChoice(const std::string& a, const char* v, dpcr::board::FirmwareConfig* c, bool* known) {
  *known = true;
  if (a == "--lidar") {
    if (std::strcmp(v, "ld06") == 0) {
      c->lidar = dpcr::LidarKind::kLd06;
    } else if (std::strcmp(v, "xv11") == 0) {
      c->lidar = dpcr::LidarKind::kXv11;
      if (c->baud == 230400) c->baud = 115200;
    } else {
      std::fprintf(stderr, "dpcr-firmware: error: unknown lidar '%s' (ld06, xv11)\n", v);
      return false;
    }
  } else if (a == "--lidar-timing") {
    if (std::strcmp(v, "arrival") != 0 && std::strcmp(v, "device") != 0) {
      std::fprintf(stderr, "dpcr-firmware: error: unknown lidar timing '%s' (arrival, device)\n", v);
      return false;
    }
    c->lidar_timing = std::strcmp(v, "device") == 0 ? dpcr::LidarTiming::kDeviceClock : dpcr::LidarTiming::kArrival;
  } else if (a == "--heading") {
    if (!dpcr::IsHeadingChoice(v)) {
      std::fprintf(stderr, "dpcr-firmware: error: unknown heading '%s' (model, wheels, gyro)\n", v);
      return false;
    }
    c->heading = v;
  } else if (a == "--angle-sign") {
    if (std::strcmp(v, "1") != 0 && std::strcmp(v, "-1") != 0) {
      std::fprintf(stderr, "dpcr-firmware: error: --angle-sign: '%s' (1 or -1)\n", v);
      return false;
    }
    c->angle_map.angle_sign = v[0] == '-' ? -1.0f : 1.0f;
  } else {
    *known = false;
  }
  return true;
}

// One option and its value; false (printed) for a bad value or an unknown option.
bool ApplyOption(const std::string& a, const char* v, dpcr::board::FirmwareConfig* c) {
  const char* o = a.c_str();
  bool known = false;
  if (!ApplyChoice(a, v, c, &known)) return false;
  if (known || a == "--config") return true;  // --config: read first
  if (a == "--uart") {
    c->uart_device = v;
  } else if (a == "--can") {
    c->can_interface = v;
  } else if (a == "--trajectory") {
    c->trajectory_path = v;
  } else if (a == "--record") {
    c->record_dir = v;
  } else if (a == "--map-dir") {
    c->map_dir = v;
  } else if (a == "--baud") {
    return ParseInt(o, v, &c->baud);
  } else if (a == "--can-fd") {
    return ParseInt(o, v, &c->can_fd);
  } else if (a == "--autosave") {
    return ParseInt(o, v, &c->autosave_s);
  } else if (a == "--lidar-timeout-ms") {
    return ParseInt(o, v, &c->lidar_timeout_ms);
  } else if (a == "--wheel-timeout-ms") {
    return ParseInt(o, v, &c->wheel_timeout_ms);
  } else if (a == "--status-period") {
    int status_s = 0;
    if (!ParseInt(o, v, &status_s)) return false;
    c->status_period_ms = status_s * 1000;
  } else if (a == "--wheel-radius") {
    return ParseFloat(o, v, &c->wheels.wheel_radius_m);
  } else if (a == "--track-width") {
    return ParseFloat(o, v, &c->wheels.track_width_m);
  } else if (a == "--ticks-per-rev") {
    return ParseFloat(o, v, &c->wheels.ticks_per_rev);
  } else if (a == "--max-range") {
    return ParseFloat(o, v, &c->max_range_m);
  } else if (a == "--laser-offset") {
    return ParseFloat(o, v, &c->laser_offset_m);
  } else if (a == "--max-accel") {
    return ParseFloat(o, v, &c->max_accel_mps2);
  } else {
    std::fprintf(stderr, "dpcr-firmware: error: unknown option %s\n", o);
    Usage();
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  dpcr::board::FirmwareConfig c;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "-h") == 0 || std::strcmp(argv[i], "--help") == 0) {
      Usage();
      return 0;
    }
  }
  // The file first, wherever --config stands: the command line overrides it.
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--config") != 0) continue;
    std::string error;
    if (!dpcr::board::LoadFirmwareConfigFile(argv[i + 1], &c, &error)) {
      std::fprintf(stderr, "dpcr-firmware: error: %s\n", error.c_str());
      return 1;
    }
  }
  for (int i = 1; i < argc; i += 2) {
    if (i + 1 >= argc) {
      std::fprintf(stderr, "dpcr-firmware: error: %s needs a value\n", argv[i]);
      Usage();
      return 1;
    }
    if (!ApplyOption(argv[i], argv[i + 1], &c)) return 1;
  }
  std::string error;
  if (!dpcr::board::ValidateFirmwareConfig(c, &error)) {
    std::fprintf(stderr, "dpcr-firmware: error: configuration: %s\n", error.c_str());
    return 1;
  }
  return dpcr::board::RunFirmware(c, stderr);
}
