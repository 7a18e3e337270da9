// UART capture files (docs/uart-capture-format.md): timestamped chunks of raw bytes.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "hal/ports.hpp"
#include "host_sim/drivers/skipped_lines.hpp"

namespace dpcr {

struct UartChunk {
  std::int64_t stamp_us = 0;
  std::vector<std::uint8_t> bytes;
};

// Reads a whole capture; false with a message naming the file and line on a bad line
// (chunks before it are kept in `out`), unless `skipped` is given: then a chunk line that does not
// parse or goes back in time is counted there and the reading goes on. `end_us`, when given,
// receives the stamp of an "# end STAMP" line (a recording's end: when the firmware took its last
// revolution), else is left as it was. A file without the header line is an error either way.
bool ReadUartCapture(const std::string& path, std::vector<UartChunk>* out, std::string* error,
                     std::int64_t* end_us = nullptr, SkippedLines* skipped = nullptr);
// Parses one data line ("sec.usec HEX"); false if malformed.
bool ParseUartCaptureLine(const std::string& line, UartChunk* out);
std::string FormatUartCaptureLine(std::int64_t stamp_us, const std::uint8_t* data, std::size_t size);

class UartCaptureWriter {
 public:
  UartCaptureWriter() = default;
  ~UartCaptureWriter();
  UartCaptureWriter(const UartCaptureWriter&) = delete;
  UartCaptureWriter& operator=(const UartCaptureWriter&) = delete;

  // `device` goes in a comment line (e.g. "ld06 baud 230400").
  bool Open(const std::string& path, const std::string& device, std::string* error);
  // Splits chunks longer than 4096 bytes.
  bool Write(std::int64_t stamp_us, const std::uint8_t* data, std::size_t size);
  bool Close();

 private:
  std::FILE* file_ = nullptr;
};

// A ByteSource over loaded chunks: each Read returns (part of) one chunk with its stamp. With a
// clock (a ReplayClock), a chunk stamped later than its now is not there yet: kWouldBlock.
class UartCaptureSource : public ByteSource {
 public:
  explicit UartCaptureSource(std::vector<UartChunk> chunks, const Clock* clock = nullptr)
      : chunks_(std::move(chunks)), clock_(clock) {}
  ByteRead Read(std::uint8_t* buffer, std::size_t capacity) override;
  // Stamp of the next unread chunk (INT64_MAX at the end).
  std::int64_t next_stamp_us() const;

 private:
  std::vector<UartChunk> chunks_;
  const Clock* clock_;
  std::size_t chunk_ = 0;
  std::size_t offset_ = 0;
};

}  // namespace dpcr
