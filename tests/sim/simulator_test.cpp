// The cycle simulator: drives brought up and run through the master, the documented timing of
// the VF1000 parameter channel (INTERBUS manual 7.1), watchdogs and every fault kind.
#include <gtest/gtest.h>

#include "ibs/base/number_text.hpp"
#include "ibs/sim/report.hpp"

#include <algorithm>

#include "ibs/devices/mc6000/device.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/vf1000/device.hpp"
#include "ibs/sim/simulator.hpp"

namespace ibs::sim {
namespace {

using drivecom::State;

// The VF1000 emulator at ring position i (the tests below reach its keypad and reset counter).
devices::Vf1000Device& vf1000_at(Simulator& sim, std::size_t i) {
  return dynamic_cast<devices::Vf1000Device&>(sim.emulator(i));
}

DeviceConfig mc6000(const std::string& name = "mc") {
  DeviceConfig d;
  d.name = name;
  d.kind = "mc6000";
  return d;
}
DeviceConfig vf1000(const std::string& name = "vf") {
  DeviceConfig d;
  d.name = name;
  d.kind = "vf1000";
  return d;
}
TimelineEntry at(Time t, const std::string& dev, Action a, const std::string& value = "", double number = 0,
                 std::uint16_t parameter = 0, Duration duration = Duration{0}, int count = 1) {
  TimelineEntry e;
  e.at = t;
  e.device = dev;
  e.action = a;
  e.value = value;
  e.number = number;
  e.parameter = parameter;
  e.duration = duration;
  e.count = count;
  return e;
}

const StateRecord* find_event(const DeviceReport& r, const std::string& what) {
  for (const auto& s : r.states) {
    if (s.what.find(what) != std::string::npos) return &s;
  }
  return nullptr;
}

TEST(Simulator, BringsBothDrivesUpRunsThemAndStopsThem) {
  Scenario s;
  s.duration = 6s;
  s.devices = {mc6000(), vf1000()};
  s.timeline = {at(0s, "mc", Action::state, "enabled"),     at(0s, "vf", Action::state, "enabled"),
                at(200ms, "mc", Action::speed, "", 2500.25), at(200ms, "vf", Action::frequency, "", 50.0),
                at(4s, "mc", Action::speed, "", 0.0),        at(4s, "vf", Action::frequency, "", 0.0),
                at(5s, "mc", Action::state, "ready"),        at(5s, "vf", Action::state, "ready")};
  Simulator sim(s);
  sim.run_until(3500ms);
  EXPECT_EQ(sim.device_state(0), State::enabled);
  EXPECT_EQ(sim.device_state(1), State::enabled);
  EXPECT_NEAR(sim.device_actual(0), 2500.25, 1e-3);
  EXPECT_DOUBLE_EQ(sim.device_actual(1), 50.0);
  sim.run();
  const Summary& r = sim.summary();
  EXPECT_EQ(r.devices[0].final_state, "READY");
  EXPECT_EQ(r.devices[1].final_state, "READY");
  EXPECT_NEAR(r.devices[0].final_actual, 0.0, 0.5);
  EXPECT_DOUBLE_EQ(r.devices[1].final_actual, 0.0);
  const auto* mc_reached = find_event(r.devices[0], "reference 2500.25 rpm reached");
  ASSERT_NE(mc_reached, nullptr);
  EXPECT_LT(mc_reached->at, 700ms);
  const auto* vf_reached = find_event(r.devices[1], "reference 50 Hz reached");
  ASSERT_NE(vf_reached, nullptr);
  EXPECT_GT(vf_reached->at, 2600ms);  // 50 Hz at 20 Hz/s from 200 ms
  EXPECT_LT(vf_reached->at, 2800ms);
  // The default ring: 14 bytes, two remote devices -> 0.726 ms (docs/bus.md).
  EXPECT_EQ(r.cycle_time, 726us);
  EXPECT_EQ(r.cycles, r.valid_cycles);
  EXPECT_EQ(r.cycles, static_cast<std::uint64_t>(6s / 726us));
}

// Numbers a person reads (issue 27.9): the summary's values in fixed decimals by unit, never an
// exponent or a negative zero, whatever the plant's last step left (8.7e-09 rpm, -0.0984 rpm).
TEST(NumberText, FixedDecimalsByUnitWithoutExponentOrNegativeZero) {
  EXPECT_EQ(quantity_text(8.73332e-09, "rpm"), "0.00");
  EXPECT_EQ(quantity_text(-0.09841918945, "rpm"), "-0.10");
  EXPECT_EQ(quantity_text(-0.0049, "Hz"), "0.00");
  EXPECT_EQ(quantity_text(994.5975647, "rpm"), "994.60");
  EXPECT_EQ(quantity_text(2500.25, "rpm"), "2500.25");
  EXPECT_EQ(quantity_text(31.98000000000012, "Hz"), "31.98");
  EXPECT_EQ(quantity_text(12.345, "%"), "12.3");
  EXPECT_EQ(quantity_text(1.0 / 3.0, "Nm"), "0.333");
  EXPECT_EQ(fixed_text(1e300, 0).find('e'), std::string::npos);
}

TEST(NumberText, TheRunSummaryPrintsItsValuesThatWay) {
  Scenario s;
  s.duration = 6s;
  s.devices = {mc6000(), vf1000()};
  s.timeline = {at(0s, "mc", Action::state, "enabled"), at(0s, "vf", Action::state, "enabled"),
                at(200ms, "mc", Action::speed, "", 1000.0), at(200ms, "vf", Action::frequency, "", 25.0),
                at(3s, "mc", Action::speed, "", 0.0), at(3s, "vf", Action::frequency, "", 0.0)};
  Simulator sim(s);
  sim.run();
  const std::string text = format_text(sim.summary());
  EXPECT_EQ(text.find("e-"), std::string::npos) << text;
  EXPECT_EQ(text.find("-0.00"), std::string::npos) << text;
  EXPECT_NE(text.find("final: ENABLED, reference 0.00 rpm, actual 0.00 rpm"), std::string::npos) << text;
  EXPECT_NE(text.find("final: ENABLED, reference 0.00 Hz, actual 0.00 Hz"), std::string::npos) << text;
  EXPECT_NE(text.find("reference 1000 rpm reached (actual "), std::string::npos) << text;
}

// INTERBUS manual 7.1, "Without KEYPAD, motor stopped": value inquiry 100 ms, value transfer 124 ms
// (RAM or unchanged EEPROM), 250 ms (EEPROM value changed), description 490 ms; within 10 %.
TEST(Simulator, Vf1000ChannelTransferTimesOfSection71) {
  for (const Duration phase : {0ms, 3ms, 7ms}) {
    Scenario s;
    s.duration = 4s;
    DeviceConfig v = vf1000();
    v.phase = phase;
    s.devices = {v};
    s.timeline = {at(0s, "vf", Action::read, "", 0, 85),          // clears the power-on bit
                  at(500ms, "vf", Action::read, "", 0, 22),       // inquiry
                  at(1000ms, "vf", Action::write, "", 1000, 22),  // transfer, EEPROM unchanged
                  at(1500ms, "vf", Action::write, "", 0, 905),    // transfer to a RAM variable
                  at(2000ms, "vf", Action::describe, "", 0, 45),  // description
                  at(3000ms, "vf", Action::write, "", 900, 22)};  // EEPROM value changes
    Simulator sim(s);
    sim.run();
    const auto& t = sim.summary().transactions;
    ASSERT_EQ(t.size(), 6U);
    auto ms = [&](std::size_t i) { return to_ms(*t[i].finished - t[i].submitted); };
    for (const auto& x : t) ASSERT_TRUE(x.finished.has_value()) << x.result;
    EXPECT_EQ(t[1].kind, devices::ParamKind::value) << t[1].result;
    EXPECT_EQ(t[1].result_value, 1000);
    EXPECT_EQ(t[2].kind, devices::ParamKind::written) << t[2].result;
    EXPECT_EQ(t[3].kind, devices::ParamKind::written) << t[3].result;
    EXPECT_EQ(t[4].kind, devices::ParamKind::description) << t[4].result;
    EXPECT_EQ(t[5].kind, devices::ParamKind::written) << t[5].result;
    // Row "without KEYPAD, motor stopped": 124 ms, (250) when an EEPROM value changes.
    EXPECT_NEAR(ms(1), 100.0, 10.0) << "phase " << phase.count();
    EXPECT_NEAR(ms(2), 124.0, 12.4) << "phase " << phase.count();
    EXPECT_NEAR(ms(3), 124.0, 12.4) << "phase " << phase.count();
    EXPECT_NEAR(ms(4), 490.0, 49.0);
    EXPECT_NEAR(ms(5), 250.0, 25.0);
  }
}

TEST(Simulator, Vf1000ChannelTransferTimesOfSection71MotorRunningAndKeypad) {
  // INTERBUS manual 7.1: "with KEYPAD, motor running" 192 / 115 / 490 ms, "without KEYPAD, motor
  // running" 131 / 100 / 490 ms (value transfer / value inquiry / description); each within 10 %.
  struct Row {
    bool keypad;
    double transfer, inquiry, description;
  };
  for (const Row row : {Row{false, 131, 100, 490}, Row{true, 192, 115, 490}}) {
    for (const Duration phase : {0ms, 3ms, 7ms}) {
      Scenario s;
      s.duration = 4s;
      DeviceConfig v = vf1000();
      v.phase = phase;
      v.settings.set_boolean("keypad", row.keypad);  // the scenario key `keypad`
      s.devices = {v};
      s.timeline = {at(0s, "vf", Action::read, "", 0, 85),  // clears the power-on bit
                    at(0s, "vf", Action::state, "enabled"), at(0s, "vf", Action::frequency, "", 20),
                    at(1000ms, "vf", Action::read, "", 0, 22),       // inquiry
                    at(1500ms, "vf", Action::write, "", 0, 905),     // transfer to a RAM variable
                    at(2000ms, "vf", Action::describe, "", 0, 45)};  // description
      Simulator sim(s);
      ASSERT_EQ(vf1000_at(sim, 0).keypad(), row.keypad);
      sim.run_until(999ms);
      ASSERT_EQ(sim.device_state(0), State::enabled);
      ASSERT_NE(vf1000_at(sim, 0).frequency_hz(), 0.0) << "the motor runs";
      sim.run();
      const auto& t = sim.summary().transactions;
      ASSERT_EQ(t.size(), 4U);
      for (const auto& x : t) ASSERT_TRUE(x.finished.has_value()) << x.result;
      auto ms = [&](std::size_t i) { return to_ms(*t[i].finished - t[i].submitted); };
      EXPECT_EQ(t[1].kind, devices::ParamKind::value) << t[1].result;
      EXPECT_EQ(t[2].kind, devices::ParamKind::written) << t[2].result;
      EXPECT_EQ(t[3].kind, devices::ParamKind::description) << t[3].result;
      const std::string where = std::string(row.keypad ? "KEYPAD" : "no KEYPAD") + ", phase " +
                                std::to_string(phase.count() / 1000000) + " ms";
      EXPECT_NEAR(ms(1), row.inquiry, row.inquiry * 0.1) << where;
      EXPECT_NEAR(ms(2), row.transfer, row.transfer * 0.1) << where;
      EXPECT_NEAR(ms(3), row.description, row.description * 0.1) << where;
    }
  }
}

TEST(Simulator, CorruptedCyclesDeliverNothingAndTheBusRecovers) {
  Scenario s;
  s.duration = 1s;
  s.devices = {mc6000()};
  s.timeline = {at(0s, "mc", Action::state, "enabled"), at(500ms, "", Action::fault_corrupt, "", 0, 0, {}, 3)};
  Simulator sim(s);
  sim.run();
  const Summary& r = sim.summary();
  EXPECT_EQ(r.cycles - r.valid_cycles, 3U + 5U);  // 3 corrupted + 5 recovery cycles
  ASSERT_EQ(r.faults.size(), 1U);
  EXPECT_EQ(r.faults[0].kind, "corrupt");
  EXPECT_EQ(sim.device_state(0), State::enabled);  // 8 cycles (5.8 ms) are no reason to stop
}

TEST(Simulator, Mc6000BusWatchdogTripsWithinOneSampleOfItsTime) {
  Scenario s;
  s.duration = 2s;
  DeviceConfig m = mc6000();
  m.watchdog_ms = 20;  // 409-BUTWD = 20 ms
  s.devices = {m};
  s.timeline = {at(0s, "mc", Action::state, "enabled"),
                at(1000ms, "", Action::fault_corrupt, "", 0, 0, {}, 40)};  // ~29 ms without data
  Simulator sim(s);
  sim.run_until(999ms);
  ASSERT_EQ(sim.device_state(0), State::enabled);
  const Time last_valid = sim.now();
  // Find the moment the servo faults.
  Time tripped{0};
  for (Time t = 1000ms; t < 1100ms; t += 100us) {
    sim.run_until(t);
    if (sim.emulator(0).error_number()) {
      tripped = t;
      break;
    }
  }
  ASSERT_GT(tripped, 0ns);
  EXPECT_EQ(*sim.emulator(0).error_number(), 16);
  // The last valid cycle was at most one cycle before 1000 ms; the watchdog runs out 20 ms after
  // it and the servo notices at its next 1 ms sample.
  EXPECT_GE(tripped, last_valid + 20ms);
  EXPECT_LE(tripped, last_valid + 20ms + 1ms + 726us + 100us);
  sim.run();
  EXPECT_EQ(sim.device_state(0), State::fault);
  bool recorded = false;
  for (const auto& f : sim.summary().faults) recorded = recorded || f.kind == "watchdog";
  EXPECT_TRUE(recorded);
}

TEST(Simulator, Vf1000WatchdogReactionsOf907) {
  // 906-IB-WD = 65 -> 100 ms (50 ms steps); 907-IBCOD 1: fault E-IBS, 2: BLOCK POWER,
  // 3: EMERGENCY STOP (braking along 36-RSTOP); 0: no reaction.
  const std::array<State, 4> expected{State::enabled, State::fault, State::start_up_inhibit,
                                      State::emergency_stop_active};
  for (int reaction = 0; reaction <= 3; ++reaction) {
    Scenario s;
    s.duration = 1500ms;
    DeviceConfig v = vf1000();
    v.watchdog_ms = 65;
    v.watchdog_reaction = reaction;
    s.devices = {v};
    s.timeline = {at(0s, "vf", Action::state, "enabled"), at(100ms, "vf", Action::frequency, "", 40.0),
                  at(1000ms, "vf", Action::fault_lost, "", 0, 0, 300ms)};
    Simulator sim(s);
    sim.run_until(999ms);
    ASSERT_EQ(sim.device_state(0), State::enabled);
    const Time last_valid = sim.now();
    // Step through the loss in 0.1 ms steps and note when the inverter reacts.
    Time reacted{0};
    for (Time t = 1000ms; t < 1200ms && reacted == 0ns; t += 100us) {
      sim.run_until(t);
      if (sim.emulator(0).watchdog_tripped()) reacted = t;
    }
    ASSERT_GT(reacted, 0ns) << "reaction " << reaction;
    // Not before 100 ms without data, and within one 8.2 ms sample after it.
    EXPECT_GT(reacted, last_valid + 100ms) << "reaction " << reaction;
    EXPECT_LE(reacted, last_valid + 100ms + ibs::devices::vf1000::kSamplePeriod + 726us + 100us) << "reaction " << reaction;
    EXPECT_EQ(sim.device_state(0), expected[static_cast<std::size_t>(reaction)]) << "reaction " << reaction;
    if (reaction == 1) {
      EXPECT_EQ(sim.emulator(0).error_number(), 12);
    }
  }
}

TEST(Simulator, PowerCycleReinitialisesTheVf1000AndTheMasterBringsItBack) {
  Scenario s;
  s.duration = 7s;
  s.devices = {vf1000()};
  s.timeline = {at(0s, "vf", Action::state, "enabled"), at(500ms, "vf", Action::fault_power_cycle),
                at(6s, "vf", Action::state, "enabled")};
  Simulator sim(s);
  sim.run_until(600ms);
  EXPECT_EQ(sim.device_state(0), State::not_ready);
  EXPECT_TRUE(sim.emulator(0).module_error(sim.now()));
  sim.run_until(4600ms);
  EXPECT_FALSE(sim.emulator(0).module_error(sim.now()));
  sim.run();
  EXPECT_EQ(sim.device_state(0), State::enabled);
  const auto& f = sim.summary().faults;
  ASSERT_FALSE(f.empty());
  EXPECT_EQ(f[0].kind, "power-cycle");
}

// Issue 9, defect 2: a VF1000 switched off and on while ENABLED shows NOT READY and then
// START-UP INHIBIT; the master must stop commanding POWER-ON/ENABLE at once, send BLOCK POWER and
// say in the summary that its request failed.
TEST(Simulator, PowerCycleWhileEnabledEndsTheRequestWithBlockPowerAndIsReported) {
  struct Words : Observer {
    void on_cycle(Time, bool, const interbus::ProcessImage&) override {}
    void on_sample(Time at, std::size_t, std::span<const Word> m2s, std::span<const Word> s2m) override {
      if (at > 500ms) seen.push_back({m2s[0], s2m[0]});
    }
    std::vector<std::pair<Word, Word>> seen;  // control word the drive read, status it showed
  } words;
  Scenario s;
  s.duration = 6s;
  s.devices = {vf1000()};
  s.timeline = {at(0s, "vf", Action::state, "enabled"), at(500ms, "vf", Action::fault_power_cycle)};
  Simulator sim(s);
  sim.add_observer(&words);
  sim.run_until(450ms);
  ASSERT_EQ(sim.device_state(0), State::enabled);
  sim.run();
  ASSERT_GT(words.seen.size(), 500U);
  std::size_t block_power = 0;
  for (std::size_t i = 0; i < words.seen.size(); ++i) {
    const auto [control, status] = words.seen[i];
    const auto cmd = drivecom::decode_command(control);
    // After the first few samples (the master sees the module error one cycle later and the
    // drive reads the new word in its next sample) nothing but BLOCK POWER with bit 7 low.
    if (i >= 4) {
      EXPECT_EQ(cmd, drivecom::Command::block_power) << "sample " << i << ": " << std::hex << control;
      EXPECT_EQ(control & 0x0080U, 0U);
      ++block_power;
    }
    const auto st = drivecom::decode_state(status);
    if (i >= 2 && (st == State::start_up_inhibit || st == State::not_ready)) {
      EXPECT_NE(cmd, drivecom::Command::enable) << "ENABLE while the drive shows " << drivecom::to_string(*st);
    }
  }
  EXPECT_GT(block_power, 500U);
  EXPECT_EQ(sim.device_state(0), State::start_up_inhibit);
  const auto& failures = sim.summary().devices[0].failures;
  ASSERT_EQ(failures.size(), 1U);
  EXPECT_EQ(failures[0].failure, "left target");
  EXPECT_GE(failures[0].at, 500ms);
  EXPECT_LT(failures[0].at, 520ms);
  EXPECT_NE(failures[0].what.find("left ENABLED"), std::string::npos) << failures[0].what;
  EXPECT_NE(find_event(sim.summary().devices[0], "request failed (left target)"), nullptr);
}

// LUSTBUS manual 11.4: after 80-SLOAD = -1 "the servocontroller will be secured against being engaged
// until the download has ended" (found missing by the fault campaign, docs/robustness.md, C).
// And 4-PROG = 1 is confirmed after up to 10 s: the driver waits for it.
TEST(Simulator, AnMc6000DownloadLocksEngagingAndFactoryDefaultsGetTheirTime) {
  Scenario s;
  s.duration = 16s;
  s.devices = {mc6000()};
  s.timeline = {at(0s, "mc", Action::read, "", 0, 85),
                at(200ms, "mc", Action::write, "", -1, 80),
                at(500ms, "mc", Action::state, "enabled"),
                at(1000ms, "mc", Action::write, "", -2, 80),
                at(1800ms, "mc", Action::read, "", 0, 80),
                at(2000ms, "mc", Action::state, "enabled"),
                at(3000ms, "mc", Action::state, "start-up-inhibit"),
                at(3500ms, "mc", Action::write, "", 1, 4)};
  Simulator sim(s);
  sim.run_until(600ms);
  EXPECT_EQ(sim.device_state(0), State::on) << "ENABLE during the download stops in ON";
  sim.run_until(950ms);
  const auto& report = sim.driver(0).sequencer().report();
  EXPECT_EQ(report.failure, drivecom::Failure::timeout);
  EXPECT_EQ(report.transition, 4);
  EXPECT_EQ(sim.device_state(0), State::start_up_inhibit) << "BLOCK POWER after the failure";
  sim.run_until(2900ms);
  EXPECT_EQ(sim.device_state(0), State::enabled) << "the download has ended: the drive can be started";
  sim.run();
  const auto& tx = sim.summary().transactions;
  ASSERT_EQ(tx.size(), 5U);
  EXPECT_EQ(tx[1].kind, devices::ParamKind::written) << tx[1].result;
  EXPECT_EQ(tx[2].kind, devices::ParamKind::written) << tx[2].result;
  EXPECT_EQ(tx[3].kind, devices::ParamKind::value) << tx[3].result;
  EXPECT_EQ(tx[3].result_value, 0) << "SLOAD 0: the dataset was accepted";
  EXPECT_EQ(tx[4].kind, devices::ParamKind::written) << "4-PROG = 1: " << tx[4].result;
  ASSERT_TRUE(tx[4].answered.has_value());
  EXPECT_GT(*tx[4].answered - tx[4].submitted, 9s);
}

TEST(Simulator, DeviceFaultIsReportedAndResetByANewRequest) {
  Scenario s;
  s.duration = 2s;
  s.devices = {mc6000()};
  s.timeline = {at(0s, "mc", Action::state, "enabled"), at(300ms, "mc", Action::speed, "", 1000),
                at(500ms, "mc", Action::fault_device, "", 0, 0, 100ms),
                at(1000ms, "mc", Action::state, "enabled")};
  Simulator sim(s);
  sim.run_until(900ms);
  EXPECT_EQ(sim.device_state(0), State::fault);
  EXPECT_EQ(sim.driver(0).sequencer().report().failure, drivecom::Failure::fault);
  sim.run();
  EXPECT_EQ(sim.device_state(0), State::enabled);
  const auto& states = sim.summary().devices[0].states;
  EXPECT_NE(find_event(sim.summary().devices[0], "FAULT RESPONSE ACTIVE"), nullptr);
  EXPECT_NE(find_event(sim.summary().devices[0], "FAULT"), nullptr);
  EXPECT_GE(states.size(), 5U);
}

TEST(Simulator, Vf1000FaultResetByANewRequestBootsTheInverterOnce) {
  // INTERBUS manual 5.2.1: RESET FAULT makes the VF1000 perform a software reset; LUSTBUS manual 8.1.1: no
  // link during the self-test. The master resets only because a new request asks for it, once,
  // and brings the inverter up after its boot.
  Scenario s;
  s.duration = 6s;
  s.devices = {vf1000()};
  s.timeline = {at(0s, "vf", Action::state, "enabled"), at(300ms, "vf", Action::frequency, "", 20),
                at(500ms, "vf", Action::fault_device, "", 0, 0, 100ms),
                at(1000ms, "vf", Action::state, "enabled")};
  Simulator sim(s);
  sim.run_until(900ms);
  EXPECT_EQ(sim.device_state(0), State::fault);
  EXPECT_EQ(vf1000_at(sim, 0).software_resets(), 0U) << "no reset before the new request";
  sim.run_until(1200ms);
  EXPECT_EQ(vf1000_at(sim, 0).software_resets(), 1U);
  EXPECT_EQ(sim.device_state(0), State::not_ready);
  EXPECT_TRUE(vf1000_at(sim, 0).module_error(sim.now()));
  sim.run();
  EXPECT_EQ(vf1000_at(sim, 0).software_resets(), 1U);
  EXPECT_EQ(sim.device_state(0), State::enabled);
  EXPECT_TRUE(sim.summary().devices[0].failures.size() == 1U)
      << "only the fault itself ends a request; the boot does not";
}

// The scenario key `reset_time` (a VF1000 setting, D13): the self-test after RESET FAULT lasts
// as long as the scenario says; the module error with it.
TEST(Simulator, Vf1000ResetTimeFromTheScenario) {
  Scenario s;
  s.duration = 4s;
  DeviceConfig v = vf1000();
  v.settings.set_duration("reset_time", 1500ms);
  s.devices = {v};
  s.timeline = {at(0s, "vf", Action::state, "enabled"), at(500ms, "vf", Action::fault_device, "", 0, 0, 100ms),
                at(1000ms, "vf", Action::state, "enabled")};
  Simulator sim(s);
  sim.run_until(1100ms);
  ASSERT_EQ(vf1000_at(sim, 0).software_resets(), 1U);
  EXPECT_TRUE(vf1000_at(sim, 0).module_error(sim.now()));
  sim.run_until(2400ms);  // within 1.5 s of the reset
  EXPECT_TRUE(vf1000_at(sim, 0).module_error(sim.now()));
  sim.run_until(2700ms);
  EXPECT_FALSE(vf1000_at(sim, 0).module_error(sim.now()));
  sim.run();
  EXPECT_EQ(sim.device_state(0), State::enabled);
}

TEST(Simulator, LostDeviceShowsAModuleErrorToTheMaster) {
  Scenario s;
  s.duration = 1s;
  s.devices = {mc6000(), vf1000()};
  s.timeline = {at(0s, "mc", Action::state, "enabled"), at(0s, "vf", Action::state, "enabled"),
                at(400ms, "mc", Action::fault_lost, "", 0, 0, 200ms)};
  Simulator sim(s);
  sim.run_until(500ms);
  // The master reads 0000H (no valid state) for the lost servo; the VF1000 carries on.
  EXPECT_EQ(sim.driver(0).sequencer().report().status_seen, 0x0000);
  EXPECT_EQ(sim.device_state(1), State::enabled);
  sim.run();
  const auto& f = sim.summary().faults;
  ASSERT_EQ(f.size(), 2U);
  EXPECT_EQ(f[0].kind, "lost");
  EXPECT_EQ(f[1].kind, "back");
}

TEST(Simulator, MasterRestartSendsBlockPowerAndStartsTheChannelsOver) {
  Scenario s;
  s.duration = 2s;
  s.devices = {vf1000()};
  s.timeline = {at(0s, "vf", Action::state, "enabled"), at(300ms, "vf", Action::read, "", 0, 85),
                at(305ms, "", Action::master_restart), at(1s, "vf", Action::state, "enabled"),
                at(1200ms, "vf", Action::read, "", 0, 22)};
  Simulator sim(s);
  sim.run_until(400ms);
  EXPECT_EQ(sim.device_state(0), State::start_up_inhibit);
  sim.run();
  EXPECT_EQ(sim.device_state(0), State::enabled);
  const auto& t = sim.summary().transactions;
  ASSERT_EQ(t.size(), 2U);
  EXPECT_EQ(t[0].kind, devices::ParamKind::aborted) << t[0].result;
  EXPECT_EQ(t[1].kind, devices::ParamKind::value) << t[1].result;
  EXPECT_EQ(t[1].result_value, 1000);
}

TEST(Simulator, Mc6000ParametersThroughPcpInTheManualsTime) {
  // INTERBUS manual 7.2: 10..35 ms per value inquiry or transfer. Over the 2-word channel of SUPI 9
  // (IBCNF 1) the calibrated latency model meets it end to end at the master (docs/pcp.md).
  Scenario s;
  s.duration = 2s;
  DeviceConfig m = mc6000();
  m.settings.set_integer("supi", 9);
  m.settings.set_integer("ibcnf", 1);
  s.devices = {m};
  s.timeline = {at(0s, "mc", Action::read, "", 0, 85),             // Initiate, then clears SERR
                at(400ms, "mc", Action::read, "", 0, 406),
                at(800ms, "mc", Action::write, "", 1, 15),  // 15-PLRDY = 1, RAM: no EEPROM time
                at(1200ms, "mc", Action::write, "", 1, 15),
                at(1600ms, "mc", Action::describe, "", 0, 409)};
  Simulator sim(s);
  sim.run();
  const auto& t = sim.summary().transactions;
  ASSERT_EQ(t.size(), 5U);
  for (std::size_t i = 1; i < t.size(); ++i) {
    ASSERT_TRUE(t[i].finished) << i;
    const double ms = to_ms(*t[i].finished - t[i].submitted);
    EXPECT_GE(ms, 10.0) << t[i].result;
    EXPECT_LE(ms, 35.0) << t[i].result;
  }
  EXPECT_EQ(t[1].kind, devices::ParamKind::value);
  EXPECT_EQ(t[1].result_value, 1);  // 406-IBCNF as configured
  EXPECT_EQ(t[2].kind, devices::ParamKind::written) << t[2].result;
  EXPECT_EQ(t[4].kind, devices::ParamKind::description) << t[4].result;
  EXPECT_NE(find_event(sim.summary().devices[0], "15-PLRDY = 1"), nullptr);
}

// INTERBUS manual 7.2: "The transfer time for value inquiries and value transfers is between 10 ms and
// 35 ms, depending on processor workload." The PCP transfer times of docs/simulator.md's table and
// erratum PCP-E7, per channel width, at workload 0 (ManualWindow spans the workload): read 406 and
// write 409 from the request to the master's confirmation, each within one bus cycle of the
// documented figure, on the default bus (an MC6000 at SUPI 11 and a VF1000, 0.726 ms cycles) and
// a short ring (three MC6000 at SUPI 3, 9 and 11, 0.989 ms) inside the manual's window, and on a
// full ring (the same three and 61 MC6000 at SUPI 12, 13.86 ms) at its physical limit: a frame per
// cycle each way is more than 35 ms for any width there (the erratum gives the arithmetic).
TEST(Simulator, PcpTransferTimesPerChannelWidthAsDocumented) {
  struct Row {
    int supi;
    int ibcnf;
    double read_ms, write_ms;            // three servos, 0.989 ms
    double full_read_ms, full_write_ms;  // the full ring
  };
  const Row rows[] = {{3, 0, 12.857, 12.857, 83.16, 83.16},
                      {9, 1, 15.824, 13.846, 124.74, 110.88},
                      {11, 2, 22.747, 20.769, 318.78, 291.06}};
  const auto run_ring = [&](bool full) {
    Scenario s;
    s.duration = 4s;
    for (const Row& r : rows) {
      DeviceConfig m = mc6000("mc" + std::to_string(r.supi));
      m.settings.set_integer("supi", r.supi);
      m.settings.set_integer("ibcnf", r.ibcnf);
      s.devices.push_back(m);
    }
    for (int k = 0; full && k < 61; ++k) {
      DeviceConfig m = mc6000("fill" + std::to_string(k));
      m.settings.set_integer("supi", 12);
      s.devices.push_back(m);
    }
    for (const Row& r : rows) s.timeline.push_back(at(0s, "mc" + std::to_string(r.supi), Action::read, "", 0, 85));
    for (const Row& r : rows) s.timeline.push_back(at(1s, "mc" + std::to_string(r.supi), Action::read, "", 0, 406));
    for (const Row& r : rows) {
      s.timeline.push_back(at(2s, "mc" + std::to_string(r.supi), Action::write, "", 100, 409));
    }
    Simulator sim(s);
    sim.run();
    const double cycle_ms = to_ms(sim.cycle_time());
    EXPECT_NEAR(cycle_ms, full ? 13.86 : 0.989, 0.001);
    const auto& t = sim.summary().transactions;
    ASSERT_EQ(t.size(), 9U);
    for (std::size_t i = 0; i < 3; ++i) {
      const Row& r = rows[i];
      for (const std::size_t k : {3 + i, 6 + i}) {
        const bool read = k < 6;
        const double want = full ? (read ? r.full_read_ms : r.full_write_ms) : (read ? r.read_ms : r.write_ms);
        ASSERT_TRUE(t[k].finished) << "SUPI " << r.supi;
        const double ms = to_ms(*t[k].finished - t[k].submitted);
        EXPECT_EQ(t[k].kind, read ? devices::ParamKind::value : devices::ParamKind::written) << t[k].result;
        EXPECT_NEAR(ms, want, cycle_ms) << "SUPI " << r.supi << (read ? " read" : " write") << (full ? ", full ring" : "");
        if (!full) {
          EXPECT_GE(ms, 10.0) << "SUPI " << r.supi << ": INTERBUS manual 7.2";
          EXPECT_LE(ms, 35.0) << "SUPI " << r.supi << ": INTERBUS manual 7.2";
        } else {
          EXPECT_GT(ms, 35.0) << "SUPI " << r.supi << ": the full ring's physical limit (PCP-E7)";
        }
      }
    }
  };
  run_ring(false);
  run_ring(true);

  // The default bus: the one-word channel of SUPI 11 (INTERBUS manual 5.3.4) beside a VF1000.
  Scenario s;
  s.duration = 3s;
  s.devices = {mc6000(), vf1000()};
  s.timeline = {at(0s, "mc", Action::read, "", 0, 85), at(1s, "mc", Action::read, "", 0, 406),
                at(2s, "mc", Action::write, "", 100, 409)};
  Simulator sim(s);
  sim.run();
  EXPECT_NEAR(to_ms(sim.cycle_time()), 0.726, 0.001);
  const auto& t = sim.summary().transactions;
  ASSERT_EQ(t.size(), 3U);
  const double want[] = {16.698, 15.246};  // read 406, write 409
  for (const std::size_t k : {1U, 2U}) {
    ASSERT_TRUE(t[k].finished) << k;
    const double ms = to_ms(*t[k].finished - t[k].submitted);
    EXPECT_NEAR(ms, want[k - 1], 0.726) << (k == 1 ? "read" : "write") << " on the default bus";
    EXPECT_GE(ms, 10.0) << "INTERBUS manual 7.2";
    EXPECT_LE(ms, 35.0) << "INTERBUS manual 7.2";
  }
}

TEST(Simulator, Mc6000SwitchedOnWithAnotherSupiNoLongerFitsTheRing) {
  // 405-SUPI is read at power-on (3.2.2): written through PCP, it changes the servo's layout and ID
  // code at the next power cycle, and the configured ring reports a module error for it.
  Scenario s;
  s.duration = 2s;
  DeviceConfig m = mc6000();
  m.settings.set_integer("supi", 9);
  m.settings.set_integer("ibcnf", 1);
  s.devices = {m};
  s.timeline = {at(0s, "mc", Action::read, "", 0, 85), at(300ms, "mc", Action::write, "", 12, 405),
                at(300ms, "mc", Action::read, "", 0, 77), at(800ms, "mc", Action::fault_power_cycle)};
  Simulator sim(s);
  sim.run_until(700ms);
  const auto& t = sim.summary().transactions;
  ASSERT_EQ(t.size(), 3U);
  EXPECT_EQ(t[1].kind, devices::ParamKind::written) << t[1].result;
  EXPECT_EQ(t[2].kind, devices::ParamKind::value) << t[2].result;  // 77-SPEED: 0 at standstill
  EXPECT_EQ(t[2].result_value, 0);
  EXPECT_FALSE(sim.module_error(0, sim.now()));
  sim.run();
  EXPECT_TRUE(dynamic_cast<const devices::Mc6000Device&>(sim.emulator(0)).configuration_mismatch());
  EXPECT_TRUE(sim.module_error(0, sim.now()));
  EXPECT_EQ(sim.driver(0).sequencer().report().status_seen, 0x0000);
}

TEST(Simulator, RandomFaultsAreReproducibleFromTheSeed) {
  Scenario s;
  s.duration = 3s;
  s.devices = {mc6000(), vf1000()};
  s.timeline = {at(0s, "mc", Action::state, "enabled"), at(0s, "vf", Action::state, "enabled")};
  s.random.seed = 42;
  s.random.corrupt_per_s = 5;
  s.random.device_fault_per_s = 1;
  s.random.lost_per_s = 1;
  auto faults = [&] {
    Simulator sim(s);
    SimOptions o;
    o.measure_master_time = false;
    sim.run(o);
    std::vector<std::string> v;
    for (const auto& f : sim.summary().faults) v.push_back(std::to_string(f.at.count()) + f.device + f.kind);
    return v;
  };
  const auto a = faults();
  const auto b = faults();
  EXPECT_EQ(a, b);
  EXPECT_GE(a.size(), 10U);
  s.random.seed = 43;
  EXPECT_NE(faults(), a);
}

TEST(Simulator, ReportsProgressInSimulatedTime) {
  Scenario s;
  s.duration = 2s;
  s.devices = {vf1000()};
  Simulator sim(s);
  std::vector<Time> seen;
  SimOptions o;
  o.progress = [&](Time now, Duration total) {
    EXPECT_EQ(total, 2s);
    seen.push_back(now);
  };
  sim.run(o);
  ASSERT_GE(seen.size(), 15U);  // every 100 ms of simulated time
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_LE(seen.back(), 2s);
}

TEST(Simulator, RefusesAConfigurationTheBusOrTheDeviceRefuses) {
  Scenario s;
  DeviceConfig m = mc6000();
  m.settings.set_integer("supi", 7);
  m.settings.set_integer("ibcnf", 2);
  s.devices = {m};
  try {
    Simulator sim(s);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "device 'mc': 406-IBCNF = 2 needs 405-SUPI 10..12, not 7 (INTERBUS manual 3.2.3)");
  }
  Scenario many;
  for (int i = 0; i < 65; ++i) many.devices.push_back(mc6000("m" + std::to_string(i)));  // 65 x 4 words
  EXPECT_THROW(Simulator{many}, std::invalid_argument);
}

// The simulator builds every device through the drive registry: a kind it does not know is named.
TEST(Simulator, RefusesADriveKindTheRegistryDoesNotKnow) {
  Scenario s;
  DeviceConfig d = mc6000();
  d.kind = "mc7000";
  s.devices = {d};
  try {
    Simulator sim(s);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "device 'mc': unknown type 'mc7000' (\"mc6000\" or \"vf1000\")");
  }
  s.devices[0] = vf1000();
  s.devices[0].bus = interbus::BusKind::local;
  try {
    Simulator sim(s);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "device 'vf': a VF1000 is always a remote bus device (INTERBUS manual 1.3)");
  }
}

}  // namespace
}  // namespace ibs::sim

