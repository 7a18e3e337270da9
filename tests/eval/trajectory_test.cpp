// TUM trajectory text: exact stamps both ways, yaw from the quaternion, malformed lines named.
#include <catch2/catch.hpp>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <string>

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

TEST_CASE("TUM lines are the text printf gives for the pose and the quaternion") {
  // Signed zeros, values that round to zero, halfway decimals, the float range's ends, and random poses.
  Trajectory t{{1, Pose2{-0.0f, 0.0f, -0.0f}},           {2, Pose2{-4e-7f, 4e-7f, -1e-9f}},
               {3, Pose2{0.0000005f, 2.675f, 3.14159f}}, {4, Pose2{FLT_MAX, -FLT_MAX, -3.14159f}},
               {5, Pose2{FLT_MIN, -FLT_MIN, 1e-30f}}};
  std::uint64_t seed = 7;
  for (int i = 0; i < 2000; ++i) {
    seed = seed * 6364136223846793005u + 1442695040888963407u;
    const float u = static_cast<float>(seed >> 40) / 16777216.0f, v = static_cast<float>((seed >> 16) & 0xffffff) / 16777216.0f;
    t.push_back({static_cast<std::int64_t>(i), Pose2{(u - 0.5f) * 200.0f, (v - 0.5f) * 0.02f, (u - v) * 6.0f}});
  }
  std::ostringstream s;
  dpcr::eval::WriteTum(s, t);
  std::string expected;
  char buf[256];
  for (const auto& p : t) {
    const double half = 0.5 * static_cast<double>(p.pose.theta);
    std::snprintf(buf, sizeof(buf), "%s %.6f %.6f 0 0 0 %.9f %.9f\n", dpcr::eval::FormatStamp(p.stamp_us).c_str(),
                  static_cast<double>(p.pose.x), static_cast<double>(p.pose.y), std::sin(half), std::cos(half));
    expected += buf;
  }
  REQUIRE(s.str() == expected);
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
