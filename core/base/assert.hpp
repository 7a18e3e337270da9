// The one assert macro of the core: for bugs, not for bad input (bad input returns a Status).
// The handler is set once per build: the board aborts, host tests fail the test.
// The default handler traps, so a bug never continues silently.
#pragma once

namespace dpcr {

using AssertHandler = void (*)(const char* expression, const char* file, int line);

// Installs the handler; nullptr restores the default (trap).
void SetAssertHandler(AssertHandler handler);
[[noreturn]] void AssertFailed(const char* expression, const char* file, int line);

}  // namespace dpcr

#define DPCR_ASSERT(condition) \
  ((condition) ? static_cast<void>(0) : ::dpcr::AssertFailed(#condition, __FILE__, __LINE__))
