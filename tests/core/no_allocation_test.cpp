// No heap during reference building or registration: global operator new is replaced in this
// test binary by a counting one (built only with DPCR_ALLOCATION_TESTS, not under sanitizers).
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>
#include <new>

#include "core/registration/classic_plicp.hpp"
#include "core/registration/plicp.hpp"
#include "registration_fixtures.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

TEST_CASE("Building a reference and registering allocate nothing") {
  dpcr_test::GridFixture f;
  const std::vector<dpcr_test::Segment> walls = {{{1.02f, 1.02f}, {6.02f, 1.02f}}, {{6.02f, 1.02f}, {6.02f, 5.02f}},
                                                 {{6.02f, 5.02f}, {1.02f, 5.02f}}, {{1.02f, 5.02f}, {1.02f, 1.02f}}};
  for (const auto& w : walls) f.Draw(w);
  const dpcr::Pose2 truth{3.0f, 3.0f, 0.2f};
  const auto scan = dpcr_test::SimulateScan(walls, truth, 450, 0.01f, 2);
  const dpcr::Span<const dpcr::Point2> target(scan.data(), scan.size());
  const dpcr::PosePrior prior{truth, 10.0f, 10.0f};
  const long before = g_allocations.load();
  const dpcr::Status built = f.Build();
  const auto a = dpcr::RegisterImproved(*f.ref, target, dpcr::Pose2{3.1f, 2.9f, 0.25f}, nullptr, dpcr::PlicpConfig{});
  const auto b = dpcr::RegisterClassic(*f.ref, target, dpcr::Pose2{3.1f, 2.9f, 0.25f}, &prior, dpcr::PlicpConfig{});
  const long after = g_allocations.load();
  REQUIRE(built == dpcr::Status::kOk);
  CHECK(a.verdict == dpcr::Status::kOk);
  CHECK(b.iterations > 0);
  CHECK(after == before);
  // The counter itself works (the check above could not pass vacuously).
  auto* probe = new int(1);
  CHECK(g_allocations.load() == after + 1);
  delete probe;
}
