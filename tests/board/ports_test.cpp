// The board's ports (hal/ports.hpp): termios UART and SocketCAN reads stamped by the clock they
// are given, CLOCK_MONOTONIC, and blobs stored as atomically replaced files.
#include <catch2/catch.hpp>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <poll.h>
#include <pty.h>
#include <sstream>
#include <string>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include "board/atomic_file.hpp"
#include "board/monotonic_clock.hpp"
#include "board/socketcan_port.hpp"
#include "board/termios_uart.hpp"
#include "hal/wheel_can_protocol.hpp"

namespace {

struct FixedClock : dpcr::Clock {
  std::int64_t NowUs() const override { return now_us; }
  std::int64_t now_us = 42;
};

std::string TempDir() {
  char path[] = "/tmp/dpcr_ports_XXXXXX";
  REQUIRE(::mkdtemp(path) != nullptr);
  return path;
}

}  // namespace

TEST_CASE("board ports: the termios UART reads raw bytes stamped by its clock") {
  int master = -1;
  int slave = -1;
  char name[128];
  termios raw{};
  cfmakeraw(&raw);
  REQUIRE(::openpty(&master, &slave, name, &raw, nullptr) == 0);
  FixedClock clock;
  dpcr::board::TermiosUart uart(&clock);
  std::string error;
  REQUIRE(uart.Open(name, 230400, &error));
  std::uint8_t buffer[16];
  const std::uint8_t bytes[3] = {0x54, 0x2C, 0x0A};  // 0x0A: no line discipline may touch it
  REQUIRE(::write(master, bytes, sizeof(bytes)) == 3);
  clock.now_us = 1234;
  pollfd readable{uart.fd(), POLLIN, 0};
  REQUIRE(::poll(&readable, 1, 1000) == 1);
  const dpcr::ByteRead r = uart.Read(buffer, sizeof(buffer));
  REQUIRE(r.status == dpcr::IoStatus::kOk);
  REQUIRE(r.size == 3);
  CHECK(buffer[2] == 0x0A);
  CHECK(r.stamp_us == 1234);
  ::close(master);
  ::close(slave);
  CHECK_FALSE(uart.Open("/dev/dpcr-no-such-tty", 230400, &error));
  CHECK(error.find("/dev/dpcr-no-such-tty") != std::string::npos);
  CHECK_FALSE(uart.Open(name, 9600, &error));
  CHECK(error.find("unsupported baud rate 9600") != std::string::npos);
}

TEST_CASE("board ports: a borrowed CAN fd is read non-blocking, stamped, and left open") {
  int sv[2];
  REQUIRE(::socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv) == 0);  // blocking: Borrow must change that
  FixedClock clock;
  {
    dpcr::board::SocketCanPort can(&clock);
    can.Borrow(sv[1]);
    CHECK(can.fd() == sv[1]);
    CHECK(can.Read().status == dpcr::IoStatus::kWouldBlock);
    dpcr::CanFrame f;
    f.id = 0x121;
    f.dlc = 6;
    REQUIRE(dpcr::board::WriteCanFrame(sv[0], f) == dpcr::IoStatus::kOk);
    clock.now_us = 777;
    const dpcr::CanRead r = can.Read();
    REQUIRE(r.status == dpcr::IoStatus::kOk);
    CHECK(r.frame.id == 0x121);
    CHECK(r.stamp_us == 777);
  }
  CHECK(::write(sv[0], "x", 1) == 1);  // the borrowed end is still open after the port went
  ::close(sv[0]);
  ::close(sv[1]);
}

TEST_CASE("board ports: the monotonic clock moves forward") {
  const dpcr::board::MonotonicClock clock;
  const std::int64_t a = clock.NowUs();
  ::usleep(2000);
  const std::int64_t b = clock.NowUs();
  CHECK(b - a >= 2000);
  CHECK(b - a < 2000000);
}

TEST_CASE("board ports: blobs are files in the store's directory, a failure keeps errno and says where") {
  const std::string dir = TempDir();
  dpcr::board::AtomicFileStore store(dir);
  const std::uint8_t data[4] = {'P', '5', '\n', 0};
  REQUIRE(store.Write("map.pgm", data, sizeof(data)) == dpcr::IoStatus::kOk);
  std::ifstream f(dir + "/map.pgm", std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  CHECK(s.str() == std::string("P5\n\0", 4));
  REQUIRE(::unlink((dir + "/map.pgm").c_str()) == 0);
  REQUIRE(::rmdir(dir.c_str()) == 0);
  CHECK(store.Write("map.pgm", data, sizeof(data)) == dpcr::IoStatus::kIoError);
  CHECK(errno == ENOENT);
  CHECK(store.last_error().find(dir + "/map.pgm.tmp: open") != std::string::npos);
}

TEST_CASE("board ports: the SocketCAN filters pass the protocol's IDs, as standard data frames only") {
  using dpcr::board::WheelFiltersPass;
  CHECK(WheelFiltersPass(dpcr::kWheelTicksCanId));
  CHECK(WheelFiltersPass(dpcr::kGyroCanId));
  CHECK(WheelFiltersPass(dpcr::kStatusCanId));
  CHECK(WheelFiltersPass(0x122));
  CHECK_FALSE(WheelFiltersPass(0x123));
  CHECK_FALSE(WheelFiltersPass(0x11F));
  CHECK_FALSE(WheelFiltersPass(0x122 | dpcr::kCanEffFlag));
  CHECK_FALSE(WheelFiltersPass(0x1000122 | dpcr::kCanEffFlag));  // an extended ID ending in 0x122
  CHECK_FALSE(WheelFiltersPass(0x122 | dpcr::kCanRtrFlag));
}
