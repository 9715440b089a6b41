// The drive family on one LUSTBUS (LUSTBUS manual 1: "Both device series can be operated in a network,
// since the most important parameters for network control are numerically compatible (address,
// transmission rate, device type)"; 5.2: 81..85 and 91 "can be communicated with via the same
// CODE-String"): the VF1000 and the MC6000 wings side by side, the same telegram to each. And
// 11.5: "the change first becomes active once the device is restarted", for both drives.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "ibs/devices/mc6000/lustbus_device.hpp"
#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "ibs/drive/parameters.hpp"
#include "support.hpp"

namespace {

using namespace ibs::lustbus;
using namespace ibs::lustbus::devtest;
using Vf = ibs::devices::vf1000::LustbusDevice;
using Mc = ibs::devices::mc6000::LustbusDevice;

// Both drives on one line at 9600 Bd, 85 read (6: the power-on bit refuses the first SELECT).
struct Family {
  Vf vf;
  Mc mc;
  Bus bus;
  static constexpr Address kVf = 1;
  static constexpr Address kMc = 2;
  Family() {
    bus.add(vf, kVf);
    bus.add(mc, kMc);
    bus.read(kVf, 85);
    bus.read(kMc, 85);
  }
  // 2.3.1: the inverter's VALUE is exactly four digits; 2.3.2: the servo's may drop leading zeros.
  static std::string value_for(Address a, std::uint32_t n) {
    char buf[16];
    std::snprintf(buf, sizeof buf, a == kVf ? "%04X" : "%X", n);
    return buf;
  }
};

// LUSTBUS manual 1 and 4 (decision LB-E18): 81 holds the rate in baud on both drives, so one number
// written with one CODE (00081, 5.2) sets one rate on either; each takes the steps of 4 up to its
// own highest rate ("2400 Baud to 9600 Baud for frequency Inverters, and from 2400 Baud to 57600
// Baud for Servocontrollers"), and a number that is no step, or above the drive's range, is an
// invalid value (9.2: 80H) on either.
TEST(NumericallyCompatible, TheSameNumberIn81SetsTheSameRateOnEitherDrive) {
  struct Row {
    std::uint32_t written;
    bool inverter_takes;
    bool servo_takes;
  };
  const Row rows[] = {{2400, true, true},   {4800, true, true},   {9600, true, true},
                      {19200, false, true}, {38400, false, true}, {57600, false, true},
                      {0, false, false},    {2, false, false},    {5000, false, false},
                      {115200 & 0xFFFF, false, false}};
  Family f;
  for (const Row& row : rows) {
    SCOPED_TRACE(row.written);
    for (const auto& [a, takes] : {std::pair{Family::kVf, row.inverter_takes}, {Family::kMc, row.servo_takes}}) {
      const Outcome o = f.bus.write(a, 81, Family::value_for(a, row.written));
      if (takes) {
        EXPECT_EQ(o.kind, OutcomeKind::acknowledged) << int(a);
        const Outcome r = f.bus.read(a, 81);  // the same CODE reads the same number back
        EXPECT_EQ(std::stoul(std::string(r.value.view()), nullptr, 16), row.written) << int(a);
      } else {
        EXPECT_EQ(o.kind, OutcomeKind::nak) << int(a);
        EXPECT_EQ(o.siof, std::optional<std::uint8_t>(0x80)) << int(a);
      }
    }
  }
  // The factory setting of 4: 9600 on both, read with 00081 as the same number.
  Vf vf;
  Mc mc;
  EXPECT_EQ(vf.value(81), 9600);
  EXPECT_EQ(mc.value(81), 9600U);
  EXPECT_TRUE(ibs::drive::is_baud_step(57600, 57600));
  EXPECT_FALSE(ibs::drive::is_baud_step(19200, 9600));
}

// LUSTBUS manual 11.5: "The Baudrate of the devices is not altered immediately after each change.
// Instead, the change first becomes active once the device is restarted." Each drive takes 4800
// with an ACK at the old rate, goes on at 9600 until its restart, then answers at 4800 only (a
// host at 9600 hears nothing, 9.1). "The servocontroller has the possibility to activate a new
// Baudrate also without having to do a restart ... the value 111 in the 4-PROG parameter": the
// servo's second row; the inverter's 71-PROG knows no 111.
TEST(BaudRate115, ANewRateIsActiveOnlyAfterARestartOnBothDrives) {
  for (const Address a : {Family::kVf, Family::kMc}) {
    SCOPED_TRACE(int(a));
    Family f;
    const auto line_baud = [&] { return a == Family::kVf ? f.vf.line_baud() : f.mc.line_baud(); };
    const int index = a == Family::kVf ? 0 : 1;
    ASSERT_EQ(f.bus.write(a, 81, Family::value_for(a, 4800)).kind, OutcomeKind::acknowledged);
    EXPECT_EQ(line_baud(), 9600U);  // not altered by the change
    f.bus.wait(1s);
    EXPECT_EQ(line_baud(), 9600U);
    EXPECT_EQ(f.bus.read(a, 91).kind, OutcomeKind::value);  // still heard at 9600
    // The restart.
    if (a == Family::kVf) {
      f.vf.restart(f.bus.line.now());
    } else {
      f.mc.restart(f.bus.line.now());
    }
    f.bus.wait(5s);  // the inverter's self-test
    EXPECT_EQ(line_baud(), 4800U);
    f.bus.line.set_device_baud(index, line_baud());
    EXPECT_EQ(f.bus.read(a, 91).kind, OutcomeKind::no_answer);  // the host at 9600
    f.bus.line.set_baud(4800);
    f.bus.line.set_device_baud(1 - index, 9600);  // the other drive stays where it was
    EXPECT_EQ(f.bus.read(a, 91).kind, OutcomeKind::value);
    EXPECT_EQ(f.bus.read(a, 85).value.view(), a == Family::kVf ? "0001" : "01");  // 6: a new start
  }
  // The servo's 4-PROG = 111: active at once, its ACK still at the old rate; the inverter refuses
  // 111 in 71-PROG (its range is 0..1).
  Family f;
  ASSERT_EQ(f.bus.write(Family::kMc, 81, "4B00").kind, OutcomeKind::acknowledged);  // 19200
  EXPECT_EQ(f.mc.line_baud(), 9600U);
  ASSERT_EQ(f.bus.write(Family::kMc, 20004, "6F").kind, OutcomeKind::acknowledged);  // 111
  EXPECT_EQ(f.mc.line_baud(), 19200U);
  ASSERT_EQ(f.bus.write(Family::kVf, 81, "12C0").kind, OutcomeKind::acknowledged);  // 4800
  const Outcome prog = f.bus.write(Family::kVf, 171, "006F");
  EXPECT_EQ(prog.kind, OutcomeKind::nak);
  EXPECT_EQ(prog.siof, std::optional<std::uint8_t>(0x80));
  EXPECT_EQ(f.vf.line_baud(), 9600U);
}

}  // namespace
