// System states of 5.2 in simulated time on the virtual bus, with fake drive nodes: logon every
// 100 ms until System Start, commands stored in Stop executed by all drives together at Start,
// the cyclic status, the watchdog; and the DRIVECOM start of 7.1.2 byte for byte.
#include <gtest/gtest.h>

#include <vector>

#include "harness.hpp"

namespace ibs::canlust {
namespace {

using test::Harness;
using test::node_config;
using Bytes = std::vector<std::uint8_t>;

Bytes bytes(const CanFrame& f) { return {f.data.begin(), f.data.begin() + f.dlc}; }

TEST(SystemTransitions, TableIsCompleteAndStartExecutesTheStoredCommand) {
  for (const auto s : {SystemState::logon, SystemState::stop, SystemState::start}) {
    for (const auto e : {SystemEvent::start_broadcast, SystemEvent::stop_broadcast}) {
      int rows = 0;
      for (const auto& t : kSystemTransitions) rows += (t.from == s && t.event == e) ? 1 : 0;
      EXPECT_EQ(rows, 1);
    }
  }
  EXPECT_TRUE(system_transition(SystemState::logon, SystemEvent::start_broadcast).execute_stored);
  EXPECT_TRUE(system_transition(SystemState::stop, SystemEvent::start_broadcast).execute_stored);
  EXPECT_EQ(system_transition(SystemState::start, SystemEvent::stop_broadcast).to, SystemState::stop);
}

// 5.2: "the drive controller transmits the logon identifier 1543 + address every 100 ms".
TEST(SystemLogon, LogonEvery100MsUntilSystemStart) {
  Harness h;
  h.add_drive(node_config(1));
  h.run_until(Time{1050ms});
  const auto logons = h.seen_with_id(1545);
  ASSERT_EQ(logons.size(), 11U);  // 0, 100, ..., 1000 ms
  for (std::size_t i = 0; i < logons.size(); ++i) {
    EXPECT_EQ(logons[i].start, Time{std::chrono::milliseconds(100 * i)});
    EXPECT_EQ(logons[i].frame.dlc, 0);
  }
  EXPECT_TRUE(h.master().drive(1).logged_on);
  EXPECT_EQ(h.master().logon_order().size(), 1U);
  EXPECT_TRUE(h.seen_with_id(883).empty());  // no status before System Start
  h.master().system_start();
  h.run_until(Time{2000ms});
  EXPECT_EQ(h.seen_with_id(1545).size(), 11U);  // no logon after the start
  EXPECT_EQ(h.node(0).state(), SystemState::start);
}

// 5.2: commands sent during System Stop are stored and executed at System Start, by every drive
// together ("synchronously (1 ms jitter)").
TEST(SystemStart, StoredCommandsRunOnAllDrivesWithin1Ms) {
  Harness h;
  for (Address a = 1; a <= 5; ++a) h.add_drive(node_config(a), Time{std::chrono::milliseconds(7 * a)});
  h.run_until(Time{300ms});
  for (Address a = 1; a <= 5; ++a) {
    h.master().send_control(a, {0x0006, q16_from_double(1.0 * a)});
    h.master().send_control(a, {0x000F, q16_from_double(10.0 * a)});  // the last one wins
  }
  h.run_until(Time{350ms});
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_TRUE(h.drive(i).executed.empty());
    ASSERT_TRUE(h.node(i).stored_command());
    EXPECT_EQ(h.node(i).stored_command()->word, 0x000F);
  }
  h.master().system_start();
  h.run_until(Time{400ms});
  Time first = Time::max(), last = Time::min();
  for (std::size_t i = 0; i < 5; ++i) {
    ASSERT_EQ(h.drive(i).executed.size(), 1U);
    EXPECT_EQ(h.drive(i).executed[0].t.word, 0x000F);
    EXPECT_EQ(h.drive(i).executed[0].t.reference, q16_from_double(10.0 * static_cast<double>(i + 1)));
    first = std::min(first, h.drive(i).executed[0].at);
    last = std::max(last, h.drive(i).executed[0].at);
    EXPECT_FALSE(h.node(i).stored_command());
  }
  EXPECT_LE(last - first, 1ms);
  EXPECT_EQ(h.master().logon_order().size(), 5U);
}

TEST(SystemStop, CommandsAreStoredAgainAndStatusReportsOn) {
  Harness h;
  h.add_drive(node_config(1));
  h.master().system_start();
  h.run_until(Time{100ms});
  h.master().send_control(1, {0x0006, 0});
  h.run_until(Time{110ms});
  EXPECT_EQ(h.drive(0).executed.size(), 1U);
  h.master().system_stop();
  h.run_until(Time{120ms});
  EXPECT_EQ(h.node(0).state(), SystemState::stop);
  h.master().send_control(1, {0x000F, 0});
  h.run_until(Time{400ms});
  EXPECT_EQ(h.drive(0).executed.size(), 1U);
  const auto statuses = h.master().drive(1).statuses;
  EXPECT_GT(statuses, 3U);  // status keeps coming in System Stop (D16)
  h.master().system_start();
  h.run_until(Time{410ms});
  ASSERT_EQ(h.drive(0).executed.size(), 2U);
  EXPECT_EQ(h.drive(0).executed[1].t.word, 0x000F);
  EXPECT_EQ(h.drive(0).states,
            (std::vector<SystemState>{SystemState::start, SystemState::stop, SystemState::start}));
}

// 575-CASCY: the status message every CASCY ms from the System Start.
TEST(CyclicStatus, EveryCascyMs) {
  Harness h;
  h.add_drive(node_config(1, 25ms));
  h.run_until(Time{50ms});
  h.master().system_start();
  h.run_until(Time{300ms});
  const auto st = h.seen_with_id(883);
  ASSERT_GE(st.size(), 10U);
  // The first status is queued at the Start broadcast's end and waits for its intermission
  // (3 bits); from then on the period is exact.
  EXPECT_LE(st[1].start - st[0].start, 25ms);
  EXPECT_GE(st[1].start - st[0].start, 25ms - 3 * h.bus().bit_time());
  for (std::size_t i = 2; i < st.size(); ++i) EXPECT_EQ(st[i].start - st[i - 1].start, 25ms);
  EXPECT_EQ(h.master().drive(1).status.word, 0x0240);
}

// 7.1.2, DRIVECOM: control 0000 -> status 0240, 0006 -> 0231, 000F -> 0237 (CDA 1: 663 / 883).
TEST(DrivecomStart, ControlAndStatusFramesOf712) {
  Harness h;
  h.add_drive(node_config(1, 10ms));
  h.master().system_start();
  h.run_until(Time{5ms});
  const std::pair<std::uint16_t, std::uint16_t> steps[] = {{0x0000, 0x0240}, {0x0006, 0x0231}, {0x000F, 0x0237}};
  Time t{5ms};
  for (const auto& [control, status] : steps) {
    ASSERT_TRUE(h.master().send_control(1, {control, q16_from_double(20.5)}));
    t += 50ms;
    h.run_until(t);
    EXPECT_EQ(h.master().drive(1).status.word, status);
  }
  const auto controls = h.seen_with_id(663);
  ASSERT_EQ(controls.size(), 3U);
  EXPECT_EQ(bytes(controls[0].frame), (Bytes{0x00, 0x00, 0x00, 0x80, 0x14, 0x00}));
  EXPECT_EQ(bytes(controls[1].frame), (Bytes{0x06, 0x00, 0x00, 0x80, 0x14, 0x00}));
  EXPECT_EQ(bytes(controls[2].frame), (Bytes{0x0F, 0x00, 0x00, 0x80, 0x14, 0x00}));
  const auto st = h.seen_with_id(883);
  ASSERT_FALSE(st.empty());
  EXPECT_EQ(bytes(st.back().frame), (Bytes{0x37, 0x02, 0x00, 0x80, 0x14, 0x00}));
  // Each status word appeared on 883 in that order.
  std::vector<std::uint16_t> words;
  for (const auto& s : st) {
    const auto w = static_cast<std::uint16_t>(s.frame.data[0] | (s.frame.data[1] << 8));
    if (words.empty() || words.back() != w) words.push_back(w);
  }
  EXPECT_EQ(words, (std::vector<std::uint16_t>{0x0240, 0x0231, 0x0237}));
}

// 574-CAWDG: no control telegram for CAWDG ms in System Start -> the drive's error reaction and
// the error telegram (E-OP2, D15); the trip comes within one status period of its time.
TEST(Watchdog, TripsWithinOneStatusPeriodOfItsTime) {
  Harness h;
  h.add_drive(node_config(1, 20ms, 50ms));
  h.master().system_start();
  h.run_until(Time{10ms});
  Time last_control{};
  for (int i = 0; i < 10; ++i) {  // a control telegram every 30 ms keeps it quiet
    h.master().send_control(1, {0x000F, 0});
    h.run_for(30ms);
  }
  EXPECT_TRUE(h.drive(0).watchdog_events.empty());
  last_control = h.drive(0).executed.back().at;
  h.run_for(200ms);
  ASSERT_EQ(h.drive(0).watchdog_events.size(), 1U);
  const auto& ev = h.drive(0).watchdog_events[0];
  EXPECT_EQ(ev.last_control, last_control);
  EXPECT_GE(ev.now, last_control + 50ms);
  EXPECT_LE(ev.now, last_control + 50ms + 20ms);
  EXPECT_EQ(ev.reaction, ErrorReaction::disable_power);
  const auto err = h.master().take_error();
  ASSERT_TRUE(err);
  EXPECT_EQ(err->address, 1);
  EXPECT_EQ(err->error, (ErrorTelegram{kErrorOp2, kLocationOp2_172, 3}));
  const auto frames = h.seen_with_id(443);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(bytes(frames[0].frame), (Bytes{0x10, 0xAC, 0x03}));
  EXPECT_EQ(h.master().drive(1).status.word, 0x0208);
  // A new control telegram re-arms it.
  h.master().send_control(1, {0x0000, 0});
  h.run_for(200ms);
  EXPECT_EQ(h.drive(0).watchdog_events.size(), 2U);
}

TEST(Watchdog, ZeroIsOff) {
  Harness h;
  h.add_drive(node_config(1, 20ms, 0ms));
  h.master().system_start();
  h.run_until(Time{2s});
  EXPECT_TRUE(h.drive(0).watchdog_events.empty());
  EXPECT_FALSE(h.master().take_error());
}

TEST(ParameterOverVirtualBus, ReadAndStringsInEverySystemState) {
  Harness h;
  h.add_drive(node_config(1));
  h.add_drive(node_config(2));
  auto& c = h.master().parameters();
  const auto r1 = c.submit(read(1, test::kParamDisp)).id;
  const auto w2 = c.submit(write_string(2, test::kParamText, "written over CAN")).id;
  const auto r2 = c.submit(read_string(2, test::kParamText)).id;
  h.run_until(Time{200ms});  // System Logon: parameter access is possible (5.2)
  ASSERT_EQ(c.poll(r1).state, RequestState::done);
  EXPECT_EQ(c.poll(r1).outcome->value, 406U);
  ASSERT_EQ(c.poll(w2).state, RequestState::done);
  EXPECT_EQ(c.poll(w2).outcome->kind, OutcomeKind::done);
  ASSERT_EQ(c.poll(r2).state, RequestState::done);
  EXPECT_EQ(c.poll(r2).outcome->text.view(), "written over CAN");
  // The parameter telegrams of CDA 1 are 1103 / 1323 (7.1.3).
  EXPECT_EQ(h.seen_with_id(1103).size(), 1U);
  EXPECT_EQ(h.seen_with_id(1323).size(), 1U);
}

// 4.3.3 / 4.5: a reply "only after successful entry": a slow write holds the drive's channel;
// the client's per-request timeout is what ends a request that gets no answer.
TEST(ParameterOverVirtualBus, SlowWriteWithinItsOwnTimeoutAndTimeoutWithout) {
  Harness h;
  h.add_drive(node_config(1));
  auto& c = h.master().parameters();
  auto slow = write(1, test::kParamSlow, 1);
  slow.timeout = 500ms;
  const auto ok = c.submit(slow).id;
  auto tight = write(1, test::kParamSlow, 1);
  tight.timeout = 100ms;
  const auto late = c.submit(tight).id;
  h.run_until(Time{2s});
  EXPECT_EQ(c.poll(ok).outcome->kind, OutcomeKind::done);
  const auto* o = c.poll(late).outcome;
  ASSERT_NE(o, nullptr);
  EXPECT_EQ(o->kind, OutcomeKind::timeout);
  EXPECT_EQ(o->finished - o->started, 100ms);
  EXPECT_EQ(c.counters().stray_replies, 1U);  // the late reply
}

}  // namespace
}  // namespace ibs::canlust