namespace ibs::sim {
namespace {

// Issue 24: a device fault with its cause reaches the drive's core, the master sees FAULT in the
// status word, and the summary names the drive's own error.
TEST(SimulatorPlantEvents, ADeviceFaultWithItsCauseShowsInTheStatusAndTheSummary) {
  Scenario s;
  s.duration = 2s;
  s.devices = {mc6000()};
  TimelineEntry f = at(500ms, "mc", Action::fault_device, "", 0, 0, 200ms);
  f.cause = "E-OP1";
  s.timeline = {at(0s, "mc", Action::state, "enabled"), f};
  Simulator sim(s);
  sim.run_until(600ms);
  EXPECT_EQ(sim.device_state(0), State::fault);
  EXPECT_EQ(dynamic_cast<devices::Mc6000Device&>(sim.emulator(0)).drive().fault_cause(), 16);
  sim.run();
  const Summary& r = sim.summary();
  EXPECT_NE(find_event(r.devices[0], "FAULT"), nullptr) << "the master saw the fault in the status word";
  ASSERT_FALSE(r.faults.empty());
  EXPECT_EQ(r.faults[0].kind, "device-fault");
  EXPECT_NE(r.faults[0].detail.find("error 16 (E-OP1)"), std::string::npos) << r.faults[0].detail;
  ASSERT_FALSE(r.devices[0].errors.empty());
  EXPECT_NE(r.devices[0].errors[0].find("error 16 (E-OP1): device fault injected"), std::string::npos);
}

TEST(SimulatorPlantEvents, MainsLossAndLoadAndInputFromTheTimeline) {
  Scenario s;
  s.duration = 2s;
  s.devices = {mc6000()};
  TimelineEntry input = at(100ms, "mc", Action::input, "IS00");
  input.level = true;
  s.timeline = {input, at(200ms, "mc", Action::load, "", 1.5), at(300ms, "mc", Action::mains, "off"),
                at(800ms, "mc", Action::mains, "on")};
  Simulator sim(s);
  sim.run_until(250ms);
  auto& servo = dynamic_cast<devices::Mc6000Device&>(sim.emulator(0));
  EXPECT_NE(servo.status_word() & 0x4000U, 0U) << "IS00 in status bit 14 (INTERBUS manual 5.3.2)";
  EXPECT_EQ(servo.drive().load_torque(), 1.5);
  sim.run_until(400ms);
  EXPECT_TRUE(sim.module_error(0, sim.now()));
  sim.run();
  EXPECT_FALSE(sim.module_error(0, sim.now()));
  std::vector<std::string> kinds;
  for (const FaultRecord& f : sim.summary().faults) kinds.push_back(f.kind);
  EXPECT_EQ(kinds, (std::vector<std::string>{"input", "load", "mains-off", "mains-on"}));
}

// VF-E22: the VF1000's terminals from the timeline: an output's stated level in the status word
// the master reads (INTERBUS manual 5.2.2: bit 15 S1OUT, bit 14 S2OUT), an input's function on the core.
TEST(SimulatorPlantEvents, Vf1000TerminalsFromTheTimeline) {
  Scenario s;
  s.duration = 1s;
  s.devices = {vf1000()};
  TimelineEntry s1out = at(100ms, "vf", Action::input, "S1OUT");
  s1out.level = true;
  TimelineEntry s2ind = at(100ms, "vf", Action::input, "S2IND");
  s2ind.level = true;
  TimelineEntry s1out_low = at(500ms, "vf", Action::input, "S1OUT");
  s.timeline = {s1out, s2ind, s1out_low};
  Simulator sim(s);
  sim.run_until(300ms);
  auto& inverter = vf1000_at(sim, 0);
  EXPECT_EQ(inverter.status_word() & 0xC000U, 0x8000U) << "S1OUT in status bit 15";
  EXPECT_TRUE(inverter.drive().input_function_active(devices::vf1000::Terminal::s2ind));
  EXPECT_FALSE(inverter.drive().input_function_active(devices::vf1000::Terminal::s1ind));
  sim.run();
  EXPECT_EQ(inverter.status_word() & 0xC000U, 0U) << "S1OUT low again";
  std::vector<std::string> details;
  for (const FaultRecord& f : sim.summary().faults) details.push_back(f.detail);
  EXPECT_EQ(details, (std::vector<std::string>{"input S1OUT high", "input S2IND high", "input S1OUT low"}));
}

// MC-D9: a SMARTCARD operation on the MC6000 from the timeline: a module error for its time,
// then the master's words count again, without a new start.
TEST(SimulatorPlantEvents, AnMc6000SmartcardOperationIsAModuleErrorForItsTime) {
  Scenario s;
  s.duration = 3s;
  s.devices = {mc6000()};
  TimelineEntry card = at(1s, "mc", Action::smartcard, "read");
  card.duration = 500ms;
  s.timeline = {at(0s, "mc", Action::state, "enabled"), card};
  Simulator sim(s);
  sim.run_until(1200ms);
  EXPECT_TRUE(sim.module_error(0, sim.now()));
  EXPECT_EQ(sim.device_state(0), State::enabled) << "the servo runs on as last commanded";
  sim.run_until(1490ms);
  EXPECT_EQ(sim.device_state(0), State::enabled) << "to the end of the operation: no new start";
  sim.run();
  EXPECT_FALSE(sim.module_error(0, sim.now()));
  // The master saw no status during the module error and ended its request (docs/errata.md
  // DC-D1); its words reach the servo again: START-UP INHIBIT.
  EXPECT_EQ(sim.device_state(0), State::start_up_inhibit);
  ASSERT_EQ(sim.summary().faults.size(), 1U);
  EXPECT_EQ(sim.summary().faults[0].kind, "smartcard");
}

// MC-D10, INTERBUS manual 3.2.1: the INTERBUS card withdrawn is a module error at once; the power-on
// after it brings the factory defaults; put back, the next power-on detects it again.
TEST(SimulatorPlantEvents, TheInterbusCardWithdrawnAndPutBackFromTheTimeline) {
  Scenario s;
  s.duration = 4s;
  s.devices = {mc6000()};
  s.timeline = {at(500ms, "mc", Action::option_card, "withdrawn"), at(1s, "mc", Action::fault_power_cycle),
                at(2s, "mc", Action::option_card, "inserted"), at(2500ms, "mc", Action::fault_power_cycle)};
  Simulator sim(s);
  auto& servo = dynamic_cast<devices::Mc6000Device&>(sim.emulator(0));
  sim.run_until(700ms);
  EXPECT_TRUE(sim.module_error(0, sim.now()));
  EXPECT_EQ(servo.drive().parameters().raw(devices::mc6000::kClsel), static_cast<std::uint32_t>(devices::mc6000::kClselOpt1))
      << "not before the next power-on";
  sim.run_until(1500ms);
  EXPECT_EQ(servo.drive().parameters().raw(devices::mc6000::kClsel), 0U) << "the factory default without the card";
  EXPECT_TRUE(sim.module_error(0, sim.now()));
  sim.run_until(2200ms);
  EXPECT_TRUE(sim.module_error(0, sim.now())) << "detected at power-on only";
  sim.run();
  EXPECT_FALSE(sim.module_error(0, sim.now()));
  EXPECT_EQ(servo.drive().parameters().raw(devices::mc6000::kClsel), static_cast<std::uint32_t>(devices::mc6000::kClselOpt1));
  std::vector<std::string> kinds;
  for (const FaultRecord& f : sim.summary().faults) kinds.push_back(f.kind);
  EXPECT_EQ(kinds, (std::vector<std::string>{"option-card", "power-cycle", "option-card", "power-cycle"}));
}

// The control channel's entries: applied at the time reached, recorded with their line.
TEST(SimulatorControl, AnEntryAppliesAtTheTimeReachedAndIsListed) {
  Scenario s;
  s.duration = 2s;
  s.devices = {mc6000()};
  s.timeline = {at(0s, "mc", Action::state, "enabled")};
  Simulator sim(s);
  sim.run_until(700ms);
  const Time when = sim.now();
  sim.control(parse_control_line(R"({"device": "mc", "speed": 500})", 4, s));
  sim.run_until(1500ms);
  EXPECT_NEAR(sim.device_actual(0), 500.0, 5.0);
  sim.control(parse_control_line(R"({"device": "mc", "fault": "device", "cause": 16})", 6, s));
  sim.run();
  const Summary& r = sim.summary();
  ASSERT_EQ(r.control.size(), 2U);
  EXPECT_EQ(r.control[0].at, when);
  EXPECT_EQ(r.control[0].line, 4U);
  EXPECT_EQ(r.control[0].entry, R"({"device": "mc", "speed": 500.0})");
  EXPECT_EQ(r.control[1].line, 6U);
  EXPECT_EQ(sim.device_state(0), State::fault);
}

// A control entry for a device that waits for a state waits like a timeline entry.
TEST(SimulatorControl, AnEntryForAWaitingDeviceIsDeferred) {
  Scenario s;
  s.duration = 3s;
  s.devices = {mc6000()};
  // Waits for a FAULT that does not come: up to its timeout, 1 s after 10 ms.
  s.timeline = {at(0s, "mc", Action::state, "enabled"), at(10ms, "mc", Action::wait_state, "fault", 0, 0, 1s)};
  Simulator sim(s);
  sim.run_until(500ms);
  sim.control(parse_control_line(R"({"device": "mc", "speed": 100})", 1, s));
  sim.run_until(1000ms);
  EXPECT_TRUE(sim.summary().control.empty()) << "deferred while the device waits";
  sim.run();
  ASSERT_EQ(sim.summary().control.size(), 1U);
  EXPECT_GE(sim.summary().control[0].at, Time{1010ms});
  EXPECT_LT(sim.summary().control[0].at, Time{1100ms});
}

}  // namespace
}  // namespace ibs::sim
