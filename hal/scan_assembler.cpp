#include "hal/scan_assembler.hpp"

#include <cmath>

#include "core/geometry/pose2.hpp"

namespace dpcr {
namespace {

constexpr float kDegToRad = kPi / 180.0f;

float WrapDeg(float deg) {
  deg = std::fmod(deg, 360.0f);
  return deg < 0.0f ? deg + 360.0f : deg;
}

}  // namespace

ScanAssembler::ScanAssembler(const ScanAssemblerConfig& config) : config_(config) {}

void ScanAssembler::Reset() {
  for (Revolution& r : revs_) r = Revolution();
  current_ = 0;
  ready_ = false;
  started_ = false;
}

void ScanAssembler::Append(Revolution* rev, const RawPoint& p) {
  ++rev->info.points_in;
  const std::uint32_t index = rev->seen++;
  if (index % rev->stride != 0) return;
  if (rev->points.full()) {
    // Halve in place (keep every other point) and keep half as many from now on.
    std::size_t w = 0;
    for (std::size_t r = 0; r < rev->points.size(); r += 2) rev->points[w++] = rev->points[r];
    static_cast<void>(rev->points.resize(w));
    rev->stride *= 2;
    rev->info.decimated = true;
    if (index % rev->stride != 0) return;
  }
  static_cast<void>(rev->points.push_back(p));
}

void ScanAssembler::CloseRevolution() {
  Revolution& rev = revs_[current_];
  if (rev.partial || rev.points.empty()) {
    if (rev.partial) ++counters_.partial_dropped;
  } else {
    ++counters_.revolutions;
    current_ = 1 - current_;
    ready_ = true;
  }
  revs_[current_] = Revolution();
}

void ScanAssembler::AddPoint(float device_deg, float range_m, std::int64_t stamp_us) {
  if (!started_) {
    started_ = true;
    revs_[current_].partial = device_deg > config_.start_tolerance_deg;
  } else if (device_deg < last_deg_ - 180.0f) {
    CloseRevolution();
  } else if (device_deg <= last_deg_) {
    ++counters_.not_advancing;  // overlap or a repeated packet: the angle must advance
    return;
  }
  last_deg_ = device_deg;
  RawPoint p;
  p.angle_rad = NormalizeAngle(config_.angle_map.angle_sign * device_deg * kDegToRad +
                               config_.angle_map.angle_offset_rad);
  p.range_m = range_m;
  p.stamp_us = stamp_us;
  ++counters_.points;
  Append(&revs_[current_], p);
}

bool ScanAssembler::Flush() {
  if (!started_ || ready_ || revs_[current_].points.empty()) return false;
  if (last_deg_ < 360.0f - config_.start_tolerance_deg) return false;
  CloseRevolution();
  return ready_;
}

bool ScanAssembler::Add(const LidarPacket& packet) {
  const bool was_ready = ready_;
  if (started_ && packet.count > 0 && packet.stamp_us - last_packet_us_ > config_.max_silence_us) {
    ++counters_.dropouts;
    revs_[current_].partial = true;
  } else if (started_ && packet.count > 0) {
    // Angle from the previous point to this packet's first point, across the wrap.
    const float jump = WrapDeg(packet.start_deg - last_deg_);
    const float step = packet.step_deg > last_step_deg_ ? packet.step_deg : last_step_deg_;
    if (step > 0.0f && jump > config_.gap_steps * step && jump < 180.0f) {
      ++counters_.gaps;
      ++revs_[current_].info.gaps;
      revs_[current_].info.missing_deg += jump - step;
    }
  }
  for (int i = 0; i < packet.count; ++i) {
    const float deg = WrapDeg(packet.start_deg + packet.step_deg * static_cast<float>(i));
    const auto stamp = packet.stamp_us +
                       static_cast<std::int64_t>(std::lround(packet.point_dt_us * static_cast<float>(i)));
    AddPoint(deg, static_cast<float>(packet.range_mm[i]) * 0.001f, stamp);
  }
  last_step_deg_ = packet.step_deg;
  if (packet.count > 0) last_packet_us_ = packet.stamp_us;
  return ready_ && !was_ready;
}

}  // namespace dpcr
