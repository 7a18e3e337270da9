#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <memory>
#include <pty.h>
#include <sstream>
#include <string>
#include <sys/socket.h>
#include <termios.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "board/firmware_loop.hpp"
#include "board/socketcan_port.hpp"
#include "core/capacity.hpp"
#include "core/geometry/pose2.hpp"
#include "hal/ld06_emitter.hpp"
#include "hal/wheel_can_protocol.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

std::string ReadLog(std::FILE* log) {
  std::fflush(log);
  std::rewind(log);
  std::string s;
  char buf[512];
  while (std::fgets(buf, sizeof(buf), log) != nullptr) s += buf;
  return s;
}

std::string Slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

struct Pty {
  int master = -1;
  int slave = -1;
  std::string name;
  Pty() {
    termios raw{};
    cfmakeraw(&raw);
    char path[128];
    REQUIRE(::openpty(&master, &slave, path, &raw, nullptr) == 0);
    name = path;
  }
  ~Pty() {
    ::close(master);
    ::close(slave);
  }
};

// A stationary robot in a 4 m x 4 m room: one LD06 revolution of 450 beams, clockwise.
void MakeRoomScan(dpcr::Scan<dpcr::VacuumProfile::kMaxBeams>* scan) {
  scan->beams.clear();
  scan->stamp_us = 0;
  const int n = 450;
  for (int i = 0; i < n; ++i) {
    const float deg = 360.0f * static_cast<float>(i) / static_cast<float>(n);
    dpcr::Beam b;
    b.angle_rad = dpcr::NormalizeAngle(-deg * dpcr::kPi / 180.0f);
    b.range_m = 2.0f / std::fmax(std::fabs(std::cos(b.angle_rad)), std::fabs(std::sin(b.angle_rad)));
    b.offset_us = static_cast<std::int32_t>(100000 * i / n);
    REQUIRE(scan->beams.push_back(b) == dpcr::Status::kOk);
  }
}

}  // namespace

TEST_CASE("firmware: a missing serial device is named with the errno reason, exit 1") {
  dpcr::board::FirmwareConfig c;
  c.uart_device = "/dev/dpcr-no-such-tty";
  std::FILE* log = std::tmpfile();
  REQUIRE(log != nullptr);
  CHECK(dpcr::board::RunFirmware(c, log) == 1);
  const std::string text = ReadLog(log);
  CHECK(text.find("/dev/dpcr-no-such-tty") != std::string::npos);
  CHECK(text.find("No such file or directory") != std::string::npos);
  std::fclose(log);
}

TEST_CASE("firmware: a missing CAN interface is named, exit 1") {
  Pty pty;
  dpcr::board::FirmwareConfig c;
  c.uart_device = pty.name;
  c.can_interface = "dpcrcan7";
  std::FILE* log = std::tmpfile();
  CHECK(dpcr::board::RunFirmware(c, log) == 1);
  const std::string text = ReadLog(log);
  CHECK(text.find("CAN dpcrcan7") != std::string::npos);
  std::fclose(log);
}

TEST_CASE("firmware: a silent lidar is reported as a timeout, exit 2") {
  Pty pty;
  int sv[2];
  REQUIRE(::socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv) == 0);
  dpcr::board::FirmwareConfig c;
  c.uart_device = pty.name;
  c.can_fd = sv[1];
  c.lidar_timeout_ms = 300;
  const dpcr::test::ScopedTempDir map_dir("firmware_timeout");  // the exit path saves a map
  c.map_dir = map_dir.str();
  std::FILE* log = std::tmpfile();
  const auto start = std::chrono::steady_clock::now();
  CHECK(dpcr::board::RunFirmware(c, log) == 2);
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(5));
  const std::string text = ReadLog(log);
  CHECK(text.find("lidar timeout") != std::string::npos);
  CHECK(text.find(pty.name) != std::string::npos);
  std::fclose(log);
  ::close(sv[0]);
  ::close(sv[1]);
}

