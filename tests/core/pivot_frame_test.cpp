// A cloud registered about its centroid: the helpers, and why (a prior about a far origin
// stiffens the cloud's turn by the lever arm).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "core/registration/pivot_frame.hpp"
#include "core/registration/plicp.hpp"
#include "registration_fixtures.hpp"

using dpcr::Point2;
using dpcr::Pose2;
using dpcr_test::C;

namespace {

constexpr float kDeg = dpcr::kPi / 180.0f;

// An L-shaped room with a cupboard: lines in every direction.
std::vector<dpcr_test::Segment> Room() {
  const Point2 p0{C(20), C(20)}, p1{C(180), C(20)}, p2{C(180), C(100)}, p3{C(110), C(100)}, p4{C(110), C(180)},
      p5{C(20), C(180)};
  const Point2 b0{C(60), C(60)}, b1{C(80), C(60)}, b2{C(80), C(72)}, b3{C(60), C(72)};
  return {{p0, p1}, {p1, p2}, {p2, p3}, {p3, p4}, {p4, p5}, {p5, p0}, {b0, b1}, {b1, b2}, {b2, b3}, {b3, b0}};
}

}  // namespace

TEST_CASE("A recentred cloud has its centroid at the origin and says where it was") {
  std::vector<Point2> pts = {{10.0f, 20.0f}, {12.0f, 20.0f}, {11.0f, 23.0f}};
  const Point2 c = dpcr::RecentreOnCentroid(dpcr::Span<Point2>(pts.data(), pts.size()));
  CHECK(c.x == Approx(11.0f));
  CHECK(c.y == Approx(21.0f));
  float sx = 0.0f, sy = 0.0f;
  for (const Point2& p : pts) {
    sx += p.x;
    sy += p.y;
  }
  CHECK(std::fabs(sx) < 1e-4f);
  CHECK(std::fabs(sy) < 1e-4f);
  const Point2 none = dpcr::RecentreOnCentroid(dpcr::Span<Point2>());
  CHECK(none.x == 0.0f);
  CHECK(none.y == 0.0f);
}

TEST_CASE("A frame's pose and its pivot's are one rigid motion apart") {
  const Pose2 frame{3.0f, -2.0f, 0.7f};
  const Point2 pivot{20.0f, 5.0f};
  const Pose2 p = dpcr::PivotPose(frame, pivot);
  // The pivot frame's origin is the pivot point seen from the frame.
  const Point2 seen = frame.Apply(pivot);
  CHECK(p.x == Approx(seen.x));
  CHECK(p.y == Approx(seen.y));
  CHECK(p.theta == Approx(frame.theta));
  const Pose2 back = dpcr::FramePose(p, pivot);
  CHECK(back.x == Approx(frame.x).margin(1e-4));
  CHECK(back.y == Approx(frame.y).margin(1e-4));
  CHECK(back.theta == Approx(frame.theta));
  // A turn of the frame about the pivot point is a pure turn for the pivot.
  const Pose2 turn_about_pivot = Pose2{pivot.x, pivot.y, 0.0f} * Pose2{0.0f, 0.0f, 0.1f} * Pose2{-pivot.x, -pivot.y, 0.0f};
  const Pose2 seen_by_pivot = dpcr::ChangeAboutPivot(turn_about_pivot, pivot);
  CHECK(std::fabs(seen_by_pivot.x) < 1e-4f);
  CHECK(std::fabs(seen_by_pivot.y) < 1e-4f);
  CHECK(seen_by_pivot.theta == Approx(0.1f));
}

