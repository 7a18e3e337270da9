#include "host_sim/output/trajectory_refinement.hpp"

#include <cmath>

namespace dpcr::output {

void ScanPointRecord::Append(Span<const Point2> points) {
  begins_.push_back(size_);
  constexpr float kReachM = 32.767f;  // int16 millimetres
  for (const Point2& p : points) {
    if (!(std::fabs(p.x) < kReachM && std::fabs(p.y) < kReachM)) {
      ++not_stored_;
      continue;
    }
    if (size_ == blocks_.size() * kBlock) blocks_.emplace_back(2 * kBlock);
    std::int16_t* xy = blocks_.back().data() + 2 * (size_ % kBlock);
    xy[0] = static_cast<std::int16_t>(std::lround(p.x * 1000.0f));
    xy[1] = static_cast<std::int16_t>(std::lround(p.y * 1000.0f));
    ++size_;
  }
}

void ScanPointRecord::Scan(std::size_t i, std::vector<Point2>* out) const {
  out->clear();
  for (std::size_t k = begins_[i]; k < End(i); ++k) {
    const std::int16_t* xy = blocks_[k / kBlock].data() + 2 * (k % kBlock);
    out->push_back(Point2{static_cast<float>(xy[0]) * 0.001f, static_cast<float>(xy[1]) * 0.001f});
  }
}

}  // namespace dpcr::output
