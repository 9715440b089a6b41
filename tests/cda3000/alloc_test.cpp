// The cycle path of the CDA3000 wing allocates nothing: the driver's receive / cycle /
// take_frame and its parameter submissions, and the emulated drive's receive / step /
// take_frame, through start-up, references, parameter and string traffic and a watchdog trip;
// and the same paths behind the registry's CANLust face (a virtual call per frame).
#include <gtest/gtest.h>

#include "../support/counting_new.hpp"
#include "bus.hpp"
#include "ibs/devices/cda3000/bus_face.hpp"
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

// What `ibs run` and `ibs canlust emulate` call per frame, through the face: the master's
// receive / cycle / take_frame / take_error, the drives' receive / step / take_frame /
// next_deadline, and a parameter read submitted and polled.
TEST(Cda3000DriverAlloc, FaceCycleAllocatesNothing) {
  const CanlustFace& face = bus_face();
  CanlustMasterOptions mo;
  mo.drives = {{1, 2, 400.0}, {2, 2, 400.0}};
  const auto master = face.make_master(mo);
  std::vector<std::unique_ptr<CanlustDrive>> drives;
  for (const std::uint8_t a : {std::uint8_t{1}, std::uint8_t{2}}) {
    CanlustFaceOptions o;
    o.address = a;
    o.watchdog_ms = a == 2 ? 20 : 0;
    drives.push_back(face.make(o));
    drives.back()->power_on(Time{0});
  }
  Time t{0};
  const auto run_for = [&](Duration d) {
    for (const Time end = t + d; t < end; t += 1ms) {
      master->cycle(t);
      while (auto f = master->take_frame()) {
        for (auto& x : drives) x->receive(*f, t);
      }
      for (auto& x : drives) {
        x->step(t);
        (void)x->next_deadline();
        while (auto f = x->take_frame()) master->receive(*f, t);
      }
      while (master->take_error()) {
      }
    }
  };
  run_for(150ms);  // warm-up
  ibs::test::AllocationCounter counter;
  master->system_start(t);
  for (const canlust::Address a : {canlust::Address{1}, canlust::Address{2}}) {
    EXPECT_TRUE(master->request(a, drivecom::Target::enabled, t));
    EXPECT_FALSE(master->set_reference_hz(a, 12.5 * a));
  }
  CanlustSubmission read;
  for (int round = 0; round < 4; ++round) {
    read = master->read(1, kDisp);
    run_for(300ms);
  }
  EXPECT_EQ(counter.count(), 0);
  EXPECT_TRUE(read);
  EXPECT_EQ(master->poll(read.id).state, canlust::RequestState::done);
  EXPECT_EQ(drives[0]->state(), drivecom::State::enabled);
  // Drive 2's watchdog (20 ms) tripped: the master sends control telegrams every 50 ms.
  EXPECT_EQ(drives[1]->state(), drivecom::State::fault);
  EXPECT_GE(drives[1]->watchdog_trips(), 1U);
}

}  // namespace
}  // namespace ibs::devices::cda3000
