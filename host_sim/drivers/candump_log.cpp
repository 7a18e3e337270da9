#include "host_sim/drivers/candump_log.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <string_view>

#include "host_sim/eval/stamp_text.hpp"

namespace dpcr {
namespace {

bool ParseHex(const std::string& s, std::uint32_t* out) {
  if (s.empty() || s.size() > 8) return false;
  std::uint32_t v = 0;
  for (char c : s) {
    int d = -1;
    if (c >= '0' && c <= '9') d = c - '0';
    if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
    if (c >= 'A' && c <= 'F') d = c - 'A' + 10;
    if (d < 0) return false;
    v = v * 16 + static_cast<std::uint32_t>(d);
  }
  *out = v;
  return true;
}

}  // namespace

bool ParseCandumpLine(const std::string& line, CandumpRecord* out) {
  // "(sec.usec) iface ID#DATA"
  if (line.size() < 4 || line[0] != '(') return false;
  const std::size_t close = line.find(')');
  if (close == std::string::npos || close + 1 >= line.size() || line[close + 1] != ' ') return false;
  if (!eval::ParseExactStamp(std::string_view(line).substr(1, close - 1), &out->stamp_us)) return false;
  const std::size_t space = line.find(' ', close + 2);
  if (space == std::string::npos) return false;
  out->interface = line.substr(close + 2, space - close - 2);
  std::string frame = line.substr(space + 1);
  const std::size_t end = frame.find_first_of(" \t\r");
  if (end != std::string::npos) frame.resize(end);  // ignore trailing fields (e.g. direction flags)
  const std::size_t hash = frame.find('#');
  if (hash == std::string::npos) return false;
  const std::string id_text = frame.substr(0, hash);
  std::string data = frame.substr(hash + 1);
  if (!data.empty() && data[0] == '#') return false;  // CAN FD
  std::uint32_t id = 0;
  if (!ParseHex(id_text, &id)) return false;
  CanFrame f;
  if (id_text.size() == 3) {
    if (id > kCanSffMask) return false;
    f.id = id;
  } else if (id_text.size() == 8) {
    // An error frame is its class bits and the error flag (the EFF and RTR bits mean nothing
    // there, and FormatCandumpLine does not write them).
    f.id = (id & kCanErrFlag) != 0 ? (id & (kCanErrFlag | kCanEffMask)) : ((id & kCanEffMask) | kCanEffFlag);
  } else {
    return false;
  }
  if (!data.empty() && (data[0] == 'R' || data[0] == 'r')) {
    // "R", or "R" and the requested length as one digit 0-8 (candump writes it when not 0).
    if (data.size() > 2 || (data.size() == 2 && (data[1] < '0' || data[1] > '8'))) return false;
    f.id |= kCanRtrFlag;
    f.dlc = data.size() == 2 ? static_cast<std::uint8_t>(data[1] - '0') : 0;
    out->frame = f;
    return true;
  }
  std::string hex;
  for (char c : data) {
    if (c != '.') hex.push_back(c);  // candump -l may group bytes with '.'
  }
  if (hex.size() % 2 != 0 || hex.size() > 16) return false;
  f.dlc = static_cast<std::uint8_t>(hex.size() / 2);
  for (std::size_t i = 0; i < f.dlc; ++i) {
    std::uint32_t b = 0;
    if (!ParseHex(hex.substr(2 * i, 2), &b)) return false;
    f.data[i] = static_cast<std::uint8_t>(b);
  }
  out->frame = f;
  return true;
}

std::string FormatCandumpLine(const CandumpRecord& record) {
  const CanFrame& f = record.frame;
  char id[16];
  if ((f.id & kCanErrFlag) != 0) {
    std::snprintf(id, sizeof(id), "%08X", f.id & (kCanErrFlag | kCanEffMask));
  } else if ((f.id & kCanEffFlag) != 0) {
    std::snprintf(id, sizeof(id), "%08X", f.id & kCanEffMask);
  } else {
    std::snprintf(id, sizeof(id), "%03X", f.id & kCanSffMask);
  }
  std::string line = "(" + eval::FormatStamp(record.stamp_us) + ") " + record.interface + " " + id + "#";
  if ((f.id & kCanRtrFlag) != 0) {
    line += "R";
    if (f.dlc > 0 && f.dlc <= 8) line.push_back(static_cast<char>('0' + f.dlc));
    return line;
  }
  static const char kHex[] = "0123456789ABCDEF";
  for (int i = 0; i < f.dlc && i < 8; ++i) {
    line.push_back(kHex[f.data[i] >> 4]);
    line.push_back(kHex[f.data[i] & 0xF]);
  }
  return line;
}

bool ReadCandumpLog(const std::string& path, std::vector<CandumpRecord>* out, std::string* error,
                    SkippedLines* skipped) {
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open: " + std::strerror(errno);
    return false;
  }
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    CandumpRecord r;
    if (!ParseCandumpLine(line, &r)) {
      if (!SkipBadLine(skipped, path + ":" + std::to_string(number) + ": not a candump log line: " + line.substr(0, 60), error)) {
        return false;
      }
      continue;
    }
    out->push_back(std::move(r));
  }
  return true;
}

bool WriteCandumpLog(const std::string& path, const std::vector<CandumpRecord>& records, std::string* error) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) {
    *error = path + ": cannot create: " + std::strerror(errno);
    return false;
  }
  bool ok = true;
  for (const CandumpRecord& r : records) ok = ok && std::fprintf(f, "%s\n", FormatCandumpLine(r).c_str()) > 0;
  ok = std::fclose(f) == 0 && ok;
  if (!ok) *error = path + ": write failed";
  return ok;
}

CanRead CandumpSource::Read() {
  CanRead r;
  if (next_ >= records_.size()) {
    r.status = IoStatus::kEndOfStream;
    return r;
  }
  if (clock_ != nullptr && records_[next_].stamp_us > clock_->NowUs()) {
    r.status = IoStatus::kWouldBlock;
    return r;
  }
  r.frame = records_[next_].frame;
  r.stamp_us = records_[next_].stamp_us;
  ++next_;
  return r;
}

std::int64_t CandumpSource::next_stamp_us() const {
  return next_ < records_.size() ? records_[next_].stamp_us : std::numeric_limits<std::int64_t>::max();
}

}  // namespace dpcr
