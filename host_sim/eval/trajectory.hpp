// Stamped 2D trajectories and their TUM text form (`t x y z qx qy qz qw`, one pose a line).
#pragma once

#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "core/geometry/pose2.hpp"
#include "host_sim/eval/stamp_text.hpp"

namespace dpcr::eval {

struct StampedPose {
  std::int64_t stamp_us = 0;
  dpcr::Pose2 pose;
};

using Trajectory = std::vector<StampedPose>;

// Calls visit(line_number, text) for each line that is neither blank nor a '#' comment
// (the convention of TUM and relations files).
template <typename Visitor>
void ForEachDataLine(std::istream& in, Visitor&& visit) {
  std::string text;
  long line = 0;
  while (std::getline(in, text)) {
    ++line;
    const std::size_t first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    visit(line, text);
  }
}

void WriteTum(std::ostream& out, const Trajectory& trajectory);
// Throws std::runtime_error("line N: reason") on malformed input.
Trajectory ReadTum(std::istream& in);
Trajectory ReadTumFile(const std::string& path);

}  // namespace dpcr::eval
