// Records what the firmware received, with the stamps it gave it, as device files the host
// replays (`dpcr-replay --uart DIR/lidar.uart --candump DIR/wheels.log`): the UART capture
// format (docs/uart-capture-format.md) and the candump log format. Decorators over the ports,
// for tests (tools/emulated-board-test): the firmware's work is unchanged, each read is written
// through a buffered file.
#pragma once

#include <cstdio>
#include <string>

#include "hal/device_options.hpp"
#include "hal/ports.hpp"

namespace dpcr::board {

class StreamRecorder {
 public:
  StreamRecorder() = default;
  ~StreamRecorder();
  StreamRecorder(const StreamRecorder&) = delete;
  StreamRecorder& operator=(const StreamRecorder&) = delete;

  // Creates DIR/lidar.uart and DIR/wheels.log, and writes DIR/device.json (the device options
  // the firmware runs with and its lidar, "ld06" / "xv11": what `dpcr-replay --uart` reads);
  // `can_interface` names the frames' interface.
  bool Open(const std::string& dir, const std::string& can_interface, const DeviceOptions& device,
            const char* lidar, std::string* error);
  void RecordLidar(std::int64_t stamp_us, const std::uint8_t* data, std::size_t size);
  void RecordCan(std::int64_t stamp_us, const CanFrame& frame);
  // `end_us`: when the firmware stops reading (it then takes the last revolution), written as
  // "# end STAMP" in lidar.uart so that the replay does the same; INT64_MIN: none.
  bool Close(std::int64_t end_us = INT64_MIN);

 private:
  std::FILE* uart_ = nullptr;
  std::FILE* can_ = nullptr;
  std::string interface_;
};

class RecordingByteSource : public ByteSource {
 public:
  RecordingByteSource(ByteSource* inner, StreamRecorder* recorder) : inner_(inner), recorder_(recorder) {}
  ByteRead Read(std::uint8_t* buffer, std::size_t capacity) override;

 private:
  ByteSource* inner_;
  StreamRecorder* recorder_;
};

class RecordingCanSource : public CanSource {
 public:
  RecordingCanSource(CanSource* inner, StreamRecorder* recorder) : inner_(inner), recorder_(recorder) {}
  CanRead Read() override;

 private:
  CanSource* inner_;
  StreamRecorder* recorder_;
};

}  // namespace dpcr::board
