// Doors that open and close (dpcr-sim --doors): the schedule, the robot never shut out, the
// lidar seeing a closed door, the world file's `leaf`, and the map check leaving doors aside.
#include <catch2/catch.hpp>

#include <cmath>

#include "host_sim/apps/map_truth_check.hpp"
#include "host_sim/sim/doors.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"

using namespace dpcr::sim;

namespace {

// Two rooms joined by a door with a leaf at x = 4, y in [1.5, 2.4].
World TwoRooms() {
  return ParseWorldText("box 0 0 8 4\nwall 4 0 4 4\ndoor 4 1.5 4 2.4 leaf\ndoor 4 3 4 3.5\nroom w 0 0 4 4\nroom e 4 0 8 4\n",
                        "two-rooms");
}

}  // namespace

TEST_CASE("A door with a leaf opens and closes on its seed's schedule, and opens for the robot") {
  const World world = TwoRooms();
  REQUIRE(world.doors.size() == 2);
  CHECK(world.doors[0].leaf);
  CHECK_FALSE(world.doors[1].leaf);
  DoorsConfig config;
  config.enabled = true;
  config.open_min_s = config.closed_min_s = 10.0;
  config.open_max_s = config.closed_max_s = 20.0;
  const Doors doors(config, world, 3, 600.0);
  REQUIRE(doors.size() == 1);  // the leafless opening stays open
  CHECK(doors.scheduled_changes() >= 600 / 20 - 1);
  CHECK(doors.scheduled_changes() <= 600 / 10);
  // Far from the robot, both states occur; a beam through the doorway returns from the closed leaf.
  const Vec2 far_robot{0.5, 0.5}, west{2.0, 1.95};
  int closed = 0, open = 0;
  for (double t = 0.0; t < 600.0; t += 1.0) {
    const bool c = doors.Closed(0, t, far_robot);
    (c ? closed : open) += 1;
    const double d = doors.Cast(west, 0.0, t, far_robot, 12.0);
    if (c) {
      CHECK(d == Approx(2.0).margin(1e-9));
    } else {
      CHECK(d < 0.0);
    }
  }
  CHECK(closed > 100);
  CHECK(open > 100);
  // The robot within a metre of the doorway: open whatever the schedule.
  for (double t = 0.0; t < 600.0; t += 1.0) CHECK_FALSE(doors.Closed(0, t, Vec2{3.3, 1.9}));
  // Same seed, same schedule; another seed, another.
  const Doors again(config, world, 3, 600.0), other(config, world, 4, 600.0);
  int same = 0, differs = 0;
  for (double t = 0.0; t < 600.0; t += 1.0) {
    same += doors.Closed(0, t, far_robot) == again.Closed(0, t, far_robot) ? 1 : 0;
    differs += doors.Closed(0, t, far_robot) != other.Closed(0, t, far_robot) ? 1 : 0;
  }
  CHECK(same == 600);
  CHECK(differs > 0);
  // Off: no door moves.
  config.enabled = false;
  CHECK(Doors(config, world, 3, 600.0).size() == 0);
}

TEST_CASE("The world file's door takes 'leaf' and nothing else") {
  REQUIRE_THROWS_WITH(ParseWorldText("box 0 0 8 4\ndoor 4 1.5 4 2.4 hinge\n", "w"),
                      Catch::Contains("w:2:") && Catch::Contains("leaf"));
  CHECK(LoadBuiltinWorld("apartment").doors.size() == 6);
  int leaves = 0;
  for (const Door& d : LoadBuiltinWorld("apartment").doors) leaves += d.leaf ? 1 : 0;
  CHECK(leaves == 4);
}

TEST_CASE("A world whose doors cut away every wall is rejected") {
  REQUIRE_THROWS_WITH(ParseWorldText("wall 0 0 4 0\ndoor -1 0 5 0\nroom r 0 -1 4 1\n", "w"),
                      Catch::Contains("w:3:") && Catch::Contains("every wall"));
  CHECK(ParseWorldText("wall 0 0 4 0\nwall 0 1 4 1\ndoor -1 0 5 0\n", "w").segments.size() == 1);
}

