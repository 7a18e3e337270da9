// CRC-8 of LDROBOT LD06/LD19 packets: polynomial 0x4D, initial value 0, no reflection, no final
// XOR (the 256-entry table in LDROBOT's SDK, ldlidar_driver/src/dataprocess/lipkg.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

namespace dpcr {

// The CRC of `size` bytes, continuing from `crc` (0 for a fresh packet).
std::uint8_t Crc8Ld(const std::uint8_t* data, std::size_t size, std::uint8_t crc = 0);

// One table entry (exposed for the golden test against the vendor table).
std::uint8_t Crc8LdTableEntry(std::uint8_t index);

}  // namespace dpcr
