#include "host_sim/eval/stamp_text.hpp"

#include <cinttypes>
#include <cstdio>
#include <limits>

namespace dpcr::eval {
namespace {

constexpr std::uint64_t kMicrosPerSecond = 1000000;
constexpr std::size_t kMaxDecimals = 9;

bool AllDigits(std::string_view text) {
  for (const char c : text) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

}  // namespace

bool ParseStamp(std::string_view text, std::int64_t* stamp_us) {
  const bool negative = !text.empty() && text.front() == '-';
  if (negative) text.remove_prefix(1);
  const std::size_t dot = text.find('.');
  const std::string_view whole = text.substr(0, dot);
  const std::string_view frac = dot == std::string_view::npos ? std::string_view() : text.substr(dot + 1);
  if (whole.empty() || frac.size() > kMaxDecimals || !AllDigits(whole) || !AllDigits(frac)) return false;
  // The magnitude in unsigned arithmetic, so that INT64_MIN's round-trips too.
  const std::uint64_t limit = negative ? std::uint64_t{1} << 63 : std::numeric_limits<std::int64_t>::max();
  std::uint64_t seconds = 0;
  for (const char c : whole) {
    seconds = seconds * 10 + static_cast<std::uint64_t>(c - '0');
    if (seconds > limit / kMicrosPerSecond) return false;
  }
  std::uint64_t micros = 0;
  for (std::size_t i = 0; i < 6; ++i) micros = micros * 10 + (i < frac.size() ? static_cast<std::uint64_t>(frac[i] - '0') : 0);
  if (frac.size() > 6 && frac[6] >= '5') ++micros;
  const std::uint64_t magnitude = seconds * kMicrosPerSecond + micros;
  if (magnitude > limit) return false;
  *stamp_us = negative ? static_cast<std::int64_t>(~magnitude + 1) : static_cast<std::int64_t>(magnitude);
  return true;
}

bool ParseExactStamp(std::string_view text, std::int64_t* stamp_us) {
  const std::size_t dot = text.find('.');
  if (dot == std::string_view::npos || text.size() - dot - 1 != 6) return false;
  return ParseStamp(text, stamp_us);
}

std::string FormatStamp(std::int64_t stamp_us) {
  // The magnitude in unsigned arithmetic: -INT64_MIN does not fit an int64.
  const std::uint64_t magnitude = stamp_us < 0 ? ~static_cast<std::uint64_t>(stamp_us) + 1 : static_cast<std::uint64_t>(stamp_us);
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%s%" PRIu64 ".%06" PRIu64, stamp_us < 0 ? "-" : "", magnitude / kMicrosPerSecond,
                magnitude % kMicrosPerSecond);
  return buf;
}

}  // namespace dpcr::eval