TEST_CASE("firmware: pty lidar + socketpair CAN, SIGTERM saves a loadable map") {
  Pty pty;
  int sv[2];
  REQUIRE(::socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv) == 0);
  const dpcr::test::ScopedTempDir map_dir("firmware_map");
  const std::string dir = map_dir.str();
  dpcr::board::FirmwareConfig c;
  c.uart_device = pty.name;
  c.can_fd = sv[1];
  c.map_dir = dir;
  c.autosave_s = 0;
  c.status_period_ms = 200;

  std::atomic<bool> stop{false};
  std::atomic<int> revolutions{0};
  std::thread feeder([&] {
    auto scan = std::make_unique<dpcr::Scan<dpcr::VacuumProfile::kMaxBeams>>();
    MakeRoomScan(scan.get());
    std::uint8_t seq = 0;
    std::uint32_t t10 = 0;
    while (!stop.load()) {
      // One revolution: 38 packets over ~100 ms, with wheel frames every ~10 ms.
      int packet = 0;
      dpcr::EmitLd06Revolution(*scan, dpcr::LidarAngleMap{}, [&](const dpcr::Ld06EmittedPacket& p) {
        std::size_t done = 0;
        while (done < sizeof(p.bytes)) {
          const ssize_t n = ::write(pty.master, p.bytes + done, sizeof(p.bytes) - done);
          if (n > 0) done += static_cast<std::size_t>(n);
        }
        if (++packet % 4 == 0) {
          dpcr::WheelTicksFrame w;
          w.sequence = seq++;
          w.time_10us = (t10 += 1000);
          static_cast<void>(dpcr::board::WriteCanFrame(sv[0], dpcr::EncodeWheelFrame(w)));
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
      });
      ++revolutions;
      if (revolutions.load() == 25) ::kill(::getpid(), SIGTERM);
    }
  });
  std::FILE* log = std::tmpfile();
  const int code = dpcr::board::RunFirmware(c, log);
  stop = true;
  feeder.join();
  const std::string text = ReadLog(log);
  INFO(text);
  CHECK(code == 0);
  CHECK(text.find("signal received") != std::string::npos);
  CHECK(text.find("scan_rate=") != std::string::npos);
  CHECK(text.find("map saved") != std::string::npos);

  // map_server-loadable: P5 header, size matches, YAML names the image.
  const std::string pgm = Slurp(dir + "/map.pgm");
  REQUIRE(pgm.size() > 20);
  CHECK(pgm.compare(0, 3, "P5\n") == 0);
  int w = 0;
  int h = 0;
  int maxval = 0;
  int header = 0;
  REQUIRE(std::sscanf(pgm.c_str(), "P5\n%d %d\n%d\n%n", &w, &h, &maxval, &header) == 3);
  CHECK(maxval == 255);
  REQUIRE(pgm.size() == static_cast<std::size_t>(header) + static_cast<std::size_t>(w * h));
  // The 4 m room at 5 cm: at least 80 cells across, walls occupied, inside free.
  CHECK(w >= 78);
  CHECK(w <= 160);  // bounds are tile-aligned
  std::size_t occupied = 0;
  std::size_t free_cells = 0;
  for (std::size_t i = static_cast<std::size_t>(header); i < pgm.size(); ++i) {
    occupied += static_cast<unsigned char>(pgm[i]) == 0 ? 1 : 0;
    free_cells += static_cast<unsigned char>(pgm[i]) == 254 ? 1 : 0;
  }
  CHECK(occupied > 200);
  CHECK(free_cells > 3000);
  const std::string yaml = Slurp(dir + "/map.yaml");
  CHECK(yaml.find("image: map.pgm") != std::string::npos);
  CHECK(yaml.find("resolution: 0.05") != std::string::npos);
  std::fclose(log);
  ::close(sv[0]);
  ::close(sv[1]);
}