TEST_CASE("A frame's information is its pivot's carried through the lever arm") {
  const Pose2 frame{1.0f, 2.0f, 0.4f};
  const Point2 pivot{15.0f, -6.0f};
  Eigen::Matrix3f pivot_info;
  pivot_info << 40.0f, 5.0f, 1.0f, 5.0f, 30.0f, -2.0f, 1.0f, -2.0f, 900.0f;
  // J = d PivotPose / d frame, by central differences.
  Eigen::Matrix3f j;
  const float h = 1e-3f;
  for (int k = 0; k < 3; ++k) {
    Pose2 up = frame, down = frame;
    (k == 0 ? up.x : k == 1 ? up.y : up.theta) += h;
    (k == 0 ? down.x : k == 1 ? down.y : down.theta) -= h;
    const Pose2 a = dpcr::PivotPose(up, pivot), b = dpcr::PivotPose(down, pivot);
    j(0, k) = (a.x - b.x) / (2.0f * h);
    j(1, k) = (a.y - b.y) / (2.0f * h);
    j(2, k) = dpcr::NormalizeAngle(a.theta - b.theta) / (2.0f * h);
  }
  const Eigen::Matrix3f expected = j.transpose() * pivot_info * j;
  const Eigen::Matrix3f got = dpcr::FrameInformation(pivot_info, frame, pivot);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) CHECK(got(r, c) == Approx(expected(r, c)).epsilon(0.01).margin(0.5));
  }
}

TEST_CASE("A cloud whose frame lies 25 m away turns as far as its points say only when posed about its centroid") {
  // The map: the room's cells. The cloud: the same cells seen from a frame 25 m from them (a
  // submap far from where the run started), whose pose is wrong by 1 deg about the cloud (the
  // robot's heading drifted). A prior at that pose, as the second registration keeps one.
  dpcr_test::GridFixture map;
  const auto walls = Room();
  for (const dpcr_test::Segment& w : walls) map.Draw(w);
  REQUIRE(map.Build() == dpcr::Status::kOk);
  const Pose2 frame_truth{-21.0f, -14.0f, 0.2f};  // the cloud's frame in the map
  std::vector<Point2> cloud;
  for (std::uint16_t i = 0; i < map.ref->cell_count(); i += 2) cloud.push_back(frame_truth.Inverse().Apply(map.ref->ObstaclePoint(i)));
  REQUIRE(cloud.size() > 100);
  std::vector<Point2> centred = cloud;
  const Point2 pivot = dpcr::RecentreOnCentroid(dpcr::Span<Point2>(centred.data(), centred.size()));
  REQUIRE(std::hypot(pivot.x, pivot.y) > 20.0f);
  const Pose2 drift{0.0f, 0.0f, 1.0f * kDeg};  // about the cloud's centroid
  const Pose2 start = dpcr::FramePose(dpcr::PivotPose(frame_truth, pivot) * drift, pivot);
  const dpcr::PlicpConfig config;

  // About the frame's origin: the prior holds the turn as 25 m x 1 deg = 0.44 m of translation.
  const dpcr::PosePrior far_prior{start, 20.0f, 20.0f};
  const auto far = dpcr::RegisterImproved(*map.ref, dpcr::Span<const Point2>(cloud.data(), cloud.size()), start,
                                          &far_prior, config);
  // About the centroid: the same prior holds a turn as a turn.
  const Pose2 pivot_start = dpcr::PivotPose(start, pivot);
  const dpcr::PosePrior near_prior{pivot_start, 20.0f, 20.0f};
  auto near = dpcr::RegisterImproved(*map.ref, dpcr::Span<const Point2>(centred.data(), centred.size()), pivot_start,
                                     &near_prior, config);
  near.pose = dpcr::FramePose(near.pose, pivot);
  const float far_error = std::fabs(dpcr::NormalizeAngle(far.pose.theta - frame_truth.theta));
  const float near_error = std::fabs(dpcr::NormalizeAngle(near.pose.theta - frame_truth.theta));
  INFO("heading error about the origin " << far_error / kDeg << " deg, about the centroid " << near_error / kDeg << " deg");
  CHECK(near.verdict == dpcr::Status::kOk);
  CHECK(near_error < 0.1f * kDeg);
  CHECK(std::hypot(near.pose.x - frame_truth.x, near.pose.y - frame_truth.y) < 0.05f);
  // The far-origin registration keeps a good part of the drift: the bug this guards against.
  CHECK(far_error > 0.3f * kDeg);
}
