// The kept start scans on their own (core/front_end/start_scans.hpp): what is kept reads back as it
// was placed, the gyro's turn is unwrapped, keeping stops where it should, the tiles come from the
// pool and go back, and the fit finds a known offset and bias.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "core/front_end/start_scans.hpp"
#include "core/grid/tile_pool.hpp"

namespace {

using dpcr::Point2;
using dpcr::Pose2;
using dpcr::StartScans;

constexpr std::int64_t kSecond = 1'000'000;

struct Pool {
  explicit Pool(std::size_t tiles) : storage(tiles), pool(dpcr::Span<dpcr::Tile>(storage.data(), storage.size())) {}
  std::vector<dpcr::Tile> storage;
  dpcr::TilePool pool;
};

std::vector<Point2> Ring(int n, float radius) {
  std::vector<Point2> points;
  for (int i = 0; i < n; ++i) {
    const float a = 6.2831853f * static_cast<float>(i) / static_cast<float>(n);
    points.push_back(Point2{radius * std::cos(a), radius * std::sin(a)});
  }
  return points;
}

}  // namespace

TEST_CASE("A kept start scan reads back where it was placed in the first map") {
  Pool p(256);
  dpcr::StartScansConfig config;
  StartScans scans;
  scans.Reset(&p.pool);
  REQUIRE(scans.Begin(&p.pool, 5 * kSecond, 0.3f, false));
  const Pose2 in_map{1.5f, -0.7f, 0.4f};
  const std::vector<Point2> hits = Ring(400, 3.0f);  // more than a kept scan holds: thinned evenly
  scans.Keep(&p.pool, 5 * kSecond, in_map, dpcr::Span<const Point2>(hits.data(), hits.size()));
  REQUIRE(scans.size() == 1);
  const StartScans::Kept k = scans.kept(p.pool, 0);
  CHECK(k.t_s == Approx(0.0f));
  CHECK(k.heading_less_turn_rad == Approx(0.4f).margin(1e-6));
  REQUIRE(k.points == 100);  // 400 hits, every fourth
  std::vector<Point2> out(StartScans::kMaxPoints);
  REQUIRE(scans.Points(p.pool, 0, dpcr::Span<Point2>(out.data(), out.size())) == 100);
  for (int i = 0; i < 100; ++i) {
    const Point2 expected = in_map.Apply(hits[static_cast<std::size_t>(4 * i)]);
    CHECK(std::fabs(out[static_cast<std::size_t>(i)].x - expected.x) <= 0.0006f);
    CHECK(std::fabs(out[static_cast<std::size_t>(i)].y - expected.y) <= 0.0006f);
  }
}

TEST_CASE("The gyro turn since the start is unwrapped scan by scan") {
  Pool p(256);
  dpcr::StartScansConfig config;
  StartScans scans;
  scans.Reset(&p.pool);
  REQUIRE(scans.Begin(&p.pool, 0, 3.0f, false));
  const std::vector<Point2> hits = Ring(50, 2.0f);
  // Three quarter turns past the yaw's wrap at pi: the turn is 4.5 rad, not 4.5 - 2 pi.
  scans.Track(kSecond / 2, true, 3.0f + 1.5f - 6.2831853f, config);
  scans.Track(kSecond, true, 3.0f + 3.0f - 6.2831853f, config);
  scans.Track(3 * kSecond / 2, true, 3.0f + 4.5f - 6.2831853f, config);
  const Pose2 in_map{0.0f, 0.0f, 0.2f};
  scans.Keep(&p.pool, 3 * kSecond / 2, in_map, dpcr::Span<const Point2>(hits.data(), hits.size()));
  const StartScans::Kept k = scans.kept(p.pool, 0);
  CHECK(k.t_s == Approx(1.5f));
  // heading less turn: 0.2 - 4.5, wrapped
  CHECK(k.heading_less_turn_rad == Approx(dpcr::NormalizeAngle(0.2f - 4.5f)).margin(1e-5));
}

TEST_CASE("Start scans are kept every_s apart, up to capacity, until the window ends or the gyro goes") {
  Pool p(256);
  dpcr::StartScansConfig config;
  config.window_s = 10.0f;
  config.every_s = 0.29f;  // the scans below come every 0.1 s: one in three
  const std::vector<Point2> hits = Ring(60, 2.0f);
  const dpcr::Span<const Point2> span(hits.data(), hits.size());
  StartScans scans;
  scans.Reset(&p.pool);
  REQUIRE(scans.Begin(&p.pool, 0, 0.0f, false));
  REQUIRE(scans.Due(p.pool, 0, config));
  scans.Keep(&p.pool, 0, Pose2::Identity(), span);
  CHECK_FALSE(scans.Due(p.pool, kSecond / 10, config));  // too soon
  for (std::int64_t t = kSecond / 10; t <= 12 * kSecond; t += kSecond / 10) {
    scans.Track(t, true, 0.0f, config);
    if (scans.Due(p.pool, t, config)) scans.Keep(&p.pool, t, Pose2::Identity(), span);
  }
  CHECK(scans.size() == StartScans::kMaxKept);  // 10 s at 0.3 s would be 34: capacity first
  for (int i = 1; i < scans.size(); ++i) CHECK(scans.kept(p.pool, i).t_s - scans.kept(p.pool, i - 1).t_s == Approx(0.3f));

  // The window.
  scans.Reset(&p.pool);
  REQUIRE(scans.Begin(&p.pool, 0, 0.0f, false));
  scans.Track(11 * kSecond, true, 0.0f, config);
  CHECK_FALSE(scans.keeping());
  CHECK_FALSE(scans.Due(p.pool, 11 * kSecond, config));
  // A missing gyro yaw: what is kept stays, nothing more is kept.
  scans.Reset(&p.pool);
  REQUIRE(scans.Begin(&p.pool, 0, 0.0f, false));
  scans.Keep(&p.pool, 0, Pose2::Identity(), span);
  scans.Track(kSecond, false, 0.0f, config);
  CHECK_FALSE(scans.keeping());
  CHECK(scans.size() == 1);
}

