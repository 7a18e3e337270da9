// CRC-32 as zlib, PNG and Ethernet compute it (reflected polynomial 0xEDB88320, initial value and
// final xor 0xFFFFFFFF): crc32 of "123456789" is 0xCBF43926. Incremental, table-driven (1 KiB
// of read-only data), no state besides the running value.
#pragma once

#include <cstddef>
#include <cstdint>

namespace dpcr {

class Crc32 {
 public:
  void Add(const std::uint8_t* data, std::size_t size);
  std::uint32_t value() const { return ~state_; }

 private:
  std::uint32_t state_ = 0xFFFFFFFFu;
};

inline std::uint32_t Crc32Of(const std::uint8_t* data, std::size_t size) {
  Crc32 c;
  c.Add(data, size);
  return c.value();
}

}  // namespace dpcr
