// A loop closure's refinement keeps the front end's guess along a ridge the search could not
// resolve, and keeps the search's answer where the guess fits worse or is too far off
// (core/back_end/closure_refinement.hpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "core/back_end/closure_refinement.hpp"
#include "registration_fixtures.hpp"

using dpcr::Point2;
using dpcr::Pose2;
using dpcr_test::C;
using dpcr_test::SpanOf;

namespace {

// A corridor 1.8 m wide along x, 12 m long (`end_wall`: closed at x = 8.6 m), and one scan of it
// from `truth`.
struct CorridorScene {
  dpcr_test::GridFixture f;
  std::vector<Point2> scan;
  CorridorScene(bool end_wall, const Pose2& truth, unsigned seed) {
    std::vector<dpcr_test::Segment> walls = {{{C(2), C(40)}, {C(250), C(40)}}, {{C(2), C(76)}, {C(250), C(76)}}};
    if (end_wall) walls.push_back({{C(172), C(40)}, {C(172), C(76)}});
    for (const dpcr_test::Segment& w : walls) f.Draw(w);
    REQUIRE(f.Build() == dpcr::Status::kOk);
    scan = dpcr_test::SimulateScan(walls, truth, 450, 0.01f, seed, 4.0f);
  }
  dpcr::ClosureRefinement Refine(const Pose2& start, const Pose2& guess, const dpcr::BackEndConfig& config,
                                 bool from_search = true) const {
    std::vector<dpcr::Correspondence> scratch(scan.size());
    const dpcr::ClosureRefinement r = dpcr::RefineClosure(*f.ref, SpanOf(scan), start, guess, from_search, config,
                                                          dpcr::Span<dpcr::Correspondence>(scratch.data(), scratch.size()));
    REQUIRE(r.result.verdict == dpcr::Status::kOk);
    return r;
  }
};

}  // namespace

TEST_CASE("A closure the search placed along an open corridor is refined again from the guess along it") {
  const Pose2 truth{6.0f, 2.9f, 0.05f};
  const CorridorScene scene(false, truth, 5);
  // The search's pick on the ridge: 0.2 m along the corridor, a little off across it. The guess is
  // right along the corridor and 4 cm off across it.
  const Pose2 search{truth.x + 0.2f, truth.y + 0.03f, truth.theta};
  const Pose2 guess{truth.x, truth.y - 0.04f, truth.theta + 0.01f};
  dpcr::BackEndConfig config;

  const dpcr::ClosureRefinement r = scene.Refine(search, guess, config);
  CHECK(r.guess_on_ridge);
  CHECK(std::fabs(r.result.pose.x - truth.x) < 0.01f);  // along the corridor: the guess's
  CHECK(std::fabs(r.result.pose.y - truth.y) < 0.01f);  // across it: the walls'
  CHECK(std::fabs(r.result.pose.theta - truth.theta) < 0.005f);

  // Without the rule the refinement stays where the search put it along the corridor.
  config.ridge_information = 0.0f;
  const dpcr::ClosureRefinement off = scene.Refine(search, guess, config);
  CHECK_FALSE(off.guess_on_ridge);
  CHECK(std::fabs(off.result.pose.x - search.x) < 0.01f);
}

TEST_CASE("A closure whose guess fits worse along the corridor keeps the search's answer") {
  const Pose2 truth{6.4f, 2.9f, 0.0f};
  const CorridorScene scene(true, truth, 7);
  // The search found the truth; the guess drifted 0.27 m along the corridor. The corridor's end
  // wall holds a small share of the returns: the direction counts as a ridge at this threshold,
  // but from the guess those returns miss the wall.
  const Pose2 guess{truth.x + 0.27f, truth.y, truth.theta};
  dpcr::BackEndConfig config;
  config.ridge_information = 0.5f;
  const dpcr::ClosureRefinement r = scene.Refine(truth, guess, config);
  CHECK_FALSE(r.guess_on_ridge);
  CHECK(std::fabs(r.result.pose.x - truth.x) < 0.02f);
  // The direction was weak enough to be tried: its information per inlier is below the threshold.
  const float along_x = r.result.hessian(0, 0) / static_cast<float>(r.result.inliers);
  CHECK(along_x < config.ridge_information);
}

TEST_CASE("A guess farther along the corridor than the search's base window is not tried") {
  const Pose2 truth{6.0f, 2.9f, 0.0f};
  const CorridorScene scene(false, truth, 11);
  // A guess that drifted 1.1 m along the corridor fits as well as the search's answer does, and
  // says nothing: the search's answer stays.
  const Pose2 guess{truth.x + 1.1f, truth.y, truth.theta};
  dpcr::BackEndConfig config;
  const dpcr::ClosureRefinement r = scene.Refine(truth, guess, config);
  CHECK_FALSE(r.guess_on_ridge);
  CHECK(std::fabs(r.result.pose.x - truth.x) < 0.01f);
  // Within a wider window it would have been taken.
  config.search_base_m = 1.5f;
  const dpcr::ClosureRefinement wide = scene.Refine(truth, guess, config);
  CHECK(wide.guess_on_ridge);
  CHECK(std::fabs(wide.result.pose.x - guess.x) < 0.01f);
}

TEST_CASE("A refinement from the front end's guess is not tried again") {
  const Pose2 truth{6.0f, 2.9f, 0.0f};
  const CorridorScene scene(false, truth, 9);
  const Pose2 start{truth.x + 0.2f, truth.y, truth.theta};
  const dpcr::ClosureRefinement r = scene.Refine(start, truth, dpcr::BackEndConfig{}, false);
  CHECK_FALSE(r.guess_on_ridge);
  CHECK(std::fabs(r.result.pose.x - start.x) < 0.01f);
}
