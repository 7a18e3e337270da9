// A CARMEN log (host_sim/carmen/carmen_reader.hpp) -> CarmenReader: no crash; each line either
// gives a record or a CarmenError naming a line that exists, and records are sane (finite poses
// and ranges, finite angles, at least one range).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz/fuzz_check.hpp"
#include "host_sim/carmen/carmen_reader.hpp"

namespace {

bool Finite(const dpcr::Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  dpcr::carmen::CarmenReader reader(in);
  dpcr::carmen::Record record;
  try {
    while (reader.Next(&record)) {
      if (record.kind == dpcr::carmen::Record::Kind::kOdom) {
        FUZZ_CHECK(Finite(record.odom.pose));
        continue;
      }
      const dpcr::carmen::LaserRecord& r = record.laser;
      FUZZ_CHECK(!r.ranges_m.empty());
      FUZZ_CHECK(Finite(r.laser_pose) && Finite(r.odom_pose));
      FUZZ_CHECK(std::isfinite(r.angle_min_rad) && std::isfinite(r.angle_increment_rad) && std::isfinite(r.max_range_m));
      for (float range : r.ranges_m) FUZZ_CHECK(std::isfinite(range));
    }
  } catch (const dpcr::carmen::CarmenError& e) {
    FUZZ_CHECK(e.line() >= 1 && e.line() <= reader.counters().lines);
  }
  FUZZ_CHECK(std::isfinite(reader.front_laser_offset_m()));
  return 0;
}
