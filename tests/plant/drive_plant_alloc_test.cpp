// The plant's step must not allocate (design.md, rules of the cycle path). The test program's
// operator new counts the allocations made while a counter is alive.
#include <gtest/gtest.h>

#include "ibs/devices/mc6000/plant.hpp"

#include "../support/counting_new.hpp"

namespace ibs::devices {
namespace {

TEST(DrivePlantAllocation, StepAndAdvanceDoNotAllocate) {
  DrivePlant plant;  // construction may allocate
  test::AllocationCounter counter;
  double sum = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const PlantInput in{k < 1000 ? 2500.25 : -300.0, k % 300 < 150 ? 0.0 : 2.0, k < 1800};
    sum += plant.step(in).speed_rpm;
    plant.advance(726us, in);
    sum += plant.torque_nm();
  }
  EXPECT_EQ(counter.count(), 0);
  EXPECT_NE(sum, 0.0);
}

TEST(DrivePlantAllocation, TheCounterSeesAllocations) {
  test::AllocationCounter counter;
  auto* p = new DrivePlant();
  test::escape(p);
  delete p;
  EXPECT_GT(counter.count(), 0);
}

}  // namespace
}  // namespace ibs::devices
