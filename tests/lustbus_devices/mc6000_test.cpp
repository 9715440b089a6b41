// The MC6000 wing as a LUSTBUS device (LUSTBUS manual): the seed's telegrams byte-exact against it, the
// shared CODEs of 5.2, 85-SERR, EEPROM in the background with 04H (3, 10.2.2), the description
// (11.2), 4-PROG, the download handshake on 80-SLOAD (11.4), the watchdog (5.2).
#include <gtest/gtest.h>

#include "ibs/devices/mc6000/lustbus_device.hpp"
#include "ibs/devices/mc6000/lustbus_face.hpp"
#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "ibs/devices/vf1000/lustbus_face.hpp"
#include "ibs/lustbus/description.hpp"
#include "servo_procedures.hpp"
#include "support.hpp"

namespace {

using namespace ibs::lustbus;
using namespace ibs::lustbus::devtest;
using ibs::Time;
using Mc = ibs::devices::mc6000::LustbusDevice;
namespace mc = ibs::devices::mc6000;

struct Fresh {
  Mc dev;
  Receiver rx{dev, 3};
  Time t{0};
  Fed send(const std::vector<std::uint8_t>& b, ibs::Duration after = 1s) {
    t += after;
    return feed(rx, b, t);
  }
  Fresh() { send(enq(0, 85)); }
  // 7.2 steps 2 and 4: the control location on the serial interface, RSSL1 = RSIO.
  void control_on_sio() {
    for (const auto& [code, v] : {std::pair{20402U, "2"}, {20417U, "3"}}) {
      EXPECT_EQ(send(sel(3, code, v)).answer, (Bytes{}(0x43)(6).v)) << code;
    }
  }
};

// 6.1.1.2 (LB-E4): 77-SPEED via address 0 answered "@ STX 20077=04FA4000 ETX 0BH", 18 bytes
// (10.1.1), the servo's plant settled at 1274.25 1/min; on the way up it reads less.
TEST(Mc6000Lustbus, SeedExample6112ByteExact) {
  Fresh f;
  f.control_on_sio();
  ASSERT_EQ(f.send(sel(3, 20428, "4FA4000")).answer, (Bytes{}(0x43)(6).v));
  ASSERT_EQ(f.send(sel(3, 20416, "1")).answer, (Bytes{}(0x43)(6).v));
  EXPECT_EQ(f.dev.drive_state(), ibs::drivecom::State::enabled);
  const auto host = Bytes{}(4)(64)(50)(48)(48)(55)(55)(5).v;
  const auto early = f.send(host, 50ms).answer;
  EXPECT_NE(early, (Bytes{}(64)(2)("20077=04FA4000")(3)(0x0B).v));
  EXPECT_GT(f.dev.speed_rpm(), 100.0);
  EXPECT_LT(f.dev.speed_rpm(), 1274.0);
  const auto a = f.send(host, 2s).answer;
  EXPECT_EQ(a, (Bytes{}(64)(2)("20077=04FA4000")(3)(0x0B).v));
  EXPECT_EQ(a.size(), 18U);
  // SCTL1 = 0: SHUTDOWN, the power stage off, the motor coasts down.
  ASSERT_EQ(f.send(sel(3, 20416, "0")).answer, (Bytes{}(0x43)(6).v));
  EXPECT_EQ(f.dev.drive_state(), ibs::drivecom::State::ready);
  f.send(host, 60s);
  EXPECT_LT(f.dev.speed_rpm(), 1.0);
}

// 7.2: 416-SCTL1 commands the servo only with 402-CLSEL = SIO (the factory OPT1 leaves it to
// the option) and 300-CFCON = SCON (the emulator's speed loop); the reference is what the
// selectors 417..420 take from 428-RSIO.
TEST(Mc6000Lustbus, ControlOnlyFromTheSerialInterface) {
  Fresh f;
  ASSERT_EQ(f.send(sel(3, 20428, "10000")).answer, (Bytes{}(0x43)(6).v));  // 1 rpm
  ASSERT_EQ(f.send(sel(3, 20416, "1")).answer, (Bytes{}(0x43)(6).v));
  EXPECT_FALSE(f.dev.running());
  EXPECT_EQ(f.dev.reference_rpm(), 0.0);  // RSSL1..4 = RCON, RCON, OPT1, RCON
  f.control_on_sio();
  EXPECT_TRUE(f.dev.running());
  EXPECT_EQ(f.dev.reference_rpm(), 1.0);
  ASSERT_EQ(f.send(sel(3, 20418, "3")).answer, (Bytes{}(0x43)(6).v));  // RSSL2 = RSIO too
  EXPECT_EQ(f.dev.reference_rpm(), 2.0);
  ASSERT_EQ(f.send(sel(3, 20300, "3")).answer, (Bytes{}(0x43)(6).v));  // PCON: not modelled
  EXPECT_FALSE(f.dev.running());
}

// 10.2.2 against the servo itself: 409-BUTWD is an EEPROM USIGN16, "memory time = parameter data
// width · 3 · 5 ms" = 30 ms, longer than a sequence of its SELECT at 9600 Bd (about 21 ms). With
// the width its face gives (LustbusParameter::eeprom_width) the host waits the difference and
// every SELECT of a series is acknowledged at once; without it the servo refuses the second one
// with 04H (3: "EEPROM busy") and the host repeats it after 9.2's wait.
TEST(Mc6000Lustbus, EepromSelectsInSeriesWaitTheTimeOf1022) {
  const auto butwd = mc::lustbus_face().find_parameter("BUTWD");
  ASSERT_TRUE(butwd.has_value());
  EXPECT_EQ(butwd->eeprom_width, 2);
  EXPECT_EQ(mc::lustbus_face().find_parameter("RSIO")->eeprom_width, 0);  // RAM: no wait (10.2.2)
  for (const bool told : {true, false}) {
    Mc dev;
    Bus bus;
    bus.add(dev, 3);
    EXPECT_EQ(bus.read(3, 85).value.view(), "01");
    for (int i = 1; i <= 4; ++i) {
      Request r = select(3, make_code(20409), make_value(std::to_string(100 * i)));
      r.eeprom_width = told ? butwd->eeprom_width : 0;
      const Outcome o = bus.run(r);
      ASSERT_EQ(o.kind, OutcomeKind::acknowledged) << i;
      if (told) {
        EXPECT_EQ(o.attempts, 1) << i;
        if (i > 1) {
          EXPECT_GT(o.eeprom_wait, 0ms) << i;
          EXPECT_LT(o.eeprom_wait, 30ms) << i;
        }
      } else if (i > 1) {
        EXPECT_EQ(o.attempts, 2) << i;
        EXPECT_EQ(o.siof, std::optional<std::uint8_t>(0x04)) << i;
      }
    }
    EXPECT_EQ(dev.value(409), 0x400U);  // 1024 ms, the last one
  }
}

// 6.2.3 (LB-E5): the printed CODE 00005 is no servo CODE (20H); the corrected 20428 is taken.
TEST(Mc6000Lustbus, SeedExample623AsPrintedAndCorrected) {
  Fresh f;
  EXPECT_EQ(f.send(Bytes{}(4)(64)(2)("00005=14D4106")(3)(0x49).v).answer, (Bytes{}(64)(0x15).v));
  EXPECT_EQ(f.dev.serr(), 0x20);
  f.send(enq(0, 85));
  EXPECT_EQ(f.send(Bytes{}(4)(64)(2)("20428=14D4106")(3)(0x40).v).answer, (Bytes{}(64)(6).v));
  EXPECT_EQ(f.dev.value(mc::kRsio), 0x14D4106U);
}

// 7.2.1 through the host: every SELECT acknowledged, the EEPROM ones without 04H (each telegram
// sequence outlasts 15 ms for one byte).
TEST(Mc6000Lustbus, ControlSequence721ThroughTheHost) {
  Mc dev;
  Bus bus;
  bus.add(dev, 3);
  EXPECT_EQ(bus.read(3, 85).value.view(), "01");
  const std::pair<std::uint32_t, std::string_view> seq[] = {
      {20300, "2"}, {20416, "0"}, {20402, "2"}, {20418, "0"},      {20419, "0"},
      {20420, "0"}, {20417, "3"}, {20428, "842666"}, {20416, "1"}};
  for (const auto& [code, v] : seq) {
    const auto o = bus.write(3, code, v);
    EXPECT_EQ(o.kind, OutcomeKind::acknowledged) << code;
    EXPECT_EQ(o.attempts, 1) << code;
  }
  EXPECT_EQ(dev.value(300), 2U);
  EXPECT_EQ(dev.value(402), 2U);
  EXPECT_EQ(dev.value(417), 3U);
  EXPECT_EQ(dev.value(mc::kRsio), 0x842666U);
  EXPECT_TRUE(dev.running());
  bus.wait(2s);  // the speed loop settles
  const auto speed = bus.read(3, 20077);
  EXPECT_EQ(speed.value.view(), "00842666");
  EXPECT_NEAR(decode(Family::enhanced, DataType::int32q16, speed.value.view()).value, 132.15, 1e-4);
}

// 5.2: the shared CODEs 000xx; 2.4.2's own ones for the same parameters.
TEST(Mc6000Lustbus, SharedCodesOf52) {
  Mc dev;
  Bus bus;
  bus.add(dev, 3);
  EXPECT_EQ(bus.read(3, 91).value.view(), "1770");  // 6000, chosen
  EXPECT_EQ(bus.read(3, 20091).value.view(), "1770");
  EXPECT_EQ(bus.read(3, 81).value.view(), "2580");  // 9600
  EXPECT_EQ(bus.read(3, 5).kind, OutcomeKind::nak);
  EXPECT_EQ(bus.read(3, 20999).kind, OutcomeKind::nak);
  EXPECT_EQ(dev.serr(), 0x01);  // 6.1 note: ENQUIRYs enter nothing
}

// 3, 10.2.2: RAM and ACK at once; the EEPROM copy takes 15 ms per byte in the background, and an
// EEPROM SELECT meanwhile is refused with 04H; the host waits > 60 ms and repeats (9.2).
TEST(Mc6000Lustbus, EepromInTheBackgroundWithBusy) {
  Fresh f;
  Time t = f.t + 1s;
  auto a = feed(f.rx, sel(3, 20081, "4B00"), t);  // 19200, 2 bytes: 30 ms
  EXPECT_EQ(a.answer, (Bytes{}(0x43)(6).v));
  EXPECT_EQ(a.due, 2ms);
  EXPECT_EQ(f.dev.value(81), 19200U);
  EXPECT_EQ(f.dev.eeprom_busy_until(), t + 30ms);
  a = feed(f.rx, sel(3, 20084, "64"), t + 20ms);
  EXPECT_EQ(a.answer, (Bytes{}(0x43)(0x15).v));
  EXPECT_EQ(f.dev.serr(), 0x04);
  EXPECT_EQ(f.dev.value(84), 0U);

  Mc dev;
  Bus bus;
  bus.add(dev, 3);
  bus.read(3, 85);
  EXPECT_EQ(bus.write(3, 20081, "4B00").kind, OutcomeKind::acknowledged);
  const auto o = bus.write(3, 20084, "64");
  EXPECT_EQ(o.kind, OutcomeKind::acknowledged);
  EXPECT_EQ(o.attempts, 2);
  EXPECT_EQ(dev.value(84), 100U);
}

// 11.2: specifier 3, 43 characters.
TEST(Mc6000Lustbus, DescriptionOf112) {
  Mc dev;
  Bus bus;
  bus.add(dev, 3);
  const auto o = bus.read(3, 30428);
  ASSERT_EQ(o.kind, OutcomeKind::value);
  EXPECT_EQ(o.value.size(), kMcDescriptionLength);
  const auto d = parse_mc_description(o.value.view());
  ASSERT_TRUE(d.ok()) << to_string(d.error);
  EXPECT_EQ(d.value.name_view(), "RSIO");
  EXPECT_EQ(d.value.kind, '1');
  EXPECT_EQ(d.value.min, 0x80000000U);
  EXPECT_EQ(d.value.max, 0x7FFFFFFFU);
  EXPECT_EQ(bus.read(3, 30085).kind, OutcomeKind::value);
}

// 10 exception 1: 4-PROG = 1 loads every factory setting; the ACK comes when done, "up to 10
// seconds": 9.9 s, the drive's one time on every bus (docs/errata.md MC-D1).
TEST(Mc6000Lustbus, Prog1LoadsFactoryDefaults) {
  Mc dev;
  Bus bus;
  bus.add(dev, 3);
  bus.read(3, 85);
  ASSERT_EQ(bus.write(3, 20417, "3").kind, OutcomeKind::acknowledged);
  Request r = select(3, make_code(20004), make_value("1"));
  r.response_timeout = 10s;
  const auto o = bus.run(r);
  EXPECT_EQ(o.kind, OutcomeKind::acknowledged);
  EXPECT_GE(o.finished - o.started, 9900ms);
  EXPECT_LT(o.finished - o.started, 10s);
  EXPECT_EQ(dev.value(417), 0U);
}

// The servo's procedures of 11 are its wing's description, which the registry's face carries and
// the host runs: 80-SLOAD with -1 / -2 (11.4), 108-STEXT (11.3), PosMOD1 over 49999 with 80
// characters of user data and the error read %RDF (11.6). The inverter offers none.
TEST(Mc6000Lustbus, TheWingDescribesItsProceduresToTheHost) {
  const DeviceProcedures& p = ibs::devices::mc6000::lustbus_procedures();
  EXPECT_EQ(ibs::devices::mc6000::lustbus_face().procedures, &p);
  EXPECT_EQ(ibs::devices::vf1000::lustbus_face().procedures, nullptr);
  ASSERT_TRUE(p.download && p.indexed_text && p.block_transfer);
  EXPECT_EQ(p.download->parameter, mc::kSload);
  EXPECT_EQ(p.download->start, -1);
  EXPECT_EQ(p.download->end, -2);
  EXPECT_EQ(parameter_code(p.download->family, p.download->parameter)->text(), "20080");
  EXPECT_EQ(p.indexed_text->index_parameter, mc::kStext);
  EXPECT_EQ(p.block_transfer->code, kPosmodCode);
  EXPECT_EQ(p.block_transfer->max_user_data, 80U);
  EXPECT_EQ(p.block_transfer->error_read.view(), "1%RDF");
  EXPECT_EQ(p.block_transfer->asks_answer('1'), true);   // 11.6.3: a request telegram
  EXPECT_EQ(p.block_transfer->asks_answer('8'), false);  // a data telegram
  EXPECT_EQ(p.block_transfer->asks_answer('G'), std::nullopt);
}

// 11.4 through the host's download: accepted, rejected (the first invalid parameter, the old
// dataset back), refused while running (40H).
TEST(Mc6000Lustbus, DownloadHandshakeOn80Sload) {
  Mc dev;
  Bus bus;
  bus.add(dev, 3);
  bus.read(3, 85);
  const Assignment good[] = {{make_code(20417), make_value("3")}, {make_code(20428), make_value("10000")}};
  auto o = bus.run(servo_download(3, good));
  EXPECT_EQ(o.kind, OutcomeKind::downloaded) << describe(o);
  EXPECT_EQ(dev.value(417), 3U);
  EXPECT_EQ(dev.eeprom_value(417), 3U);
  EXPECT_EQ(dev.value(mc::kRsio), 0U);  // not CardWriteable: acknowledged, not taken (11.4)
  const Assignment bad[] = {{make_code(20418), make_value("3")}, {make_code(20419), make_value("9")}};
  o = bus.run(servo_download(3, bad));
  EXPECT_EQ(o.kind, OutcomeKind::download_rejected) << describe(o);
  EXPECT_EQ(o.rejected_parameter, 419U);
  EXPECT_EQ(dev.value(418), 0U);  // the old dataset
  EXPECT_EQ(dev.value(419), 6U);
  ASSERT_EQ(bus.write(3, 20402, "2").kind, OutcomeKind::acknowledged);  // CLSEL = SIO
  ASSERT_EQ(bus.write(3, 20416, "1").kind, OutcomeKind::acknowledged);  // running
  ASSERT_TRUE(dev.running());
  o = bus.run(servo_download(3, good));
  EXPECT_EQ(o.kind, OutcomeKind::download_refused);
  EXPECT_EQ(o.siof, 0x40);
}

// 11.4 "Important": a SELECT of a parameter without CardWriteable during the download is
// acknowledged and dropped — a start through 416-SCTL1 too, so the servo stays disengaged; a
// rejected dataset brings back the CardWriteable parameters only.
TEST(Mc6000Lustbus, DownloadTakesOnlyCardWriteableParameters) {
  Fresh f;
  f.control_on_sio();
  ASSERT_EQ(f.send(sel(3, 20080, "FFFF")).answer, (Bytes{}(0x43)(6).v));
  EXPECT_TRUE(f.dev.downloading());
  EXPECT_EQ(f.send(sel(3, 20416, "1")).answer, (Bytes{}(0x43)(6).v));
  EXPECT_EQ(f.dev.value(mc::kSctl1), 0U);
  EXPECT_EQ(f.send(sel(3, 20083, "55")).answer, (Bytes{}(0x43)(6).v));  // SDMMY: dropped
  EXPECT_EQ(f.dev.value(83), 0U);
  EXPECT_EQ(f.send(sel(3, 20418, "3")).answer, (Bytes{}(0x43)(6).v));
  EXPECT_EQ(f.send(sel(3, 20300, "9")).answer, (Bytes{}(0x43)(6).v));  // CFCON 9 > 6, untested
  EXPECT_EQ(f.dev.value(300), 9U);
  EXPECT_EQ(f.send(sel(3, 20080, "FFFE")).answer, (Bytes{}(0x43)(6).v));
  f.dev.advance(f.t + 300ms);
  EXPECT_FALSE(f.dev.downloading());
  EXPECT_EQ(f.dev.value(mc::kSload), 300U);  // the first invalid one
  EXPECT_EQ(f.dev.value(300), 2U);
  EXPECT_EQ(f.dev.value(418), 0U);
  EXPECT_EQ(f.dev.value(402), 2U);  // from before the download, untouched
  EXPECT_FALSE(f.dev.running());
}

// 5.2 with 84-SWDGT; 8.1.2: bit 7 of 416-SCTL1 resets the error.
TEST(Mc6000Lustbus, WatchdogAndSctl1Reset) {
  Fresh f;
  f.control_on_sio();
  Time t = f.t + 1s;
  ASSERT_EQ(feed(f.rx, sel(3, 84, "32"), t).answer, (Bytes{}(0x43)(6).v));  // 50 ms, shared CODE
  ASSERT_EQ(feed(f.rx, sel(3, 20416, "1"), t + 40ms).answer, (Bytes{}(0x43)(6).v));
  ASSERT_EQ(feed(f.rx, sel(3, 83, "7"), t + 80ms).answer, (Bytes{}(0x43)(6).v));  // dummy
  EXPECT_TRUE(f.dev.running());
  f.dev.advance(t + 135ms);
  EXPECT_TRUE(f.dev.watchdog_fault());
  EXPECT_FALSE(f.dev.running());
  EXPECT_EQ(feed(f.rx, enq(3, 85), t + 140ms).answer,
            bytes(encode_text_answer(3, make_code(85), make_value("02")).span()));
  ASSERT_EQ(feed(f.rx, sel(3, 84, "0"), t + 150ms).answer, (Bytes{}(0x43)(6).v));
  ASSERT_EQ(feed(f.rx, sel(3, 20416, "81"), t + 160ms).answer, (Bytes{}(0x43)(6).v));
  EXPECT_FALSE(f.dev.watchdog_fault());
  EXPECT_TRUE(f.dev.running());
}

// 5.2: "For servocontrollers, the additional possibility exists to program the error reaction of
// the device via parameter" (511-RESIO, MC-D7); 8.1.2 on a servo with its serial interface alone:
// with 5 (RESET) the watchdog's fault reset by 416-SCTL1 bit 7 boots the servo -- the ACK cut to
// its ADR, no answer during the boot, then the power-on bit in 85-SERR (9.2).
TEST(Mc6000Lustbus, WatchdogWithReactionResetBootsTheServoOnItsReset) {
  Fresh f;
  const auto ack = Bytes{}(0x43)(6).v;
  ASSERT_EQ(f.send(sel(3, 20511, "5")).answer, ack);
  f.control_on_sio();
  Time t = f.t + 1s;
  ASSERT_EQ(feed(f.rx, sel(3, 84, "32"), t).answer, ack);  // 50 ms
  ASSERT_EQ(feed(f.rx, sel(3, 20416, "1"), t + 40ms).answer, ack);
  EXPECT_TRUE(f.dev.running());
  f.dev.advance(t + 135ms);
  ASSERT_TRUE(f.dev.watchdog_fault());
  EXPECT_EQ(f.dev.drive_state(), ibs::drivecom::State::fault) << "the power stage off at once";
  EXPECT_EQ(feed(f.rx, enq(3, 85), t + 140ms).answer,
            bytes(encode_text_answer(3, make_code(85), make_value("02")).span()));
  ASSERT_EQ(feed(f.rx, sel(3, 84, "0"), t + 150ms).answer, ack);
  EXPECT_EQ(feed(f.rx, sel(3, 20416, "81"), t + 200ms).answer, (Bytes{}(0x43).v))
      << "8.1.2: the ACK-answer telegram is not sent in full";
  EXPECT_EQ(f.dev.drive_state(), ibs::drivecom::State::not_ready);
  EXPECT_TRUE(feed(f.rx, enq(3, 85), t + 400ms).answer.empty()) << "the connection is broken for the boot";
  EXPECT_EQ(feed(f.rx, enq(3, 85), t + 800ms).answer,
            bytes(encode_text_answer(3, make_code(85), make_value("01")).span()));
  EXPECT_FALSE(f.dev.watchdog_fault());
  EXPECT_FALSE(f.dev.running()) << "416-SCTL1 is RAM: the boot does not start the drive";
}

// 5.2 (LB-E13): the scan's ENQUIRY of 91-TYPE at 1..30 is answered with the value (6.1), not the
// "ACK" 5.2 says; the 20091 probe tells the servo (it answers) from the inverter (NAK, LB-D6).
TEST(LustbusWings, NetworkScanTellsInvertersFromServos) {
  ibs::devices::vf1000::LustbusDevice vf;
  Mc servo;
  Bus bus;
  bus.add(vf, 1);
  bus.add(servo, 3);
  const auto o = bus.run(network_scan());
  ASSERT_EQ(o.kind, OutcomeKind::scan);
  const auto found = o.scan.found();
  ASSERT_EQ(found.size(), 2U);
  EXPECT_EQ(found[0].address, 1);
  EXPECT_EQ(found[0].family, Family::standard);
  EXPECT_EQ(found[0].type, 1000U);
  EXPECT_EQ(found[1].address, 3);
  EXPECT_EQ(found[1].family, Family::enhanced);
  EXPECT_EQ(found[1].type, 6000U);
  EXPECT_EQ(vf.siof(), 0x01);  // an ENQUIRY answered NAK enters nothing (6.1 note)
}

}  // namespace
