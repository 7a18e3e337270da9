// The RAM bill of each profile (sizeof the whole core state) against its budget, and the proof
// that a full mapping run allocates nothing on the heap after start-up.
#include <catch2/catch.hpp>

#include <cstdio>
#include <memory>

#include "core/mapper.hpp"
#include "tests/budget/allocation_counter.hpp"
#include "tests/budget/synthetic_run.hpp"

namespace {

template <class Profile>
void CheckFootprint() {
  const std::size_t bytes = sizeof(dpcr::Mapper<Profile>);
  std::printf("footprint: profile %-8s sizeof(Mapper) = %8zu bytes (%.2f MiB) of budget %zu bytes\n", Profile::kName,
              bytes, static_cast<double>(bytes) / (1024.0 * 1024.0), Profile::kRamBudgetBytes);
  CHECK(bytes <= Profile::kRamBudgetBytes);
}

template <class Profile>
std::size_t AllocationsDuringRun(int scans) {
  using MapperType = dpcr::Mapper<Profile>;
  auto mapper = std::make_unique<MapperType>();  // start-up: the one allocation a host test may make
  dpcr::MapperConfig config;
  if (config.front_end.submap_scans > Profile::kSubmapMaxScans) config.front_end.submap_scans = Profile::kSubmapMaxScans;
  REQUIRE(mapper->Init(config) == dpcr::Status::kOk);
  const dpcr::test::SyntheticRun<MapperType> run(8.0f, scans, 450);
  std::size_t odom = 0;
  dpcr::test::ArmAllocationCounter();
  for (const auto& scan : run.scans) {
    while (odom < run.odometry.size() && run.odometry[odom].stamp_us <= scan.stamp_us) mapper->AddOdometry(run.odometry[odom++]);
    (void)mapper->AddScan(scan);
  }
  // Reading the map out is part of the run too.
  const dpcr::CellBox box = mapper->MapBounds();
  (void)box;
  const std::size_t allocations = dpcr::test::DisarmAllocationCounter();
  REQUIRE(mapper->counters().scans == static_cast<std::uint32_t>(scans));
  REQUIRE(mapper->region_count() > 1);  // the run crosses regions
  return allocations;
}

}  // namespace

TEST_CASE("Each profile's core state fits its RAM budget") {
  CheckFootprint<dpcr::VacuumProfile>();
  CheckFootprint<dpcr::TinyProfile>();
  CheckFootprint<dpcr::BuildingProfile>();
}

TEST_CASE("The allocation counter sees allocations") {
  dpcr::test::ArmAllocationCounter();
  auto p = std::make_unique<int>(3);
  REQUIRE(dpcr::test::DisarmAllocationCounter() == 1);
}

TEST_CASE("A full mapping run makes zero heap allocations") {
  REQUIRE(AllocationsDuringRun<dpcr::VacuumProfile>(600) == 0);
  REQUIRE(AllocationsDuringRun<dpcr::TinyProfile>(300) == 0);
}
