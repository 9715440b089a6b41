// Replaces the global operator new/delete with malloc/free and counts the allocations made while
// an AllocationCounter is alive. Include it in exactly one source file of a test binary.
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>

namespace ibs::test {
inline std::atomic<bool> g_counting{false};
inline std::atomic<long> g_allocations{0};

// Counts from construction to destruction (one at a time).
struct AllocationCounter {
  AllocationCounter() {
    g_allocations = 0;
    g_counting = true;
  }
  ~AllocationCounter() { g_counting = false; }
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;
  [[nodiscard]] long count() const { return g_allocations.load(); }
};

// Makes `p` escape, so that the compiler keeps an allocation whose result is otherwise unused
// (a new/delete pair may be removed since C++14, and is with link-time optimisation).
inline void escape(const void* p) { asm volatile("" : : "g"(p) : "memory"); }
}  // namespace ibs::test

// GCC (12, optimising) takes these for the library's operator new/delete and warns that free()
// releases what "operator new" returned; here both sides are malloc/free.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t n) {
  if (ibs::test::g_counting.load()) ibs::test::g_allocations.fetch_add(1);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
// The nothrow forms too, so that every allocation and its release go through malloc/free.
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  if (ibs::test::g_counting.load()) ibs::test::g_allocations.fetch_add(1);
  return std::malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

#pragma GCC diagnostic pop
