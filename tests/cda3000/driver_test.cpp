// The master driver against emulated CDA3000 drives on the virtual bus: the logon list, System
// Start, the DRIVECOM sequencers bringing the drives to ENABLED with references in Hz, presets in
// System Stop executed by all drives together at the next Start, a late logon started again,
// the watchdog's fault reported and never reset by the driver itself, and parameter access with
// the table's checks, a queue and timeouts.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bus.hpp"
#include "ibs/canlust/errors.hpp"
#include "ibs/devices/cda3000/driver.hpp"

namespace ibs::devices::cda3000 {
namespace {

using namespace ibs::canlust;
using drivecom::State;
using drivecom::Target;
using test::Bus;
using test::commissioned;

DriverConfig config_for(std::initializer_list<Address> addresses, std::uint8_t cacnf = 2) {
  DriverConfig c;
  for (const Address a : addresses) c.drives.push_back({a, cacnf, 400.0});
  return c;
}

const Outcome* wait(Bus<Driver>& b, Driver& d, RequestId id, Duration limit = 5s) {
  b.run_until_true([&] { return d.parameters().poll(id).state == RequestState::done; }, limit);
  return d.parameters().poll(id).outcome;
}

// 5.5.4 logon list, 5.2 System Start, 5.4.2 DRIVECOM start (0006, then 000F taking 3 and 4),
// 5.5.5 references in Hz.
TEST(Cda3000Driver, LogonStartAndEnableThreeDrives) {
  Driver d(config_for({1, 2, 3}));
  Bus<Driver> b(d);
  b.add(commissioned(3), Time{10ms});
  b.add(commissioned(1), Time{20ms});
  b.add(commissioned(2), Time{30ms});
  b.run_until(Time{150ms});
  EXPECT_EQ(std::vector<Address>(d.logon_order().begin(), d.logon_order().end()), (std::vector<Address>{3, 1, 2}));
  EXPECT_TRUE(d.all_logged_on());
  EXPECT_TRUE(b.seen_with_id(663).empty());  // nothing to drive before the first status
  d.system_start(b.now());
  for (Address a = 1; a <= 3; ++a) {
    EXPECT_TRUE(d.request(a, Target::enabled, b.now()));
    EXPECT_EQ(d.set_reference_hz(a, 10.0 * a + 0.5), ReferenceError::none);
  }
  b.run_for(3s);
  for (Address a = 1; a <= 3; ++a) {
    const DriveReport r = d.drive(a);
    EXPECT_EQ(r.state, State::enabled) << drivecom::describe(r.sequencer);
    EXPECT_EQ(r.sequencer.phase, drivecom::Phase::reached);
    EXPECT_NEAR(r.actual_hz, 10.0 * a + 0.5, 0.05);
  }
  // CDA 1: SHUTDOWN until READY shows, then POWER-ON/ENABLE with 10.5 Hz = 00 80 0A 00.
  const auto c = b.seen_with_id(663);
  ASSERT_GE(c.size(), 2U);
  EXPECT_EQ(c[0].frame.data[0], 0x06);
  std::size_t i = 0;
  while (i < c.size() && c[i].frame.data[0] == 0x06) ++i;
  ASSERT_LT(i, c.size());
  EXPECT_EQ(c[i].frame.data[0], 0x0F);
  EXPECT_EQ(c[i].frame.data[2], 0x00);
  EXPECT_EQ(c[i].frame.data[3], 0x80);
  EXPECT_EQ(c[i].frame.data[4], 0x0A);
  for (; i < c.size(); ++i) EXPECT_EQ(c[i].frame.data[0], 0x0F);
  // At least one control telegram each control period once reached (574-CAWDG, D30).
  for (std::size_t k = 1; k < c.size(); ++k) EXPECT_LE(c[k].start - c[k - 1].start, 51ms);
}

TEST(Cda3000Driver, ReferencesAreCheckedAndScaledPerCacnf) {
  DriverConfig cfg = config_for({1});
  cfg.drives.push_back({2, 1, 50.0});
  Driver d(cfg);
  EXPECT_EQ(d.set_reference_hz(1, 400.5), ReferenceError::above_limit);
  EXPECT_EQ(d.set_reference_hz(2, 50.5), ReferenceError::above_limit);
  EXPECT_EQ(d.set_reference_hz(2, std::nan("")), ReferenceError::not_finite);
  EXPECT_EQ(d.set_reference_hz(3, 1.0), ReferenceError::unknown_drive);
  EXPECT_EQ(d.set_reference_hz(2, 20.4), ReferenceError::none);
  EXPECT_DOUBLE_EQ(d.drive(2).reference_hz, 20.0);  // Int16Q0: whole Hz (D25)
  EXPECT_EQ(d.set_reference_hz(1, -20.5), ReferenceError::none);
  EXPECT_DOUBLE_EQ(d.drive(1).reference_hz, -20.5);
}

// 5.2: presets sent in System Stop are stored and executed by all drives at the next Start,
// within 1 ms of each other.
TEST(Cda3000Driver, PresetsInStopRunOnAllDrivesAtStartWithin1Ms) {
  Driver d(config_for({1, 2, 3, 4}));
  Bus<Driver> b(d);
  for (std::uint8_t a = 1; a <= 4; ++a) b.add(commissioned(a), Time{std::chrono::milliseconds(5 * a)});
  b.run_until(Time{100ms});
  d.system_start(b.now());
  for (Address a = 1; a <= 4; ++a) d.request(a, Target::on, b.now());
  b.run_for(1s);
  for (std::size_t i = 0; i < 4; ++i) ASSERT_EQ(b.drive(i).state(), State::on);
  d.system_stop(b.now());
  b.run_for(20ms);
  for (Address a = 1; a <= 4; ++a) {
    d.request(a, Target::enabled, b.now());
    d.set_reference_hz(a, 5.0 * a);
  }
  b.run_for(2s);  // the stored commands wait; the sequencers' clock stands still meanwhile
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(b.drive(i).state(), State::on);
    EXPECT_EQ(b.drive(i).node()->stored_command()->word, 0x000F);
  }
  EXPECT_EQ(d.drive(1).sequencer.phase, drivecom::Phase::moving);
  d.system_start(b.now());
  b.run_for(20ms);
  Time first = Time::max();
  Time last = Time::min();
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(b.drive(i).state(), State::enabled);
    first = std::min(first, b.drive(i).state_since());
    last = std::max(last, b.drive(i).state_since());
  }
  EXPECT_LE(last - first, 1ms);
  b.run_for(1s);
  for (Address a = 1; a <= 4; ++a) EXPECT_EQ(d.drive(a).sequencer.phase, drivecom::Phase::reached);
}

