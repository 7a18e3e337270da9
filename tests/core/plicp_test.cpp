// Improved and classic PLICP: exact recovery, outliers, degenerate corridors, real submaps.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <Eigen/LU>

#include "core/registration/classic_plicp.hpp"
#include "core/registration/plicp.hpp"
#include "registration_fixtures.hpp"

using dpcr::Point2;
using dpcr::Pose2;
using dpcr_test::GridFixture;
using dpcr_test::Segment;
using dpcr_test::C;
using dpcr_test::SpanOf;

namespace {

std::vector<Segment> LRoom() {
  const Point2 p0{C(20), C(20)}, p1{C(180), C(20)}, p2{C(180), C(100)}, p3{C(110), C(100)}, p4{C(110), C(180)},
      p5{C(20), C(180)};
  std::vector<Segment> w = {{p0, p1}, {p1, p2}, {p2, p3}, {p3, p4}, {p4, p5}, {p5, p0}};
  // A cupboard: a box inside the room.
  const Point2 b0{C(60), C(60)}, b1{C(80), C(60)}, b2{C(80), C(72)}, b3{C(60), C(72)};
  w.insert(w.end(), {{b0, b1}, {b1, b2}, {b2, b3}, {b3, b0}});
  return w;
}

// A submap as the robot builds it: 10 noisy 450-beam scans from poses along a short arc.
void InsertNoisyScans(GridFixture& f, const std::vector<Segment>& walls) {
  for (int k = 0; k < 10; ++k) {
    const Pose2 p{3.0f + 0.1f * static_cast<float>(k), 2.5f + 0.05f * static_cast<float>(k), 0.05f * static_cast<float>(k)};
    dpcr_test::InsertScan(f, dpcr_test::SimulateScan(walls, p, 450, 0.02f, 10u + static_cast<unsigned>(k)), p,
                          static_cast<std::uint32_t>(k + 1));
  }
}

float PosErr(Pose2 a, Pose2 b) { return std::hypot(a.x - b.x, a.y - b.y); }
float AngErr(Pose2 a, Pose2 b) { return std::fabs(dpcr::NormalizeAngle(a.theta - b.theta)); }

constexpr float kDeg = dpcr::kPi / 180.0f;

}  // namespace

TEST_CASE("Improved PLICP recovers a known transform exactly on noiseless data") {
  GridFixture f;
  const auto walls = LRoom();
  for (const Segment& w : walls) f.Draw(w);
  REQUIRE(f.Build() == dpcr::Status::kOk);
  const Pose2 truth{4.0f, 3.0f, 0.3f};
  const auto scan = dpcr_test::SimulateScan(walls, truth, 450, 0.0f, 1);
  const Pose2 start{truth.x + 0.15f, truth.y - 0.1f, truth.theta + 4.0f * kDeg};
  const auto r = dpcr::RegisterImproved(*f.ref, SpanOf(scan), start, nullptr, dpcr::PlicpConfig{});
  CHECK(r.verdict == dpcr::Status::kOk);
  CHECK(PosErr(r.pose, truth) < 0.002f);
  CHECK(AngErr(r.pose, truth) < 0.05f * kDeg);
  CHECK(r.mean_residual_m < 0.002f);
  CHECK(r.inlier_ratio > 0.9f);
  CHECK_FALSE(r.degenerate);
  CHECK(r.hessian.determinant() > 0.0f);
}

