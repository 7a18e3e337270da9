// A doubtful loop closure waits for a second search of the same map to agree with it.
#include <catch2/catch.hpp>

#include "core/back_end/closure_confirmation.hpp"

using dpcr::BackEndConfig;
using dpcr::ClosureConfirmation;
using dpcr::Pose2;

namespace {

// The robot tracked 2 m further on than where a search finds it, turned 0.03 rad: a drift's
// correction, the same for every search while the drift is the same.
const Pose2 kCorrection{-2.0f, 0.3f, -0.03f};

Pose2 Found(const Pose2& tracked, const Pose2& correction = kCorrection) { return correction * tracked; }

}  // namespace

TEST_CASE("A clear closure is taken at once and a doubtful one waits") {
  const BackEndConfig config;
  ClosureConfirmation c;
  const Pose2 tracked{12.0f, -3.0f, 1.2f};
  CHECK(c.Take(4, false, Found(tracked), tracked, config));
  CHECK_FALSE(c.waiting());
  CHECK_FALSE(c.Take(4, true, Found(tracked), tracked, config));
  CHECK(c.waiting());
}

TEST_CASE("A second search of the same map that lands on the same correction takes the closure") {
  const BackEndConfig config;
  ClosureConfirmation c;
  const Pose2 first{12.0f, -3.0f, 1.2f}, later{12.4f, -1.9f, 1.9f};  // 1.2 m on, turned 40 degrees
  REQUIRE_FALSE(c.Take(4, true, Found(first), first, config));
  // The same drift, measured again: taken, whether the second search is doubtful too or not.
  CHECK(c.Take(4, true, Found(later, Pose2{-2.05f, 0.32f, -0.031f}), later, config));
  CHECK_FALSE(c.waiting());
  REQUIRE_FALSE(c.Take(4, true, Found(first), first, config));
  CHECK(c.Take(4, false, Found(later), later, config));
}

TEST_CASE("A search of the same map that contradicts the closure waiting waits in its place") {
  const BackEndConfig config;
  ClosureConfirmation c;
  const Pose2 first{12.0f, -3.0f, 1.2f}, later{12.4f, -1.9f, 1.9f}, last{12.9f, -1.2f, 2.0f};
  REQUIRE_FALSE(c.Take(4, true, Found(first), first, config));
  // A clear search 0.9 m along the corridor from the waiting one: one of them is a look-alike.
  const Pose2 other{-2.9f, 0.3f, -0.03f};
  CHECK_FALSE(c.Take(4, false, Found(later, other), later, config));
  CHECK(c.waiting());
  // The next search agrees with the second: taken.
  CHECK(c.Take(4, false, Found(last, other), last, config));
}

TEST_CASE("A search of another map is judged alone and a taken closure clears the one waiting") {
  const BackEndConfig config;
  ClosureConfirmation c;
  const Pose2 first{12.0f, -3.0f, 1.2f}, later{12.4f, -1.9f, 1.9f};
  REQUIRE_FALSE(c.Take(4, true, Found(first), first, config));
  // Map 9 is not yet tied to map 4 by the loop between them: its correction may differ and be right.
  CHECK(c.Take(9, false, Found(later, Pose2{0.4f, 0.1f, 0.0f}), later, config));
  CHECK(c.waiting());
  c.Clear();
  CHECK_FALSE(c.waiting());
  // With nothing waiting, a clear search of map 4 is taken whatever it says.
  CHECK(c.Take(4, false, Found(later, Pose2{0.4f, 0.1f, 0.0f}), later, config));
}
