#include "core/base/assert.hpp"

namespace dpcr {
namespace {
// The only mutable global of the core: set once at start-up, read on a bug.
AssertHandler g_handler = nullptr;
}  // namespace

void SetAssertHandler(AssertHandler handler) { g_handler = handler; }

void AssertFailed(const char* expression, const char* file, int line) {
  if (g_handler != nullptr) g_handler(expression, file, line);
  // A handler that returns (or none) must not let the bug go on.
  __builtin_trap();
}

}  // namespace dpcr
