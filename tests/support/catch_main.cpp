// Catch2 main for every test binary. Core asserts fail the test run instead of trapping.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>

#include "core/base/assert.hpp"

namespace {
void FailOnCoreAssert(const char* expression, const char* file, int line) {
  std::fprintf(stderr, "core assert failed: %s at %s:%d\n", expression, file, line);
  std::abort();
}
}  // namespace

int main(int argc, char* argv[]) {
  dpcr::SetAssertHandler(&FailOnCoreAssert);
  return Catch::Session().run(argc, argv);
}
