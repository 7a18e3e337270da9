// What the Mapper reports: its state and its counters (metrics.json reads these).
#pragma once

#include <cstdint>

namespace dpcr {

enum class MapperStatus : std::uint8_t {
  kWaitingForData,  // no scan yet
  kTracking,
  kLost,      // repeated rejected registrations: poses come from odometry alone
  kPoolFull,  // a region or tile pool is exhausted: the map stops growing, localisation goes on
};

const char* ToString(MapperStatus status);

struct MapperCounters {
  std::uint32_t scans = 0;
  std::uint32_t scans_rejected = 0;          // not fused into the map
  std::uint32_t scans_without_odometry = 0;  // pose held: no odometry sample had arrived
  std::uint32_t odometry_samples = 0;
  std::uint32_t odometry_steps_back = 0;     // samples stamped earlier than their predecessor
  std::uint32_t beams_invalid = 0;           // no return, or outside [min, max] range
  std::uint32_t regions_created = 0;
  std::uint32_t region_pool_full = 0;        // scans that wanted a new region and got none
  std::uint32_t updates_out_of_box = 0;      // cell updates past a regional map's box
  std::uint32_t updates_dropped_pool_full = 0;
  // Scans kept out of the regional maps: the robot was back in a known map after a loop and had
  // not yet placed itself in it (no smeared copy of the room).
  std::uint32_t scans_not_inserted = 0;
};

}  // namespace dpcr
