// CARMEN parser: good lines of each kind, the counters, and malformed lines named by number.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "host_sim/carmen/carmen_reader.hpp"
#include "host_sim/carmen/laser_odometry.hpp"
#include "host_sim/carmen/laser_scan.hpp"

using dpcr::carmen::CarmenError;
using dpcr::carmen::CarmenReader;
using dpcr::carmen::Record;

TEST_CASE("FLASER, ODOM, PARAM and comment lines are read in file order") {
  std::istringstream log(
      "# a comment\n"
      "PARAM robot_frontlaser_offset 0.25 nohost 0\n"
      "ODOM 1.0 2.0 0.5 0.1 0.0 0.0 100.000001 nohost 0.0\n"
      "FLASER 4 1.0 2.0 3.0 4.0 0.1 0.2 0.3 1.1 2.1 0.4 100.500000 nohost 0.5\n"
      "SYNC 100.6 nohost 0.6\n"
      "FLASER 3 1 2 3 0 0 0 0 0 0 99.000000 nohost 0.7\n");
  CarmenReader reader(log);
  Record r;
  REQUIRE(reader.Next(&r));
  REQUIRE(r.kind == Record::Kind::kOdom);
  REQUIRE(r.odom.stamp_us == 100000001LL);
  REQUIRE(r.odom.pose.theta == Approx(0.5f));
  REQUIRE(reader.Next(&r));
  REQUIRE(r.kind == Record::Kind::kLaser);
  REQUIRE(r.laser.line == 4);
  REQUIRE(r.laser.stamp_us == 100500000LL);
  REQUIRE(r.laser.ranges_m.size() == 4);
  REQUIRE(r.laser.ranges_m[3] == 4.0f);
  REQUIRE(r.laser.odom_pose.x == Approx(1.1f));
  REQUIRE(r.laser.angle_min_rad == Approx(-dpcr::kPi / 2));
  REQUIRE(r.laser.angle_increment_rad == Approx(dpcr::kPi / 4));  // 4 beams: 45 deg steps
  REQUIRE(reader.front_laser_offset_m() == Approx(0.25f));
  REQUIRE(reader.Next(&r));
  REQUIRE(r.laser.angle_increment_rad == Approx(dpcr::kPi / 2));  // 3 beams span both ends
  REQUIRE_FALSE(reader.Next(&r));
  REQUIRE(reader.counters().laser_steps_back == 1);
  REQUIRE(reader.counters().other_messages == 1);
  REQUIRE(reader.counters().comments == 1);
}

TEST_CASE("Words a plain decimal does not cover are read whole: exponents and tabs mid-line") {
  // The reader parses plain decimals as it meets them; anything else is read as a whole word.
  std::istringstream log("FLASER\t3 1e0 2.5\t+3 0 0 0 0 0 0 99.000000 nohost 0.7\r\n");
  CarmenReader reader(log);
  Record r;
  REQUIRE(reader.Next(&r));
  REQUIRE(r.laser.ranges_m.size() == 3);
  REQUIRE(r.laser.ranges_m[0] == 1.0f);
  REQUIRE(r.laser.ranges_m[1] == 2.5f);
  REQUIRE(r.laser.ranges_m[2] == 3.0f);
  REQUIRE(r.laser.stamp_us == 99000000LL);
  // A number run into letters is named whole in the error.
  std::istringstream bad("FLASER 2 1 1.5x 0 0 0 0 0 0 1.0 h 1\n");
  CarmenReader bad_reader(bad);
  try {
    bad_reader.Next(&r);
    FAIL("no error");
  } catch (const CarmenError& e) {
    REQUIRE(std::string(e.what()) == "line 1: bad range reading '1.5x'");
  }
}

TEST_CASE("ROBOTLASER1 lines carry their own angles and range") {
  std::istringstream log(
      "ROBOTLASER1 0 -1.5 3.0 1.0 30.0 0.01 0 4 1 2 3 4 0 0.5 0.6 0.7 0.1 0.2 0.3 0 0 0 0 0 5.000000 host 5.1\n");
  CarmenReader reader(log);
  Record r;
  REQUIRE(reader.Next(&r));
  REQUIRE(r.laser.angle_min_rad == Approx(-1.5f));
  REQUIRE(r.laser.angle_increment_rad == Approx(1.0f));
  REQUIRE(r.laser.max_range_m == Approx(30.0f));
  REQUIRE(r.laser.laser_pose.x == Approx(0.5f));
  REQUIRE(r.laser.odom_pose.y == Approx(0.2f));
  REQUIRE(r.laser.stamp_us == 5000000);
}

