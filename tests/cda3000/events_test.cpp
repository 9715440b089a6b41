// Plant and fault events of the emulated CDA3000 (issue 24; docs/canlust.md D34-D36), on the
// virtual bus against the core's master: a device fault with each cause of the CANLust manual's table 5.9
// shows in the error telegram (441 + 2 x address), in the status telegram (FAULT) and in 95-ERR1
// read over the parameter channel; the load makes the motor slip; ENPO blocks the power stage; the
// face takes the causes by name and number and refuses the others.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

// CDA 1 enabled at 20 Hz by the core's master: control 663, status 883 every 20 ms.
void run_up(Bus<Master>& b, Master& m) {
  m.system_start();
  b.run_for(5ms);
  const auto ref = *wire_from_hz(ValueWidth::int32q16, 20.0);
  m.send_control(1, {0x0006, ref});
  b.run_for(10ms);
  m.send_control(1, {0x000F, ref});
  b.run_for(1500ms);
}

std::uint32_t read_value(Bus<Master>& b, Master& m, std::uint16_t parameter) {
  const auto id = m.parameters().submit(read(1, parameter)).id;
  EXPECT_TRUE(b.run_until_true([&] { return m.parameters().poll(id).state == RequestState::done; }, 2s));
  const auto p = m.parameters().poll(id);
  EXPECT_TRUE(p.outcome != nullptr && p.outcome->kind == OutcomeKind::done);
  return p.outcome != nullptr ? p.outcome->value : 0xFFFFFFFFU;
}

class Cda3000DeviceFault : public ::testing::TestWithParam<ErrorInfo> {};

// CANLust manual, table 5.9 (6.2) row by row: the error number in byte 0 of the error telegram and of
// 95-ERR1 (ERR_STRUC, 4.1.1), the default response of 6.1 (power stage off: FAULT at once,
// reaction 3 in byte 2), FAULT in the next status telegram; the error reset bit acknowledges it.
TEST_P(Cda3000DeviceFault, ShowsInErrorTelegramStatusAndErr1) {
  const ErrorInfo e = GetParam();
  Master m;
  Bus<Master> b(m);
  DeviceConfig dc = commissioned(1);
  dc.saved.emplace_back(kCascy, 20);
  b.add(dc);
  run_up(b, m);
  ASSERT_EQ(b.drive(0).state(), drivecom::State::enabled);
  EXPECT_EQ(read_value(b, m, kErr1), 0U);  // no error yet
  const Time at = b.now();
  ASSERT_TRUE(b.drive(0).inject_fault(e.number, at));
  b.run_for(30ms);
  const auto errors = b.seen_with_id(443);
  ASSERT_EQ(errors.size(), 1U);
  EXPECT_EQ(bytes(errors[0].frame), (Bytes{e.number, 0, static_cast<std::uint8_t>(ErrorReaction::disable_power)}));
  const auto status = b.seen_with_id(883, at);
  ASSERT_FALSE(status.empty());
  EXPECT_LE(status[0].start, at + 21ms);
  EXPECT_EQ(drivecom::decode_state(word(status[0].frame)), drivecom::State::fault) << explain_status_word(word(status[0].frame));
  const std::uint32_t err1 = read_value(b, m, kErr1);
  EXPECT_EQ(err_struc_from_wire(err1).number, e.number);
  EXPECT_EQ(err_struc_from_wire(err1).location, 0U);
  EXPECT_EQ(format_value(*find_parameter(kErr1), err1),
            std::to_string(e.number) + " " + std::string(e.name) + " at location 0, 0 h");
  // 6.5: the error reset bit acknowledges; 95-ERR1 keeps the last error.
  m.send_control(1, {0x0000, 0});
  b.run_for(10ms);
  m.send_control(1, {0x0080, 0});
  b.run_for(10ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::start_up_inhibit);
  EXPECT_EQ(err_struc_from_wire(read_value(b, m, kErr1)).number, e.number);
}

INSTANTIATE_TEST_SUITE_P(Table59, Cda3000DeviceFault, ::testing::ValuesIn(kErrorTable),
                         [](const ::testing::TestParamInfo<ErrorInfo>& p) {
                           std::string n(p.param.name);
                           n.erase(std::remove(n.begin(), n.end(), '-'), n.end());
                           return n;
                         });

