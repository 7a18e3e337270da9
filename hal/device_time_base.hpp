// The wheel board's clock in host time (and the LD06's: hal/ld06_decoder.hpp). Each frame
// carries its device time d and arrives at host time a = d + offset + latency: latency >= the
// bus's minimum, with jitter above it (a busy bus, a late interrupt, a loaded SoC), and the
// offset moves with the drift between the two crystals (20-50 ppm: 80-210 ms in 70 minutes). The
// first frame's offset (the old way) keeps that frame's latency and none of the drift.
//
// The estimate follows the lower envelope of a - d, the least-delayed frames: the smallest
// a - d of each block of kBlockUs device time, over the last kBlocks blocks; their drift is the
// least-squares slope of those minima, and the offset at device time d is the lowest of them,
// each carried forward to d along that slope. Jitter only ever delays a frame, so the minima
// track the minimum latency (a reader stalled for seconds only raises a - d: ignored); the slope
// follows the drift. A device clock that steps back by more than kRestartUs (the board
// restarted) starts the estimate again. No heap, fixed state (~1 KiB).
#pragma once

#include <cstdint>

namespace dpcr {

class DeviceTimeBase {
 public:
  enum class Mode : std::uint8_t {
    kTracked,     // the minimum-latency, drift-following estimate (the firmware's)
    kFirstFrame,  // the first frame's offset for ever (the old way: for comparison only)
  };
  explicit DeviceTimeBase(Mode mode = Mode::kTracked) : mode_(mode) {}

  static constexpr std::int64_t kBlockUs = 2000000;      // 2 s: ~200 ticks frames per minimum
  static constexpr int kBlocks = 32;                     // a 64 s window
  static constexpr std::int64_t kRestartUs = 1000000;    // the device clock back by 1 s: a new clock
  static constexpr double kMaxDriftPpm = 500.0;          // a fitted drift past this is noise
  static constexpr double kLateToleranceUs = 1000.0;     // a block's minimum this far above the envelope: late

  // Observes one frame (device time `device_us`, unwrapped; arrival `host_us`) and returns its
  // device time in host time.
  std::int64_t ToHostUs(std::int64_t device_us, std::int64_t host_us);

  // The current estimate: host = device + offset (at the last frame's device time); drift in ppm
  // (host minus device rate), 0 until the window holds kMinBlocksForDrift blocks.
  std::int64_t offset_us() const { return OffsetAt(last_device_us_); }
  double drift_ppm() const { return slope_ * 1e6; }
  std::uint32_t restarts() const { return restarts_; }

  static constexpr int kMinBlocksForDrift = 4;

 private:
  struct Block {
    std::int64_t device_us;  // device time of the block's least-delayed frame
    std::int64_t offset_us;  // its arrival - device time
  };
  void Restart(std::int64_t device_us, std::int64_t offset);
  void CloseBlock();
  void FitDrift();
  bool Late(int block) const;
  std::int64_t OffsetAt(std::int64_t device_us) const;

  Mode mode_;
  bool started_ = false;
  Block blocks_[kBlocks] = {};
  int block_count_ = 0;
  int block_next_ = 0;           // ring position of the next closed block
  Block current_{};              // the block being filled
  std::int64_t block_start_us_ = 0;
  std::int64_t last_device_us_ = 0;
  double slope_ = 0.0;           // d(offset)/d(device time)
  std::uint32_t restarts_ = 0;
};

}  // namespace dpcr
