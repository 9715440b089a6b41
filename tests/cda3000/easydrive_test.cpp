// EasyDrive direct control (492-CACNF = 4, CANLust manual 5.4.1, 7.1.1; decision D26): the driver sends
// the caller's bits as they are, the drive starts clockwise with STR and counter-clockwise with
// STL at the size of the reference, ramps down without a start bit, reports its EasyDrive status
// bits (the seed's ACTIV 4, ROT_0 5, BRK 6, warning 7, CAN status 8; READY 0, ERROR 3 and
// reference reached 10 chosen), trips its watchdog into ERROR and is reset by the error reset
// bit's edge - never by the driver on its own (the watchdog and the reset: tests/sim, the
// scenario `EasyDriveWatchdogAndErrorReset`).
#include <gtest/gtest.h>

#include "bus.hpp"
#include "ibs/devices/cda3000/descriptor.hpp"
#include "ibs/devices/cda3000/driver.hpp"

namespace ibs::devices::cda3000 {
namespace {

using namespace ibs::canlust;
using test::Bus;
using test::commissioned;
namespace es = easydrive::status;

constexpr ibs::Word bitw(unsigned b) { return static_cast<ibs::Word>(1U << b); }

TEST(Cda3000EasyDrive, DirectControlBothSides) {
  DriverConfig c;
  c.drives.push_back({1, 4, 400.0});
  Driver d(c);
  Bus<Driver> b(d);
  DeviceConfig dc = commissioned(1, 4);
  dc.saved.push_back({kCawdg, 100});
  b.add(dc);
  b.run_until(Time{150ms});
  EXPECT_EQ(b.drive(0).layout().mode, WordMode::easydrive);
  d.system_start(b.now());
  EXPECT_FALSE(d.request(1, drivecom::Target::enabled, b.now()));  // no DRIVECOM sequencer here
  ASSERT_EQ(d.set_reference_hz(1, 20.5), ReferenceError::none);
  b.run_for(500ms);
  // Nothing asked: the drive stands, READY, CAN Start.
  const ibs::Word idle = d.drive(1).status_word;
  EXPECT_TRUE(bit(idle, es::kReady));
  EXPECT_FALSE(bit(idle, es::kActiv));
  EXPECT_TRUE(bit(idle, es::kRot0));
  EXPECT_TRUE(bit(idle, es::kCanStart));
  EXPECT_FALSE(d.drive(1).state.has_value());
  EXPECT_TRUE(d.drive(1).easydrive);
  // STR: clockwise at the reference.
  ASSERT_TRUE(d.set_easydrive(1, bitw(easydrive::kStr)));
  b.run_for(100ms);
  EXPECT_TRUE(bit(d.drive(1).status_word, es::kActiv));
  EXPECT_FALSE(bit(d.drive(1).status_word, es::kRot0));
  b.run_for(2s);
  EXPECT_NEAR(d.drive(1).actual_hz, 20.5, 0.05);
  EXPECT_TRUE(bit(d.drive(1).status_word, es::kReferenceReached));
  // STL: the other way round at the same size; braking on the way through.
  ASSERT_TRUE(d.set_easydrive(1, bitw(easydrive::kStl)));
  b.run_for(60ms);
  EXPECT_TRUE(bit(d.drive(1).status_word, es::kBrk));
  b.run_for(3s);
  EXPECT_NEAR(d.drive(1).actual_hz, -20.5, 0.05);
  // No start bit: down to 0 Hz with the ramp, then the power stage off.
  ASSERT_TRUE(d.set_easydrive(1, 0));
  b.run_for(3s);
  EXPECT_NEAR(d.drive(1).actual_hz, 0.0, 0.1);
  EXPECT_FALSE(bit(d.drive(1).status_word, es::kActiv));
  EXPECT_EQ(b.drive(0).state(), drivecom::State::ready);
  // The error reset bit alone starts nothing: READY stays READY.
  ASSERT_TRUE(d.set_easydrive(1, bitw(easydrive::kEres)));
  b.run_for(500ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::ready);
  EXPECT_NEAR(d.drive(1).actual_hz, 0.0, 0.1);
}

// The text of the monitor and `ibs decode` for EasyDrive words.
TEST(Cda3000EasyDrive, WordsExplained) {
  EXPECT_EQ(explain_easydrive_control(0x0081), "0081 STR, error reset");
  EXPECT_EQ(explain_easydrive_control(0x0000), "0000 (none)");
  EXPECT_EQ(explain_easydrive_control(0x1002), "1002 STL, bits 1000 (no function)");
  EXPECT_EQ(explain_easydrive_status(0x0531), "0531 READY, ACTIV, ROT_0, CAN Start, reference reached");
  const IdentifierMap ids{};
  CanFrame f;
  f.id = 663;
  f.dlc = 6;
  f.data = {0x01, 0x00, 0x00, 0x80, 0x14, 0x00, 0, 0};
  EXPECT_EQ(explain_frame(f, ids, *process_layout_for_cacnf(4)).text,
            "control CDA 1: EasyDrive 0001 STR; reference 20.5 Hz");
}

}  // namespace
}  // namespace ibs::devices::cda3000