// D34: the operating hours of 95-ERR1 count from the first power-on (4.1.1's ERR_STRUC example:
// E-OP2 at 172 after 85 h = 10 AC 55 00 is the layout).
TEST(Cda3000Events, Err1CountsOperatingHoursFromTheFirstPowerOn) {
  Cda3000 d(commissioned(1));
  d.power_on(Time{0});
  ASSERT_TRUE(d.inject_fault(kErrorOti, Time{0} + std::chrono::hours(85) + 20min));
  EXPECT_EQ(*d.value(kErr1), 0x00550008U);
  EXPECT_FALSE(d.inject_fault(7, Time{0}));  // not a number of table 5.9
  d.power_off();
  EXPECT_FALSE(d.inject_fault(kErrorOti, Time{0}));  // mains off: nothing to report
}

// D35: 100 % load makes the motor slip by the rated 3 Hz; the reference is no longer reached
// (status bit 10); without load it is.
TEST(Cda3000Events, LoadTorqueMakesTheMotorSlip) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  run_up(b, m);
  EXPECT_NEAR(b.drive(0).actual_hz(b.now()), 20.0, 0.05);
  b.drive(0).set_load(100.0, b.now());
  b.run_for(1500ms);
  EXPECT_NEAR(b.drive(0).actual_hz(b.now()), 17.0, 0.05);
  EXPECT_EQ(read_value(b, m, kReff), 0x00140000U);  // the reference is still 20 Hz
  const auto last = b.seen_with_id(883).back();
  EXPECT_FALSE(bit(word(last.frame), status_bits::kReferenceReached));
  b.drive(0).set_load(0.0, b.now());
  b.run_for(1500ms);
  EXPECT_NEAR(b.drive(0).actual_hz(b.now()), 20.0, 0.05);
  EXPECT_TRUE(bit(word(b.seen_with_id(883).back().frame), status_bits::kReferenceReached));
}

// 2.3 / 3.1 / 7.1.2 step 6 (D36): without ENPO the power stage cannot run: START-UP INHIBIT, the
// motor coasts; with ENPO again the master walks the machine up as at the start.
TEST(Cda3000Events, EnpoLowBlocksThePowerStage) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  run_up(b, m);
  ASSERT_EQ(b.drive(0).state(), drivecom::State::enabled);
  b.drive(0).set_input(Input::enpo, false, b.now());
  EXPECT_EQ(b.drive(0).state(), drivecom::State::start_up_inhibit);
  const auto ref = *wire_from_hz(ValueWidth::int32q16, 20.0);
  m.send_control(1, {0x0006, ref});
  b.run_for(100ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::start_up_inhibit);  // still blocked
  b.drive(0).set_input(Input::enpo, true, b.now());
  m.send_control(1, {0x0006, ref});
  b.run_for(10ms);
  m.send_control(1, {0x000F, ref});
  b.run_for(10ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::enabled);
  // ISD00 has no function in the seed: its level is kept, nothing else changes.
  b.drive(0).set_input(Input::isd00, true, b.now());
  EXPECT_TRUE(b.drive(0).input(Input::isd00));
  EXPECT_EQ(b.drive(0).state(), drivecom::State::enabled);
}

// CANLust manual 5.1 "Controller enable (ENPO)": "The drive units require an additional hardware
// enable via control terminal X2/8 ENPO for control over the CAN bus. This control signal is
// high-active. When this control signal is removed the motor runs out freely." Row by row: with
// ENPO low from the power-on, no command of the bus enables the drive (DRIVECOM and EasyDrive);
// taken away from a running motor, it coasts (D28: 2 s, not the 200 ms of a stop) (CAN-E14, D36).
struct EnpoRow {
  const char* name;
  std::uint8_t cacnf;
  ibs::Word first;   // the commands the master sends with ENPO low
  ibs::Word second;
};
class Cda3000Enpo : public ::testing::TestWithParam<EnpoRow> {};

