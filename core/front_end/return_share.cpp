#include "core/front_end/return_share.hpp"

namespace dpcr {

float UpdateReturnShare(float share, const ProjectedScan& scan) {
  if (scan.beams_in_returning_sectors == 0) return share;
  const float now = static_cast<float>(scan.hits) / static_cast<float>(scan.beams_in_returning_sectors);
  return share + kReturnShareWeight * (now - share);
}

ReferenceConfig ReferenceForReturnShare(const ReferenceConfig& base, float share, float full_share) {
  ReferenceConfig c = base;
  if (full_share <= 0.0f || share >= full_share || share < 0.0f) return c;
  c.obstacle_threshold = static_cast<std::int16_t>(static_cast<float>(base.obstacle_threshold) * share / full_share + 0.5f);
  return c;
}

}  // namespace dpcr
