// Errors and warnings of the emulated CDA3000 as the CANLust manual chapter 6 gives them (docs/canlust.md
// D38, errata CAN-E16, CAN-E17), on the virtual bus against the core's master:
//   6.1 "The error response is programmable for each error in four stages": one response
//       parameter per error of table 5.9 (520-ROTI .. 525-ROP2), written over the bus like any
//       parameter; the bus watchdog's reaction is 525-ROP2 (it reports E-OP2), not a setting of
//       the emulator;
//   6.2 the error telegram carries the number and the reaction taken;
//   6.3 "Parameterizable warnings on the CAN", masks 0004H (I2t integrator active), 0008H (motor
//       temperature above 502-WLTM), 0010H (heat sink temperature): 577-CAWRN shows the warnings
//       present, 576-CAWMK selects those reported on the CAN (status bit 7);
//   6.5 the error reset bit and System Start -> Stop acknowledge.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "bus.hpp"
#include "ibs/canlust/errors.hpp"
#include "ibs/devices/cda3000/bus_face.hpp"
#include "ibs/devices/cda3000/descriptor.hpp"

namespace ibs::devices::cda3000 {
namespace {

using namespace ibs::canlust;
using test::Bus;
using test::commissioned;
using Bytes = std::vector<std::uint8_t>;

Bytes bytes(const CanFrame& f) { return {f.data.begin(), f.data.begin() + f.dlc}; }
ibs::Word word(const CanFrame& f) { return static_cast<ibs::Word>(f.data[0] | (f.data[1] << 8U)); }

const Outcome& finish(Bus<Master>& b, Master& m, const Request& r) {
  const auto id = m.parameters().submit(r).id;
  EXPECT_NE(id, 0U);
  b.run_until_true([&] { return m.parameters().poll(id).state == RequestState::done; }, 5s);
  static const Outcome none{};
  const auto p = m.parameters().poll(id);
  return p.outcome != nullptr ? *p.outcome : none;
}

// CDA 1 enabled at 20 Hz, status every 20 ms; control telegrams only from the test.
void run_up(Bus<Master>& b, Master& m) {
  m.system_start();
  b.run_for(5ms);
  const auto ref = *wire_from_hz(ValueWidth::int32q16, 20.0);
  m.send_control(1, {0x0006, ref});
  b.run_for(10ms);
  m.send_control(1, {0x000F, ref});
  b.run_for(1500ms);
}

DeviceConfig fast_status() {
  DeviceConfig dc = commissioned(1);
  dc.saved.emplace_back(kCascy, 20);
  return dc;
}

// ---- 6.1: four stages per error -------------------------------------------------------------

struct ResponseRow {
  std::uint32_t code;            // the value written to the error's response parameter
  const char* name;              // its substitution text
  drivecom::State first;         // the first status telegram after the error
  drivecom::State settled;       // 2 s later
  bool warning_bit;              // status bit 7 in the first status
  double min_hz_after_100ms;     // the motor: still running (WRN, STOP) or coasting / stopping
  double max_hz_after_100ms;
};

// CANLust manual 6.1 (p. 66-67): the default disables the power stage; the response is programmable
// in four stages, of which the seed names WRN ("the device indicates the warning") and STOP; D7
// gives the other two. The motor after 100 ms from 20 Hz with D28's time constants: 200 ms (STOP,
// 12.1 Hz), 50 ms (quick stop, 2.7 Hz), 2 s coasting (PWOFF, 19.0 Hz).
const ResponseRow kResponseRows[] = {
    {0, "WRN", drivecom::State::enabled, drivecom::State::enabled, true, 19.5, 20.5},
    {1, "STOP", drivecom::State::fault_response_active, drivecom::State::fault, false, 11.0, 13.0},
    {2, "QSTOP", drivecom::State::fault_response_active, drivecom::State::fault, false, 2.0, 3.5},
    {3, "PWOFF", drivecom::State::fault, drivecom::State::fault, false, 18.0, 19.5},
};

class Cda3000ErrorResponse : public ::testing::TestWithParam<ResponseRow> {};

TEST_P(Cda3000ErrorResponse, TheErrorsParameterChoosesOneOfTheFourStages) {
  const ResponseRow row = GetParam();
  Master m;
  Bus<Master> b(m);
  b.add(fast_status());
  run_up(b, m);
  ASSERT_EQ(b.drive(0).state(), drivecom::State::enabled);
  // The response is a parameter: written over the bus by its substitution text's code.
  ASSERT_EQ(finish(b, m, write(1, kRoti, row.code)).kind, OutcomeKind::done);
  EXPECT_EQ(format_value(*find_parameter(kRoti), *b.drive(0).value(kRoti)),
            std::to_string(row.code) + " (" + row.name + ")");
  const Time at = b.now();
  ASSERT_TRUE(b.drive(0).inject_fault(kErrorOti, at));
  b.run_for(100ms);
  // 6.2 / D6: the error telegram carries the number and the reaction taken.
  const auto errors = b.seen_with_id(443);
  ASSERT_EQ(errors.size(), 1U);
  EXPECT_EQ(bytes(errors[0].frame), (Bytes{kErrorOti, 0, static_cast<std::uint8_t>(row.code)}));
  const auto status = b.seen_with_id(883, at);
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(drivecom::decode_state(word(status[0].frame)), row.first) << explain_status_word(word(status[0].frame));
  EXPECT_EQ(bit(word(status[0].frame), status_bits::kWarning), row.warning_bit);
  const double hz = b.drive(0).actual_hz(b.now());
  EXPECT_GE(hz, row.min_hz_after_100ms);
  EXPECT_LE(hz, row.max_hz_after_100ms);
  b.run_for(2s);
  EXPECT_EQ(b.drive(0).state(), row.settled);
  EXPECT_EQ(err_struc_from_wire(*b.drive(0).value(kErr1)).number, kErrorOti);
  // 6.5: the error reset bit acknowledges the error, or the warning of a WRN response.
  m.send_control(1, {0x0000, 0});
  b.run_for(10ms);
  m.send_control(1, {0x0080, 0});
  b.run_for(30ms);
  EXPECT_FALSE(bit(word(b.seen_with_id(883).back().frame), status_bits::kWarning));
  if (row.code != 0) {
    EXPECT_EQ(b.drive(0).state(), drivecom::State::start_up_inhibit);
  }
}

INSTANTIATE_TEST_SUITE_P(Section61, Cda3000ErrorResponse, ::testing::ValuesIn(kResponseRows),
                         [](const ::testing::TestParamInfo<ResponseRow>& p) { return std::string(p.param.name); });

// 6.1 "for each error": each error of table 5.9 has its own parameter, all at the default of 6.1
// (power stage off) from the factory; setting one changes no other.
TEST(Cda3000ErrorResponses, EachErrorOfTable59HasItsOwnParameter) {
  std::vector<std::uint16_t> seen;
  for (const ErrorInfo& e : kErrorTable) {
    const auto p = response_parameter(e.number);
    ASSERT_TRUE(p.has_value()) << e.name;
    EXPECT_EQ(find_parameter(*p)->factory, 3) << e.name;
    EXPECT_EQ(find_choice(*find_parameter(*p), "PWOFF")->code, 3U);
    EXPECT_EQ(find_choice(*find_parameter(*p), "WRN")->code, 0U);
    for (const auto s : seen) EXPECT_NE(s, *p);
    seen.push_back(*p);
  }
  EXPECT_FALSE(response_parameter(7).has_value());
  DeviceConfig dc = commissioned(1);
  dc.saved.emplace_back(kRpls, 0);  // E-PLS: WRN
  Cda3000 d(dc);
  d.power_on(Time{0});
  ASSERT_TRUE(d.inject_fault(kErrorPls, Time{0} + 1ms));
  EXPECT_EQ(d.state(), drivecom::State::start_up_inhibit);
  EXPECT_FALSE(d.fault().has_value());
  EXPECT_TRUE(d.warning());
  ASSERT_TRUE(d.inject_fault(kErrorPar, Time{0} + 2ms));  // E-PAR keeps the default
  EXPECT_EQ(d.state(), drivecom::State::fault);
}

// The watchdog's reaction is 525-ROP2 (6.1, D15: the watchdog reports E-OP2 at 172), read when it
// runs out: written over the bus while the drive runs, it takes effect at the next trip.
TEST(Cda3000ErrorResponses, WatchdogReactionIsParameter525WrittenOverTheBus) {
  Master m;
  Bus<Master> b(m);
  DeviceConfig dc = fast_status();
  dc.saved.emplace_back(kCawdg, 50);
  b.add(dc);
  EXPECT_EQ(*b.drive(0).value(kRop2), 3U);  // factory: the power stage off (D15)
  m.system_start();
  b.run_for(5ms);
  ASSERT_EQ(finish(b, m, write(1, kRop2, 0)).kind, OutcomeKind::done);  // WRN
  const auto ref = *wire_from_hz(ValueWidth::int32q16, 20.0);
  m.send_control(1, {0x0006, ref});
  b.run_for(10ms);
  for (int i = 0; i < 50; ++i) {
    m.send_control(1, {0x000F, ref});
    b.run_for(30ms);
  }
  ASSERT_EQ(b.drive(0).state(), drivecom::State::enabled);
  b.run_for(100ms);  // no control telegram: 574-CAWDG runs out
  const auto errors = b.seen_with_id(443);
  ASSERT_EQ(errors.size(), 1U);
  EXPECT_EQ(bytes(errors[0].frame), (Bytes{kErrorOp2, kLocationOp2_172, 0}));
  EXPECT_EQ(b.drive(0).state(), drivecom::State::enabled);
  EXPECT_TRUE(bit(word(b.seen_with_id(883).back().frame), status_bits::kWarning));
  // The face's option is the same parameter, stored as a commissioning tool saves it.
  CanlustFaceOptions o;
  o.watchdog_reaction = ErrorReaction::stop;
  EXPECT_EQ(*bus_face().make(o)->value(kRop2), 1U);
}

// ---- 6.3: parameterizable warnings ----------------------------------------------------------

class Cda3000Warning : public ::testing::TestWithParam<WarningInfo> {};

// Each warning of 6.3 by its mask: 577-CAWRN shows it, status bit 7 reports it while 576-CAWMK
// has its bit; the error reset bit deletes it. The drive runs on (a warning, not an error).
TEST_P(Cda3000Warning, ShowsIn577AndInStatusBit7AsTheMask576Selects) {
  const WarningInfo w = GetParam();
  Master m;
  Bus<Master> b(m);
  b.add(fast_status());
  run_up(b, m);
  EXPECT_EQ(finish(b, m, read(1, kCawrn)).value, 0U);
  EXPECT_EQ(finish(b, m, read(1, kCawmk)).value, 0xFFFFU);  // factory: every warning reported
  // Through the face, as a scenario or a control line raises it: by name or by mask.
  char hex[16];
  std::snprintf(hex, sizeof hex, "%04XH", static_cast<unsigned>(w.mask));
  ASSERT_NE(find_warning(w.name), nullptr);
  EXPECT_EQ(find_warning(w.name)->mask, w.mask);
  ASSERT_NE(find_warning(hex), nullptr);
  EXPECT_EQ(find_warning(hex)->mask, w.mask);
  ASSERT_TRUE(b.drive(0).raise_warning(w.mask, b.now()));
  b.run_for(30ms);
  EXPECT_EQ(finish(b, m, read(1, kCawrn)).value, w.mask);
  EXPECT_TRUE(bit(word(b.seen_with_id(883).back().frame), status_bits::kWarning));
  EXPECT_EQ(b.drive(0).state(), drivecom::State::enabled);
  // Masked off: still present in 577, no longer reported on the CAN.
  ASSERT_EQ(finish(b, m, write(1, kCawmk, 0xFFFFU & ~static_cast<std::uint32_t>(w.mask))).kind, OutcomeKind::done);
  b.run_for(30ms);
  EXPECT_EQ(finish(b, m, read(1, kCawrn)).value, w.mask);
  EXPECT_FALSE(bit(word(b.seen_with_id(883).back().frame), status_bits::kWarning));
  ASSERT_EQ(finish(b, m, write(1, kCawmk, w.mask)).kind, OutcomeKind::done);
  b.run_for(30ms);
  EXPECT_TRUE(bit(word(b.seen_with_id(883).back().frame), status_bits::kWarning));
  // 6.5: the error reset bit deletes it.
  const auto ref = *wire_from_hz(ValueWidth::int32q16, 20.0);
  m.send_control(1, {0x008F, ref});
  b.run_for(30ms);
  EXPECT_EQ(finish(b, m, read(1, kCawrn)).value, 0U);
  EXPECT_FALSE(bit(word(b.seen_with_id(883).back().frame), status_bits::kWarning));
}

INSTANTIATE_TEST_SUITE_P(Section63, Cda3000Warning, ::testing::ValuesIn(kWarnings),
                         [](const ::testing::TestParamInfo<WarningInfo>& p) {
                           char b[16];
                           std::snprintf(b, sizeof b, "Mask%04X", static_cast<unsigned>(p.param.mask));
                           return std::string(b);
                         });

// 6.3 0004H "I2t integrator of device is active": it integrates while the power stage drives a
// load above the rated torque, and the warning goes when the load does (CAN-E17).
TEST(Cda3000Warnings, I2tFollowsALoadAboveTheRatedTorque) {
  Master m;
  Bus<Master> b(m);
  b.add(fast_status());
  run_up(b, m);
  b.drive(0).set_load(150.0, b.now());
  b.run_for(30ms);
  EXPECT_EQ(b.drive(0).warnings(), kWarningI2t);
  EXPECT_TRUE(bit(word(b.seen_with_id(883).back().frame), status_bits::kWarning));
  b.drive(0).set_load(80.0, b.now());
  b.run_for(30ms);
  EXPECT_EQ(b.drive(0).warnings(), 0U);
  EXPECT_FALSE(bit(word(b.seen_with_id(883).back().frame), status_bits::kWarning));
  // No power stage, no current: a load alone raises nothing.
  Cda3000 d(commissioned(1));
  d.power_on(Time{0});
  d.set_load(200.0, Time{0});
  EXPECT_EQ(d.warnings(), 0U);
}

// EasyDrive (CACNF 4) reports the same warnings in its bit 7 (D26), and System Start -> Stop
// acknowledges them (6.5).
TEST(Cda3000Warnings, EasyDriveBit7AndSystemStopAcknowledges) {
  Master m;
  Bus<Master> b(m);
  DeviceConfig dc = commissioned(1, 4);
  dc.saved.emplace_back(kCascy, 20);
  b.add(dc);
  m.system_start();
  b.run_for(30ms);
  ASSERT_TRUE(b.drive(0).raise_warning(kWarningHeatSink, b.now()));
  b.run_for(30ms);
  EXPECT_TRUE(bit(word(b.seen_with_id(883).back().frame), easydrive::status::kWarning));
  m.system_stop();
  b.run_for(30ms);
  EXPECT_EQ(b.drive(0).warnings(), 0U);
  EXPECT_FALSE(bit(word(b.seen_with_id(883).back().frame), easydrive::status::kWarning));
}

// The face takes the warnings by name and mask beside table 5.9's errors, and says what it did.
TEST(Cda3000Warnings, FaceRaisesAWarningAndSaysWhetherTheCanReportsIt) {
  const CanlustFace& face = bus_face();
  using K = CanlustEvent::Kind;
  auto d = face.make({});
  d->power_on(Time{0});
  const CanlustEventResult r = d->apply({K::fault, "W-TM", 0.0, "", false}, Time{0} + 1ms);
  EXPECT_TRUE(r.ok) << r.text;
  EXPECT_EQ(r.text, "0008H W-TM (motor temperature above 502-WLTM), warning, status bit 7");
  EXPECT_EQ(*d->value(kCawrn), 0x0008U);
  EXPECT_EQ(d->state(), drivecom::State::start_up_inhibit);
  EXPECT_TRUE(face.check_event({K::fault, "0010h", 0.0, "", false}).empty());
}

}  // namespace
}  // namespace ibs::devices::cda3000