TEST_P(Cda3000Enpo, WithoutEnpoTheBusCannotEnableTheDrive) {
  const EnpoRow row = GetParam();
  Master m;
  Bus<Master> b(m);
  DeviceConfig dc = commissioned(1, row.cacnf);
  dc.saved.emplace_back(kCascy, 20);
  b.add(dc);
  b.drive(0).set_input(Input::enpo, false, Time{0});
  b.run_for(1ms);
  m.system_start();
  b.run_for(5ms);
  const auto ref = *wire_from_hz(ValueWidth::int32q16, 20.0);
  m.send_control(1, {row.first, ref});
  b.run_for(20ms);
  m.send_control(1, {row.second, ref});
  b.run_for(500ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::start_up_inhibit);
  EXPECT_EQ(b.drive(0).actual_hz(b.now()), 0.0);
  // High-active: with ENPO the same commands enable it.
  b.drive(0).set_input(Input::enpo, true, b.now());
  m.send_control(1, {row.first, ref});
  b.run_for(20ms);
  m.send_control(1, {row.second, ref});
  b.run_for(1500ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::enabled);
  EXPECT_NEAR(b.drive(0).actual_hz(b.now()), 20.0, 0.1);
  // Removed: the motor runs out freely (coasting, 20 Hz x e^-0.05 after 100 ms).
  b.drive(0).set_input(Input::enpo, false, b.now());
  b.run_for(100ms);
  EXPECT_NEAR(b.drive(0).actual_hz(b.now()), 19.02, 0.05);
  EXPECT_FALSE(drivecom::power_stage_enabled(b.drive(0).state()));
}

const EnpoRow kEnpoRows[] = {
    {"Drivecom", 2, 0x0006, 0x000F},
    {"EasyDriveStr", 4, 0x0001, 0x0001},
};
INSTANTIATE_TEST_SUITE_P(Section51, Cda3000Enpo, ::testing::ValuesIn(kEnpoRows),
                         [](const ::testing::TestParamInfo<EnpoRow>& p) { return std::string(p.param.name); });

// The face (what scenarios and `emulate --control` use): the cause by name, short name or number;
// unknown causes, inputs and loads refused with what the drive takes.
TEST(Cda3000Events, FaceTakesCausesByNameOrNumberAndRefusesOthers) {
  const CanlustFace& face = bus_face();
  using K = CanlustEvent::Kind;
  for (const std::string cause : {"E-OTI", "oti", "8"}) {
    auto d = face.make({});
    d->power_on(Time{0});
    const CanlustEventResult r = d->apply({K::fault, cause, 0.0, "", false}, Time{0} + 10ms);
    EXPECT_TRUE(r.ok) << r.text;
    EXPECT_EQ(r.text, "8 E-OTI (drive unit overheating), FAULT, error telegram sent");
    EXPECT_EQ(d->state(), drivecom::State::fault);
    EXPECT_EQ(*d->value(kErr1) & 0xFFU, 8U);
  }
  EXPECT_EQ(face.check_event({K::fault, "E-XYZ", 0.0, "", false}),
            "cause 'E-XYZ': the CDA3000's errors (CANLust manual, table 5.9) are 8 E-OTI, 9 E-PLS, 10 E-PAR, 11 E-FLT, "
            "12 E-PWR, 16 E-OP2; its warnings (6.3) are 0004H W-I2T, 0008H W-TM, 0010H W-TH");
  EXPECT_EQ(face.check_event({K::input, "", 0.0, "X9", true}),
            "input 'X9': the CDA3000's terminals in the CANLust manual are ENPO (X2-8) and ISD00 (X2-9)");
  EXPECT_FALSE(face.check_event({K::load, "", 301.0, "", false}).empty());
  EXPECT_TRUE(face.check_event({K::load, "", -300.0, "", false}).empty());
  // Power cycle: back from the stored settings, the fault gone, the error kept in 95-ERR1.
  auto d = face.make({});
  d->power_on(Time{0});
  ASSERT_TRUE(d->apply({K::fault, "E-PWR", 0.0, "", false}, Time{0}).ok);
  ASSERT_TRUE(d->apply({K::power_cycle, "", 0.0, "", false}, Time{0} + 1s).ok);
  EXPECT_EQ(d->state(), drivecom::State::start_up_inhibit);
  EXPECT_EQ(*d->value(kErr1) & 0xFFU, 12U);
  ASSERT_TRUE(d->apply({K::mains_off, "", 0.0, "", false}, Time{0} + 2s).ok);
  EXPECT_FALSE(d->apply({K::fault, "E-PWR", 0.0, "", false}, Time{0} + 2s).ok);
}

}  // namespace
}  // namespace ibs::devices::cda3000
