// Stamped 2D trajectories and their TUM text form (`t x y z qx qy qz qw`, one pose a line).
#pragma once

#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "core/pose2.hpp"

namespace dpcr::eval {

struct StampedPose {
  std::int64_t stamp_us = 0;
  dpcr::Pose2 pose;
};

using Trajectory = std::vector<StampedPose>;

// "976052857.337530": seconds with exactly six decimals, so that stamps round-trip exactly.
std::string FormatStamp(std::int64_t stamp_us);

void WriteTum(std::ostream& out, const Trajectory& trajectory);
// Throws std::runtime_error("line N: reason") on malformed input.
Trajectory ReadTum(std::istream& in);
Trajectory ReadTumFile(const std::string& path);

}  // namespace dpcr::eval