TEST_CASE("Both methods register a noisy scan against a ray-cast submap to 2-3 cm and 0.5 deg") {
  GridFixture f;
  const auto walls = LRoom();
  InsertNoisyScans(f, walls);
  REQUIRE(f.Build() == dpcr::Status::kOk);
  const Pose2 truth{4.1f, 3.0f, 0.55f};
  const auto scan = dpcr_test::SimulateScan(walls, truth, 450, 0.02f, 99);
  const Pose2 start{truth.x - 0.1f, truth.y + 0.08f, truth.theta - 3.0f * kDeg};
  const auto improved = dpcr::RegisterImproved(*f.ref, SpanOf(scan), start, nullptr, dpcr::PlicpConfig{});
  const auto classic = dpcr::RegisterClassic(*f.ref, SpanOf(scan), start, nullptr, dpcr::PlicpConfig{});
  INFO("improved " << improved.pose.x << " " << improved.pose.y << " " << improved.pose.theta << " it "
                   << improved.iterations << "; classic " << classic.pose.x << " " << classic.pose.y << " "
                   << classic.pose.theta << " it " << classic.iterations);
  CHECK(improved.verdict == dpcr::Status::kOk);
  CHECK(PosErr(improved.pose, truth) < 0.02f);
  CHECK(AngErr(improved.pose, truth) < 0.5f * kDeg);
  // The classic method matches the two nearest obstacle cells. The hit margin (GridConfig::
  // hit_margin_m) leaves the cell in front of a noisy wall occupied more often, which pulls those
  // cells towards the viewer: 2.6 cm here, against 0.6 cm for the line-feature method.
  CHECK(PosErr(classic.pose, truth) < 0.03f);
  CHECK(AngErr(classic.pose, truth) < 0.5f * kDeg);
}

TEST_CASE("Improved PLICP survives 30 percent outliers (people, chair legs)") {
  GridFixture f;
  const auto walls = LRoom();
  for (const Segment& w : walls) f.Draw(w);
  REQUIRE(f.Build() == dpcr::Status::kOk);
  const Pose2 truth{4.0f, 3.0f, -0.4f};
  auto scan = dpcr_test::SimulateScan(walls, truth, 450, 0.01f, 5);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> range(0.3f, 3.0f), angle(-dpcr::kPi, dpcr::kPi);
  for (std::size_t i = 0; i < scan.size(); i += 1) {
    if (i % 10 < 3) {  // 30 % of the beams hit something that is not in the map
      const float a = angle(rng), r = range(rng);
      scan[i] = Point2{r * std::cos(a), r * std::sin(a)};
    }
  }
  const Pose2 start{truth.x + 0.1f, truth.y + 0.1f, truth.theta + 3.0f * kDeg};
  const auto r = dpcr::RegisterImproved(*f.ref, SpanOf(scan), start, nullptr, dpcr::PlicpConfig{});
  INFO("pose " << r.pose.x << " " << r.pose.y << " " << r.pose.theta << " inliers " << r.inlier_ratio);
  CHECK(PosErr(r.pose, truth) < 0.02f);
  CHECK(AngErr(r.pose, truth) < 0.5f * kDeg);
  CHECK(r.verdict == dpcr::Status::kOk);
}

// Legs (a circle of radius 0.12 m) centred at `centre` in the robot frame, in front of the walls:
// the beams that reach them return from them.
void AddLegs(std::vector<Point2>* scan, Point2 centre, float radius) {
  for (Point2& p : *scan) {
    const float range = std::hypot(p.x, p.y);
    const Point2 dir{p.x / range, p.y / range};
    const float along = dir.x * centre.x + dir.y * centre.y;
    const float off2 = centre.x * centre.x + centre.y * centre.y - along * along;
    if (along <= 0.0f || off2 > radius * radius) continue;
    const float d = along - std::sqrt(radius * radius - off2);
    if (d < range) p = Point2{d * dir.x, d * dir.y};
  }
}

