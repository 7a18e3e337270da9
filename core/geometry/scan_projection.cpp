#include "core/geometry/scan_projection.hpp"

#include <cmath>
#include <cstdint>

#include "core/base/assert.hpp"
#include "core/geometry/return_smoothing.hpp"

namespace dpcr {
namespace {

bool Valid(const Beam& b, const LidarConfig& lidar) {
  return PlausibleBeam(b) && std::isfinite(b.range_m) && b.range_m >= lidar.min_range_m && b.range_m <= lidar.max_range_m;
}

// The beams of a scan as they came, or packed (PackedBeam), read one at a time.
Beam BeamAt(Span<const Beam> beams, std::size_t i) { return beams[i]; }
Beam BeamAt(Span<const PackedBeam> beams, std::size_t i) { return beams[i].Unpack(); }

// Whether a valid return within two beams of beam i agrees with its range (LidarConfig::drop_isolated_returns).
template <class Beams>
bool Confirmed(Beams beams, std::size_t i, const LidarConfig& lidar) {
  const float r = BeamAt(beams, i).range_m, step = 0.05f + 0.05f * r;
  for (std::size_t k = 1; k <= 2; ++k) {
    const float tolerance = static_cast<float>(k) * step;
    if (i >= k) {
      const Beam n = BeamAt(beams, i - k);
      if (Valid(n, lidar) && std::fabs(n.range_m - r) <= tolerance) return true;
    }
    if (i + k < beams.size()) {
      const Beam n = BeamAt(beams, i + k);
      if (Valid(n, lidar) && std::fabs(n.range_m - r) <= tolerance) return true;
    }
  }
  return false;
}

template <class Beams>
ProjectedScan Project(Beams beams, const LidarConfig& lidar, const ScanMotion& motion, Span<Point2> hits_out,
                      Span<Point2> free_ends_out) {
  DPCR_ASSERT(hits_out.size() >= beams.size() && free_ends_out.size() >= beams.size());
  ProjectedScan out;
  const bool deskew = motion.moves();
  // Beams of one packet share a motion estimate closely; cache the last offset's correction.
  std::int32_t cached_offset = 0;
  Pose2 sensor = lidar.mount;
  // The sector of the last return: a sector is counted at its first return (the last one may be short).
  std::size_t counted_sector = SIZE_MAX;
  for (std::size_t i = 0; i < beams.size(); ++i) {
    const Beam b = BeamAt(beams, i);
    if (!PlausibleBeam(b)) {
      ++out.invalid;
      continue;
    }
    if (deskew && b.offset_us != cached_offset) {
      cached_offset = b.offset_us;
      sensor = motion.At(b.offset_us) * lidar.mount;
    }
    const bool finite = std::isfinite(b.range_m), valid = Valid(b, lidar);
    if (valid && lidar.drop_isolated_returns && !Confirmed(beams, i, lidar)) {
      ++out.isolated;
    } else if (valid) {
      const std::size_t sector = i / kReturnSectorBeams;
      if (sector != counted_sector) {
        counted_sector = sector;
        const std::size_t first = sector * kReturnSectorBeams;
        out.beams_in_returning_sectors += beams.size() - first < kReturnSectorBeams ? beams.size() - first : kReturnSectorBeams;
      }
      hits_out[out.hits++] = sensor.Apply(Point2{b.range_m * std::cos(b.angle_rad), b.range_m * std::sin(b.angle_rad)});
    } else if (lidar.no_return_free_m > 0.0f && (!finite || b.range_m <= 0.0f || b.range_m > lidar.max_range_m)) {
      const float r = lidar.no_return_free_m;
      free_ends_out[out.free_ends++] = sensor.Apply(Point2{r * std::cos(b.angle_rad), r * std::sin(b.angle_rad)});
    } else {
      ++out.invalid;
    }
  }
  // A lidar that declares its range noise has its returns on straight walls moved onto them.
  if (lidar.range_noise_m > 0.0f && beams.size() > 0) {
    ReturnSmoothingConfig smoothing;
    smoothing.noise_m = lidar.range_noise_m;
    smoothing.max_gap_beams = lidar.smoothing_max_gap_beams;
    // A revolution's beams, evenly spaced (a 360-degree lidar; a narrower one only lets wider gaps through).
    const float beam_step_rad = 2.0f * kPi / static_cast<float>(beams.size());
    (void)SmoothReturns(Span<Point2>(hits_out.data(), out.hits), Point2{lidar.mount.x, lidar.mount.y}, beam_step_rad,
                        smoothing);
  }
  return out;
}

}  // namespace

ProjectedScan ProjectScan(Span<const Beam> beams, const LidarConfig& lidar, const ScanMotion& motion,
                          Span<Point2> hits_out, Span<Point2> free_ends_out) {
  return Project(beams, lidar, motion, hits_out, free_ends_out);
}

ProjectedScan ProjectScan(Span<const PackedBeam> beams, const LidarConfig& lidar, const ScanMotion& motion,
                          Span<Point2> hits_out, Span<Point2> free_ends_out) {
  return Project(beams, lidar, motion, hits_out, free_ends_out);
}

}  // namespace dpcr
