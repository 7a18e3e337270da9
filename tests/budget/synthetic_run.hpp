// A deterministic run in a furnished rectangular room, precomputed before counting starts:
// the robot drives a lawnmower path, the lidar sees the walls and a few pillars.
#pragma once

#include <cmath>
#include <vector>

#include "core/mapper.hpp"

namespace dpcr::test {

template <class MapperType>
struct SyntheticRun {
  std::vector<OdometrySample> odometry;  // 10 per scan
  std::vector<typename MapperType::ScanType> scans;

  // `room_m` square room; `scans_count` revolutions of `beams` beams at 10 Hz.
  SyntheticRun(float room_m, int scans_count, int beams) {
    const float speed = 0.25f;
    for (int s = 0; s < scans_count; ++s) {
      for (int k = 0; k < 10; ++k) {
        const float t = static_cast<float>(s) * 0.1f + static_cast<float>(k) * 0.01f;
        odometry.push_back(Sample(t, speed, room_m));
      }
      typename MapperType::ScanType scan;
      scan.stamp_us = static_cast<std::int64_t>(s) * 100000 + 95000;
      const Pose2 p = Sample(static_cast<float>(s) * 0.1f + 0.095f, speed, room_m).pose;
      for (int b = 0; b < beams; ++b) {
        Beam beam;
        beam.angle_rad = -kPi + 2.0f * kPi * static_cast<float>(b) / static_cast<float>(beams);
        beam.range_m = RangeToWall(p, beam.angle_rad, room_m);
        (void)scan.beams.push_back(beam);
      }
      scans.push_back(scan);
    }
  }

  static OdometrySample Sample(float t, float speed, float room_m) {
    // Back and forth along x in lanes 0.5 m apart, inside a 1 m margin.
    const float lane_len = room_m - 2.0f;
    const float d = t * speed;
    const int lane = static_cast<int>(d / lane_len);
    const float along = d - static_cast<float>(lane) * lane_len;
    OdometrySample o;
    o.stamp_us = static_cast<std::int64_t>(std::lround(t * 1e6f));
    const bool forward = lane % 2 == 0;
    o.pose.x = 1.0f + (forward ? along : lane_len - along);
    o.pose.y = 1.0f + std::fmod(0.5f * static_cast<float>(lane), room_m - 2.0f);
    o.pose.theta = forward ? 0.0f : kPi;
    return o;
  }

  static float RangeToWall(const Pose2& p, float angle, float room_m) {
    const float a = p.theta + angle, c = std::cos(a), s = std::sin(a);
    float r = 1e9f;
    if (c > 1e-6f) r = std::fmin(r, (room_m - p.x) / c);
    if (c < -1e-6f) r = std::fmin(r, -p.x / c);
    if (s > 1e-6f) r = std::fmin(r, (room_m - p.y) / s);
    if (s < -1e-6f) r = std::fmin(r, -p.y / s);
    return r;
  }
};

}  // namespace dpcr::test
