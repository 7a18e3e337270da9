#include "host_sim/sim/world.hpp"
#include "tests/support/temp_dir.hpp"

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
  CHECK(ErrorOf("wall 4 0 4 4\nwall 4 1 4 6\n") == "w.txt:2: world has no area (its walls lie on one line) and no room");
  CHECK(ErrorOf("wall 4 0 4 4\nroom r 0 0 4 4\n").empty());
  CHECK(ErrorOf("box 0 0 4 3\n").empty());
}

TEST_CASE("World files load by extension, missing files fail clearly", "[world]") {
  const dpcr::test::ScopedTempDir dir("world_files");
  const std::string text_path = (dir.path() / "test.world").string();
  std::ofstream(text_path) << "box 0 0 2 2\n";
  CHECK(LoadWorldFile(text_path).segments.size() == 4);
  CHECK_THROWS_WITH(LoadWorldFile("/nonexistent/x.world"), "/nonexistent/x.world: cannot open world file");

  // 4 x 3 plain PGM, one dark pixel at column 1, row 0 (top): a 5 cm square at y in [0.10, 0.15].
  const std::string pgm_path = (dir.path() / "test.pgm").string();
  std::ofstream(pgm_path) << "P2\n# comment\n4 3\n255\n255 0 255 255\n255 255 255 255\n255 255 255 255\n";
  const World w = LoadWorldFile(pgm_path);
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

TEST_CASE("Worlds too big or too far for a simulated floor are refused before anything is built", "[world]") {
  // A 5 km box once took the simulator to 2.7 GB and a crash, a 1 km one never started.
  CHECK(ErrorOf("box 0 0 500 400\n") == "w.txt: world spans 500 m x 400 m, more than the 200 m a side a simulated floor may");
  CHECK(ErrorOf("box 0 0 5000 5000\n").find("w.txt: world reaches past 1000 m from the origin") == 0);
  CHECK(ErrorOf("box 0 0 200 150\n").empty());
  CHECK(ErrorOf("box 0 0 4 3\nroom far 0 0 4 300\n").find("w.txt: world spans 4 m x 300 m") == 0);
  CHECK(ErrorOf("box 5000 5000 5004 5003\n").find("w.txt: world reaches past 1000 m from the origin") == 0);
  CHECK(ErrorOf("box 0 0 4 3\nstart 1e6 0 0\n").find("w.txt: world reaches past 1000 m") == 0);
  // A PGM's footprint counts, resolution and origin included.
  const std::string one_dark_pixel = "P2 1 1 255 0\n";
  CHECK_NOTHROW(ParsePgmWorld(one_dark_pixel, "x.pgm", 0.05, Vec2{-100.0, -100.0}));
  CHECK_THROWS_WITH(ParsePgmWorld(one_dark_pixel, "x.pgm", 500.0, Vec2{}),
                    "x.pgm: world spans 500 m x 500 m, more than the 200 m a side a simulated floor may");
  CHECK_THROWS_WITH(ParsePgmWorld(one_dark_pixel, "x.pgm", 0.05, Vec2{1e300, 0.0}),
                    Catch::StartsWith("x.pgm: world reaches past 1000 m"));
}

TEST_CASE("A PGM header promising more pixels than the file holds is refused without allocating them", "[world]") {
  // 10^10 pixels (10 GB of raster) from a 24-byte file: refused at once, P5 or P2.
  CHECK_THROWS_WITH(ParsePgmWorld("P5 100000 100000 255\n\x01", "x.pgm", 0.05, Vec2{}), "x.pgm: PGM pixel data truncated");
  CHECK_THROWS_WITH(ParsePgmWorld("P2 100000 100000 255\n0 0 0", "x.pgm", 0.05, Vec2{}), "x.pgm: PGM pixel data truncated");
  // Plain-PGM pixels are numbers within [0, maxval].
  CHECK_THROWS_WITH(ParsePgmWorld("P2 2 1 255 0 99999999999999999999\n", "x.pgm", 0.05, Vec2{}),
                    "x.pgm: bad PGM pixel '99999999999999999999'");
  CHECK_THROWS_WITH(ParsePgmWorld("P2 2 1 255 0 -3\n", "x.pgm", 0.05, Vec2{}), "x.pgm: bad PGM pixel '-3'");
  CHECK_THROWS_WITH(ParsePgmWorld("P2 2 1 255 0 12x\n", "x.pgm", 0.05, Vec2{}), "x.pgm: bad PGM pixel '12x'");
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
