// The plant's step must not allocate (design.md, rules of the cycle path). This file replaces
// the global operator new of the test program to count allocations between two marks.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "ibs/devices/drive_plant.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t /*size*/) noexcept {
  std::free(p);
}

namespace ibs::devices {
namespace {

TEST(DrivePlantAllocation, StepAndAdvanceDoNotAllocate) {
  DrivePlant plant;  // construction may allocate
  const long before = g_allocations.load();
  double sum = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const PlantInput in{k < 1000 ? 2500.25 : -300.0, k % 300 < 150 ? 0.0 : 2.0, k < 1800};
    sum += plant.step(in).speed_rpm;
    sum += plant.advance(726us, in).torque_nm;
  }
  const long after = g_allocations.load();
  EXPECT_EQ(after - before, 0);
  EXPECT_NE(sum, 0.0);
}

TEST(DrivePlantAllocation, TheCounterSeesAllocations) {
  const long before = g_allocations.load();
  auto* p = new DrivePlant();
  delete p;
  EXPECT_GT(g_allocations.load() - before, 0);
}

}  // namespace
}  // namespace ibs::devices
