// The fault campaign (sim/campaign.hpp): a short run passes every check, and every check can
// fail: the oracle is fed observations that break each rule and must report them.
#include "ibs/sim/campaign.hpp"

#include <gtest/gtest.h>

namespace ibs::sim {
namespace {

using devices::ParamKind;
using devices::ParamOp;
using drivecom::State;

// A small device: parameter 10 (RAM, 0..100, default 5), parameter 20 (EEPROM, 0..9, default 1,
// save within 30 ms), 4 = PROG (command), 409-like watchdog parameter 30 (ms).
CheckerDeviceSpec small_device() {
  CheckerDeviceSpec d;
  d.name = "dev";
  d.period = 1ms;
  d.params = {
      {10, ParamRole::normal, false, false, 5, 5, 0, 100, Duration{0}},
      {20, ParamRole::normal, true, false, 1, 1, 0, 9, 30ms},
      {4, ParamRole::command, false, false, 0, 0, 0, 255, Duration{0}},
      {30, ParamRole::normal, true, false, 50, 0, 0, 65535, 30ms},
  };
  d.watchdog_parameter = 30;
  return d;
}

std::vector<StoreEntry> store(std::int64_t p10, std::int64_t p20, std::int64_t e20, std::int64_t p30 = 50) {
  return {{10, p10, std::nullopt}, {20, p20, e20}, {4, 0, std::nullopt}, {30, p30, p30}};
}

bool has(const CampaignChecker& c, const std::string& check) {
  for (const auto& v : c.violations()) {
    if (v.check == check) return true;
  }
  return false;
}

TEST(Campaign, AShortCampaignPassesEveryCheck) {
  CampaignOptions o;
  o.seed = 1;
  o.transactions = 20000;
  const CampaignResult r = run_campaign(o);
  EXPECT_GE(r.transactions, 3000U);
  EXPECT_GT(r.state_commands, 2000U);
  EXPECT_GT(r.checks.store_checks, 10000U);
  EXPECT_GT(r.checks.read_checks, 500U);
  EXPECT_GT(r.checks.state_checks, 100U);
  EXPECT_GT(r.checks.stop_checks, 50U);
  EXPECT_GT(r.faults.at("corrupt"), 0U);
  for (const auto& v : r.violations) ADD_FAILURE() << to_ms(v.at) << " ms " << v.device << " [" << v.check << "] " << v.what;
  EXPECT_EQ(r.violation_count, 0U);
}

TEST(Campaign, TheSameSeedGivesTheSameRun) {
  CampaignOptions o;
  o.seed = 7;
  o.transactions = 500;
  const CampaignResult a = run_campaign(o);
  const CampaignResult b = run_campaign(o);
  EXPECT_EQ(a.simulated, b.simulated);
  EXPECT_EQ(a.transactions_by, b.transactions_by);
  EXPECT_EQ(a.faults, b.faults);
  EXPECT_EQ(a.state_commands, b.state_commands);
}

TEST(CampaignChecker, AStoreHoldingAValueNobodyWroteIsAViolation) {
  CampaignChecker c;
  const auto d = c.add_device(small_device());
  c.check_store(d, 1ms, store(5, 1, 1));
  EXPECT_EQ(c.violation_count(), 0U);
  c.check_store(d, 2ms, store(77, 1, 1));
  EXPECT_TRUE(has(c, "store"));
}

TEST(CampaignChecker, AConfirmedWriteMustBeHeld) {
  CampaignChecker c;
  const auto d = c.add_device(small_device());
  c.submitted(d, ParamOp::write, 10, 42, 0ms, 1s);
  c.check_store(d, 1ms, store(42, 1, 1));  // may have landed already
  c.check_store(d, 2ms, store(5, 1, 1));   // or not yet
  c.ended(d, ParamKind::written, 0, 10ms);
  EXPECT_EQ(c.violation_count(), 0U);
  c.check_store(d, 11ms, store(5, 1, 1));  // confirmed, but the old value
  EXPECT_TRUE(has(c, "store"));
}

TEST(CampaignChecker, AnAbortedWriteMayOrMayNotHaveLandedANakNever) {
  CampaignChecker c;
  const auto d = c.add_device(small_device());
  c.submitted(d, ParamOp::write, 10, 42, 0ms, 1s);
  c.ended(d, ParamKind::aborted, 0, 10ms);
  c.check_store(d, 11ms, store(42, 1, 1));
  c.check_store(d, 12ms, store(5, 1, 1));
  EXPECT_EQ(c.violation_count(), 0U);
  c.submitted(d, ParamOp::write, 10, 60, 20ms, 1s);
  c.ended(d, ParamKind::nak, 0, 30ms);
  c.check_store(d, 31ms, store(60, 1, 1));
  EXPECT_TRUE(has(c, "store"));
}

TEST(CampaignChecker, PowerOnRestoresEepromValuesAndRamDefaults) {
  CampaignChecker c;
  const auto d = c.add_device(small_device());
  c.submitted(d, ParamOp::write, 10, 42, 0ms, 1s);
  c.ended(d, ParamKind::written, 0, 10ms);
  c.submitted(d, ParamOp::write, 20, 7, 10ms, 1s);
  c.ended(d, ParamKind::written, 0, 20ms);
  c.check_store(d, 21ms, store(42, 7, 1));  // the EEPROM copy follows within 30 ms
  c.check_store(d, 60ms, store(42, 7, 7));
  EXPECT_EQ(c.violation_count(), 0U);
  c.power_cycle(d, 70ms);
  c.check_store(d, 71ms, store(5, 7, 7));
  EXPECT_EQ(c.violation_count(), 0U);
  c.check_store(d, 72ms, store(42, 7, 7));  // the RAM value survived the power-on
  EXPECT_TRUE(has(c, "store"));
}

TEST(CampaignChecker, AReadMustReturnAValueTheModelAllows) {
  CampaignChecker c;
  const auto d = c.add_device(small_device());
  c.submitted(d, ParamOp::read, 10, 0, 0ms, 1s);
  c.ended(d, ParamKind::value, 5, 10ms);
  EXPECT_EQ(c.violation_count(), 0U);
  c.submitted(d, ParamOp::read, 10, 0, 20ms, 1s);
  c.ended(d, ParamKind::value, 6, 30ms);
  EXPECT_TRUE(has(c, "read"));
}

TEST(CampaignChecker, AnOutOfRangeWriteMustNotBeConfirmed) {
  CampaignChecker c;
  const auto d = c.add_device(small_device());
  c.submitted(d, ParamOp::write, 10, 101, 0ms, 1s);
  c.ended(d, ParamKind::written, 0, 10ms);
  EXPECT_TRUE(has(c, "outcome"));
}

TEST(CampaignChecker, AnOutcomeTheOperationCannotHaveIsAViolation) {
  CampaignChecker c;
  const auto d = c.add_device(small_device());
  c.submitted(d, ParamOp::read, 10, 0, 0ms, 1s);
  c.ended(d, ParamKind::written, 0, 10ms);
  EXPECT_TRUE(has(c, "outcome"));
}

TEST(CampaignChecker, AnOverdueRequestIsReportedWhilePendingAndWhenItEnds) {
  CampaignChecker c;
  const auto d = c.add_device(small_device());
  c.submitted(d, ParamOp::read, 10, 0, 0ms, 500ms);
  c.check_overdue(500ms);
  EXPECT_EQ(c.violation_count(), 0U);
  c.check_overdue(501ms);
  EXPECT_TRUE(has(c, "overdue"));
  EXPECT_EQ(c.violation_count(), 1U);
  c.check_overdue(600ms);  // once
  EXPECT_EQ(c.violation_count(), 1U);
  c.ended(d, ParamKind::timeout, 0, 700ms);
  EXPECT_EQ(c.violation_count(), 1U);
  c.submitted(d, ParamOp::read, 10, 0, 1s, 500ms);
  c.ended(d, ParamKind::timeout, 0, 2s);  // never polled in between
  EXPECT_EQ(c.violation_count(), 2U);
}

TEST(CampaignChecker, EnabledWithoutARequestIsAViolation) {
  CampaignChecker c;
  const auto d = c.add_device(small_device());
  c.observe(d, 1ms, State::ready, false, false);
  EXPECT_EQ(c.violation_count(), 0U);
  c.observe(d, 2ms, State::enabled, false, false);
  EXPECT_TRUE(has(c, "enabled"));
}

TEST(CampaignChecker, EnabledAfterAFaultNeedsANewRequest) {
  CampaignChecker c;
  const auto d = c.add_device(small_device());
  c.state_command(d, StateCommand::enable, 0ms);
  c.observe(d, 5ms, State::enabled, false, false);
  EXPECT_EQ(c.violation_count(), 0U);
  c.power_cycle(d, 10ms);
  c.observe(d, 11ms, State::not_ready, false, false);
  c.observe(d, 600ms, State::enabled, false, false);  // came back up by itself
  EXPECT_TRUE(has(c, "enabled"));
  CampaignChecker c2;
  const auto d2 = c2.add_device(small_device());
  c2.state_command(d2, StateCommand::enable, 0ms);
  c2.power_cycle(d2, 10ms);
  c2.state_command(d2, StateCommand::enable, 20ms);  // asked again: fine
  c2.observe(d2, 600ms, State::enabled, false, false);
  EXPECT_EQ(c2.violation_count(), 0U);
}

TEST(CampaignChecker, AnEmergencyStopMustReachTheDriveWithinOneSampleOfItsDelivery) {
  CampaignChecker c;
  const auto d = c.add_device(small_device());
  c.state_command(d, StateCommand::enable, 0ms);
  c.observe(d, 5ms, State::enabled, false, false);
  c.state_command(d, StateCommand::emergency_stop, 5ms);  // after the master's cycle at 5 ms
  c.master_cycle(6ms);                                    // the word goes out
  c.exchange(d, 6ms, true, true);                         // not yet: the cycle carries the old word
  c.observe(d, 6ms, State::enabled, false, false);
  c.exchange(d, 7ms, false, false);  // a corrupted cycle delivers nothing
  c.observe(d, 7ms, State::enabled, false, false);
  c.exchange(d, 8ms, true, true);    // delivered: out of ENABLED by 9 ms
  c.observe(d, 8ms, State::enabled, false, false);
  EXPECT_EQ(c.violation_count(), 0U);
  c.observe(d, 9ms, State::enabled, false, false);
  EXPECT_TRUE(has(c, "stop"));
}

TEST(CampaignChecker, EnabledDuringAnOpenDownloadIsAViolation) {
  CampaignChecker c;
  auto spec = small_device();
  spec.params.push_back({80, ParamRole::download, false, false, 0, 0, -2, 999, Duration{0}});
  const auto d = c.add_device(spec);
  c.state_command(d, StateCommand::enable, 0ms);
  c.submitted(d, ParamOp::write, 80, -1, 1ms, 1s);
  c.ended(d, ParamKind::written, 0, 10ms);
  EXPECT_TRUE(c.download_open(d));
  c.observe(d, 11ms, State::enabled, false, false);
  EXPECT_TRUE(has(c, "download-lock"));
}

TEST(CampaignChecker, AWatchdogMustTripNeitherEarlyNorLate) {
  // Parameter 30 = 50 ms.
  CampaignChecker early;
  auto d = early.add_device(small_device());
  early.exchange(d, 1ms, true, true);
  early.observe(d, 1ms, State::ready, false, false);
  early.exchange(d, 40ms, false, false);
  early.observe(d, 40ms, State::fault, true, true);  // 39 ms after the last valid cycle
  EXPECT_TRUE(has(early, "watchdog-early"));

  CampaignChecker late;
  d = late.add_device(small_device());
  late.exchange(d, 1ms, true, true);
  late.observe(d, 1ms, State::ready, false, false);
  late.exchange(d, 51ms, false, false);
  late.observe(d, 51ms, State::ready, false, false);  // 50 ms: not yet due
  late.exchange(d, 52ms, false, false);
  late.observe(d, 52ms, State::ready, false, false);  // 51 ms: the sample after 50 ms is due
  EXPECT_EQ(late.violation_count(), 0U);
  late.exchange(d, 53ms, false, false);
  late.observe(d, 53ms, State::ready, false, false);
  EXPECT_TRUE(has(late, "watchdog-late"));

  CampaignChecker in_time;
  d = in_time.add_device(small_device());
  in_time.exchange(d, 1ms, true, true);
  in_time.observe(d, 1ms, State::ready, false, false);
  in_time.exchange(d, 52ms, false, false);
  in_time.observe(d, 52ms, State::fault, true, true);
  EXPECT_EQ(in_time.violation_count(), 0U);
}

// The watchdog parameter's raw value is a monitoring time only as the drive's profile reads it
// (e.g. the VF1000's 906-IB-WD in 50 ms steps): here 10 ms a step, raw 5 = 50 ms, raw 0 = off.
TEST(CampaignChecker, TheWatchdogTimeIsTheProfilesReadingOfTheRawValue) {
  auto stepped = [](std::int64_t raw_value) {
    CheckerDeviceSpec d = small_device();
    d.params[3].initial = raw_value;
    d.watchdog_ms = [](std::int64_t raw) { return raw * 10; };
    return d;
  };
  CampaignChecker early;
  auto d = early.add_device(stepped(5));
  early.exchange(d, 1ms, true, true);
  early.observe(d, 1ms, State::ready, false, false);
  early.exchange(d, 40ms, false, false);
  early.observe(d, 40ms, State::fault, true, true);  // 39 ms: raw 5 taken as ms would allow it
  EXPECT_TRUE(has(early, "watchdog-early"));

  CampaignChecker in_time;
  d = in_time.add_device(stepped(5));
  in_time.exchange(d, 1ms, true, true);
  in_time.observe(d, 1ms, State::ready, false, false);
  in_time.exchange(d, 52ms, false, false);
  in_time.observe(d, 52ms, State::fault, true, true);
  EXPECT_EQ(in_time.violation_count(), 0U);

  CampaignChecker off;
  d = off.add_device(stepped(0));
  off.exchange(d, 1ms, true, true);
  off.observe(d, 1ms, State::ready, false, false);
  off.exchange(d, 900ms, false, false);
  off.observe(d, 900ms, State::ready, false, false);  // off: never late
  EXPECT_EQ(off.violation_count(), 0U);
  off.observe(d, 901ms, State::fault, true, true);
  EXPECT_TRUE(has(off, "watchdog-early"));
}

}  // namespace
}  // namespace ibs::sim
