// The MC6000 wing as a LUSTBUS device (seed 000): the seed's telegrams byte-exact against it, the
// shared CODEs of 5.2, 85-SERR, EEPROM in the background with 04H (3, 10.2.2), the description
// (11.2), 4-PROG, the download handshake on 80-SLOAD (11.4), the watchdog (5.2).
#include "ibs/devices/mc6000/lustbus_device.hpp"
#include "ibs/devices/vf1000/lustbus_device.hpp"

#include <gtest/gtest.h>

#include "ibs/lustbus/description.hpp"
#include "support.hpp"

namespace {

using namespace ibs::lustbus;
using namespace ibs::lustbus::devtest;
using ibs::Time;
using Mc = ibs::devices::mc6000::LustbusDevice;
namespace mc = ibs::devices::mc6000;

std::vector<std::uint8_t> sel(Address a, std::uint32_t code, std::string_view v) {
  return bytes(encode_select(a, make_code(code), make_value(v)).span());
}
std::vector<std::uint8_t> enq(Address a, std::uint32_t code) {
  return bytes(encode_enquiry(a, make_code(code)).span());
}

struct Fresh {
  Mc dev;
  Receiver rx{dev, 3};
  Time t{0};
  Fed send(const std::vector<std::uint8_t>& b) {
    t += 1s;
    return feed(rx, b, t);
  }
  Fresh() { send(enq(0, 85)); }
};

// 6.1.1.2 (LB-E4): 77-SPEED via address 0 answered "@ STX 20077=04FA4000 ETX 0BH", 18 bytes
// (10.1.1), the servo running at 1274.25 1/min.
TEST(Mc6000Lustbus, SeedExample6112ByteExact) {
  Fresh f;
  ASSERT_EQ(f.send(sel(3, 20428, "4FA4000")).answer, (Bytes{}(0x43)(6).v));
  ASSERT_EQ(f.send(sel(3, 20416, "1")).answer, (Bytes{}(0x43)(6).v));
  const auto host = Bytes{}(4)(64)(50)(48)(48)(55)(55)(5).v;
  const auto a = f.send(host).answer;
  EXPECT_EQ(a, (Bytes{}(64)(2)("20077=04FA4000")(3)(0x0B).v));
  EXPECT_EQ(a.size(), 18U);
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
  const auto speed = bus.read(3, 20077);
  EXPECT_EQ(speed.value.view(), "00842666");
  EXPECT_NEAR(decode(Family::mc6000, DataType::int32q16, speed.value.view()).value, 132.15, 1e-4);
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

// 10 exception 1: 4-PROG = 1 loads every factory setting; the ACK comes when done.
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
  EXPECT_GT(o.finished - o.started, 2s);
  EXPECT_EQ(dev.value(417), 0U);
}

// 11.4 through the host's download: accepted, rejected (the first invalid parameter, the old
// dataset back), refused while running (40H).
TEST(Mc6000Lustbus, DownloadHandshakeOn80Sload) {
  Mc dev;
  Bus bus;
  bus.add(dev, 3);
  bus.read(3, 85);
  const Assignment good[] = {{make_code(20417), make_value("3")}, {make_code(20428), make_value("10000")}};
  auto o = bus.run(download(3, good));
  EXPECT_EQ(o.kind, OutcomeKind::downloaded) << describe(o);
  EXPECT_EQ(dev.value(417), 3U);
  EXPECT_EQ(dev.eeprom_value(417), 3U);
  const Assignment bad[] = {{make_code(20418), make_value("3")}, {make_code(20419), make_value("9")}};
  o = bus.run(download(3, bad));
  EXPECT_EQ(o.kind, OutcomeKind::download_rejected) << describe(o);
  EXPECT_EQ(o.rejected_parameter, 419U);
  EXPECT_EQ(dev.value(418), 0U);  // the old dataset
  EXPECT_EQ(dev.value(419), 6U);
  ASSERT_EQ(bus.write(3, 20416, "1").kind, OutcomeKind::acknowledged);  // running
  o = bus.run(download(3, good));
  EXPECT_EQ(o.kind, OutcomeKind::download_refused);
  EXPECT_EQ(o.siof, 0x40);
}

// 5.2 with 84-SWDGT; 8.1.2: bit 7 of 416-SCTL1 resets the error.
TEST(Mc6000Lustbus, WatchdogAndSctl1Reset) {
  Fresh f;
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
  EXPECT_EQ(found[0].family, Family::vf1000);
  EXPECT_EQ(found[0].type, 1000U);
  EXPECT_EQ(found[1].address, 3);
  EXPECT_EQ(found[1].family, Family::mc6000);
  EXPECT_EQ(found[1].type, 6000U);
  EXPECT_EQ(vf.siof(), 0x01);  // an ENQUIRY answered NAK enters nothing (6.1 note)
}

}  // namespace
