#include <catch2/catch.hpp>

#include "core/front_end/region_tracker.hpp"

TEST_CASE("Regions are keyed from the start and switch only past the hysteresis") {
  dpcr::RegionTracker t;
  t.Start(dpcr::Point2{10.0f, 10.0f}, 4.0f, 0.3f);  // region (0,0) spans 8..12
  REQUIRE(t.current() == dpcr::RegionKey{0, 0});
  REQUIRE_FALSE(t.Update(dpcr::Point2{12.2f, 10.0f}));  // past the border, within hysteresis
  REQUIRE(t.current() == dpcr::RegionKey{0, 0});
  REQUIRE(t.Update(dpcr::Point2{12.4f, 10.0f}));
  REQUIRE(t.current() == dpcr::RegionKey{1, 0});
  // Back across the border: stays in (1,0) until 0.3 m into (0,0).
  REQUIRE_FALSE(t.Update(dpcr::Point2{11.8f, 10.0f}));
  REQUIRE(t.Update(dpcr::Point2{11.6f, 7.0f}));
  REQUIRE(t.current() == dpcr::RegionKey{0, -1});
  REQUIRE(t.Centre(dpcr::RegionKey{0, -1}).y == Approx(6.0f));
}
