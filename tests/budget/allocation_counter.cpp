// glibc lets a program interpose malloc and friends; the originals stay reachable as __libc_*.
#include "tests/budget/allocation_counter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void __libc_free(void*);
}

namespace {
std::atomic<bool> g_armed{false};
std::atomic<std::size_t> g_count{0};
void Note() {
  if (g_armed.load(std::memory_order_relaxed)) g_count.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

namespace dpcr::test {
void ArmAllocationCounter() {
  g_count = 0;
  g_armed = true;
}
std::size_t DisarmAllocationCounter() {
  g_armed = false;
  return g_count.load();
}
}  // namespace dpcr::test

extern "C" {
void* malloc(std::size_t n) {
  Note();
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t m) {
  Note();
  return __libc_calloc(n, m);
}
void* realloc(void* p, std::size_t n) {
  Note();
  return __libc_realloc(p, n);
}
void free(void* p) { __libc_free(p); }
}

void* operator new(std::size_t n) {
  Note();
  void* p = __libc_malloc(n == 0 ? 1 : n);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  Note();
  return __libc_malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return operator new(n, std::nothrow); }
void operator delete(void* p) noexcept { __libc_free(p); }
void operator delete[](void* p) noexcept { __libc_free(p); }
void operator delete(void* p, std::size_t) noexcept { __libc_free(p); }
void operator delete[](void* p, std::size_t) noexcept { __libc_free(p); }
