#include "host_sim/output/trajectory_refinement.hpp"

#include <cmath>

namespace dpcr::output {
namespace {

constexpr float kReachM = 32.767f;  // int16 millimetres

// To the nearest millimetre (half away from zero; |m| < kReachM): lround's answer without its call.
std::int16_t Millimetres(float m) { return static_cast<std::int16_t>(m * 1000.0f + (m < 0.0f ? -0.5f : 0.5f)); }

}  // namespace

void ScanPointRecord::Append(Span<const Point2> points) {
  begins_.push_back(size_);
  for (const Point2& p : points) {
    if (!(std::fabs(p.x) < kReachM && std::fabs(p.y) < kReachM)) {
      ++not_stored_;
      continue;
    }
    if (size_ == blocks_.size() * kBlock) blocks_.emplace_back(2 * kBlock);
    std::int16_t* xy = blocks_.back().data() + 2 * (size_ % kBlock);
    xy[0] = Millimetres(p.x);
    xy[1] = Millimetres(p.y);
    ++size_;
  }
}

void ScanPointRecord::Scan(std::size_t i, std::vector<Point2>* out) const {
  const std::size_t begin = begins_[i], end = End(i);
  out->resize(end - begin);
  for (std::size_t k = begin; k < end; ++k) {
    const std::int16_t* xy = blocks_[k / kBlock].data() + 2 * (k % kBlock);
    (*out)[k - begin] = Point2{static_cast<float>(xy[0]) * 0.001f, static_cast<float>(xy[1]) * 0.001f};
  }
}

}  // namespace dpcr::output
