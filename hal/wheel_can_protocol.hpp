// The wheel-encoder CAN protocol (docs/can-protocol.md): encoder and decoder.
// Ticks frame 0x120, DLC 8: left u16, right u16 (free-running, wrapping), sequence u8,
// device time u24 in 10 us units (wraps every 167.77216 s). Gyro frame 0x121, DLC 6: yaw rate
// i16 in mrad/s, sequence u8, device time u24 (10 us). Status frame 0x122, DLC 5: flags u8 (bit 0:
// wheels lifted), sequence u8, device time u24 (10 us). All fields little-endian.
// The decoder unwraps counters and time, and detects lost, duplicated and reordered frames from
// the sequence counter; foreign IDs, extended/RTR/error frames and bad DLCs are counted and ignored.
#pragma once

#include <cstdint>

#include "hal/can_frame.hpp"

namespace dpcr {

constexpr std::uint32_t kWheelTicksCanId = 0x120;
constexpr std::uint32_t kGyroCanId = 0x121;
constexpr std::uint8_t kWheelTicksDlc = 8;
constexpr std::uint8_t kGyroDlc = 6;
constexpr std::uint32_t kStatusCanId = 0x122;
constexpr std::uint8_t kStatusDlc = 5;
constexpr std::uint8_t kStatusLiftedFlag = 0x01;  // any wheel-drop switch open
constexpr std::uint8_t kStatusReservedFlags = static_cast<std::uint8_t>(~kStatusLiftedFlag);
constexpr std::int64_t kWheelTimeUnitUs = 10;
constexpr std::int64_t kWheelTimeWrapUnits = 1 << 24;

// Raw frame contents (what the encoder board sends).
struct WheelTicksFrame {
  std::uint16_t left_ticks = 0;
  std::uint16_t right_ticks = 0;
  std::uint8_t sequence = 0;
  std::uint32_t time_10us = 0;  // 24 bits
};

struct GyroFrame {
  std::int16_t yaw_rate_mrad_s = 0;
  std::uint8_t sequence = 0;
  std::uint32_t time_10us = 0;  // 24 bits
};

// Sent on every change of a flag and periodically (10 Hz), so that a lost frame is replaced.
struct StatusFrame {
  std::uint8_t flags = 0;  // kStatusLiftedFlag; the other bits reserved, sent as 0
  std::uint8_t sequence = 0;
  std::uint32_t time_10us = 0;  // 24 bits
};

CanFrame EncodeWheelFrame(const WheelTicksFrame& frame);
CanFrame EncodeGyroFrame(const GyroFrame& frame);
CanFrame EncodeStatusFrame(const StatusFrame& frame);

// Decoded, unwrapped wheel state: cumulative ticks since the first frame plus the first
// frame's raw value, so differences are exact across any number of 16-bit rollovers.
struct WheelTicks {
  std::int64_t device_time_us = 0;  // unwrapped device time
  std::int64_t left_ticks = 0;
  std::int64_t right_ticks = 0;
};

struct GyroRate {
  std::int64_t device_time_us = 0;
  float yaw_rate_rad_s = 0.0f;
};

// The robot's state as of `device_time_us` (unwrapped on the status stream's own sequence, as
// each stream is: equal to the other streams' device times modulo the 24-bit wrap).
struct RobotStatus {
  std::int64_t device_time_us = 0;
  bool lifted = false;
};

enum class CanDecodeResult : std::uint8_t {
  kTicks,       // ticks() holds a new sample
  kGyro,        // gyro() holds a new sample
  kStatus,      // status() holds a new state
  kIgnored,     // foreign ID, extended, RTR
  kErrorFrame,
  kBadDlc,
  kDuplicate,   // same sequence as the last frame: dropped
  kReordered,   // older than the last frame: dropped (counters are absolute, nothing is lost)
};

struct WheelCanCounters {
  std::uint32_t ticks_frames = 0;
  std::uint32_t gyro_frames = 0;
  std::uint32_t status_frames = 0;
  std::uint32_t reserved_flags = 0;  // status frames with reserved bits set (accepted, bits ignored)
  std::uint32_t foreign = 0;
  std::uint32_t error_frames = 0;
  std::uint32_t bad_dlc = 0;
  std::uint32_t lost = 0;        // sequence gaps, minus frames that later arrived late
  std::uint32_t duplicated = 0;
  std::uint32_t reordered = 0;
};

class WheelCanDecoder {
 public:
  CanDecodeResult Feed(const CanFrame& frame);
  const WheelTicks& ticks() const { return ticks_; }
  const GyroRate& gyro() const { return gyro_; }
  const RobotStatus& status() const { return status_; }
  const WheelCanCounters& counters() const { return counters_; }

 private:
  // Sequence tracking for one frame stream.
  struct Stream {
    bool started = false;
    std::uint8_t last_sequence = 0;
    std::uint32_t last_time = 0;
    std::int64_t time_us = 0;
  };
  CanDecodeResult CheckSequence(Stream* stream, std::uint8_t sequence);
  static void AdvanceTime(Stream* stream, std::uint32_t time_10us, bool first);
  CanDecodeResult Accept(Stream* stream, const CanFrame& frame, std::uint8_t dlc, int sequence_byte, int time_byte);
  CanDecodeResult FeedTicks(const CanFrame& frame);
  CanDecodeResult FeedGyro(const CanFrame& frame);
  CanDecodeResult FeedStatus(const CanFrame& frame);

  Stream ticks_stream_;
  Stream gyro_stream_;
  Stream status_stream_;
  std::uint16_t last_left_ = 0;
  std::uint16_t last_right_ = 0;
  WheelTicks ticks_;
  GyroRate gyro_;
  RobotStatus status_;
  WheelCanCounters counters_;
};

}  // namespace dpcr