TEST_CASE("A person walking beside the robot does not outweigh the room when near points weigh less") {
  // The reference holds the room and the person where they were a moment ago; they walked on
  // with the robot, so the scan sees them in the same place around it: they pull the match back.
  const auto walls = LRoom();
  float plain_sum = 0.0f, weighted_sum = 0.0f;
  for (int k = 0; k < 8; ++k) {
    const float a = 0.785f * static_cast<float>(k);
    const Pose2 before{C(70), C(40), a};
    const Pose2 truth{before.x + 0.06f * std::cos(a), before.y + 0.06f * std::sin(a), a};
    // Two people, one each side, a little ahead.
    const Point2 legs[2] = {{0.3f * std::cos(1.2f), 0.3f * std::sin(1.2f)}, {0.3f * std::cos(-1.9f), 0.3f * std::sin(-1.9f)}};
    GridFixture f;
    for (const Segment& w : walls) f.Draw(w);
    auto scan = dpcr_test::SimulateScan(walls, truth, 450, 0.01f, 40u + static_cast<unsigned>(k));
    for (const Point2& l : legs) {
      const Point2 legs_before = before.Apply(l);
      for (int i = 0; i < 64; ++i) {
        const float t = 0.09817477f * static_cast<float>(i);
        f.Mark(Point2{legs_before.x + 0.12f * std::cos(t), legs_before.y + 0.12f * std::sin(t)});
      }
      AddLegs(&scan, l, 0.12f);
    }
    REQUIRE(f.Build() == dpcr::Status::kOk);
    const dpcr::PosePrior prior{truth, 20.0f, 20.0f};
    dpcr::PlicpConfig config;
    const auto plain = dpcr::RegisterImproved(*f.ref, SpanOf(scan), truth, &prior, config);
    config.near_weight_range_m = 0.5f;
    const auto weighted = dpcr::RegisterImproved(*f.ref, SpanOf(scan), truth, &prior, config);
    CHECK(weighted.verdict == dpcr::Status::kOk);
    plain_sum += PosErr(plain.pose, truth);
    weighted_sum += PosErr(weighted.pose, truth);
  }
  // Millimetres either way with the prior at the truth, but the pull is the people's: about halved.
  INFO("mean error plain " << plain_sum / 8.0f << " m, weighted " << weighted_sum / 8.0f << " m");
  CHECK(weighted_sum < 0.7f * plain_sum);
}

TEST_CASE("A featureless corridor is flagged degenerate, and the odometry prior stops the slide") {
  GridFixture f;
  const std::vector<Segment> walls = {{{C(2), C(40)}, {C(250), C(40)}}, {{C(2), C(76)}, {C(250), C(76)}}};
  for (const Segment& w : walls) f.Draw(w);
  REQUIRE(f.Build() == dpcr::Status::kOk);
  const Pose2 truth{6.0f, 2.9f, 0.1f};
  const auto scan = dpcr_test::SimulateScan(walls, truth, 450, 0.01f, 3, 4.0f);
  const Pose2 start{truth.x + 0.2f, truth.y + 0.05f, truth.theta + 2.0f * kDeg};

  const auto free_run = dpcr::RegisterImproved(*f.ref, SpanOf(scan), start, nullptr, dpcr::PlicpConfig{});
  CHECK(free_run.degenerate);
  CHECK(free_run.verdict == dpcr::Status::kRejected);

  // Odometry says we are at `start` (0.2 m off along the corridor, which no scan can tell).
  dpcr::PosePrior prior{start, 50.0f, 50.0f};
  const auto with_prior = dpcr::RegisterImproved(*f.ref, SpanOf(scan), start, &prior, dpcr::PlicpConfig{});
  CHECK(with_prior.degenerate);
  CHECK(with_prior.verdict == dpcr::Status::kOk);
  CHECK(std::fabs(with_prior.pose.x - start.x) < 0.01f);        // no slide along the corridor
  CHECK(std::fabs(with_prior.pose.y - truth.y) < 0.01f);        // across it: corrected
  CHECK(AngErr(with_prior.pose, truth) < 0.5f * kDeg);
}

TEST_CASE("Registration against an empty reference reports not enough data") {
  GridFixture f;
  REQUIRE(f.Build() == dpcr::Status::kOk);
  const std::vector<Point2> scan(100, Point2{1.0f, 0.0f});
  const auto r = dpcr::RegisterImproved(*f.ref, SpanOf(scan), Pose2{3.0f, 3.0f, 0.0f}, nullptr, dpcr::PlicpConfig{});
  CHECK(r.verdict == dpcr::Status::kNotEnoughData);
  CHECK(r.pose.x == 3.0f);
}

