// One UART capture data line (docs/uart-capture-format.md) -> ParseUartCaptureLine: no crash;
// an accepted line formats to one that parses to the same chunk.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_check.hpp"
#include "host_sim/drivers/uart_capture.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string line(reinterpret_cast<const char*>(data), size);
  dpcr::UartChunk chunk;
  if (!dpcr::ParseUartCaptureLine(line, &chunk)) return 0;
  FUZZ_CHECK(!chunk.bytes.empty());
  const std::string text = dpcr::FormatUartCaptureLine(chunk.stamp_us, chunk.bytes.data(), chunk.bytes.size());
  dpcr::UartChunk again;
  FUZZ_CHECK(dpcr::ParseUartCaptureLine(text, &again));
  FUZZ_CHECK(again.stamp_us == chunk.stamp_us && again.bytes == chunk.bytes);
  return 0;
}
