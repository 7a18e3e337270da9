// A tiny-profile mapper's configuration and a short synthetic room run (tests/budget/
// synthetic_run.hpp): the map-file target's seed map is made from it, and loaded maps map on
// with it.
#pragma once

#include <cstddef>
#include <vector>

#include "core/mapper.hpp"
#include "tests/budget/synthetic_run.hpp"

namespace dpcr::fuzz {

struct TinyMapRun {
  using Tiny = Mapper<TinyProfile>;
  TinyMapRun() : run(6.0f, 60, 180) { config.front_end.submap_scans = TinyProfile::kSubmapMaxScans; }

  // Scans [first, first + count) with the odometry up to each.
  void Feed(Tiny& mapper, std::size_t first, std::size_t count) const {
    std::size_t odom = 0;
    for (std::size_t i = first; i < run.scans.size() && i - first < count; ++i) {
      const auto& scan = run.scans[i];
      while (odom < run.odometry.size() && run.odometry[odom].stamp_us <= scan.stamp_us) mapper.AddOdometry(run.odometry[odom++]);
      (void)mapper.AddScan(scan);
    }
  }

  MapperConfig config;
  test::SyntheticRun<Tiny> run;
};

}  // namespace dpcr::fuzz
