#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "board/atomic_file.hpp"
#include "board/socketcan_port.hpp"
#include "tests/support/temp_dir.hpp"

#include <sys/socket.h>

namespace {
std::string Slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}
}  // namespace

TEST_CASE("atomic write replaces the file and leaves no temp file") {
  const dpcr::test::ScopedTempDir dir("atomic_file");
  const std::string path = dir.str() + "/atomic_test.txt";
  std::string error;
  REQUIRE(dpcr::board::WriteFileAtomic(path, "first", 5, &error));
  REQUIRE(dpcr::board::WriteFileAtomic(path, "second", 6, &error));
  CHECK(Slurp(path) == "second");
  CHECK(::access((path + ".tmp").c_str(), F_OK) != 0);
}

TEST_CASE("atomic write into a missing directory fails, naming the path and errno") {
  std::string error;
  CHECK_FALSE(dpcr::board::WriteFileAtomic("no-such-dir/map.pgm", "x", 1, &error));
  CHECK(error.find("no-such-dir/map.pgm.tmp") != std::string::npos);
  CHECK(error.find("No such file or directory") != std::string::npos);
}

TEST_CASE("can frames cross a socketpair as struct can_frame") {
  int sv[2];
  REQUIRE(::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_NONBLOCK, 0, sv) == 0);
  dpcr::CanFrame f;
  f.id = 0x120;
  f.dlc = 8;
  f.data[7] = 0x5A;
  REQUIRE(dpcr::board::WriteCanFrame(sv[0], f) == dpcr::IoStatus::kOk);
  dpcr::CanFrame g;
  REQUIRE(dpcr::board::ReadCanFrame(sv[1], &g) == dpcr::IoStatus::kOk);
  CHECK(g.id == 0x120);
  CHECK(g.dlc == 8);
  CHECK(g.data[7] == 0x5A);
  CHECK(dpcr::board::ReadCanFrame(sv[1], &g) == dpcr::IoStatus::kWouldBlock);
  ::close(sv[0]);
  CHECK(dpcr::board::ReadCanFrame(sv[1], &g) == dpcr::IoStatus::kEndOfStream);
  ::close(sv[1]);
}

TEST_CASE("opening a CAN interface that does not exist names it and the reason") {
  std::string error;
  CHECK(dpcr::board::OpenSocketCan("dpcrcan9", &error) < 0);
  CHECK(error.find("dpcrcan9") != std::string::npos);
  CHECK(error.find(": ") != std::string::npos);
}
