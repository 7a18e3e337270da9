// dpcr-firmware: the mapper on a Linux vacuum SoC (lidar on a UART, wheel encoders on CAN).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "board/firmware_loop.hpp"

namespace {

void Usage() {
  std::fprintf(stderr,
               "usage: dpcr-firmware [--uart DEV] [--baud N] [--lidar ld06|xv11] [--can IFACE]\n"
               "                     [--map-dir DIR] [--autosave S] [--lidar-timeout-ms MS]\n"
               "                     [--angle-sign 1|-1] [--wheel-radius M] [--track-width M] [--ticks-per-rev N]\n"
               "                     [--max-range M] [--laser-offset M]   (defaults: hal/device_options.hpp)\n"
               "                     [--can-fd FD]   (an open fd carrying struct can_frame, for tests)\n"
               "                     [--lidar-timing arrival|device] (LD06: stamp packets by their own clock)\n"
               "                     [--trajectory FILE] (TUM, written at exit) [--record DIR] (received streams)\n");
}

}  // namespace

int main(int argc, char** argv) {
  dpcr::board::FirmwareConfig c;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      Usage();
      return 0;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "dpcr-firmware: error: %s needs a value\n", a.c_str());
      Usage();
      return 1;
    }
    const char* v = argv[++i];
    if (a == "--uart") {
      c.uart_device = v;
    } else if (a == "--baud") {
      c.baud = std::atoi(v);
    } else if (a == "--lidar") {
      if (std::strcmp(v, "ld06") == 0) {
        c.lidar = dpcr::LidarKind::kLd06;
      } else if (std::strcmp(v, "xv11") == 0) {
        c.lidar = dpcr::LidarKind::kXv11;
        if (c.baud == 230400) c.baud = 115200;
      } else {
        std::fprintf(stderr, "dpcr-firmware: error: unknown lidar '%s' (ld06, xv11)\n", v);
        return 1;
      }
    } else if (a == "--can") {
      c.can_interface = v;
    } else if (a == "--can-fd") {
      c.can_fd = std::atoi(v);
    } else if (a == "--lidar-timing") {
      if (std::strcmp(v, "arrival") == 0) {
        c.lidar_timing = dpcr::LidarTiming::kArrival;
      } else if (std::strcmp(v, "device") == 0) {
        c.lidar_timing = dpcr::LidarTiming::kDeviceClock;
      } else {
        std::fprintf(stderr, "dpcr-firmware: error: unknown lidar timing '%s' (arrival, device)\n", v);
        return 1;
      }
    } else if (a == "--trajectory") {
      c.trajectory_path = v;
    } else if (a == "--record") {
      c.record_dir = v;
    } else if (a == "--map-dir") {
      c.map_dir = v;
    } else if (a == "--autosave") {
      c.autosave_s = std::atoi(v);
    } else if (a == "--lidar-timeout-ms") {
      c.lidar_timeout_ms = std::atoi(v);
    } else if (a == "--angle-sign") {
      c.angle_map.angle_sign = std::atoi(v) < 0 ? -1.0f : 1.0f;
    } else if (a == "--wheel-radius") {
      c.wheels.wheel_radius_m = std::strtof(v, nullptr);
    } else if (a == "--track-width") {
      c.wheels.track_width_m = std::strtof(v, nullptr);
    } else if (a == "--ticks-per-rev") {
      c.wheels.ticks_per_rev = std::strtof(v, nullptr);
    } else if (a == "--max-range") {
      c.max_range_m = std::strtof(v, nullptr);
    } else if (a == "--laser-offset") {
      c.laser_offset_m = std::strtof(v, nullptr);
    } else {
      std::fprintf(stderr, "dpcr-firmware: error: unknown option %s\n", a.c_str());
      Usage();
      return 1;
    }
  }
  return dpcr::board::RunFirmware(c, stderr);
}
