// CARMEN parser: good lines of each kind, the counters, and malformed lines named by number.
#include <catch2/catch.hpp>

#include <sstream>

#include "host_sim/carmen/carmen_reader.hpp"

using dpcr::carmen::CarmenError;
using dpcr::carmen::CarmenReader;
using dpcr::carmen::Record;

TEST_CASE("Timestamps parse to exact microseconds") {
  REQUIRE(dpcr::carmen::ParseStampMicros("976052857.337530") == 976052857337530LL);
  REQUIRE(dpcr::carmen::ParseStampMicros("12") == 12000000LL);
  REQUIRE(dpcr::carmen::ParseStampMicros("1.0000005") == 1000001LL);
  REQUIRE_THROWS(dpcr::carmen::ParseStampMicros("1e9"));
  REQUIRE_THROWS(dpcr::carmen::ParseStampMicros("-1.5"));
}

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
  REQUIRE(r.laser.ranges_m.size() == 4);
  REQUIRE(r.laser.ranges_m[3] == 4.0f);
  REQUIRE(r.laser.stamp_text == "100.500000");
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
