// The marker of the scan being inserted, for the grid's once-per-scan rule (at most one update
// per cell per scan, TiledGrid::Update): a new value for each scan, never 0 (0 asks the grid for
// no such rule). A marker is a count of insertions, not a time.
#pragma once

#include <cstdint>

namespace dpcr {

class ScanMarker {
 public:
  // Starts the next scan and returns its marker (after 2^32 - 1 scans it wraps past 0 to 1).
  std::uint32_t Next() {
    if (++value_ == 0) value_ = 1;
    return value_;
  }
  // The marker of the scan being inserted.
  std::uint32_t current() const { return value_; }
  void Reset() { value_ = 0; }

 private:
  std::uint32_t value_ = 0;
};

}  // namespace dpcr
