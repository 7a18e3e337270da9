// candump log files, the format `candump -l` writes and `canplayer` replays:
//   (1700000000.010000) can0 120#E803D0070A102700
// Standard IDs are 3 hex digits, extended IDs 8 (CAN_EFF_FLAG set), error frames 8 digits with
// CAN_ERR_FLAG (0x2xxxxxxx), remote frames "ID#R". CAN FD lines ("ID##F...") are rejected.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "hal/can_frame.hpp"
#include "hal/ports.hpp"
#include "host_sim/drivers/skipped_lines.hpp"

namespace dpcr {

struct CandumpRecord {
  std::int64_t stamp_us = 0;
  std::string interface = "can0";
  CanFrame frame;
};

bool ParseCandumpLine(const std::string& line, CandumpRecord* out);
std::string FormatCandumpLine(const CandumpRecord& record);

// Reads a whole log; false with "path:line: reason" on the first bad line.
// With `skipped`, a line that does not parse is counted there and the reading goes on.
bool ReadCandumpLog(const std::string& path, std::vector<CandumpRecord>* out, std::string* error,
                    SkippedLines* skipped = nullptr);
bool WriteCandumpLog(const std::string& path, const std::vector<CandumpRecord>& records, std::string* error);

// A CanSource over loaded records. With a clock (a ReplayClock), a record stamped later than
// its now is not there yet: kWouldBlock.
class CandumpSource : public CanSource {
 public:
  explicit CandumpSource(std::vector<CandumpRecord> records, const Clock* clock = nullptr)
      : records_(std::move(records)), clock_(clock) {}
  CanRead Read() override;
  // Stamp of the next unread record (INT64_MAX at the end).
  std::int64_t next_stamp_us() const;

 private:
  std::vector<CandumpRecord> records_;
  const Clock* clock_;
  std::size_t next_ = 0;
};

}  // namespace dpcr
