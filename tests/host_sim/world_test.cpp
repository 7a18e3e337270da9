#include "host_sim/sim/world.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>

using namespace dpcr::sim;

namespace {
std::string ErrorOf(const std::string& text) {
  try {
    ParseWorldText(text, "w.txt");
  } catch (const WorldError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("Text world parses every keyword", "[world]") {
  const World w = ParseWorldText(
      "# a test world\n"
      "name test-room\n"
      "material glass 0.3\n"
      "box 0 0 4 3\n"
      "wall 0 1.5 4 1.5 glass   # partition\n"
      "door 1 1.5 2 1.5\n"
      "circle 3 2.5 0.05 glass\n"
      "room north 0 1.5 4 3\n"
      "room south 0 0 4 1.5\n"
      "start 1 0.5 1.5708\n",
      "w.txt");
  CHECK(w.name == "test-room");
  REQUIRE(w.materials.size() == 2);
  CHECK(w.materials[1].return_probability == Approx(0.3));
  // Four box sides, the partition cut in two by the door.
  REQUIRE(w.segments.size() == 6);
  CHECK(w.segments[4].b.x == Approx(1.0));
  CHECK(w.segments[5].a.x == Approx(2.0));
  CHECK(w.segments[5].material == 1);
  REQUIRE(w.circles.size() == 1);
  CHECK(w.circles[0].material == 1);
  CHECK(w.rooms.size() == 2);
  CHECK(w.has_start);
  CHECK(w.start.theta == Approx(1.5708));
}

TEST_CASE("Malformed text worlds report the line", "[world]") {
  CHECK(ErrorOf("box 0 0 4 3\nwal 0 0 1 1\n") == "w.txt:2: unknown keyword 'wal'");
  CHECK(ErrorOf("box 0 0 4 3\n\nwall 0 0 1\n").find("w.txt:3: expected 'wall") == 0);
  CHECK(ErrorOf("wall 0 0 1 x1\n") == "w.txt:1: not a number: 'x1'");
  CHECK(ErrorOf("wall 0 0 1 1 marble\n").find("w.txt:1: unknown material 'marble'") == 0);
  CHECK(ErrorOf("material glass 1.5\n").find("w.txt:1: return probability") == 0);
  CHECK(ErrorOf("circle 0 0 -1\n").find("w.txt:1: circle radius") == 0);
  CHECK(ErrorOf("box 0 0 1 1\nroom r 2 0 1 1\n").find("w.txt:2: room needs") == 0);
  CHECK(ErrorOf("wall 1 1 1 1\n").find("w.txt:1: wall has zero length") == 0);
  CHECK(ErrorOf("# nothing\n").find("w.txt:1: world has no walls") == 0);
  CHECK(ErrorOf("box 0 0 4 3\n").empty());
}

TEST_CASE("World files load by extension, missing files fail clearly", "[world]") {
  const std::string text_path = "dpcr_world_test.world";
  std::ofstream(text_path) << "box 0 0 2 2\n";
  CHECK(LoadWorldFile(text_path).segments.size() == 4);
  std::remove(text_path.c_str());
  CHECK_THROWS_WITH(LoadWorldFile("/nonexistent/x.world"), "/nonexistent/x.world: cannot open world file");

  // 4 x 3 plain PGM, one dark pixel at column 1, row 0 (top): a 5 cm square at y in [0.10, 0.15].
  const std::string pgm_path = "dpcr_world_test.pgm";
  std::ofstream(pgm_path) << "P2\n# comment\n4 3\n255\n255 0 255 255\n255 255 255 255\n255 255 255 255\n";
  const World w = LoadWorldFile(pgm_path);
  std::remove(pgm_path.c_str());
  REQUIRE(w.segments.size() == 4);
  double x0, y0, x1, y1;
  w.Bounds(&x0, &y0, &x1, &y1);
  CHECK(w.rooms.size() == 1);
  CHECK(w.rooms[0].xmax == Approx(0.20));
  CHECK(w.rooms[0].ymax == Approx(0.15));
}

TEST_CASE("PGM floor plans merge wall edges into runs", "[world]") {
  // Binary 5 x 2 image: a dark bar of 3 pixels on the bottom row.
  std::string pgm = "P5 5 2 255\n";
  const unsigned char px[] = {255, 255, 255, 255, 255, 255, 0, 0, 0, 255};
  pgm.append(reinterpret_cast<const char*>(px), sizeof(px));
  const World w = ParsePgmWorld(pgm, "bar.pgm", 0.1, Vec2{1.0, 2.0});
  REQUIRE(w.segments.size() == 4);  // top, bottom, left, right of the bar
  CHECK_THROWS_WITH(ParsePgmWorld("P6 1 1 255\n", "x.pgm", 0.1, Vec2{}), "x.pgm: not a PGM file (magic 'P6')");
  CHECK_THROWS_WITH(ParsePgmWorld("P5 4 4 255\n\x01", "x.pgm", 0.1, Vec2{}), "x.pgm: PGM pixel data truncated");
}

TEST_CASE("Built-in worlds load with rooms, doors and a start", "[world]") {
  for (const std::string& name : BuiltinWorldNames()) {
    INFO(name);
    const World w = LoadBuiltinWorld(name);
    CHECK(w.name == name);
    CHECK(w.rooms.size() >= 3);
    CHECK(w.doors.size() >= 2);
    CHECK(w.has_start);
  }
  const World apartment = LoadBuiltinWorld("apartment");
  double area = 0.0;
  for (const Room& r : apartment.rooms) area += (r.xmax - r.xmin) * (r.ymax - r.ymin);
  CHECK(area == Approx(100.0).margin(10.0));
  CHECK(apartment.materials[static_cast<std::size_t>(apartment.FindMaterial("black"))].return_probability < 0.1);
  CHECK_THROWS_AS(LoadBuiltinWorld("castle"), WorldError);
}
