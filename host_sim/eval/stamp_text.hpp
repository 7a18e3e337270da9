// Time stamps as text, "seconds.microseconds" (976052857.337530): the one parser and the one
// formatter behind every host file that carries stamps — TUM trajectories, relations, CARMEN
// logs, candump logs and UART captures.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace dpcr::eval {

// "[-]seconds[.fraction]" -> microseconds; more than six decimals (at most 9) are rounded
// half up. False on anything else, and on a stamp outside int64 microseconds (14-digit seconds).
bool ParseStamp(std::string_view text, std::int64_t* stamp_us);

// Only the form FormatStamp writes (exactly six decimals): candump logs and UART captures are
// written by programs, so any other form is a damaged line, not a stamp.
bool ParseExactStamp(std::string_view text, std::int64_t* stamp_us);

// Exactly six decimals, so that stamps round-trip; negative stamps keep their sign in front
// ("-0.000001"), whatever their size.
std::string FormatStamp(std::int64_t stamp_us);

}  // namespace dpcr::eval
