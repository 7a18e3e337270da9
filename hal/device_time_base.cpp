#include "hal/device_time_base.hpp"

#include <cmath>
#include <cstdlib>

namespace dpcr {

void DeviceTimeBase::Restart(std::int64_t device_us, std::int64_t offset) {
  started_ = true;
  block_count_ = 0;
  block_next_ = 0;
  slope_ = 0.0;
  current_ = Block{device_us, offset};
  block_start_us_ = device_us;
}

void DeviceTimeBase::CloseBlock() {
  blocks_[block_next_] = current_;
  block_next_ = (block_next_ + 1) % kBlocks;
  if (block_count_ < kBlocks) ++block_count_;
  FitDrift();
}

// A block whose minimum lies above another's by more than the largest drift between them could
// make, plus kLateToleranceUs: all its frames were late (a reader stalled longer than a block).
bool DeviceTimeBase::Late(int i) const {
  for (int j = 0; j < block_count_; ++j) {
    const double apart_us = std::fabs(static_cast<double>(blocks_[i].device_us - blocks_[j].device_us));
    if (static_cast<double>(blocks_[i].offset_us - blocks_[j].offset_us) > kMaxDriftPpm * 1e-6 * apart_us + kLateToleranceUs) {
      return true;
    }
  }
  return false;
}

// Least squares of the blocks' minima against their device times (centred: no precision lost
// to hours of microseconds), late blocks left out: one block of a stalled reader's frames,
// seconds late, pulled the slope to its bound and every stamp after it off by milliseconds.
void DeviceTimeBase::FitDrift() {
  bool late[kBlocks] = {};
  int used = 0;
  double mean_d = 0.0;
  double mean_o = 0.0;
  for (int i = 0; i < block_count_; ++i) {
    late[i] = Late(i);
    if (late[i]) continue;
    ++used;
    mean_d += static_cast<double>(blocks_[i].device_us - current_.device_us);
    mean_o += static_cast<double>(blocks_[i].offset_us - current_.offset_us);
  }
  if (used < kMinBlocksForDrift) return;
  mean_d /= used;
  mean_o /= used;
  double sdd = 0.0;
  double sdo = 0.0;
  for (int i = 0; i < block_count_; ++i) {
    if (late[i]) continue;
    const double d = static_cast<double>(blocks_[i].device_us - current_.device_us) - mean_d;
    const double o = static_cast<double>(blocks_[i].offset_us - current_.offset_us) - mean_o;
    sdd += d * d;
    sdo += d * o;
  }
  if (sdd <= 0.0) return;
  const double slope = sdo / sdd;
  const double limit = kMaxDriftPpm * 1e-6;
  slope_ = slope > limit ? limit : (slope < -limit ? -limit : slope);
}

std::int64_t DeviceTimeBase::OffsetAt(std::int64_t device_us) const {
  double best = static_cast<double>(current_.offset_us) + slope_ * static_cast<double>(device_us - current_.device_us);
  for (int i = 0; i < block_count_; ++i) {
    const double o =
        static_cast<double>(blocks_[i].offset_us) + slope_ * static_cast<double>(device_us - blocks_[i].device_us);
    if (o < best) best = o;
  }
  return static_cast<std::int64_t>(std::llround(best));
}

std::int64_t DeviceTimeBase::ToHostUs(std::int64_t device_us, std::int64_t host_us) {
  const std::int64_t offset = host_us - device_us;
  if (!started_) {
    Restart(device_us, offset);
  } else if (mode_ == Mode::kFirstFrame) {
    // the offset of the first frame stays
  } else if (device_us < last_device_us_ - kRestartUs) {
    ++restarts_;  // the device clock went back: the board restarted
    Restart(device_us, offset);
  } else {
    if (device_us - block_start_us_ >= kBlockUs) {
      CloseBlock();
      current_ = Block{device_us, offset};
      block_start_us_ = device_us;
    } else if (offset < current_.offset_us) {
      current_ = Block{device_us, offset};
    }
  }
  last_device_us_ = device_us;
  return device_us + OffsetAt(device_us);
}

}  // namespace dpcr
