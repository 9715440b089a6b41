// The cycle path of the CDA3000 wing allocates nothing: the driver's receive / cycle /
// take_frame and its parameter submissions, and the emulated drive's receive / step /
// take_frame, through start-up, references, parameter and string traffic and a watchdog trip.
#include <gtest/gtest.h>

#include "../support/counting_new.hpp"
#include "bus.hpp"
#include "ibs/devices/cda3000/driver.hpp"

namespace ibs::devices::cda3000 {
namespace {

TEST(Cda3000DriverAlloc, CycleAllocatesNothing) {
  DriverConfig cfg;
  cfg.drives = {{1, 2, 400.0}, {2, 1, 400.0}, {3, 2, 400.0}};
  Driver d(cfg);
  test::Bus<Driver> b(d);
  b.add(test::commissioned(1));
  b.add(test::commissioned(2, 1));
  DeviceConfig dc = test::commissioned(3);
  dc.saved.emplace_back(kCawdg, 20);
  b.add(dc);
  b.run_until(Time{150ms});  // warm-up
  ibs::test::AllocationCounter counter;
  d.system_start(b.now());
  for (canlust::Address a = 1; a <= 3; ++a) {
    d.request(a, drivecom::Target::enabled, b.now());
    d.set_reference_hz(a, 12.5 * a);
  }
  for (int round = 0; round < 4; ++round) {
    (void)d.read(1, kDisp);
    (void)d.write(2, kCascy, static_cast<std::uint32_t>(60 + round));
    (void)d.read(2, kOptn2);
    (void)d.write_text(1, kName, "no allocation");
    (void)d.describe(1, kCawdg, 2);
    b.run_for(500ms);
  }
  d.system_stop(b.now());
  d.set_reference_hz(1, 30.0);
  b.run_for(200ms);
  d.system_start(b.now());
  b.run_for(500ms);
  EXPECT_EQ(counter.count(), 0);
  EXPECT_EQ(d.drive(1).state, drivecom::State::enabled);
  EXPECT_EQ(b.drive(2).state(), drivecom::State::fault);  // its watchdog (20 ms) tripped
  EXPECT_TRUE(d.parameters().idle());
}

}  // namespace
}  // namespace ibs::devices::cda3000