TEST_CASE("A correction beyond what odometry makes plausible is rejected") {
  GridFixture f;
  const auto walls = LRoom();
  for (const Segment& w : walls) f.Draw(w);
  REQUIRE(f.Build() == dpcr::Status::kOk);
  const Pose2 truth{4.0f, 3.0f, 0.3f};
  const auto scan = dpcr_test::SimulateScan(walls, truth, 450, 0.0f, 1);
  dpcr::PlicpConfig config;
  config.max_correction_m = 0.05f;
  const auto r = dpcr::RegisterImproved(*f.ref, SpanOf(scan), Pose2{4.15f, 3.0f, 0.3f}, nullptr, config);
  INFO("pose " << r.pose.x << " " << r.pose.y << " " << r.pose.theta << " it " << r.iterations << " in " << r.inliers);
  CHECK(PosErr(r.pose, truth) < 0.01f);
  CHECK(r.verdict == dpcr::Status::kRejected);
}

TEST_CASE("Second registration: obstacle cells of one grid against the lines of another") {
  // Grid A (the "regional map") from scans at true poses; grid B (the "submap") from other scans,
  // built in a frame rotated and shifted by a known transform; B's obstacle cells are the target.
  const auto walls = LRoom();
  GridFixture a, b;
  const Pose2 b_in_a{0.12f, -0.08f, 3.0f * kDeg};  // the submap frame in the regional map frame
  for (int k = 0; k < 8; ++k) {
    const Pose2 p{3.0f + 0.2f * static_cast<float>(k), 2.5f + 0.1f * static_cast<float>(k), 0.1f * static_cast<float>(k)};
    dpcr_test::InsertScan(a, dpcr_test::SimulateScan(walls, p, 450, 0.01f, 30u + static_cast<unsigned>(k)), p,
                          static_cast<std::uint32_t>(k + 1));
    const Pose2 q{p.x + 0.1f, p.y + 0.15f, p.theta + 0.05f};
    dpcr_test::InsertScan(b, dpcr_test::SimulateScan(walls, q, 450, 0.01f, 60u + static_cast<unsigned>(k)),
                          b_in_a.Inverse() * q, static_cast<std::uint32_t>(k + 1));
  }
  REQUIRE(a.Build() == dpcr::Status::kOk);
  REQUIRE(b.Build() == dpcr::Status::kOk);
  std::vector<Point2> cells;
  for (std::uint16_t i = 0; i < b.ref->cell_count(); ++i) cells.push_back(b.ref->ObstaclePoint(i));
  REQUIRE(cells.size() > 200);
  const Pose2 start{0.0f, 0.0f, 0.0f};  // the drift estimate before the second registration
  const auto r = dpcr::RegisterImproved(*a.ref, SpanOf(cells), start, nullptr, dpcr::PlicpConfig{});
  INFO("pose " << r.pose.x << " " << r.pose.y << " " << r.pose.theta / kDeg << " deg, it " << r.iterations);
  CHECK(r.verdict == dpcr::Status::kOk);
  CHECK(PosErr(r.pose, b_in_a) < 0.02f);
  CHECK(AngErr(r.pose, b_in_a) < 0.5f * kDeg);
}

TEST_CASE("Improved PLICP converges from 40 seeded random starts within 0.3 m and 10 deg") {
  GridFixture f;
  const auto walls = LRoom();
  InsertNoisyScans(f, walls);
  REQUIRE(f.Build() == dpcr::Status::kOk);
  const Pose2 truth{4.1f, 3.0f, 0.55f};
  const auto scan = dpcr_test::SimulateScan(walls, truth, 450, 0.02f, 99);
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> t(-0.3f, 0.3f), a(-10.0f * kDeg, 10.0f * kDeg);
  int ok = 0;
  for (int i = 0; i < 40; ++i) {
    const Pose2 start{truth.x + t(rng) / 1.4142f, truth.y + t(rng) / 1.4142f, truth.theta + a(rng)};
    const auto r = dpcr::RegisterImproved(*f.ref, SpanOf(scan), start, nullptr, dpcr::PlicpConfig{});
    ok += PosErr(r.pose, truth) < 0.02f && AngErr(r.pose, truth) < 0.5f * kDeg && r.verdict == dpcr::Status::kOk;
  }
  CHECK(ok == 40);
}

