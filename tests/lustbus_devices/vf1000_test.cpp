// The VF1000 wing as a LUSTBUS device (LUSTBUS manual): the seed's telegrams byte-exact against it, the
// 85-SIOF latch (6, 9.2), EEPROM timing (3, 10 exception 4), the description (11.1), 71-PROG,
// 11-STAT's reset (8.1.1) and the watchdog (5.2), with the host on the simulated line.
#include "ibs/devices/vf1000/lustbus_device.hpp"

#include <gtest/gtest.h>

#include "ibs/lustbus/description.hpp"
#include "support.hpp"

namespace {

using namespace ibs::lustbus;
using namespace ibs::lustbus::devtest;
using ibs::Time;
using Vf = ibs::devices::vf1000::LustbusDevice;
namespace pnr = ibs::devices::vf1000::pnr;

// A VF1000 whose power-on bit has been read (6).
struct Fresh {
  Vf dev;
  Receiver rx{dev, 5};
  Time t{0};
  Fed send(const std::vector<std::uint8_t>& b, ibs::Duration after = 1s) {
    t += after;
    return feed(rx, b, t);
  }
  Fresh() { send(enq(0, 85)); }
  // 7.1 steps 1-3: control and reference on the serial interface.
  void control_on_sio() {
    for (const auto& [code, v] : {std::pair{101U, "0000"}, {102U, "0003"}, {104U, "0008"}}) {
      EXPECT_EQ(send(sel(5, code, v)).answer, (Bytes{}(0x45)(6).v)) << code;
    }
  }
};

TEST(Vf1000Lustbus, PowerOnBitRefusesTheFirstSelectUntil85IsRead) {
  Vf dev;
  Receiver rx(dev, 5);
  EXPECT_EQ(dev.siof(), 0x01);  // 6: after every new start
  EXPECT_EQ(feed(rx, sel(5, 105, "03E8"), Time{1s}).answer, (Bytes{}(0x45)(0x15).v));
  EXPECT_EQ(dev.value(pnr::kFssio), 0);
  // 9.2: the refused SELECT enters no further cause while the latch holds.
  EXPECT_EQ(feed(rx, enq(5, 85), Time{2s}).answer, bytes(encode_text_answer(5, make_code(85), make_value("0001")).span()));
  EXPECT_EQ(dev.siof(), 0);
  EXPECT_EQ(feed(rx, sel(5, 105, "03E8"), Time{3s}).answer, (Bytes{}(0x45)(6).v));
}

// 6.2.2: 05-FSSIO = 50.00 Hz via address 0, byte-exact (BCC 74H); 6.1.1.1 (LB-E1, LB-E3): the
// rotary-field frequency 12 read via address 0, answer "@ STX 00112=03E8 ETX 72H" once the ramp
// (20 Hz/s) has brought the inverter up to 50 Hz; on the way it reads less.
TEST(Vf1000Lustbus, SeedExamples622And6111ByteExact) {
  Fresh f;
  f.control_on_sio();
  const auto s622 = Bytes{}(4)(64)(2)("00105=03E8")(3)(0x74).v;
  EXPECT_EQ(f.send(s622).answer, (Bytes{}(64)(6).v));
  EXPECT_EQ(f.dev.value(pnr::kFssio), 0x03E8);
  EXPECT_EQ(f.send(sel(0, 103, "0080")).answer, (Bytes{}(64)(6).v));  // CNTL: start clockwise
  const auto e6111 = Bytes{}(4)(64)(48)(48)(49)(49)(50)(5).v;
  const auto early = f.send(e6111, 1s).answer;  // about 20 Hz after 1 s
  EXPECT_EQ(f.dev.drive_state(), ibs::drivecom::State::enabled);
  ASSERT_EQ(early.size(), 14U);
  EXPECT_NE(early, (Bytes{}(64)(2)("00112=03E8")(3)(0x72).v));
  EXPECT_NEAR(f.dev.frequency_hz(), 20.0, 0.5);
  EXPECT_EQ(f.send(e6111, 2s).answer, (Bytes{}(64)(2)("00112=03E8")(3)(0x72).v));
  // Without the start bit the ramp brings it down, then READY TO SWITCH ON.
  EXPECT_EQ(f.send(sel(0, 103, "0000")).answer, (Bytes{}(64)(6).v));
  f.send(enq(5, 112), 3s);
  EXPECT_EQ(f.dev.frequency_hz(), 0.0);
  EXPECT_EQ(f.dev.drive_state(), ibs::drivecom::State::ready);
}

// LUSTBUS manual 2.4.1: "Devices No.: For VF1000, always 1"; yet 2.4.1's own C example builds "000%02u"
// (device digit 0), 7.1.1's telegram list and 5.2's shared CODEs use 000xx, and 11.1 says that for
// basis parameters "the device number in the telegram CODE ... can contain a 0 (general for basis
// parameter) as well as the specific device number" (LB-E19): the inverter answers a basis
// parameter under device digit 0 and 1 alike -- value, description and SELECT -- and another
// device digit is no CODE of its (NAK, 20H on a SELECT). Every row of its table is a basis
// parameter (kinds '0'..'3'); the parser hands the digit on, and an inverter-specific kind ('4'..
// '7') would need the 1 (vf1000::LustbusDevice::resolve).
TEST(Vf1000Lustbus, DeviceDigit0And1ReachTheBasisParameters) {
  Fresh f;
  const auto value0 = f.send(enq(5, 1)).answer;    // 00001
  const auto value1 = f.send(enq(5, 101)).answer;  // 00101
  ASSERT_EQ(value0.size(), 14U);
  EXPECT_EQ(std::vector<std::uint8_t>(value0.begin() + 8, value0.end() - 2),
            std::vector<std::uint8_t>(value1.begin() + 8, value1.end() - 2));
  EXPECT_EQ(f.send(enq(5, 10001)).answer.size(), 36U);  // 11.1: 26 characters either way
  EXPECT_EQ(f.send(enq(5, 10101)).answer.size(), 36U);
  EXPECT_EQ(f.send(enq(5, 201)).answer, (Bytes{}(0x45)(0x15).v));  // device 2: NAK (6.1 note)
  EXPECT_EQ(f.send(sel(5, 5, "0064")).answer, (Bytes{}(0x45)(6).v));
  EXPECT_EQ(f.send(sel(5, 105, "00C8")).answer, (Bytes{}(0x45)(6).v));
  EXPECT_EQ(f.dev.value(pnr::kFssio), 0x00C8);
  EXPECT_EQ(f.send(sel(5, 205, "0001")).answer, (Bytes{}(0x45)(0x15).v));
  EXPECT_EQ(f.dev.siof(), 0x20);
  for (const auto& p : f.dev.table().params()) {
    EXPECT_LE(static_cast<int>(p.category), 3) << p.number << ": a basis parameter";
  }
}

// 7.1: 3-CNTL commands the inverter only with 1-MODE = 0 and 2-CSEL = 3 (the standard factory
// CSEL 0 of a drive on LUSTBUS alone, VF-E20, leaves it to the terminals); 40H is the start bit
// counter-clockwise.
TEST(Vf1000Lustbus, ControlOnlyFromTheSerialInterface) {
  Fresh f;
  EXPECT_EQ(f.send(sel(5, 105, "0064")).answer, (Bytes{}(0x45)(6).v));  // 5 Hz
  EXPECT_EQ(f.send(sel(5, 103, "0080")).answer, (Bytes{}(0x45)(6).v));
  f.send(enq(5, 112));
  EXPECT_FALSE(f.dev.power_stage_enabled());
  EXPECT_EQ(f.dev.frequency_hz(), 0.0);
  EXPECT_EQ(f.send(sel(5, 103, "0000")).answer, (Bytes{}(0x45)(6).v));
  f.control_on_sio();
  EXPECT_EQ(f.send(sel(5, 103, "0040")).answer, (Bytes{}(0x45)(6).v));
  f.send(enq(5, 112));
  EXPECT_TRUE(f.dev.power_stage_enabled());
  EXPECT_DOUBLE_EQ(f.dev.frequency_hz(), -5.0);
  EXPECT_EQ(f.dev.status() & 0x07, 0x07);  // ready, running, counter-clockwise
  EXPECT_EQ(f.send(enq(5, 111)).answer, bytes(encode_text_answer(5, make_code(111), make_value("0007")).span()));
}

// 7.1.1 as corrected (LB-E11) through the host: MODE 0, CSEL 3, FSSEL 8, FSSIO 463, CNTL 128 last.
TEST(Vf1000Lustbus, ControlSequence711ThroughTheHost) {
  Vf dev;
  Bus bus;
  bus.add(dev, 1);
  EXPECT_EQ(bus.read(1, 85).value.view(), "0001");
  const std::pair<std::uint32_t, std::string_view> seq[] = {
      {1, "0000"}, {2, "0003"}, {4, "0008"}, {5, "01CF"}, {3, "0080"}};
  for (const auto& [code, v] : seq) {
    EXPECT_EQ(bus.write(1, code, v).kind, OutcomeKind::acknowledged) << code;
  }
  EXPECT_EQ(dev.value(pnr::kMode), 0);
  EXPECT_EQ(dev.value(pnr::kCsel), 3);
  EXPECT_EQ(dev.value(pnr::kFssel), 8);
  EXPECT_EQ(dev.value(pnr::kFssio), 463);
  bus.wait(2s);  // the ramp: 20 Hz/s
  EXPECT_EQ(bus.read(1, 112).value.view(), "01CF");  // 23.15 Hz
  EXPECT_TRUE(dev.power_stage_enabled());
}

// 9.2: 20H, 40H, 80H through the host (it reads 85 after the NAK); 3: an EEPROM parameter is not
// writable while the power stage runs, whatever the value.
TEST(Vf1000Lustbus, RefusalsCarryTheirCause) {
  Vf dev;
  Bus bus;
  bus.add(dev, 1);
  bus.read(1, 85);
  auto o = bus.write(1, 199, "0000");  // no parameter 99
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  EXPECT_EQ(o.siof, 0x20);
  o = bus.write(1, 104, "001A");  // FSSEL 26 > 25
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  EXPECT_EQ(o.siof, 0x80);
  o = bus.write(1, 191, "0001");  // TYPE is read-only
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  EXPECT_EQ(o.siof, 0x40);
  ASSERT_EQ(bus.write(1, 101, "0000").kind, OutcomeKind::acknowledged);  // 7.1: MODE, CSEL
  ASSERT_EQ(bus.write(1, 102, "0003").kind, OutcomeKind::acknowledged);
  ASSERT_EQ(bus.write(1, 104, "0008").kind, OutcomeKind::acknowledged);  // FSSIO: 5 Hz
  ASSERT_EQ(bus.write(1, 105, "0064").kind, OutcomeKind::acknowledged);  // (at 0 Hz: off, VF-E19)
  ASSERT_EQ(bus.write(1, 103, "0080").kind, OutcomeKind::acknowledged);  // running
  o = bus.write(1, 101, "0004");  // MODE, an EEPROM parameter
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  EXPECT_EQ(o.siof, 0x40);
  EXPECT_EQ(dev.value(pnr::kMode), 0);
  EXPECT_EQ(bus.write(1, 105, "0100").kind, OutcomeKind::acknowledged);  // EEPROM/RAM: RAM
}

// 6.1 note: an ENQUIRY answered NAK enters no cause; 9.2: further SELECTs refused while a bit is
// set, reading 85 returns the bits and clears them.
TEST(Vf1000Lustbus, LatchHoldsUntilReadAndEnquiriesSetNothing) {
  Fresh f;
  EXPECT_EQ(f.send(enq(5, 199)).answer, (Bytes{}(0x45)(0x15).v));
  EXPECT_EQ(f.dev.siof(), 0);
  EXPECT_EQ(f.send(sel(5, 104, "0063")).answer, (Bytes{}(0x45)(0x15).v));  // 99 > 25
  EXPECT_EQ(f.dev.siof(), 0x80);
  EXPECT_EQ(f.send(sel(5, 104, "0008")).answer, (Bytes{}(0x45)(0x15).v));  // valid, refused
  EXPECT_EQ(f.dev.value(pnr::kFssel), 0);  // the standard factory value (VF-E20)
  EXPECT_EQ(f.send(enq(5, 85)).answer, bytes(encode_text_answer(5, make_code(85), make_value("0080")).span()));
  EXPECT_EQ(f.dev.siof(), 0);
  EXPECT_EQ(f.send(sel(5, 104, "0008")).answer, (Bytes{}(0x45)(6).v));
  // A wrong BCC: NAK by the receiver and 08H.
  auto bad = sel(5, 104, "0007");
  bad.back() ^= 0x01;
  EXPECT_EQ(f.send(bad).answer, (Bytes{}(0x45)(0x15).v));
  EXPECT_EQ(f.dev.siof(), 0x08);
  EXPECT_EQ(f.dev.value(pnr::kFssel), 8);
}

// 3 and 10 exception 4: the ACK comes once the EEPROM holds the value; a changed two-byte value
// costs about 120 ms more, one byte 60 ms, an unchanged value nothing; RAM parameters nothing.
TEST(Vf1000Lustbus, EepromAnswersOnlyOnceStored) {
  Fresh f;
  EXPECT_EQ(f.send(sel(5, 122, "01F4")).due, 122ms);  // FMAX1, PT_FIXPOINT16
  EXPECT_EQ(f.dev.eeprom_value(pnr::kFmax1), 0x01F4);
  EXPECT_EQ(f.send(sel(5, 122, "01F4")).due, 2ms);  // unchanged
  EXPECT_EQ(f.send(sel(5, 101, "0001")).due, 62ms);  // MODE, PT_USIGN8
  EXPECT_EQ(f.send(sel(5, 183, "1234")).due, 2ms);   // SIOW, RAM
  EXPECT_EQ(f.send(sel(5, 105, "0010")).due, 122ms);  // FSSIO, stopped: into EEPROM too
}

// 11.1: specifier 1, 26 characters; 45-VB2 as the INTERBUS manual's 4.1.3.3.1 gives it completely.
TEST(Vf1000Lustbus, DescriptionOf111) {
  Vf dev;
  Bus bus;
  bus.add(dev, 1);
  const auto o = bus.read(1, 10145);
  ASSERT_EQ(o.kind, OutcomeKind::value);
  EXPECT_EQ(o.value.size(), kVfDescriptionLength);
  EXPECT_EQ(o.value.view(), "   VB2     %22000001F400A0");
  const auto d = parse_vf_description(o.value.view());
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(d.value.name_view(), "VB2");
  EXPECT_EQ(d.value.max, 0x01F4);
  EXPECT_EQ(bus.read(1, 10112).kind, OutcomeKind::value);  // 12 exists
  EXPECT_EQ(bus.read(1, 10199).kind, OutcomeKind::nak);
}

// 10 exception 1: 71-PROG = 1 loads every factory setting; the ACK comes when done.
TEST(Vf1000Lustbus, Prog1LoadsFactoryDefaults) {
  Vf dev;
  Bus bus;
  bus.add(dev, 1);
  bus.read(1, 85);
  ASSERT_EQ(bus.write(1, 101, "0001").kind, OutcomeKind::acknowledged);
  Request r = select(1, make_code(171), make_value("0001"));
  EXPECT_EQ(bus.run(r).kind, OutcomeKind::no_answer);  // the default 250 ms is too short
  bus.read(1, 85);
  r.response_timeout = 10s;
  const auto o = bus.run(r);
  EXPECT_EQ(o.kind, OutcomeKind::acknowledged);
  EXPECT_GT(o.finished - o.started, 1500ms);
  EXPECT_EQ(dev.value(pnr::kMode), 0);  // a drive on LUSTBUS alone: the standard value (VF-E20)
  EXPECT_EQ(dev.value(pnr::kProg), 0);
}

// INTERBUS manual 3.1.1: the INTERBUS software package changes the standard factory values of 1-MODE
// (4), 2-CSEL (5) and 4-FSSEL (25); a drive on LUSTBUS alone (LUSTBUS manual 4.1: one device, address 0)
// has the standard ones, which no seed lists: 0, 0, 0 (VF-E20). Its description's basis value
// (11.1) and 71-PROG say the same; every other value is the table's.
TEST(Vf1000Lustbus, ADriveOnLustbusAloneHasTheStandardFactoryValues) {
  struct Row {
    std::uint16_t number;
    ibs::Word standard;
    ibs::Word interbus;  // INTERBUS manual 3.1.1
  };
  const Row rows[] = {{pnr::kMode, 0, 4}, {pnr::kCsel, 0, 5}, {pnr::kFssel, 0, 25}, {pnr::kFmax1, 1000, 1000},
                      {pnr::kSouta, 0, 0}, {pnr::kSioc, 9600, 9600}};
  Vf dev;
  const ibs::devices::vf1000::Drive on_interbus(ibs::devices::vf1000::DriveConfig{}, ibs::DeviceStart::operational,
                                                Time{0});
  Bus bus;
  bus.add(dev, 1);
  for (const Row& row : rows) {
    SCOPED_TRACE(row.number);
    EXPECT_EQ(dev.value(row.number), row.standard);
    EXPECT_EQ(on_interbus.value(row.number), row.interbus);
    const auto d = parse_vf_description(bus.read(1, 10100U + row.number).value.view());
    ASSERT_TRUE(d.ok());
    EXPECT_EQ(d.value.basis, row.standard);
  }
  bus.read(1, 85);
  ASSERT_EQ(bus.write(1, 101, "0004").kind, OutcomeKind::acknowledged);
  Request prog = select(1, make_code(171), make_value("0001"));
  prog.response_timeout = 10s;
  ASSERT_EQ(bus.run(prog).kind, OutcomeKind::acknowledged);
  EXPECT_EQ(dev.value(pnr::kMode), 0);
  EXPECT_EQ(dev.eeprom_value(pnr::kMode), 0);
}

// LUSTBUS manual 4: "SMARTDRIVE Inverters with the RS-485 interface must additionally have the
// parameter 61-SOUTA = 7 set. This activates the data direction switch of the internal interface
// software driver." VF-E20: on RS-485 the drive hears nothing unless 61-SOUTA = 7 (ENQUIRY and
// SELECT alike, so nothing it was sent takes effect); on a line without the switch SOUTA does not
// matter. The SELECT that changes SOUTA is answered (the telegram came in while it listened).
TEST(Vf1000Lustbus, OnRs485ItAnswersOnlyWithSouta7) {
  struct Row {
    bool rs485;
    ibs::Word souta;
    bool answers;
  };
  const Row rows[] = {{false, 0, true}, {false, 7, true}, {true, 0, false}, {true, 6, false}, {true, 7, true}};
  for (const Row& row : rows) {
    SCOPED_TRACE(std::string(row.rs485 ? "RS-485" : "no direction switch") + ", SOUTA " + std::to_string(row.souta));
    ibs::devices::vf1000::LustbusTiming timing;
    timing.rs485 = row.rs485;
    Vf dev(timing);
    dev.drive().set_value(pnr::kSouta, row.souta);  // as at its KEYPAD
    Bus bus;
    bus.add(dev, 1);
    EXPECT_EQ(bus.read(1, 85).kind, row.answers ? OutcomeKind::value : OutcomeKind::no_answer);
    EXPECT_EQ(bus.write(1, 183, "1234").kind, row.answers ? OutcomeKind::acknowledged : OutcomeKind::no_answer);
    EXPECT_EQ(dev.value(pnr::kSiow), row.answers ? 0x1234 : 0);
  }
  // Commissioned over the line: the ACK of SOUTA = 0 still goes out, then the drive is deaf.
  ibs::devices::vf1000::LustbusTiming timing;
  timing.rs485 = true;
  Vf dev(timing);
  dev.drive().set_value(pnr::kSouta, 7);
  Bus bus;
  bus.add(dev, 1);
  bus.read(1, 85);
  EXPECT_EQ(bus.write(1, 161, "0000").kind, OutcomeKind::acknowledged);
  EXPECT_EQ(bus.read(1, 161).kind, OutcomeKind::no_answer);
}

// 5.2: 84-SIOT in ms; any valid telegram (the dummy on 83-SIOW) resets it; running out sets 02H and
// stops the inverter. 8.1.1: with the error bit set in 11-STAT, 000FH resets it: the ACK is cut
// (ADR only), the inverter is deaf during its self-test, then back with the power-on bit and
// the start bit cleared.
TEST(Vf1000Lustbus, WatchdogAndStatReset) {
  Fresh f;
  f.control_on_sio();
  Time t = f.t + 1s;
  // A reference above 0 Hz: at 0 Hz the power stage would be off (INTERBUS manual 5.2.3, VF-E19).
  ASSERT_EQ(f.send(sel(5, 105, "0064")).answer, (Bytes{}(0x45)(6).v));
  t = f.t + 1s;
  // SIOT is an EEPROM parameter: set before the start (40H while running).
  ASSERT_EQ(feed(f.rx, sel(5, 184, "0064"), t).answer, (Bytes{}(0x45)(6).v));  // 100 ms
  t += 80ms;
  ASSERT_EQ(feed(f.rx, sel(5, 103, "0080"), t).answer, (Bytes{}(0x45)(6).v));
  for (int i = 0; i < 10; ++i) {
    t += 80ms;
    EXPECT_EQ(feed(f.rx, sel(5, 183, "0000"), t).answer, (Bytes{}(0x45)(6).v)) << i;
  }
  EXPECT_FALSE(f.dev.watchdog_fault());
  EXPECT_TRUE(f.dev.power_stage_enabled());
  f.dev.advance(t + 150ms);
  EXPECT_TRUE(f.dev.watchdog_fault());
  EXPECT_FALSE(f.dev.power_stage_enabled());
  EXPECT_EQ(f.dev.drive_state(), ibs::drivecom::State::fault);
  t += 200ms;
  EXPECT_EQ(feed(f.rx, enq(5, 85), t).answer,
            bytes(encode_text_answer(5, make_code(85), make_value("0002")).span()));
  t += 50ms;
  EXPECT_EQ(feed(f.rx, enq(5, 111), t).answer,
            bytes(encode_text_answer(5, make_code(111), make_value("0081")).span()));  // ready, error
  t += 50ms;
  EXPECT_EQ(feed(f.rx, sel(5, 111, "000F"), t).answer, (Bytes{}(0x45).v));  // cut
  EXPECT_FALSE(f.dev.watchdog_fault());
  EXPECT_FALSE(f.dev.listening(t + 3s));
  EXPECT_TRUE(feed(f.rx, enq(5, 85), t + 3s).answer.empty());  // the self-test: no answer
  EXPECT_TRUE(feed(f.rx, sel(5, 105, "0000"), t + 3500ms).answer.empty());
  EXPECT_EQ(feed(f.rx, enq(5, 85), t + 4100ms).answer,
            bytes(encode_text_answer(5, make_code(85), make_value("0001")).span()));
  EXPECT_EQ(f.dev.value(pnr::kCntl), 0);
  // Without an error 000FH is acknowledged and resets nothing.
  EXPECT_EQ(feed(f.rx, sel(5, 111, "000F"), t + 4200ms).answer, (Bytes{}(0x45)(6).v));
  EXPECT_EQ(f.dev.drive_state(), ibs::drivecom::State::ready);  // not started again
  EXPECT_EQ(f.dev.siof(), 0);
  EXPECT_TRUE(f.dev.listening(t + 4300ms));
  // Any other value is no command: 80H.
  EXPECT_EQ(feed(f.rx, sel(5, 111, "0001"), t + 4300ms).answer, (Bytes{}(0x45)(0x15).v));
  EXPECT_EQ(f.dev.siof(), 0x80);
}

// 8.1.1 through the host, with each of the reset's answers: the outcome, and the power-on bit
// the host must read (8.1.1: "before the next SELECT") once the inverter is back.
TEST(Vf1000Lustbus, StatResetThroughTheHost) {
  for (const auto answer : {Reply::ack, Reply::cut, Reply::none}) {
    ibs::devices::vf1000::LustbusTiming timing;
    timing.reset_answer = answer;
    Vf dev(timing);
    Bus bus;
    bus.add(dev, 1);
    bus.read(1, 85);
    dev.set_fault(true, bus.line.now());
    bus.wait(50ms);
    dev.set_fault(false, bus.line.now());  // a fault that has gone, still to be acknowledged
    EXPECT_EQ(bus.read(1, 111).value.view(), "0081");
    const auto o = bus.write(1, 111, "000F");
    switch (answer) {
      case Reply::ack:
        EXPECT_EQ(o.kind, OutcomeKind::acknowledged);
        break;
      case Reply::cut:
        EXPECT_EQ(o.kind, OutcomeKind::bad_answer) << describe(o);
        EXPECT_EQ(o.answer_error, AnswerError::incomplete);
        EXPECT_FALSE(o.siof);  // the host's read of 85 after it found nobody
        break;
      default:
        EXPECT_EQ(o.kind, OutcomeKind::no_answer);
        break;
    }
    EXPECT_EQ(bus.read(1, 85).kind, OutcomeKind::no_answer);  // still in its self-test
    bus.wait(4s);
    EXPECT_EQ(bus.read(1, 85).value.view(), "0001");
    EXPECT_EQ(bus.read(1, 111).value.view(), "0001");  // ready, no error
  }
}

}  // namespace
