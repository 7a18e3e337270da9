#include "board/stream_recorder.hpp"

#include <cerrno>
#include <cinttypes>
#include <cstring>

namespace dpcr::board {
namespace {

constexpr std::size_t kMaxChunk = 4096;  // the capture format's longest line of bytes
constexpr char kHex[] = "0123456789ABCDEF";

void PrintStamp(std::FILE* f, std::int64_t stamp_us) {
  const std::int64_t s = stamp_us / 1000000;
  const std::int64_t us = stamp_us % 1000000;
  std::fprintf(f, "%" PRId64 ".%06" PRId64, s, us < 0 ? -us : us);
}

}  // namespace

StreamRecorder::~StreamRecorder() { Close(); }

bool StreamRecorder::Open(const std::string& dir, const std::string& can_interface, const DeviceOptions& device,
                          const char* lidar, std::string* error) {
  Close();
  // device.json, the keys of dpcr-sim --emit-device (host_sim/drivers/device_files.cpp).
  const std::string json_path = dir + "/device.json";
  std::FILE* json = std::fopen(json_path.c_str(), "w");
  if (json == nullptr) {
    *error = json_path + ": " + std::strerror(errno);
    return false;
  }
  std::fprintf(json,
               "{\n  \"lidar\": \"%s\",\n  \"angle_sign\": %.1f,\n  \"wheel_radius_m\": %.9g,\n"
               "  \"track_width_m\": %.9g,\n  \"ticks_per_rev\": %.9g,\n  \"max_range_m\": %.9g,\n"
               "  \"laser_offset_m\": %.9g\n}\n",
               lidar, static_cast<double>(device.angle_sign), static_cast<double>(device.wheels.wheel_radius_m),
               static_cast<double>(device.wheels.track_width_m), static_cast<double>(device.wheels.ticks_per_rev),
               static_cast<double>(device.max_range_m), static_cast<double>(device.laser_offset_m));
  if (std::fclose(json) != 0) {
    *error = json_path + ": " + std::strerror(errno);
    return false;
  }
  interface_ = can_interface;
  const std::string uart_path = dir + "/lidar.uart";
  const std::string can_path = dir + "/wheels.log";
  uart_ = std::fopen(uart_path.c_str(), "w");
  can_ = std::fopen(can_path.c_str(), "w");
  if (uart_ == nullptr || can_ == nullptr) {
    *error = dir + ": cannot create the recording: " + std::strerror(errno);
    Close();
    return false;
  }
  std::fprintf(uart_, "# dpcr-uart-capture 1\n# device recorded by dpcr-firmware\n");
  return true;
}

void StreamRecorder::RecordLidar(std::int64_t stamp_us, const std::uint8_t* data, std::size_t size) {
  if (uart_ == nullptr) return;
  for (std::size_t at = 0; at < size; at += kMaxChunk) {
    const std::size_t n = size - at < kMaxChunk ? size - at : kMaxChunk;
    PrintStamp(uart_, stamp_us);
    std::fputc(' ', uart_);
    for (std::size_t i = 0; i < n; ++i) {
      std::fputc(kHex[data[at + i] >> 4], uart_);
      std::fputc(kHex[data[at + i] & 0xF], uart_);
    }
    std::fputc('\n', uart_);
  }
}

void StreamRecorder::RecordCan(std::int64_t stamp_us, const CanFrame& f) {
  if (can_ == nullptr) return;
  std::fputc('(', can_);
  PrintStamp(can_, stamp_us);
  std::fprintf(can_, ") %s ", interface_.c_str());
  if ((f.id & kCanErrFlag) != 0) {
    std::fprintf(can_, "%08" PRIX32 "#", f.id & (kCanErrFlag | kCanEffMask));
  } else if ((f.id & kCanEffFlag) != 0) {
    std::fprintf(can_, "%08" PRIX32 "#", f.id & kCanEffMask);
  } else {
    std::fprintf(can_, "%03" PRIX32 "#", f.id & kCanSffMask);
  }
  if ((f.id & kCanRtrFlag) != 0) {
    std::fputs("R\n", can_);
    return;
  }
  for (int i = 0; i < f.dlc && i < 8; ++i) {
    std::fputc(kHex[f.data[i] >> 4], can_);
    std::fputc(kHex[f.data[i] & 0xF], can_);
  }
  std::fputc('\n', can_);
}

bool StreamRecorder::Close(std::int64_t end_us) {
  bool ok = true;
  if (uart_ != nullptr && end_us != INT64_MIN) {
    std::fputs("# end ", uart_);  // the replay takes the last revolution after the frames received before this
    PrintStamp(uart_, end_us);
    std::fputc('\n', uart_);
  }
  if (uart_ != nullptr) ok = std::fclose(uart_) == 0 && ok;
  if (can_ != nullptr) ok = std::fclose(can_) == 0 && ok;
  uart_ = nullptr;
  can_ = nullptr;
  return ok;
}

ByteRead RecordingByteSource::Read(std::uint8_t* buffer, std::size_t capacity) {
  const ByteRead r = inner_->Read(buffer, capacity);
  if (r.status == IoStatus::kOk && r.size > 0) {
    const int saved = errno;
    recorder_->RecordLidar(r.stamp_us, buffer, r.size);
    errno = saved;
  }
  return r;
}

CanRead RecordingCanSource::Read() {
  const CanRead r = inner_->Read();
  if (r.status == IoStatus::kOk) {
    const int saved = errno;
    recorder_->RecordCan(r.stamp_us, r.frame);
    errno = saved;
  }
  return r;
}

}  // namespace dpcr::board
