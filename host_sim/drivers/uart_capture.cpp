#include "host_sim/drivers/uart_capture.hpp"

#include <cstring>
#include <fstream>
#include <limits>
#include <string_view>

#include "host_sim/eval/stamp_text.hpp"

namespace dpcr {
namespace {

constexpr const char* kMagic = "# dpcr-uart-capture 1";
constexpr const char* kEndMarker = "# end ";
constexpr std::size_t kMaxChunk = 4096;

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

bool ParseUartCaptureLine(const std::string& line, UartChunk* out) {
  const std::size_t space = line.find(' ');
  if (space == std::string::npos) return false;
  if (!eval::ParseExactStamp(std::string_view(line).substr(0, space), &out->stamp_us)) return false;
  const std::size_t hex_len = line.size() - space - 1;
  if (hex_len == 0 || hex_len % 2 != 0 || hex_len / 2 > kMaxChunk) return false;
  out->bytes.resize(hex_len / 2);
  for (std::size_t i = 0; i < hex_len / 2; ++i) {
    const int hi = HexValue(line[space + 1 + 2 * i]);
    const int lo = HexValue(line[space + 2 + 2 * i]);
    if (hi < 0 || lo < 0) return false;
    out->bytes[i] = static_cast<std::uint8_t>(hi * 16 + lo);
  }
  return true;
}

std::string FormatUartCaptureLine(std::int64_t stamp_us, const std::uint8_t* data, std::size_t size) {
  static const char kHex[] = "0123456789ABCDEF";
  std::string line = eval::FormatStamp(stamp_us);
  line.push_back(' ');
  for (std::size_t i = 0; i < size; ++i) {
    line.push_back(kHex[data[i] >> 4]);
    line.push_back(kHex[data[i] & 0xF]);
  }
  return line;
}

bool ReadUartCapture(const std::string& path, std::vector<UartChunk>* out, std::string* error, std::int64_t* end_us,
                     SkippedLines* skipped) {
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open: " + std::strerror(errno);
    return false;
  }
  std::string line;
  int number = 0;
  std::int64_t last = std::numeric_limits<std::int64_t>::min();
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1 && line != kMagic) {
      *error = path + ":1: not a dpcr UART capture (expected '" + kMagic + "')";
      return false;
    }
    if (line.rfind(kEndMarker, 0) == 0 && end_us != nullptr) {
      UartChunk end;  // "# end STAMP": parsed as a chunk line without bytes
      if (!ParseUartCaptureLine(line.substr(std::strlen(kEndMarker)) + " 00", &end)) {
        *error = path + ":" + std::to_string(number) + ": malformed end line";
        return false;
      }
      *end_us = end.stamp_us;
      continue;
    }
    if (line.empty() || line[0] == '#') continue;
    UartChunk chunk;
    if (!ParseUartCaptureLine(line, &chunk) || chunk.stamp_us < last) {
      if (!SkipBadLine(skipped, path + ":" + std::to_string(number) + ": malformed or out-of-order chunk", error)) {
        return false;
      }
      continue;
    }
    last = chunk.stamp_us;
    out->push_back(std::move(chunk));
  }
  if (number == 0) {
    *error = path + ": empty file";
    return false;
  }
  return true;
}

UartCaptureWriter::~UartCaptureWriter() { Close(); }

bool UartCaptureWriter::Open(const std::string& path, const std::string& device, std::string* error) {
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) {
    *error = path + ": cannot create: " + std::strerror(errno);
    return false;
  }
  std::fprintf(file_, "%s\n# device %s\n", kMagic, device.c_str());
  return true;
}

bool UartCaptureWriter::Write(std::int64_t stamp_us, const std::uint8_t* data, std::size_t size) {
  for (std::size_t at = 0; at < size; at += kMaxChunk) {
    const std::size_t n = size - at < kMaxChunk ? size - at : kMaxChunk;
    const std::string line = FormatUartCaptureLine(stamp_us, data + at, n);
    if (std::fprintf(file_, "%s\n", line.c_str()) < 0) return false;
  }
  return true;
}

bool UartCaptureWriter::Close() {
  if (file_ == nullptr) return true;
  const bool ok = std::fclose(file_) == 0;
  file_ = nullptr;
  return ok;
}

ByteRead UartCaptureSource::Read(std::uint8_t* buffer, std::size_t capacity) {
  ByteRead r;
  if (chunk_ >= chunks_.size()) {
    r.status = IoStatus::kEndOfStream;
    return r;
  }
  if (clock_ != nullptr && chunks_[chunk_].stamp_us > clock_->NowUs()) {
    r.status = IoStatus::kWouldBlock;
    return r;
  }
  const UartChunk& c = chunks_[chunk_];
  const std::size_t n = c.bytes.size() - offset_ < capacity ? c.bytes.size() - offset_ : capacity;
  std::memcpy(buffer, c.bytes.data() + offset_, n);
  r.size = n;
  r.stamp_us = c.stamp_us;
  offset_ += n;
  if (offset_ == c.bytes.size()) {
    ++chunk_;
    offset_ = 0;
  }
  return r;
}

std::int64_t UartCaptureSource::next_stamp_us() const {
  return chunk_ < chunks_.size() ? chunks_[chunk_].stamp_us : std::numeric_limits<std::int64_t>::max();
}

}  // namespace dpcr
