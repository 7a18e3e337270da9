// The dominant wall direction of one scan (core/geometry/wall_direction.hpp): found within a degree
// in a noisy room at any heading, not found in clutter or a scan too sparse to tell.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "core/geometry/wall_direction.hpp"
#include "tests/core/cabinet_room.hpp"

namespace {

constexpr float kDeg = dpcr::kPi / 180.0f;

// The cabinet room seen from (2.0, 1.5) at `heading`: 450 returns in beam order, in the robot frame,
// with Gaussian range noise `sigma_m` (an LD06's is 1-3 cm).
std::vector<dpcr::Point2> RoomScan(float heading, float sigma_m, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, sigma_m);
  std::vector<dpcr::Point2> points;
  for (int b = 0; b < 450; ++b) {
    const float beam = -dpcr::kPi + 2.0f * dpcr::kPi * static_cast<float>(b) / 450.0f;
    const float r = dpcr::test::CabinetRoomRange(2.0f, 1.5f, heading + beam) + noise(rng);
    points.push_back(dpcr::Point2{r * std::cos(beam), r * std::sin(beam)});
  }
  return points;
}

// a - b modulo 90 degrees, in (-45, 45].
float Mod90(float a, float b) { return 0.25f * dpcr::NormalizeAngle(4.0f * (a - b)); }

}  // namespace

TEST_CASE("The wall direction is found within a degree at any heading of a noisy scan") {
  for (const float heading_deg : {0.0f, 2.0f, -5.0f, 17.0f, 40.0f, 44.0f, 90.0f, -133.0f}) {
    const auto points = RoomScan(heading_deg * kDeg, 0.02f, 7u);
    const dpcr::WallDirection d = dpcr::DominantWallDirection(dpcr::Span<const dpcr::Point2>(points.data(), points.size()),
                                                              dpcr::WallDirectionConfig{});
    INFO("heading " << heading_deg << " deg: found " << d.found << ", angle " << d.angle_rad / kDeg << " deg, pieces "
                    << d.pieces << ", agreement " << d.agreement);
    REQUIRE(d.found);
    // The room's walls run along the world's axes: in the robot frame they lie at -heading.
    CHECK(std::fabs(Mod90(d.angle_rad, -heading_deg * kDeg)) < 1.0f * kDeg);
    CHECK(d.angle_rad >= -0.25f * dpcr::kPi);
    CHECK(d.angle_rad < 0.25f * dpcr::kPi);
  }
}

TEST_CASE("Clutter and a sparse scan give no wall direction") {
  std::mt19937 rng(3u);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  std::vector<dpcr::Point2> clutter;
  for (int i = 0; i < 450; ++i) clutter.push_back(dpcr::Point2{u(rng), u(rng)});
  CHECK_FALSE(dpcr::DominantWallDirection(dpcr::Span<const dpcr::Point2>(clutter.data(), clutter.size()),
                                          dpcr::WallDirectionConfig{})
                  .found);
  // A spin-up revolution: a dozen returns of a room.
  const auto room = RoomScan(0.3f, 0.01f, 5u);
  std::vector<dpcr::Point2> sparse;
  for (std::size_t i = 0; i < room.size(); i += 37) sparse.push_back(room[i]);
  CHECK_FALSE(
      dpcr::DominantWallDirection(dpcr::Span<const dpcr::Point2>(sparse.data(), sparse.size()), dpcr::WallDirectionConfig{})
          .found);
}
