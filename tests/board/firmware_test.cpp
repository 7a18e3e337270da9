// dpcr-firmware on the board's own ports (termios on a pty, SocketCAN, systemd's notify socket)
// and its configuration file. The loop itself is tested on fake ports: firmware_loop_test.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <pty.h>
#include <string>
#include <sys/socket.h>
#include <sys/un.h>
#include <termios.h>
#include <unistd.h>
#include <vector>

#include "board/firmware_config_file.hpp"
#include "board/firmware_loop.hpp"
#include "board/systemd_notifier.hpp"
#include "board/unique_fd.hpp"
#include "tests/board/read_log.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using dpcr::test::ReadLog;

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

// A service manager's notify socket in a temporary directory, named by $NOTIFY_SOCKET (and the
// watchdog period by $WATCHDOG_USEC) while it exists.
struct FakeNotifySocket {
  explicit FakeNotifySocket(const std::string& dir, long watchdog_us) : path(dir + "/notify") {
    fd.Reset(::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    REQUIRE(path.size() < sizeof(addr.sun_path));
    std::snprintf(addr.sun_path, sizeof(addr.sun_path), "%s", path.c_str());
    REQUIRE(::bind(fd.get(), reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0);
    ::setenv("NOTIFY_SOCKET", path.c_str(), 1);
    if (watchdog_us > 0) ::setenv("WATCHDOG_USEC", std::to_string(watchdog_us).c_str(), 1);
  }
  ~FakeNotifySocket() {
    ::unsetenv("NOTIFY_SOCKET");
    ::unsetenv("WATCHDOG_USEC");
  }
  std::vector<std::string> Messages() {
    std::vector<std::string> out;
    char buf[256];
    for (;;) {
      const ssize_t n = ::recv(fd.get(), buf, sizeof(buf), 0);
      if (n < 0) return out;
      out.emplace_back(buf, static_cast<std::size_t>(n));
    }
  }
  std::string path;
  dpcr::board::UniqueFd fd;
};

dpcr::board::FirmwareConfig BoardConfig() {
  dpcr::board::FirmwareConfig c;
  c.wheels.ticks_per_rev = 4096.0f;
  return c;
}

}  // namespace

TEST_CASE("firmware: a missing serial device is named with its errno, exit 1") {
  dpcr::board::FirmwareConfig c = BoardConfig();
  c.uart_device = "/dev/dpcr-no-such-tty";
  const dpcr::test::ScopedTempDir map_dir("firmware_no_tty");
  c.map_dir = map_dir.str();
  std::FILE* log = std::tmpfile();
  REQUIRE(log != nullptr);
  CHECK(dpcr::board::RunFirmware(c, log) == 1);
  const std::string text = ReadLog(log);
  INFO(text);
  CHECK(text.find("/dev/dpcr-no-such-tty") != std::string::npos);
  CHECK(text.find("No such file or directory") != std::string::npos);
  std::fclose(log);
}

TEST_CASE("firmware: no CAN interface -> the lidar alone, said once, systemd hears ready, watchdog kicks, stopping") {
  Pty pty;
  const dpcr::test::ScopedTempDir dir("firmware_no_can");
  FakeNotifySocket notify(dir.str(), 100000);  // kicks every 50 ms: the socket queues 10 datagrams
  dpcr::board::FirmwareConfig c = BoardConfig();
  c.uart_device = pty.name;
  c.can_interface = "dpcrcan7";
  c.map_dir = dir.str();
  c.lidar_timeout_ms = 300;  // the pty stays silent: the run ends by the lidar timeout
  std::FILE* log = std::tmpfile();
  CHECK(dpcr::board::RunFirmware(c, log) == 2);
  const std::string text = ReadLog(log);
  INFO(text);
  // "no such CAN interface: ENODEV" on a board, "socket(PF_CAN): EAFNOSUPPORT" on a kernel without CAN.
  CHECK(text.find("warning: CAN dpcrcan7 unavailable (dpcrcan7: ") != std::string::npos);
  CHECK(text.find("mapping from the lidar alone") != std::string::npos);
  CHECK(text.find("running: lidar on " + pty.name) != std::string::npos);
  CHECK(text.find("lidar timeout") != std::string::npos);
  std::fclose(log);
  const std::vector<std::string> messages = notify.Messages();
  std::string all;
  for (const std::string& m : messages) all += "[" + m + "] ";
  INFO(all);
  REQUIRE(messages.size() >= 3);
  CHECK(messages.front().rfind("READY=1", 0) == 0);
  CHECK(messages.back().rfind("STOPPING=1", 0) == 0);
  // 300 ms of loop with a 100 ms watchdog: a kick every 50 ms.
  const auto kicks = std::count(messages.begin(), messages.end(), std::string("WATCHDOG=1"));
  CHECK(kicks >= 5);
}

TEST_CASE("systemd notifier: disabled without NOTIFY_SOCKET, abstract and path sockets, WATCHDOG_PID of another process") {
  ::unsetenv("NOTIFY_SOCKET");
  CHECK_FALSE(dpcr::board::SystemdNotifier().enabled());
  const dpcr::test::ScopedTempDir dir("notifier");
  FakeNotifySocket notify(dir.str(), 2000000);
  {
    dpcr::board::SystemdNotifier n;
    REQUIRE(n.enabled());
    CHECK(n.watchdog_period_us() == 2000000);
    n.Ready();
    n.Alive();
    n.Stopping();
    const std::vector<std::string> m = notify.Messages();
    REQUIRE(m.size() == 3);
    CHECK(m[0] == "READY=1\nSTATUS=mapping");
    CHECK(m[1] == "WATCHDOG=1");
    CHECK(m[2].rfind("STOPPING=1", 0) == 0);
  }
  ::setenv("WATCHDOG_PID", "1", 1);  // the watchdog is someone else's
  CHECK(dpcr::board::SystemdNotifier().watchdog_period_us() == 0);
  ::unsetenv("WATCHDOG_PID");
}

TEST_CASE("firmware config file: the robot's parameters, every mistake one line naming the key") {
  const dpcr::test::ScopedTempDir dir("firmware_config");
  const auto load = [&](const std::string& json, dpcr::board::FirmwareConfig* c, std::string* error) {
    const std::string path = dir.str() + "/robot.json";
    std::ofstream(path) << json;
    return dpcr::board::LoadFirmwareConfigFile(path, c, error);
  };
  dpcr::board::FirmwareConfig c;
  std::string error;
  REQUIRE(load(R"({"uart": "/dev/ttyS3", "can": "can1", "lidar": "xv11", "angle_sign": 1, "wheel_radius_m": 0.04,
                   "track_width_m": 0.25, "ticks_per_rev": 4096, "max_range_m": 6, "laser_offset_m": 0.05, "max_accel_mps2": 1.5,
                   "heading": "gyro", "profile": "vacuum", "map_dir": "/var/lib/dpcr", "autosave_s": 30,
                   "status_period_s": 60})",
               &c, &error));
  CHECK(c.uart_device == "/dev/ttyS3");
  CHECK(c.can_interface == "can1");
  CHECK(c.lidar == dpcr::LidarKind::kXv11);
  CHECK(c.baud == 115200);
  CHECK(c.angle_map.angle_sign == 1.0f);
  CHECK(c.wheels.wheel_radius_m == 0.04f);
  CHECK(c.wheels.ticks_per_rev == 4096.0f);
  CHECK(c.laser_offset_m == 0.05f);
  CHECK(c.max_accel_mps2 == 1.5f);
  CHECK(c.heading == "gyro");  // named: not the lidar model's (ModelGyroHeading)
  CHECK(c.autosave_s == 30);
  CHECK(c.status_period_ms == 60000);

  // dpcr-sim's device.json is a valid config (its keys are a subset).
  dpcr::board::FirmwareConfig d;
  CHECK(load(R"({"lidar": "ld06", "angle_sign": 1.0, "wheel_radius_m": 0.035, "track_width_m": 0.235,
                 "ticks_per_rev": 4096.0, "max_range_m": 12.0, "laser_offset_m": 0.0})",
             &d, &error));
  CHECK(d.heading == "model");  // not named: the lidar model's
  dpcr::board::FirmwareConfig named_model;
  named_model.heading = "wheels";
  CHECK(load(R"({"ticks_per_rev": 4096, "heading": "model"})", &named_model, &error));
  CHECK(named_model.heading == "model");

  const auto refused = [&](const std::string& json, const std::string& expect) {
    dpcr::board::FirmwareConfig x;
    std::string e;
    CHECK_FALSE(load(json, &x, &e));
    INFO(e);
    CHECK(e.find(expect) != std::string::npos);
    CHECK(e.find('\n') == std::string::npos);
  };
  refused(R"({"wheel_radius_m": 0.035})", "ticks_per_rev: required");
  refused(R"({"ticks_per_rev": 4096, "tick_per_rev": 1})", "tick_per_rev: unknown key");
  refused(R"({"ticks_per_rev": "4096"})", "ticks_per_rev: expected a number");
  refused(R"({"ticks_per_rev": 4096, "max_accel_mps2": -1})", "max_accel_mps2: out of range");
  refused(R"({"ticks_per_rev": 4096, "profile": "building"})", "profile: \"building\"");
  refused(R"({"ticks_per_rev": 4096, "lidar": "rplidar"})", "lidar: \"rplidar\" is not ld06 or xv11");
  refused(R"({"ticks_per_rev": 4096, "wheel_radius_m": 3})", "wheel_radius_m: out of range");
  refused(R"({"ticks_per_rev": 4096, "heading": "compass"})", "heading: \"compass\" is not model, wheels or gyro");
  refused(R"({"ticks_per_rev": 4096, "angle_sign": 0.5})", "angle_sign: expected 1 or -1");
  refused(R"({"ticks_per_rev": 4096, "autosave_s": 1.5})", "autosave_s: expected a whole number");
  refused(R"([1, 2])", "expected a JSON object");
  refused(R"({"ticks_per_rev": 40)", "not JSON");
}
