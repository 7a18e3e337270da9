// Whole lidar revolutions from packets: split where the device angle wraps past 360 degrees,
// per-point timestamps interpolated across each packet, gaps (dropped packets) recorded,
// and uniform decimation when a revolution has more points than the Scan holds.
#pragma once

#include <cstdint>

#include "core/geometry/scan.hpp"
#include "core/base/static_vector.hpp"
#include "hal/lidar_packet.hpp"

namespace dpcr {

// How device angles (degrees in the device's rotation sense, 0..360) become Beam angles:
// angle_rad = NormalizeAngle(angle_sign * deg * pi/180 + angle_offset_rad). LD06 and XV-11
// turn clockwise seen from above: a lidar mounted upright needs angle_sign = -1.
struct LidarAngleMap {
  float angle_sign = -1.0f;
  float angle_offset_rad = 0.0f;
};

struct ScanAssemblerConfig {
  LidarAngleMap angle_map;
  // A jump between packets larger than gap_steps x the point spacing is a dropped-packet gap.
  float gap_steps = 2.5f;
  // The revolution in progress at start-up is dropped unless its first point is this close
  // to the wrap (it would be a partial revolution).
  float start_tolerance_deg = 10.0f;
  // A packet stamped this long after the previous one follows a dropout (the lidar stopped, or
  // its line was cut): counted, and the revolution in progress, which would join points from
  // both sides of the silence, is dropped as partial. An angle-based gap cannot see a silence
  // of whole turns.
  std::int64_t max_silence_us = 500000;
};

struct RevolutionInfo {
  std::uint32_t points_in = 0;    // points received for this revolution
  std::uint32_t gaps = 0;         // dropped-packet gaps inside it
  float missing_deg = 0.0f;       // angle not covered because of the gaps
  bool decimated = false;         // more points than the Scan holds: evenly decimated
};

struct ScanAssemblerCounters {
  std::uint32_t revolutions = 0;
  std::uint32_t partial_dropped = 0;  // the first revolution when it started mid-turn, or cut by a dropout
  std::uint32_t gaps = 0;
  std::uint32_t dropouts = 0;         // silences longer than max_silence_us
  std::uint32_t decimated = 0;
  std::uint32_t points = 0;
  std::uint32_t not_advancing = 0;    // points at or behind the previous angle: dropped
};

class ScanAssembler {
 public:
  // Raw points kept per revolution before decimation starts in place (LD06: ~450-900).
  static constexpr int kMaxRawPoints = 2048;

  explicit ScanAssembler(const ScanAssemblerConfig& config = ScanAssemblerConfig());

  // Adds a packet; true when it closed a revolution, which TakeScan() then returns
  // (the packet's points past the wrap start the next revolution).
  bool Add(const LidarPacket& packet);
  bool revolution_ready() const { return ready_; }
  // At the end of a stream no wrap follows to close the revolution in progress: this closes it
  // when it got within start_tolerance_deg of a full turn (the start rule's mirror); true then.
  bool Flush();

  // Moves the ready revolution into `out` (decimated evenly to N beams when longer).
  template <int N>
  void TakeScan(Scan<N>* out, RevolutionInfo* info = nullptr);

  const ScanAssemblerCounters& counters() const { return counters_; }
  void Reset();

 private:
  struct RawPoint {
    float angle_rad = 0.0f;
    float range_m = 0.0f;
    std::int64_t stamp_us = 0;
  };
  struct Revolution {
    StaticVector<RawPoint, kMaxRawPoints> points;
    RevolutionInfo info;
    std::uint32_t stride = 1;     // keep one point in `stride` (grows by 2 on overflow)
    std::uint32_t seen = 0;
    bool partial = false;
  };

  void AddPoint(float device_deg, float range_m, std::int64_t stamp_us);
  void CloseRevolution();
  static void Append(Revolution* rev, const RawPoint& p);

  ScanAssemblerConfig config_;
  Revolution revs_[2];
  int current_ = 0;
  bool ready_ = false;
  bool started_ = false;
  float last_deg_ = 0.0f;
  float last_step_deg_ = 0.0f;
  std::int64_t last_packet_us_ = 0;
  ScanAssemblerCounters counters_;
};

template <int N>
void ScanAssembler::TakeScan(Scan<N>* out, RevolutionInfo* info) {
  Revolution& done = revs_[1 - current_];
  out->beams.clear();
  const std::size_t n = done.points.size();
  const std::size_t kept = n > static_cast<std::size_t>(N) ? static_cast<std::size_t>(N) : n;
  if (n > kept) done.info.decimated = true;
  out->stamp_us = n > 0 ? done.points[0].stamp_us : 0;
  for (std::size_t j = 0; j < kept; ++j) {
    const RawPoint& p = done.points[j * n / kept];  // even decimation, first point kept
    Beam beam;
    beam.angle_rad = p.angle_rad;
    beam.range_m = p.range_m;
    beam.offset_us = static_cast<std::int32_t>(p.stamp_us - out->stamp_us);
    static_cast<void>(out->beams.push_back(beam));  // cannot fail: kept <= N
  }
  if (done.info.decimated) ++counters_.decimated;
  if (info != nullptr) *info = done.info;
  ready_ = false;
}

}  // namespace dpcr