// D31: a drive switched on after the System Start logs on; the driver starts it again.
TEST(Cda3000Driver, LateLogonIsStartedAgain) {
  Driver d(config_for({1, 2}));
  Bus<Driver> b(d);
  b.add(commissioned(1));
  b.add(commissioned(2), Time{1s});
  b.run_until(Time{100ms});
  d.system_start(b.now());
  d.request(1, Target::enabled, b.now());
  d.request(2, Target::enabled, b.now());
  b.run_until(Time{2s});
  EXPECT_EQ(b.seen_with_id(kIdSystem).size(), 2U);
  EXPECT_EQ(b.drive(1).system_state(), SystemState::start);
  EXPECT_EQ(d.drive(2).state, State::enabled);
  EXPECT_EQ(d.drive(1).state, State::enabled);
}

// The watchdog of a drive trips (its 574-CAWDG below the driver's control period): the error
// telegram reaches the driver, the sequencer reports the fault and sends BLOCK POWER; it never
// resets the fault by itself. A new request does.
TEST(Cda3000Driver, WatchdogFaultIsReportedAndNotResetByItself) {
  DriverConfig cfg = config_for({1});
  cfg.control_period = 100ms;
  Driver d(cfg);
  Bus<Driver> b(d);
  DeviceConfig dc = commissioned(1);
  dc.saved.emplace_back(kCawdg, 60);
  b.add(dc);
  d.system_start(b.now());
  d.request(1, Target::enabled, b.now());
  b.run_for(2s);
  const auto e = d.take_error();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->address, 1);
  EXPECT_EQ(e->error.number, kErrorOp2);
  const DriveReport r = d.drive(1);
  EXPECT_EQ(r.sequencer.phase, drivecom::Phase::failed);
  EXPECT_EQ(r.sequencer.failure, drivecom::Failure::fault);
  EXPECT_EQ(r.sequencer.command_sent, 0x0000);
  b.run_for(2s);
  EXPECT_EQ(b.drive(0).state(), State::fault);  // still: the driver did not reset it
}

