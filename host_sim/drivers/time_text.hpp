// "sec.usec" time stamps as candump and UART captures write them (exactly six decimals).
#pragma once

#include <cstdint>
#include <string>

namespace dpcr {

bool ParseSecUsec(const std::string& text, std::int64_t* stamp_us);
std::string FormatSecUsec(std::int64_t stamp_us);

}  // namespace dpcr