TEST_CASE("Malformed lines are errors that name the line and the reason") {
  const char* bad[] = {
      "FLASER 3 1 2\n",                                              // truncated
      "FLASER 2 1 x 0 0 0 0 0 0 1.0 h 1\n",                          // not a number
      "FLASER -1 0 0 0 0 0 0 1.0 h 1\n",                             // negative count
      "ODOM 1 2 3 0 0 0 notastamp h 1\n",                            // bad stamp
      "garbage line\n",                                              // not a message
      // Found by fuzz/fuzz_carmen.cpp: one FLASER reading made an infinite angle step (180 / 0),
      // and a finite double past the float range an infinite float.
      "FLASER 1 1 2 3 0 0 0 0 0 0 99.000000 nohost 0.7\n",          // one reading
      "FLASER 2 1e39 2 0 0 0 0 0 0 1.0 h 1\n",                      // range past float
      "ODOM 1 -4e38 3 0 0 0 1.0 h 1\n",                             // pose past float
      "ROBOTLASER1 0 -1e300 3.0 1.0 30.0 0.01 0 2 1 2 0 0 0 0 0 0 0 0 0 0 0 5.0 h 5.1\n",  // angle past float
      // A count smaller than the readings: read on, readings were taken for the pose and stamps.
      "FLASER 2 1 2 3 4 0 0 0 0 0 0 1.0 h 1\n",
      // ODOM lines cut short: inside the time stamp, before the host name, before the logger stamp.
      "ODOM 1 2 3 0 0 0 12\n",
      "ODOM 1 2 3 0 0 0 1.0\n",
      "ODOM 1 2 3 0 0 0 1.0 h\n",
      "ODOM 1 2 3 0 0 0 1.0 h 1 extra\n",
  };
  for (const char* text : bad) {
    std::istringstream log(std::string("# header\n") + text);
    CarmenReader reader(log);
    Record r;
    try {
      reader.Next(&r);
      FAIL("no error for: " << text);
    } catch (const CarmenError& e) {
      REQUIRE(e.line() == 2);
      REQUIRE(std::string(e.what()).rfind("line 2: ", 0) == 0);
    }
  }
}

TEST_CASE("Numbers parse to the double strtod gives (the short-decimal fast path included)") {
  const char* const words[] = {"0", "-0", "+0", "0.0", "-0.000", "1", "1.", ".5", "-.5", "+2.25", "17", "-17.5",
                               "0.1", "0.3", "2.675", "81.9100", "999999999999999", "0.000000000000001",
                               "9007199254740993", "1234567890123456.7", "1e3", "-2.5E-3", "3.4028235e38",
                               "0.30000000000000004"};
  for (const char* w : words) {
    double v = 42.0;
    REQUIRE(dpcr::carmen::ParseNumber(w, &v));
    const double expected = std::strtod(w, nullptr);
    REQUIRE(std::memcmp(&v, &expected, sizeof v) == 0);  // bit for bit (signed zeros too)
  }
  for (const char* bad : {"", "-", "+", ".", "1.2.3", "1,5", "abc", "1e", "--1", "inf", "nan", "1e999"}) {
    double v = 0.0;
    REQUIRE_FALSE(dpcr::carmen::ParseNumber(bad, &v));
  }
  // Random plain decimals of up to 15 digits, as lasers and odometry write them.
  std::uint64_t seed = 99;
  char text[40];
  for (int i = 0; i < 200000; ++i) {
    seed = seed * 6364136223846793005u + 1442695040888963407u;
    const int digits = 1 + static_cast<int>((seed >> 33) % 15), point = static_cast<int>((seed >> 40) % static_cast<std::uint64_t>(digits + 1));
    std::uint64_t m = seed >> 11;
    int n = 0;
    if ((seed >> 50) & 1u) text[n++] = '-';
    for (int d = 0; d < digits; ++d, m /= 10) {
      if (d == point) text[n++] = '.';
      text[n++] = static_cast<char>('0' + m % 10);
    }
    text[n] = '\0';
    double v = 0.0;
    REQUIRE(dpcr::carmen::ParseNumber(text, &v));
    const double expected = std::strtod(text, nullptr);
    REQUIRE(std::memcmp(&v, &expected, sizeof v) == 0);
  }
}

TEST_CASE("Laser records become scans, more beams than a scan holds are decimated, not truncated") {
  dpcr::carmen::LaserRecord laser;
  laser.stamp_us = 42;
  laser.angle_min_rad = -1.0f;
  laser.angle_increment_rad = 0.01f;
  for (int i = 0; i < 10; ++i) laser.ranges_m.push_back(1.0f + 0.1f * static_cast<float>(i));
  dpcr::Scan<16> roomy;
  CHECK_FALSE(dpcr::carmen::ToScan(laser, &roomy));
  REQUIRE(roomy.beams.size() == 10);
  CHECK(roomy.stamp_us == 42);
  CHECK(roomy.beams[9].angle_rad == Approx(-0.91f));
  CHECK(roomy.beams[9].range_m == Approx(1.9f));
  dpcr::Scan<4> small;
  CHECK(dpcr::carmen::ToScan(laser, &small));
  REQUIRE(small.beams.size() == 4);  // every third beam: 0, 3, 6, 9
  CHECK(small.beams[1].range_m == Approx(1.3f));
  CHECK(small.beams[3].angle_rad == Approx(-0.91f));
  CHECK(dpcr::carmen::ToScan(laser, &small));  // a scan reused: overwritten, not appended
  CHECK(small.beams.size() == 4);
}

TEST_CASE("A laser record's odometry pose repeated exactly is no new measurement") {
  dpcr::carmen::LaserOdometry odometry;
  CHECK(odometry.IsNewMeasurement(dpcr::Pose2{0.0f, 0.0f, 0.0f}));  // the first one is
  CHECK_FALSE(odometry.IsNewMeasurement(dpcr::Pose2{0.0f, 0.0f, 0.0f}));
  CHECK_FALSE(odometry.IsNewMeasurement(dpcr::Pose2{0.0f, 0.0f, 0.0f}));
  CHECK(odometry.IsNewMeasurement(dpcr::Pose2{0.85f, 0.1f, 0.8f}));  // the catch-up step
  CHECK(odometry.IsNewMeasurement(dpcr::Pose2{0.85f, 0.1f, 0.81f}));  // any field differing
  CHECK(odometry.repeats() == 2);
}
