// The one stamp parser and formatter: exact microseconds, sign, range, and the fixed form.
#include <catch2/catch.hpp>

#include <cstdint>
#include <limits>
#include <string>

#include "host_sim/eval/stamp_text.hpp"

using dpcr::eval::FormatStamp;
using dpcr::eval::ParseExactStamp;
using dpcr::eval::ParseStamp;

namespace {

std::int64_t Parsed(const std::string& text) {
  std::int64_t us = 12345;  // a value no case expects: a parser that skips the write fails
  REQUIRE(ParseStamp(text, &us));
  return us;
}

bool Rejects(const std::string& text) {
  std::int64_t us = 0;
  return !ParseStamp(text, &us);
}

}  // namespace

TEST_CASE("Stamps parse to exact microseconds, extra decimals rounded") {
  CHECK(Parsed("976052857.337530") == 976052857337530LL);
  CHECK(Parsed("12") == 12000000LL);
  CHECK(Parsed("12.5") == 12500000LL);
  CHECK(Parsed("1.0000005") == 1000001LL);
  CHECK(Parsed("1.0000004") == 1000000LL);
  CHECK(Parsed("-1.5") == -1500000LL);
  CHECK(Parsed("-0.000001") == -1LL);
  CHECK(Rejects("1e9"));
  CHECK(Rejects(""));
  CHECK(Rejects("-"));
  CHECK(Rejects(".5"));
  CHECK(Rejects("1.5x"));
  CHECK(Rejects("+1.5"));
  CHECK(Rejects("1.0000000001"));  // more than nine decimals
}

TEST_CASE("Negative stamps format with the sign in front") {
  CHECK(FormatStamp(-1) == "-0.000001");
  CHECK(FormatStamp(-1500000) == "-1.500000");
  CHECK(FormatStamp(-976052857337530LL) == "-976052857.337530");
  CHECK(FormatStamp(0) == "0.000000");
  CHECK(Parsed(FormatStamp(-1)) == -1);
}

TEST_CASE("14-digit stamps: exact when they fit int64 microseconds, rejected when they do not") {
  // 14 digits of microseconds (a monotonic clock after ~5 months) round-trip exactly.
  CHECK(FormatStamp(12345678901234LL) == "12345678.901234");
  CHECK(Parsed("12345678.901234") == 12345678901234LL);
  // 14 digits of seconds are 1e19 us and more: beyond int64, so not a stamp (no silent wrap).
  CHECK(Rejects("12345678901234.000000"));
  CHECK(Rejects("-12345678901234.000000"));
  // The extremes of int64 microseconds round-trip.
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  constexpr std::int64_t kMin = std::numeric_limits<std::int64_t>::min();
  CHECK(FormatStamp(kMax) == "9223372036854.775807");
  CHECK(FormatStamp(kMin) == "-9223372036854.775808");
  CHECK(Parsed(FormatStamp(kMax)) == kMax);
  CHECK(Parsed(FormatStamp(kMin)) == kMin);
  CHECK(Rejects("9223372036854.775808"));
  CHECK(Rejects("-9223372036854.775809"));
}

TEST_CASE("The exact form takes six decimals only") {
  std::int64_t us = 0;
  CHECK(ParseExactStamp("1700000000.010000", &us));
  CHECK(us == 1700000000010000LL);
  CHECK(ParseExactStamp("-2.000001", &us));
  CHECK(us == -2000001LL);
  CHECK_FALSE(ParseExactStamp("1.0", &us));
  CHECK_FALSE(ParseExactStamp("1.0000000", &us));
  CHECK_FALSE(ParseExactStamp("1", &us));
}