TEST(Cda3000Driver, ParametersCheckedQueuedAndTimedOut) {
  Driver d(config_for({1, 2, 7}));
  Bus<Driver> b(d);
  b.add(commissioned(1));
  b.add(commissioned(2));
  // Refused before anything is sent, saying what and which limit.
  const auto too_big = d.write(1, kCawdg, 300);
  EXPECT_EQ(too_big.error, ParameterError::value);
  EXPECT_EQ(describe(too_big, kCawdg, 300), "574-CAWDG: 300 ms is above the maximum 255 ms");
  EXPECT_EQ(d.write(1, kReff, 0).error, ParameterError::read_only);
  EXPECT_EQ(d.read(1, 999).error, ParameterError::unknown_parameter);
  EXPECT_EQ(d.read(9, kDisp).error, ParameterError::unknown_drive);
  EXPECT_EQ(d.write(1, kName, 1).error, ParameterError::string_parameter);
  EXPECT_EQ(d.write_text(1, kCawdg, "x").error, ParameterError::not_a_string);
  EXPECT_EQ(d.write_text(1, kName, std::string(100, 'x')).error, ParameterError::text_too_long);
  EXPECT_TRUE(b.seen().empty() || b.seen_with_id(1103).empty());
  // Queued: several per drive, drives in parallel.
  const auto r1 = d.read(1, kDisp);
  const auto w1 = d.write(1, kCascy, 40);
  const auto s2 = d.read(2, kOptn2);
  const auto t2 = d.write_text(2, kName, "conveyor 2");
  const auto n2 = d.read(2, kName);
  const auto x7 = d.read(7, kDisp);  // configured, but no drive answers
  ASSERT_TRUE(r1 && w1 && s2 && t2 && n2 && x7);
  EXPECT_EQ(wait(b, d, r1.id)->value, 406U);
  EXPECT_EQ(wait(b, d, w1.id)->kind, OutcomeKind::done);
  EXPECT_EQ(*b.drive(0).value(kCascy), 40U);
  EXPECT_EQ(wait(b, d, s2.id)->text.view(), "LCAN");
  EXPECT_EQ(wait(b, d, t2.id)->kind, OutcomeKind::done);
  EXPECT_EQ(wait(b, d, n2.id)->text.view(), "conveyor 2");
  const Outcome* o = wait(b, d, x7.id);
  ASSERT_NE(o, nullptr);
  EXPECT_EQ(o->kind, OutcomeKind::timeout);
  EXPECT_EQ(o->finished - o->started, 250ms);
  // 150-SAVE answers after its backup time: the driver gives it a longer timeout.
  const auto save = d.write(1, kSave, 1);
  EXPECT_EQ(wait(b, d, save.id)->kind, OutcomeKind::done);
}

TEST(Cda3000Driver, BadConfigurationsNameTheDrive) {
  const auto refused = [](const DriverConfig& c) {
    try {
      Driver d(c);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(refused(config_for({1, 1})), "CDA3000 driver: drive 1: configured twice");
  EXPECT_EQ(refused(config_for({100})), "CDA3000 driver: drive 100: address above 99");
  EXPECT_EQ(refused(config_for({4}, 5)),
            "CDA3000 driver: drive 4: 492-CACNF 5 is not a layout of 4.3.2 (1..3 DRIVECOM, 4 EasyDrive)");
  DriverConfig c = config_for({1});
  c.control_period = 0ms;
  EXPECT_EQ(refused(c), "CDA3000 driver: control_period must be positive");
}

}  // namespace
}  // namespace ibs::devices::cda3000
