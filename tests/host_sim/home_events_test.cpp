// The simulator's changing home: kidnaps (the robot carried with its wheels lifted, put down at a
// waypoint of its plan) and people walking through the lidar's view.
#include <catch2/catch.hpp>

#include <cmath>

#include "host_sim/sim/people.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"

using namespace dpcr::sim;

TEST_CASE("A kidnap lifts the wheels, stills them, and puts the robot down elsewhere on its plan") {
  SimConfig config;
  config.duration_min = 2.0;
  config.kidnaps.count = 2;
  config.kidnaps.from_min = 0.5;
  Simulation sim(LoadBuiltinWorld("apartment"), config);
  SimEvent e;
  bool lifted_seen = false, carried = false;
  int put_down = 0;
  dpcr::Pose2 odometry_at_lift;
  while (sim.Step(&e)) {
    if (e.type != SimEventType::kOdometry) continue;
    if (e.odometry.lifted) {
      if (!carried) odometry_at_lift = e.odometry.pose;
      lifted_seen = carried = true;
      // The wheels stand still while carried.
      CHECK(std::hypot(e.odometry.pose.x - odometry_at_lift.x, e.odometry.pose.y - odometry_at_lift.y) < 1e-3f);
      continue;
    }
    if (carried) {
      // Just put down where the kidnap said (still turning towards its next waypoint).
      ++put_down;
      CHECK(std::hypot(e.truth.x - sim.kidnaps().back().to.x, e.truth.y - sim.kidnaps().back().to.y) < 1e-6);
    }
    carried = false;
  }
  REQUIRE(lifted_seen);
  REQUIRE(put_down == 2);
  REQUIRE(sim.kidnaps().size() == 2);
  for (const KidnapEvent& k : sim.kidnaps()) {
    CHECK(k.down_us - k.lift_us >= 3000000);
    CHECK(k.down_us - k.lift_us <= 6000000);
    bool on_plan = false;
    for (const Vec2& w : sim.plan().waypoints) on_plan = on_plan || (w.x == k.to.x && w.y == k.to.y);
    CHECK(on_plan);
  }
}

TEST_CASE("Kidnaps that cannot fit the run are an error") {
  SimConfig config;
  config.duration_min = 1.0;
  config.kidnaps.count = 20;
  REQUIRE_THROWS_AS(Simulation(LoadBuiltinWorld("apartment"), config), WorldError);
}

namespace {

// One person walking a three-waypoint tour without standing still.
PeopleConfig OneWalker() {
  PeopleConfig config;
  config.count = 1;
  config.stand_probability = 0.0;
  return config;
}

People WalkTheTour(const PeopleConfig& config) {
  const std::vector<Vec2> tour{{0.0, 0.0}, {4.0, 0.0}, {4.0, 4.0}};
  return People(config, tour, 7, 60.0);
}

}  // namespace

TEST_CASE("People walk the tour and block beams in front of them") {
  const PeopleConfig config = OneWalker();
  const People people = WalkTheTour(config);
  REQUIRE(people.size() == 1);
  // Walking: the position moves at the walking speed along the tour's edges.
  const Vec2 a = people.PositionAt(0, 1.0), b = people.PositionAt(0, 2.0);
  CHECK(Norm(b - a) == Approx(config.speed_mps).margin(1e-6));
  // A beam aimed at the person returns at the near side of their legs; one aimed away does not.
  const Vec2 p = people.PositionAt(0, 1.0);
  const Vec2 from{p.x - 2.0, p.y};
  CHECK(people.Cast(from, 0.0, 1.0, 12.0, from) == Approx(2.0 - config.radius_m).margin(1e-9));
  CHECK(people.Cast(from, 3.14159265358979, 1.0, 12.0, from) < 0.0);
  CHECK(people.Cast(from, 0.0, 1.0, 1.0, from) < 0.0);  // beyond the range
}

TEST_CASE("People step aside from the robot instead of walking through it") {
  const PeopleConfig config = OneWalker();
  const People people = WalkTheTour(config);
  const Vec2 walk = people.PositionAt(0, 1.0);
  // The robot 0.1 m from where the walk is: the person stands clear of it, on the same side.
  const Vec2 robot{walk.x + 0.1, walk.y};
  const Vec2 beside = people.PositionBeside(0, 1.0, robot);
  CHECK(Norm(beside - robot) == Approx(config.robot_clearance_m).margin(1e-9));
  CHECK(beside.x < robot.x);
  // Far from the robot: where the walk is.
  CHECK(Norm(people.PositionBeside(0, 1.0, Vec2{walk.x + 3.0, walk.y}) - walk) < 1e-12);
  // The lidar at the robot's centre never sees legs closer than the clearance less their radius.
  for (int k = 0; k < 64; ++k) {
    const double d = people.Cast(robot, 0.09817477042468103 * k, 1.0, 12.0, robot);
    if (d >= 0.0) CHECK(d >= config.robot_clearance_m - config.radius_m - 1e-9);
  }
}
