// One candump log line (host_sim/drivers/candump_log.hpp) -> ParseCandumpLine: no crash; an
// accepted line formats to a line that parses to the same record, and formats the same again.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz/fuzz_check.hpp"
#include "host_sim/drivers/candump_log.hpp"

namespace {

bool SameFrame(const dpcr::CanFrame& a, const dpcr::CanFrame& b) {
  if (a.id != b.id || a.dlc != b.dlc) return false;
  if ((a.id & dpcr::kCanRtrFlag) != 0) return true;  // a remote frame carries no data
  return std::memcmp(a.data, b.data, a.dlc) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string line(reinterpret_cast<const char*>(data), size);
  dpcr::CandumpRecord record;
  if (!dpcr::ParseCandumpLine(line, &record)) return 0;
  FUZZ_CHECK(record.frame.dlc <= 8);
  const std::string text = dpcr::FormatCandumpLine(record);
  dpcr::CandumpRecord again;
  FUZZ_CHECK(dpcr::ParseCandumpLine(text, &again));
  FUZZ_CHECK(again.stamp_us == record.stamp_us);
  FUZZ_CHECK(again.interface == record.interface);
  FUZZ_CHECK(SameFrame(again.frame, record.frame));
  FUZZ_CHECK(dpcr::FormatCandumpLine(again) == text);
  return 0;
}
