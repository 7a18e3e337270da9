// TUM trajectory text: exact stamps both ways, yaw from the quaternion, malformed lines named.
#include <catch2/catch.hpp>

#include <sstream>

#include "host_sim/eval/trajectory.hpp"

using dpcr::Pose2;
using dpcr::eval::Trajectory;

TEST_CASE("TUM files round-trip stamps exactly and reject malformed lines") {
  Trajectory t{{976052857337530LL, Pose2{1.5f, -2.0f, 3.0f}}};
  std::stringstream s;
  dpcr::eval::WriteTum(s, t);
  REQUIRE(s.str().rfind("976052857.337530 1.500000 -2.000000 0 0 0 ", 0) == 0);
  const Trajectory back = dpcr::eval::ReadTum(s);
  REQUIRE(back.size() == 1);
  REQUIRE(back[0].stamp_us == 976052857337530LL);
  REQUIRE(back[0].pose.theta == Approx(3.0f));
  std::istringstream bad("1.0 2.0 3.0\n");
  REQUIRE_THROWS_WITH(dpcr::eval::ReadTum(bad), Catch::Contains("line 1"));
}

TEST_CASE("TUM lines skip comments and blank lines, and name a bad stamp") {
  std::istringstream in("# t x y z qx qy qz qw\n\n-0.500000 1 2 0 0 0 0.7071068 0.7071068\n");
  const Trajectory t = dpcr::eval::ReadTum(in);
  REQUIRE(t.size() == 1);
  REQUIRE(t[0].stamp_us == -500000);
  REQUIRE(t[0].pose.theta == Approx(dpcr::kPi / 2));
  std::istringstream bad("1.0 1 2 0 0 0 0 1\n1,5 1 2 0 0 0 0 1\n");
  REQUIRE_THROWS_WITH(dpcr::eval::ReadTum(bad), Catch::Contains("line 2: bad timestamp '1,5'"));
}
