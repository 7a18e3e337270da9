#include <catch2/catch.hpp>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "host_sim/drivers/uart_capture.hpp"
#include "tests/support/temp_dir.hpp"

TEST_CASE("uart capture write and read back, long chunks split") {
  const dpcr::test::ScopedTempDir dir("uart_round_trip");
  const std::string path = (dir.path() / "uart_capture_test.uart").string();
  std::vector<std::uint8_t> big(5000);
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<std::uint8_t>(i * 7);
  {
    dpcr::UartCaptureWriter w;
    std::string error;
    REQUIRE(w.Open(path, "ld06 baud 230400", &error));
    const std::uint8_t small[3] = {0x54, 0x2C, 0x00};
    REQUIRE(w.Write(1700000000000123, small, 3));
    REQUIRE(w.Write(1700000000002901, big.data(), big.size()));
    REQUIRE(w.Close());
  }
  std::vector<dpcr::UartChunk> chunks;
  std::string error;
  REQUIRE(dpcr::ReadUartCapture(path, &chunks, &error));
  REQUIRE(chunks.size() == 3);
  CHECK(chunks[0].stamp_us == 1700000000000123);
  CHECK(chunks[0].bytes == std::vector<std::uint8_t>({0x54, 0x2C, 0x00}));
  CHECK(chunks[1].bytes.size() == 4096);
  CHECK(chunks[2].bytes.size() == 904);
  CHECK(chunks[2].bytes.back() == big.back());
  dpcr::UartCaptureSource source(chunks);
  std::uint8_t buf[2];
  dpcr::ByteRead r = source.Read(buf, 2);
  CHECK(r.size == 2);
  CHECK(r.stamp_us == 1700000000000123);
  r = source.Read(buf, 2);
  CHECK(r.size == 1);
}

TEST_CASE("uart capture read with a skip count loses only its bad lines") {
  const dpcr::test::ScopedTempDir dir("uart_skip");
  const std::string path = (dir.path() / "flipped.uart").string();
  {
    std::ofstream f(path);
    // A flipped byte (G), a chunk going back in time, then good chunks again.
    f << "# dpcr-uart-capture 1\n1.000000 54AA\n2.000000 5G\n0.500000 54\n3.000000 2C\n4.000000 0102\n";
  }
  std::vector<dpcr::UartChunk> chunks;
  std::string error;
  dpcr::SkippedLines skipped;
  REQUIRE(dpcr::ReadUartCapture(path, &chunks, &error, nullptr, &skipped));
  REQUIRE(chunks.size() == 3);
  CHECK(chunks[2].stamp_us == 4000000);
  CHECK(skipped.count == 2);
  CHECK(skipped.first == path + ":3: malformed or out-of-order chunk");
  // Without the header it is no capture, skip count or not.
  { std::ofstream(path) << "1.000000 54AA\n"; }
  CHECK_FALSE(dpcr::ReadUartCapture(path, &chunks, &error, nullptr, &skipped));
}

TEST_CASE("uart capture rejects a bad line and names it") {
  const dpcr::test::ScopedTempDir dir("uart_bad_line");
  const std::string path = (dir.path() / "uart_capture_bad.uart").string();
  {
    std::ofstream f(path);
    f << "# dpcr-uart-capture 1\n1.000000 54AA\n2.000000 5G\n";
  }
  std::vector<dpcr::UartChunk> chunks;
  std::string error;
  CHECK_FALSE(dpcr::ReadUartCapture(path, &chunks, &error));
  CHECK(error.find(":3:") != std::string::npos);
  CHECK(chunks.size() == 1);
  dpcr::UartChunk c;
  CHECK_FALSE(dpcr::ParseUartCaptureLine("1.00 54", &c));      // 2 decimals
  CHECK_FALSE(dpcr::ParseUartCaptureLine("1.000000 545", &c));  // odd hex
  CHECK_FALSE(dpcr::ReadUartCapture("does-not-exist.uart", &chunks, &error));
  CHECK(error.find("does-not-exist.uart") != std::string::npos);
}

TEST_CASE("uart capture: a recording's end line gives its stamp, other comment lines are skipped") {
  const dpcr::test::ScopedTempDir dir("uart_end");
  const std::string path = (dir.path() / "lidar.uart").string();
  std::ofstream(path) << "# dpcr-uart-capture 1\n# device recorded by dpcr-firmware\n1.000100 54\n2.000200 2C\n# end 3.500000\n";
  std::vector<dpcr::UartChunk> chunks;
  std::string error;
  std::int64_t end_us = INT64_MIN;
  REQUIRE(dpcr::ReadUartCapture(path, &chunks, &error, &end_us));
  CHECK(chunks.size() == 2);
  CHECK(end_us == 3500000);
  std::ofstream(path) << "# dpcr-uart-capture 1\n1.000100 54\n# end soon\n";
  chunks.clear();
  CHECK_FALSE(dpcr::ReadUartCapture(path, &chunks, &error, &end_us));
  CHECK(error.find(":3: malformed end line") != std::string::npos);
}
