#include "hal/wheel_can_protocol.hpp"

#include "hal/byte_order.hpp"

namespace dpcr {
namespace {

// A sequence step of 1..127 is "newer" (lost = step - 1); 128..255 is an older frame.
constexpr int kSequenceHalfRange = 128;

std::int16_t Wrap16(int v) { return static_cast<std::int16_t>(static_cast<std::uint16_t>(v & 0xFFFF)); }

}  // namespace

CanFrame EncodeWheelFrame(const WheelTicksFrame& frame) {
  CanFrame out;
  out.id = kWheelTicksCanId;
  out.dlc = kWheelTicksDlc;
  StoreLe16(&out.data[0], frame.left_ticks);
  StoreLe16(&out.data[2], frame.right_ticks);
  out.data[4] = frame.sequence;
  StoreLe24(&out.data[5], frame.time_10us);
  return out;
}

CanFrame EncodeGyroFrame(const GyroFrame& frame) {
  CanFrame out;
  out.id = kGyroCanId;
  out.dlc = kGyroDlc;
  StoreLe16(&out.data[0], static_cast<std::uint16_t>(frame.yaw_rate_mrad_s));
  out.data[2] = frame.sequence;
  StoreLe24(&out.data[3], frame.time_10us);
  return out;
}

CanFrame EncodeStatusFrame(const StatusFrame& frame) {
  CanFrame out;
  out.id = kStatusCanId;
  out.dlc = kStatusDlc;
  out.data[0] = frame.flags;
  out.data[1] = frame.sequence;
  StoreLe24(&out.data[2], frame.time_10us);
  return out;
}

// kTicks here means "accepted" for every stream.
CanDecodeResult WheelCanDecoder::CheckSequence(Stream* stream, std::uint8_t sequence) {
  if (!stream->started) return CanDecodeResult::kTicks;
  const int step = (sequence - stream->last_sequence + 256) % 256;
  if (step == 0) {
    ++counters_.duplicated;
    return CanDecodeResult::kDuplicate;
  }
  if (step >= kSequenceHalfRange) {
    ++counters_.reordered;
    if (counters_.lost > 0) --counters_.lost;  // it was counted lost when the gap appeared
    return CanDecodeResult::kReordered;
  }
  counters_.lost += static_cast<std::uint32_t>(step - 1);
  return CanDecodeResult::kTicks;
}

void WheelCanDecoder::AdvanceTime(Stream* stream, std::uint32_t time_10us, bool first) {
  if (first) {
    stream->time_us = static_cast<std::int64_t>(time_10us) * kWheelTimeUnitUs;
  } else {
    const std::int64_t delta =
        (static_cast<std::int64_t>(time_10us) - stream->last_time + kWheelTimeWrapUnits) % kWheelTimeWrapUnits;
    stream->time_us += delta * kWheelTimeUnitUs;
  }
  stream->last_time = time_10us;
}

CanDecodeResult WheelCanDecoder::Feed(const CanFrame& frame) {
  if ((frame.id & kCanErrFlag) != 0) {
    ++counters_.error_frames;
    return CanDecodeResult::kErrorFrame;
  }
  if ((frame.id & (kCanEffFlag | kCanRtrFlag)) != 0) {
    ++counters_.foreign;
    return CanDecodeResult::kIgnored;
  }
  switch (frame.id) {
    case kWheelTicksCanId:
      return FeedTicks(frame);
    case kGyroCanId:
      return FeedGyro(frame);
    case kStatusCanId:
      return FeedStatus(frame);
    default:
      ++counters_.foreign;
      return CanDecodeResult::kIgnored;
  }
}

// What every stream's frame goes through: its DLC, its sequence (lost, duplicated, reordered
// frames) and its device time. kTicks: accepted and the stream's clock advanced (the caller reads
// the payload); otherwise the verdict to return.
CanDecodeResult WheelCanDecoder::Accept(Stream* stream, const CanFrame& frame, std::uint8_t dlc, int sequence_byte,
                                        int time_byte) {
  if (frame.dlc != dlc) {
    ++counters_.bad_dlc;
    return CanDecodeResult::kBadDlc;
  }
  const std::uint8_t sequence = frame.data[sequence_byte];
  const CanDecodeResult r = CheckSequence(stream, sequence);
  if (r != CanDecodeResult::kTicks) return r;
  AdvanceTime(stream, LoadLe24(&frame.data[time_byte]), !stream->started);
  stream->started = true;
  stream->last_sequence = sequence;
  return CanDecodeResult::kTicks;
}

CanDecodeResult WheelCanDecoder::FeedTicks(const CanFrame& frame) {
  const bool first = !ticks_stream_.started;
  const CanDecodeResult r = Accept(&ticks_stream_, frame, kWheelTicksDlc, 4, 5);
  if (r != CanDecodeResult::kTicks) return r;
  const std::uint16_t left = LoadLe16(&frame.data[0]);
  const std::uint16_t right = LoadLe16(&frame.data[2]);
  if (first) {
    ticks_.left_ticks = left;
    ticks_.right_ticks = right;
  } else {
    ticks_.left_ticks += Wrap16(left - last_left_);
    ticks_.right_ticks += Wrap16(right - last_right_);
  }
  last_left_ = left;
  last_right_ = right;
  ticks_.device_time_us = ticks_stream_.time_us;
  ++counters_.ticks_frames;
  return CanDecodeResult::kTicks;
}

CanDecodeResult WheelCanDecoder::FeedGyro(const CanFrame& frame) {
  const CanDecodeResult r = Accept(&gyro_stream_, frame, kGyroDlc, 2, 3);
  if (r != CanDecodeResult::kTicks) return r;
  gyro_.device_time_us = gyro_stream_.time_us;
  gyro_.yaw_rate_rad_s = static_cast<float>(static_cast<std::int16_t>(LoadLe16(&frame.data[0]))) * 0.001f;
  ++counters_.gyro_frames;
  return CanDecodeResult::kGyro;
}

CanDecodeResult WheelCanDecoder::FeedStatus(const CanFrame& frame) {
  const CanDecodeResult r = Accept(&status_stream_, frame, kStatusDlc, 1, 2);
  if (r != CanDecodeResult::kTicks) return r;
  const std::uint8_t flags = frame.data[0];
  // A newer sender may define more flags: the frame still says what bit 0 says.
  if ((flags & kStatusReservedFlags) != 0) ++counters_.reserved_flags;
  status_.device_time_us = status_stream_.time_us;
  status_.lifted = (flags & kStatusLiftedFlag) != 0;
  ++counters_.status_frames;
  return CanDecodeResult::kStatus;
}

}  // namespace dpcr
