// The reference ramp helper of drive_plant.hpp.
#include <gtest/gtest.h>

#include "ibs/devices/mc6000/plant.hpp"

namespace ibs::devices {
namespace {

TEST(ReferenceRamp, RisesAtItsRateAndStopsExactlyAtTheTarget) {
  ReferenceRamp r{5000.0, 0.0};  // 5 rpm per 1 ms step
  EXPECT_DOUBLE_EQ(r.step(2500.25, 1ms), 5.0);
  EXPECT_DOUBLE_EQ(r.step(2500.25, 1ms), 10.0);
  int steps = 2;
  while (r.value_rpm < 2500.25 && steps < 10000) {
    r.step(2500.25, 1ms);
    ++steps;
  }
  EXPECT_EQ(steps, 501);  // 500 full steps of 5 rpm, then the last 0.25 rpm
  EXPECT_EQ(r.value_rpm, 2500.25);
  EXPECT_EQ(r.step(2500.25, 1ms), 2500.25);
}

TEST(ReferenceRamp, FallsAtTheSameRateAndScalesWithTheStep) {
  ReferenceRamp r{1000.0, 100.0};
  EXPECT_DOUBLE_EQ(r.step(-100.0, 8200us), 91.8);  // VF1000 period: 8.2 rpm
  EXPECT_DOUBLE_EQ(r.step(-100.0, 0ms), 91.8);
}

TEST(ReferenceRamp, NoRateMeansNoRamp) {
  ReferenceRamp r;
  EXPECT_EQ(r.step(2500.25, 1ms), 2500.25);
  EXPECT_EQ(r.step(-3.0, 1ms), -3.0);
}

}  // namespace
}  // namespace ibs::devices
