#include <catch2/catch.hpp>

#include "core/config.hpp"

TEST_CASE("Default configuration carries the paper's parameters and validates") {
  const dpcr::MapperConfig config;
  REQUIRE(dpcr::Validate(config) == dpcr::Status::kOk);
  REQUIRE(config.front_end.submap_scans == 20);
  REQUIRE(config.front_end.submap_line_period == 10);
  REQUIRE(config.front_end.region_line_period == 50);
  REQUIRE(config.front_end.second_registration_period == 5);
  REQUIRE(config.front_end.region_width_m == 4.0f);
  REQUIRE(config.grid.resolution_m == 0.05f);
}

TEST_CASE("Validate rejects meaningless parameters") {
  dpcr::MapperConfig bad;
  bad.front_end.region_line_period = 0;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kInvalidArgument);
  bad = dpcr::MapperConfig{};
  bad.grid.miss_delta = 10;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kInvalidArgument);
  bad = dpcr::MapperConfig{};
  bad.lidar.max_range_m = 0.0f;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kInvalidArgument);
  bad = dpcr::MapperConfig{};
  bad.grid.hit_margin_m = -0.01f;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kInvalidArgument);
  // A submap ray that starts inside the hit margin would have nothing to clear, or run backwards.
  bad = dpcr::MapperConfig{};
  bad.front_end.submap_miss_range_m = bad.grid.hit_margin_m;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kInvalidArgument);
  // Neighbouring regional maps must be a whole number of cells apart (4 m / 3 cm is not).
  bad = dpcr::MapperConfig{};
  bad.grid.resolution_m = 0.03f;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kInvalidArgument);
  bad.front_end.region_width_m = 3.6f;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kOk);
}