TEST_CASE("With doors on, the lidar sees closed doors and the robot still covers every room") {
  SimConfig config;
  config.duration_min = 8.0;
  config.doors.enabled = true;
  config.doors.open_min_s = config.doors.closed_min_s = 20.0;
  config.doors.open_max_s = config.doors.closed_max_s = 60.0;
  const World world = LoadBuiltinWorld("apartment");
  Simulation sim(world, config);
  REQUIRE(sim.doors().size() == 4);
  SimEvent e;
  int door_returns = 0;
  while (sim.Step(&e)) {
    if (e.type != SimEventType::kScan) continue;
    const Vec2 robot{e.truth.x, e.truth.y};
    // The robot is never within 0.5 m of a closed door: it does not drive through one.
    for (std::size_t i = 0; i < sim.doors().size(); ++i) {
      if (!sim.doors().Closed(i, static_cast<double>(e.scan.stamp_us) * 1e-6, robot)) continue;
      const Segment& s = sim.doors().leaves()[i];
      CHECK(PointSegmentDistance(robot, s.a, s.b) > 0.5);
    }
    // Returns that lie on a leaf (within the range noise) come from a closed door.
    for (const auto& b : e.scan.beams) {
      if (b.range_m <= 0.0f) continue;
      const Pose2d& sp = e.sensor_truth;
      const double a = sp.theta + static_cast<double>(b.angle_rad);
      const Vec2 hit{sp.x + static_cast<double>(b.range_m) * std::cos(a), sp.y + static_cast<double>(b.range_m) * std::sin(a)};
      for (const Segment& s : sim.doors().leaves()) {
        const double along = Dot(hit - s.a, s.b - s.a) / Dot(s.b - s.a, s.b - s.a);
        if (PointSegmentDistance(hit, s.a, s.b) < 0.03 && along > 0.1 && along < 0.9) ++door_returns;
      }
    }
  }
  CHECK(door_returns > 100);
}

TEST_CASE("The map check counts cells at a door apart, and ghosts where people stood") {
  const World world = TwoRooms();
  const WorldRayCaster caster(world);
  // A 10 x 5 m map at 5 cm, origin at the world's: occupied cells on the door's line, in the
  // middle of the east room (where someone stood) and in the middle of the west room.
  dpcr::output::FusedMap map;
  map.resolution_m = 0.05f;
  map.box = dpcr::CellBox{dpcr::CellIndex{0, 0}, dpcr::CellIndex{200, 100}};
  map.cells.assign(200 * 100, -2000);
  const auto set = [&](double x, double y) {
    map.cells[static_cast<std::size_t>(std::floor(y / 0.05)) * 200 + static_cast<std::size_t>(std::floor(x / 0.05))] = 3000;
  };
  set(4.01, 1.9);
  set(4.01, 2.0);
  set(6.01, 2.01);
  set(2.01, 2.01);
  dpcr::apps::HomeChanges changes;
  const nlohmann::json plain = dpcr::apps::MapTruthCheck(map, dpcr::Pose2::Identity(), caster, changes);
  CHECK(plain["occupied_cells"] == 4);
  CHECK(plain["off_wall_cells"] == 4);
  Doors doors(DoorsConfig{true}, world, 1, 60.0);
  changes.door_leaves = doors.leaves();
  changes.standing_spots = {Vec2{6.0, 2.0}};
  const nlohmann::json j = dpcr::apps::MapTruthCheck(map, dpcr::Pose2::Identity(), caster, changes);
  CHECK(j["door_cells"] == 2);
  CHECK(j["occupied_cells"] == 2);
  CHECK(j["off_wall_cells"] == 2);
  CHECK(j["stood_cells"] == 1);
}
