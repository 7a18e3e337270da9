#include "host_sim/output/trajectory_refinement.hpp"

#include <algorithm>
#include <cmath>

namespace dpcr::output {
namespace {

constexpr float kReachM = 32.767f;  // int16 millimetres

// To the nearest millimetre (half away from zero; |m| < kReachM): lround's answer without its call.
std::int16_t Millimetres(float m) { return static_cast<std::int16_t>(m * 1000.0f + std::copysign(0.5f, m)); }

}  // namespace

void ScanPointRecord::Append(Span<const Point2> points) {
  begins_.push_back(size_);
  // Block by block: the per-point work is the range check and two roundings.
  std::size_t i = 0;
  while (i < points.size()) {
    if (size_ == blocks_.size() * kBlock) blocks_.emplace_back(2 * kBlock);
    std::int16_t* const xy = blocks_.back().data() + 2 * (size_ % kBlock);
    const std::size_t room = kBlock - size_ % kBlock;
    std::size_t stored = 0;
    for (; i < points.size() && stored < room; ++i) {
      const Point2 p = points[i];
      if (!(std::fabs(p.x) < kReachM && std::fabs(p.y) < kReachM)) {
        ++not_stored_;
        continue;
      }
      xy[2 * stored] = Millimetres(p.x);
      xy[2 * stored + 1] = Millimetres(p.y);
      ++stored;
    }
    size_ += stored;
  }
}

void ScanPointRecord::Scan(std::size_t i, std::vector<Point2>* out) const {
  const std::size_t begin = begins_[i], end = End(i);
  out->resize(end - begin);
  Point2* to = out->data();
  for (std::size_t k = begin; k < end;) {  // block by block, as Append wrote them
    const std::size_t stop = std::min(end, (k / kBlock + 1) * kBlock);
    const std::int16_t* xy = blocks_[k / kBlock].data() + 2 * (k % kBlock);
    for (; k < stop; ++k, xy += 2) *to++ = Point2{static_cast<float>(xy[0]) * 0.001f, static_cast<float>(xy[1]) * 0.001f};
  }
}

}  // namespace dpcr::output