TEST_CASE("A reference of clutter only (pillars, no line features) still registers through the fallbacks") {
  GridFixture f;
  std::vector<Segment> pillars;  // 10 cm square pillars: too short to be lines
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 4; ++j) {
      const float x = 1.5f + 1.1f * static_cast<float>(i) + 0.013f, y = 1.5f + 1.3f * static_cast<float>(j) + 0.011f;
      const Point2 a{x, y}, b{x + 0.1f, y}, c{x + 0.1f, y + 0.1f}, d{x, y + 0.1f};
      pillars.insert(pillars.end(), {{a, b}, {b, c}, {c, d}, {d, a}});
    }
  }
  for (const Segment& s : pillars) f.Draw(s);
  REQUIRE(f.Build() == dpcr::Status::kOk);
  CHECK(f.ref->line_count() == 0);
  const Pose2 truth{3.9f, 3.4f, 0.2f};
  const auto scan = dpcr_test::SimulateScan(pillars, truth, 450, 0.005f, 8);
  const Pose2 start{truth.x + 0.06f, truth.y - 0.05f, truth.theta + 2.0f * kDeg};
  const auto r = dpcr::RegisterImproved(*f.ref, SpanOf(scan), start, nullptr, dpcr::PlicpConfig{});
  INFO("pose " << r.pose.x << " " << r.pose.y << " " << r.pose.theta << " it " << r.iterations);
  CHECK(PosErr(r.pose, truth) < 0.03f);
  CHECK(AngErr(r.pose, truth) < 1.0f * kDeg);
}

TEST_CASE("A noisy lidar's returns stay inliers when the trim floor is twice its noise") {
  // An LD06: sigma 1 cm + 0.5 % of the range. Censi's adaptive threshold follows the bulk of the
  // residuals (the near walls) and trims the far returns as outliers; a floor at twice the noise
  // at 3 m (FirstRegistrationPlicp: 5 cm) keeps them, and the pose holds.
  GridFixture f;
  const auto walls = LRoom();
  for (const Segment& w : walls) f.Draw(w);
  REQUIRE(f.Build() == dpcr::Status::kOk);
  const Pose2 truth{2.0f, 2.0f, 0.3f};  // in a corner: walls from 1 to 8 m away
  auto scan = dpcr_test::SimulateScan(walls, truth, 450, 0.0f, 1, 12.0f);
  std::mt19937 rng(7);
  std::normal_distribution<float> unit(0.0f, 1.0f);
  for (Point2& p : scan) {
    const float r = std::hypot(p.x, p.y), noisy = r + unit(rng) * (0.01f + 0.005f * r);
    p = Point2{p.x * noisy / r, p.y * noisy / r};
  }
  const Pose2 start{truth.x + 0.03f, truth.y - 0.02f, truth.theta + 1.0f * kDeg};
  dpcr::PlicpConfig floor_at_noise;
  floor_at_noise.trim_floor_m = 0.05f;
  const auto trimmed = dpcr::RegisterImproved(*f.ref, SpanOf(scan), start, nullptr, dpcr::PlicpConfig{});
  const auto kept = dpcr::RegisterImproved(*f.ref, SpanOf(scan), start, nullptr, floor_at_noise);
  INFO("inliers " << trimmed.inlier_ratio << " (3 cm floor) vs " << kept.inlier_ratio << " (5 cm)");
  REQUIRE(trimmed.verdict == dpcr::Status::kOk);
  REQUIRE(kept.verdict == dpcr::Status::kOk);
  CHECK(kept.inlier_ratio > trimmed.inlier_ratio + 0.02f);  // measured 0.907 -> 0.938
  CHECK(PosErr(kept.pose, truth) < 0.02f);
  CHECK(AngErr(kept.pose, truth) < 0.3f * kDeg);
}
