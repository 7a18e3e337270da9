// Lidar bytes -> revolutions: the packet decoder (LD06 or XV-11), packet timing and the
// ScanAssembler in one object, shared by the firmware and the host replay.
// Timing: kArrival takes the host arrival time of the bytes that complete a packet as the
// time of its last point (exact for emitted device files, within UART latency on a robot);
// kDeviceClock (LD06 only) uses the sensor's millisecond timestamp, mapped to host time by its
// least-delayed packets (Ld06TimeBase in hal/ld06_decoder.hpp, over DeviceTimeBase): bytes
// handed over in bursts (a USB-serial adapter's latency timer) or a late reader do not move the
// stamps (docs/board.md).
#pragma once

#include <cstddef>
#include <cstdint>

#include "hal/ld06_decoder.hpp"
#include "hal/scan_assembler.hpp"
#include "hal/xv11_decoder.hpp"

namespace dpcr {

enum class LidarKind : std::uint8_t { kLd06, kXv11 };
enum class LidarTiming : std::uint8_t { kArrival, kDeviceClock };

struct LidarStreamConfig {
  LidarKind kind = LidarKind::kLd06;
  LidarTiming timing = LidarTiming::kArrival;
  ScanAssemblerConfig assembler;
};

struct LidarStreamCounters {
  std::uint32_t packets = 0;
  std::uint32_t bad_packets = 0;      // CRC / checksum failures
  std::uint32_t resyncs = 0;
  std::uint32_t discarded_bytes = 0;
  std::uint32_t out_of_range = 0;     // LD06: bad fields or far points; XV-11: far points
  std::uint32_t invalid_points = 0;   // XV-11 invalid-data flag
  std::uint32_t revolutions = 0;
  std::uint32_t gaps = 0;
  std::uint32_t dropouts = 0;
  std::uint32_t decimated = 0;
  std::uint32_t partial_dropped = 0;
};

class LidarStream {
 public:
  explicit LidarStream(const LidarStreamConfig& config = LidarStreamConfig());

  // Consumes bytes that arrived at `arrival_us`; stops early when a revolution is ready
  // (take it, then feed the rest). Returns the number of bytes consumed.
  std::size_t Feed(const std::uint8_t* data, std::size_t size, std::int64_t arrival_us);
  bool revolution_ready() const { return assembler_.revolution_ready(); }
  // End of the stream: the last revolution, if nearly complete, becomes ready (ScanAssembler::Flush).
  bool Flush() { return assembler_.Flush(); }
  template <int N>
  void TakeScan(Scan<N>* out, RevolutionInfo* info = nullptr) {
    assembler_.TakeScan(out, info);
  }
  LidarStreamCounters counters() const;
  // Host time of the last accepted packet (0 before the first): for "lidar silent" timeouts.
  std::int64_t last_packet_us() const { return last_packet_us_; }

 private:
  void OnPacket(const LidarPacket& packet);

  LidarStreamConfig config_;
  Ld06Decoder ld06_;
  Xv11Decoder xv11_;
  Ld06TimeBase time_base_;
  ScanAssembler assembler_;
  std::int64_t last_packet_us_ = 0;
};

}  // namespace dpcr
