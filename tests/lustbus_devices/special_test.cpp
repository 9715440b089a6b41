// The MC6000's special functions over LUSTBUS (LUSTBUS manual 11): the description's service
// structure with binary elements that are frame characters (11.2.1, LB-D10), the value
// substitution texts of 11.3 with their NAK rules, the PosMOD1 channel of 11.6 with the
// examples of 11.6.4 byte-exact, and the reaction times of 10.
#include <gtest/gtest.h>

#include "ibs/devices/mc6000/lustbus_device.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/service.hpp"
#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "ibs/lustbus/description.hpp"
#include "servo_procedures.hpp"
#include "support.hpp"

namespace {

using namespace ibs::lustbus;
using namespace ibs::lustbus::devtest;
using ibs::Time;
using Mc = ibs::devices::mc6000::LustbusDevice;
namespace mc = ibs::devices::mc6000;

// A SELECT / ENQUIRY of 49999 as the host sends it, with the BCC by 2.2's rule.
std::vector<std::uint8_t> pm_select(Address a, std::string_view user) { return sel(a, kPosmodCode.number(), user); }
std::vector<std::uint8_t> pm_enquiry(Address a) { return enq(a, kPosmodCode.number()); }
std::vector<std::uint8_t> pm_answer(Address a, std::string_view user) {
  return bytes(encode_text_answer(a, kPosmodCode, make_value(user)).span());
}

struct Servo {
  Mc dev;
  Receiver rx{dev, 3};
  Time t{0};
  Fed send(const std::vector<std::uint8_t>& b, ibs::Duration after = 1s) {
    t += after;
    return feed(rx, b, t);
  }
  Servo() {
    send(enq(3, 85));
    for (const auto& [code, v] : {std::pair{20402U, "2"}, {20417U, "3"}, {20416U, "1"}}) send(sel(3, code, v));
  }
};

const auto kAck = Bytes{}(0x43)(6).v;
const auto kNak = Bytes{}(0x43)(0x15).v;

// 11.6.4 "Passing a manual command": 38H GOA0V1000, ADR ACK. The frame as printed, BCC filled in.
TEST(PosMod1, ManualCommandOf1164) {
  Servo s;
  const auto host = Bytes{}(4)(0x43)(2)("49999=8GOA0V1000")(3).v;
  auto framed = host;
  std::uint8_t bcc = 0;
  for (std::size_t i = 3; i < framed.size(); ++i) bcc ^= framed[i];
  framed.push_back(bcc);
  EXPECT_EQ(framed, pm_select(3, "8GOA0V1000"));
  EXPECT_EQ(s.send(framed).answer, kAck);
  // The axis is at 0 already; a relative move of 500 at 1000/s takes half a second.
  EXPECT_EQ(s.send(pm_select(3, "8GOR500V1000")).answer, kAck);
  EXPECT_TRUE(s.dev.posmod().moving());
  s.send(pm_select(3, "1?"), 600ms);
  EXPECT_EQ(s.dev.posmod().position(), 500);
  EXPECT_FALSE(s.dev.posmod().moving());
}

// 11.6.4 "Transmitting a program" and "Program request": 3CH %P10 (RPF), 3CH N10 GO 0, 38H END;
// then 31H %RDP10 and ENQUIRYs answered 34H %P10 (RPF), 34H N10 GO 0, 30H END.
TEST(PosMod1, ProgramTransferAndRequestOf1164) {
  Servo s;
  EXPECT_EQ(s.send(pm_select(3, "<%P10 (RPF)")).answer, kAck);  // '<' = 3CH
  EXPECT_EQ(s.send(pm_select(3, "<N10 GO 0")).answer, kAck);
  EXPECT_EQ(s.send(pm_select(3, "8END")).answer, kAck);
  EXPECT_EQ(s.dev.posmod().stored_programs(), 1U);
  EXPECT_EQ(s.send(pm_select(3, "1%RDP10")).answer, kAck);
  EXPECT_EQ(s.send(pm_enquiry(3)).answer, pm_answer(3, "4%P10 (RPF)"));
  EXPECT_EQ(s.send(pm_enquiry(3)).answer, pm_answer(3, "4N10 GO 0"));
  EXPECT_EQ(s.send(pm_enquiry(3)).answer, pm_answer(3, "0END"));
  // Nothing more was asked for: NAK, and %RDF tells why.
  EXPECT_EQ(s.send(pm_enquiry(3)).answer, kNak);
  EXPECT_EQ(s.send(pm_select(3, "1%RDF")).answer, kAck);
  EXPECT_EQ(s.send(pm_enquiry(3)).answer, pm_answer(3, "0F04 no request pending"));
  EXPECT_EQ(s.dev.serr(), 0);  // the PosMOD1's errors are its own (LB-D22)
}

// 11.6.4 "Status request": 31H ?, then the ENQUIRY answered 30H G10H10 ... (enabled, standing,
// referenced, no error).
TEST(PosMod1, StatusRequestOf1164) {
  Servo s;
  EXPECT_EQ(s.send(pm_select(3, "8HOME")).answer, kAck);
  EXPECT_EQ(s.send(pm_select(3, "1?")).answer, kAck);
  EXPECT_EQ(s.send(pm_enquiry(3)).answer, pm_answer(3, "0G10H10 P0"));
}

// 11.6: NAKs and %RDF; the PosMOD1 channel is not held by the 85-SERR latch.
TEST(PosMod1, RefusalsReadWithRdf) {
  Mc dev;  // power-on bit set: parameter SELECTs refused
  Receiver rx{dev, 3};
  Time t{1s};
  EXPECT_EQ(feed(rx, pm_select(3, "8GOA100"), t).answer, kNak);  // not enabled
  EXPECT_EQ(feed(rx, pm_select(3, "1%RDF"), t + 1s).answer, kAck);
  EXPECT_EQ(feed(rx, pm_enquiry(3), t + 2s).answer, pm_answer(3, "0F07 drive not enabled"));
  EXPECT_EQ(feed(rx, pm_select(3, "8JUMP"), t + 3s).answer, kNak);
  EXPECT_EQ(feed(rx, pm_select(3, "<N10 GO 0"), t + 4s).answer, kNak);  // no %P first
  EXPECT_EQ(feed(rx, pm_select(3, "1%RDP77"), t + 5s).answer, kNak);
  EXPECT_EQ(feed(rx, pm_select(3, "\x7F?"), t + 6s).answer, kNak);  // bits 6 / 7 set
  EXPECT_EQ(dev.posmod().error(), ibs::devices::mc6000::PosmodError::status_byte);
  EXPECT_EQ(dev.serr(), 0x01);  // only the power-on bit: the SERR latch saw none of it
}

// The host's PosMOD1 exchange (11.6): SELECT and, for a request, the ENQUIRY; after a NAK the
// %RDF read; multiblock answers one ENQUIRY at a time.
TEST(PosMod1, ThroughTheHost) {
  Mc dev;
  Bus bus;
  bus.add(dev, 3);
  bus.read(3, 85);
  auto o = bus.run(posmod_request(3, "8GOA10"));
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  EXPECT_EQ(o.value.view(), "0F07 drive not enabled");
  for (const auto& [code, v] : {std::pair{20402U, "2"}, {20417U, "3"}, {20416U, "1"}}) {
    ASSERT_EQ(bus.write(3, code, v).kind, OutcomeKind::acknowledged);
  }
  EXPECT_EQ(bus.run(posmod_request(3, "<%P3")).kind, OutcomeKind::acknowledged);
  EXPECT_EQ(bus.run(posmod_request(3, "<N1 GOA10")).kind, OutcomeKind::acknowledged);
  EXPECT_EQ(bus.run(posmod_request(3, "8END")).kind, OutcomeKind::acknowledged);
  o = bus.run(posmod_request(3, "1%RDP3"));
  ASSERT_EQ(o.kind, OutcomeKind::value) << describe(o);
  EXPECT_EQ(o.value.view(), "4%P3");
  EXPECT_EQ(parse_posmod_status(o.value.view()[0])->multiblock, true);
  EXPECT_EQ(bus.run(posmod_request(3, "")).value.view(), "4N1 GOA10");
  EXPECT_EQ(bus.run(posmod_request(3, "")).value.view(), "0END");
  o = bus.run(posmod_request(3, "1?"));
  EXPECT_EQ(o.value.view(), "0G10H00 P0");
  // User data the status byte of 11.6.3 does not start, or over 80 characters: refused.
  EXPECT_EQ(bus.host.submit(posmod_request(3, "GOA1")).error, SubmitError::invalid_request);
  EXPECT_EQ(bus.host.submit(posmod_request(3, "8" + std::string(80, 'A'))).error,
            SubmitError::invalid_request);
}

// 11.3 through the host: 108-STEXT = index, ENQUIRY 61xxx; NAK for a parameter that is not there,
// one without ShowText, and an index above the parameter's maximum.
TEST(SubstitutionTexts, Of113) {
  Mc dev;
  Bus bus;
  bus.add(dev, 3);
  bus.read(3, 85);
  auto o = bus.run(substitution_text_request(3, 300, 2));
  ASSERT_EQ(o.kind, OutcomeKind::value) << describe(o);
  EXPECT_EQ(substitution_text(o.value.view()), "SCON");
  EXPECT_EQ(bus.run(substitution_text_request(3, 402, 2)).value.view(), "SIO");
  EXPECT_EQ(bus.run(substitution_text_request(3, 417, 3)).value.view(), "RSIO");
  EXPECT_EQ(bus.run(substitution_text_request(3, 107, 1)).value.view(), "rpm");  // 11.2.1: UNIT
  EXPECT_EQ(bus.run(substitution_text_request(3, 999, 0)).kind, OutcomeKind::nak);  // no parameter
  EXPECT_EQ(bus.run(substitution_text_request(3, 428, 0)).kind, OutcomeKind::nak);  // no ShowText
  EXPECT_EQ(bus.run(substitution_text_request(3, 402, 6)).kind, OutcomeKind::nak);  // > max 5
  EXPECT_EQ(dev.value(mc::kStext), 6U);
}

// 11.2.1 through the host: the service structure's areas, among them frame characters (CFCON's
// activity area SC_DRIVE = 05H = ENQ, SPEED's subject area VAL = 15H = NAK), read by length.
TEST(McDescriptionAreas, CarryFrameCharacters) {
  Mc dev;
  Bus bus;
  bus.add(dev, 3);
  auto o = bus.read(3, 30300);
  ASSERT_EQ(o.kind, OutcomeKind::value) << describe(o);
  auto d = parse_mc_description(o.value.view());
  ASSERT_TRUE(d.ok()) << to_string(d.error);
  EXPECT_EQ(d.value.name_view(), "CFCON");
  EXPECT_EQ(d.value.activity_area, 5);  // SC_DRIVE: CardWriteable
  EXPECT_EQ(d.value.subject_area, 0);   // CONF
  EXPECT_EQ(d.value.structure_filter, mc::kAllControlTypes);
  EXPECT_EQ(d.value.attribute & kAttrShowText, kAttrShowText);
  o = bus.read(3, 30077);
  ASSERT_EQ(o.kind, OutcomeKind::value) << describe(o);
  d = parse_mc_description(o.value.view());
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(d.value.subject_area, 21);  // VAL
  EXPECT_EQ(d.value.unit, 1);           // rpm, 107-UNIT's text 1
  EXPECT_EQ(d.value.activity_area, 0);
  // Every parameter of the table has its row, and its description travels.
  for (const auto& p : mc::parameters()) {
    ASSERT_NE(mc::service_entry(p.number), nullptr) << p.number;
    EXPECT_EQ(bus.read(3, 30000U + p.number).kind, OutcomeKind::value) << p.number;
    const bool show_text = (p.attributes & kAttrShowText) != 0;
    EXPECT_EQ(show_text, !mc::service_entry(p.number)->texts.empty()) << p.number;
  }
}

// The wing's service structure codes its areas as 11.2.1's tables do (the protocol core's rows,
// pinned as printed in McDescription1121.EveryRowOfTheTablesAsPrinted).
TEST(McDescriptionAreas, TheWingsCodesAreThoseOfTheTables) {
  const auto code_of = [](std::span<const AreaRow> rows, std::string_view name) -> int {
    for (const AreaRow& r : rows) {
      if (r.name == name) return r.code;
    }
    return -1;
  };
  const std::pair<mc::Subject, std::string_view> subjects[] = {
      {mc::Subject::conf, "CONF"}, {mc::Subject::opt1, "OPT1"}, {mc::Subject::scon, "SCON"},
      {mc::Subject::sio, "SIO"},   {mc::Subject::scty, "SCTY"}, {mc::Subject::sys, "SYS"},
      {mc::Subject::ref, "REF"},   {mc::Subject::menu, "MENU"}, {mc::Subject::val, "VAL"}};
  for (const auto& [s, name] : subjects) EXPECT_EQ(static_cast<int>(s), code_of(kSubjectAreas, name)) << name;
  const std::pair<mc::Activity, std::string_view> activities[] = {
      {mc::Activity::nothing, "SC_Nothing"}, {mc::Activity::opt1, "SC_OPT1"}, {mc::Activity::sys, "SC_SYS"},
      {mc::Activity::drive, "SC_DRIVE"},     {mc::Activity::ref, "SC_REF"}};
  for (const auto& [a, name] : activities) EXPECT_EQ(static_cast<int>(a), code_of(kActivityAreas, name)) << name;
  std::uint16_t all = 0;
  for (const FlagRow& r : kStructureFlags) all = static_cast<std::uint16_t>(all | r.mask);
  EXPECT_EQ(mc::kAllControlTypes, all);  // TorqueCtrl .. ESlave
}

// 10: reaction times drawn from the table, with and without KEYPAD; the same seed, the same times.
TEST(ReactionTimes, Of10SeededWithinTheTable) {
  for (const bool keypad : {false, true}) {
    for (const auto& m : {mc::lustbus_reaction(keypad, 7), ibs::devices::vf1000::lustbus_reaction(keypad, 7)}) {
      ReactionTimes a(m);
      ReactionTimes b(m);
      ibs::Duration lo = m.max;
      ibs::Duration hi = m.min;
      for (int i = 0; i < 2000; ++i) {
        const auto r = a.next();
        EXPECT_EQ(r, b.next());
        EXPECT_GE(r, 1ms);
        EXPECT_LE(r, m.max);
        lo = std::min(lo, r);
        hi = std::max(hi, r);
      }
      EXPECT_LT(lo, 3ms);  // the range is used, not one value
      EXPECT_GT(hi, m.max - 3ms);
    }
  }
  EXPECT_EQ(mc::lustbus_reaction(true, 0).max, 30ms);
  EXPECT_EQ(mc::lustbus_reaction(false, 0).max, 25ms);
  EXPECT_EQ(ibs::devices::vf1000::lustbus_reaction(true, 0).max, 60ms);
  EXPECT_EQ(ibs::devices::vf1000::lustbus_reaction(false, 0).max, 30ms);
  EXPECT_NE(ReactionTimes(mc::lustbus_reaction(false, 1)).next(),
            ReactionTimes(mc::lustbus_reaction(false, 2)).next());
  // A drive with the model answers after the time drawn.
  ibs::devices::vf1000::LustbusTiming timing;
  timing.reaction = ibs::devices::vf1000::lustbus_reaction(false, 42);
  ibs::devices::vf1000::LustbusDevice vf(timing);
  Receiver rx(vf, 1);
  ReactionTimes expect(timing.reaction);
  for (int i = 0; i < 5; ++i) {
    const auto f = feed(rx, enq(1, 191), Time{1s * (i + 1)});
    EXPECT_EQ(f.due, expect.next());
  }
}

}  // namespace
