// Time stamps as text (host_sim/eval/stamp_text.hpp), behind every host file with stamps (TUM,
// relations, CARMEN, candump, UART captures): no crash; FormatStamp's text parses back exactly,
// by both parsers, and a stamp ParseExactStamp accepts is one ParseStamp reads the same.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "fuzz/fuzz_check.hpp"
#include "host_sim/eval/stamp_text.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::int64_t loose = 0, exact = 0;
  const bool loose_ok = dpcr::eval::ParseStamp(text, &loose);
  if (dpcr::eval::ParseExactStamp(text, &exact)) {
    FUZZ_CHECK(loose_ok && loose == exact);
  }
  if (loose_ok) {
    const std::string formatted = dpcr::eval::FormatStamp(loose);
    std::int64_t back = 0;
    FUZZ_CHECK(dpcr::eval::ParseExactStamp(formatted, &back) && back == loose);
    FUZZ_CHECK(dpcr::eval::ParseStamp(formatted, &back) && back == loose);
  }
  // Any 8 bytes as a stamp: formatted and parsed back.
  if (size >= 8) {
    std::int64_t any = 0;
    std::memcpy(&any, data, 8);
    std::int64_t back = 0;
    const std::string formatted = dpcr::eval::FormatStamp(any);
    FUZZ_CHECK(dpcr::eval::ParseExactStamp(formatted, &back) && back == any);
  }
  return 0;
}