TEST_CASE("Start scans borrow tiles from the pool and give them back") {
  SECTION("borrowed and returned") {
    Pool p(256);
    StartScans scans;
    scans.Reset(&p.pool);
    REQUIRE(scans.Begin(&p.pool, 0, 0.0f, false));
    CHECK(p.pool.used() == static_cast<std::size_t>(StartScans::kTiles));
    CHECK(scans.holds_tiles());
    scans.Release(&p.pool);
    CHECK(p.pool.used() == 0);
    CHECK(scans.size() == 0);
    CHECK_FALSE(scans.holds_tiles());
    CHECK(scans.start_stamp_us() == 0);
    // A second Begin after a Reset borrows again (here with the wheels' heading, which the front
    // end uses only if the ticks turn out to carry an IMU's), and Reset gives them back.
    REQUIRE(scans.Begin(&p.pool, 7, 0.0f, true));
    CHECK(scans.wheel_turns());
    scans.Reset(&p.pool);
    CHECK(p.pool.used() == 0);
  }
  SECTION("a small pool keeps none") {
    Pool p(StartScans::kMinPoolTiles - 1);
    StartScans scans;
    scans.Reset(&p.pool);
    CHECK_FALSE(scans.Begin(&p.pool, 0, 0.0f, false));
    CHECK(p.pool.used() == 0);
  }
  SECTION("a pool without enough free tiles keeps none and loses none") {
    Pool p(StartScans::kMinPoolTiles);
    while (p.pool.used() + 2 < p.pool.capacity()) (void)p.pool.Allocate();
    const std::size_t used = p.pool.used();
    StartScans scans;
    scans.Reset(&p.pool);
    CHECK_FALSE(scans.Begin(&p.pool, 0, 0.0f, false));
    CHECK(p.pool.used() == used);
    CHECK_FALSE(scans.holds_tiles());
  }
}

TEST_CASE("The start offset fit finds a known offset and gyro bias") {
  Pool p(256);
  dpcr::StartScansConfig config;
  StartScans scans;
  scans.Reset(&p.pool);
  const float start_heading = 0.1f, offset = 0.004f, bias = 0.002f;
  REQUIRE(scans.Begin(&p.pool, 0, 0.0f, false));
  const std::vector<Point2> hits = Ring(30, 2.0f);
  float yaw = 0.0f;
  std::vector<float> registered;
  for (int i = 0; i < 20; ++i) {
    const std::int64_t t = i * kSecond / 2;
    const float t_s = static_cast<float>(t) * 1e-6f;
    // The robot turns 0.1 rad per step; the gyro adds its bias; the map placed the scan then at
    // a heading the registration against the finished map corrects by `registered`.
    const float true_turn = 0.1f * static_cast<float>(i);
    if (i > 0) {
      yaw = dpcr::NormalizeAngle(true_turn + bias * t_s);
      scans.Track(t, true, yaw, config);
    }
    const float then = start_heading + true_turn + 0.003f * std::sin(static_cast<float>(i));
    const float finished = start_heading + offset + true_turn + 0.0002f * (static_cast<float>(i % 3) - 1.0f);
    registered.push_back(finished - then);
    scans.Keep(&p.pool, t, Pose2{0.0f, 0.0f, then}, dpcr::Span<const Point2>(hits.data(), hits.size()));
  }
  REQUIRE(scans.size() == 20);
  dpcr::StartOffsetFit fit;
  REQUIRE(dpcr::FitStartOffset(scans, p.pool, registered.data(), start_heading, config, &fit));
  CHECK(fit.scans == 20);
  CHECK(fit.offset_rad == Approx(offset).margin(2e-4));
  CHECK(fit.bias_rad_s == Approx(bias).margin(1e-4));
  // The residuals are the 0.0002 rad pattern above: the offset's standard error is of its size
  // over the square root of the scans, not zero and not the offset's.
  CHECK(fit.offset_se_rad > 1e-5f);
  CHECK(fit.offset_se_rad < 2e-4f);

  // Refused registrations do not count; too few left: no fit.
  std::vector<float> few(registered);
  for (std::size_t i = static_cast<std::size_t>(config.min_scans) - 1; i < few.size(); ++i) few[i] = NAN;
  CHECK_FALSE(dpcr::FitStartOffset(scans, p.pool, few.data(), start_heading, config, &fit));
  CHECK(fit.scans == config.min_scans - 1);
  // An offset past the bound is refused (and still reported).
  std::vector<float> far(registered);
  for (float& r : far) r += 0.1f;
  CHECK_FALSE(dpcr::FitStartOffset(scans, p.pool, far.data(), start_heading, config, &fit));
  CHECK(fit.offset_rad == Approx(offset + 0.1f).margin(2e-4));
}
