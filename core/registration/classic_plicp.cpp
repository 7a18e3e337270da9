#include "core/registration/classic_plicp.hpp"

#include <cmath>

namespace dpcr {
namespace {

bool FindTwoNearest(const RegistrationReference& ref, Point2 w, const PlicpConfig& /*config*/, Correspondence* out) {
  const std::uint16_t j = ref.Nearest(w);
  if (j == kNoCell) return false;
  const Point2 q1 = ref.ObstaclePoint(j);
  const ObstacleCell& c1 = ref.cell(j);
  float best = 1e30f;
  Point2 q2{};
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      if (dx == 0 && dy == 0) continue;
      const std::uint16_t k = ref.ObstacleAt(c1.x + dx, c1.y + dy);
      if (k == kNoCell) continue;
      const Point2 q = ref.ObstaclePoint(k);
      const float d2 = (q.x - w.x) * (q.x - w.x) + (q.y - w.y) * (q.y - w.y);
      if (d2 < best) best = d2, q2 = q;
    }
  }
  if (best >= 1e30f) return false;  // an isolated cell defines no line
  const float tx = q2.x - q1.x, ty = q2.y - q1.y;
  const float inv = 1.0f / std::sqrt(tx * tx + ty * ty);
  out->normal = Point2{-ty * inv, tx * inv};
  out->offset = out->normal.x * q1.x + out->normal.y * q1.y;
  out->q = q1;
  out->ref = j;
  out->weight = 1.0f;
  return true;
}

}  // namespace

RegistrationResult RegisterClassic(const RegistrationReference& ref, Span<const Point2> target, Pose2 initial,
                                   const PosePrior* prior, const PlicpConfig& config) {
  return RunPlicp(ref, target, initial, prior, config, &FindTwoNearest);
}

}  // namespace dpcr
