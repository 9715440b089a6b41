// Asynchronous loops (issue 37, 4): a board runs its bus cycle on its own clock, the application's
// loop on another, so that a loop reads the same bus cycle again or misses cycles. The sequencer's
// timeouts, the communication-word handshake and the PCP timeouts hold with the master's loop at a
// third of and at three times the board's cycle: stepped (the wrapped ReadWriteData runs the
// board's cycles at the pace a test wants, the same on any machine), and once in real time with
// the board's own thread.
#include "rig.hpp"

namespace ibs::test {
namespace {

using devices::ParamKind;
using devices::ParamOp;

struct Pace {
  const char* name;
  void (*install)();
  int thirds;  // the loop's period in thirds of the board's cycle
};
const Pace kPaces[] = {{"a third of the cycle", &master_three_times_as_fast, 1},
                       {"three cycles", &master_three_times_as_slow, 9}};

TEST_F(Board, TimeoutsAndTheHandshakeHoldWhateverTheLoopsPace) {
  for (const Pace& pace : kPaces) {
    SCOPED_TRACE(pace.name);
    shim::reset();
    // A 1 ms bus whose cycles are corrupted from 3 s for 400 ms: the drives see nothing then.
    Rig rig(scenario_file("board_async.toml", kServo + kFan, R"(
[[timeline]]
at = "3 s"
fault = "corrupt"
count = 400
)"));
    ASSERT_TRUE(rig.up());
    rig.period = Duration{1ms} * pace.thirds / 3;
    pace.install();
    // The communication word's handshake and PCP, at the pace.
    ASSERT_EQ(rig.transact(1, ParamOp::read, 85).kind, ParamKind::value);
    EXPECT_EQ(rig.transact(1, ParamOp::describe, 45).kind, ParamKind::description);
    EXPECT_EQ(rig.describe_last(1), "description VB2 [%], category 2, type 2, min 0000H, max 01F4H, default 00A0H");
    ASSERT_EQ(rig.transact(0, ParamOp::read, 85).kind, ParamKind::value) << rig.describe_last(0);
    // A PCP confirmation that never comes: the driver's timeout, 500 ms or 240 of the loop's
    // cycles when longer, in the loop's time -- not earlier, and at most the loop's next cycle
    // after it (the request goes out with the cycle after its submission).
    edit_next_read_confirmation([](T_DDI_MXI_ACCESS*) { return true; });
    const Time submitted = rig.t;
    EXPECT_EQ(rig.transact(0, ParamOp::read, 406).kind, ParamKind::timeout);
    const Duration timeout = std::max<Duration>(500ms, rig.period * 240);
    EXPECT_GE(rig.t - submitted, timeout);
    EXPECT_LE(rig.t - submitted, timeout + 2 * rig.period);
    const devices::ParamStatus next = rig.transact(0, ParamOp::read, 406);
    EXPECT_EQ(next.kind, ParamKind::value);
    EXPECT_EQ(next.value, 2);
    // The sequencer's transition timeout: both drives READY, then asked for ENABLED while the bus
    // carries nothing; neither answers, and each request fails after its 200 ms.
    for (std::size_t i = 0; i < 2; ++i) rig.driver(i).sequencer().request(drivecom::Target::ready, rig.t);
    ASSERT_TRUE(rig.until([&] { return rig.seen(0) == State::ready && rig.seen(1) == State::ready; }, 9000));
    ASSERT_LT(rig.t, Time{3s});
    ASSERT_TRUE(rig.until([&] { return rig.t >= Time{3010ms}; }, 9000));
    const Time asked = rig.t;
    for (std::size_t i = 0; i < 2; ++i) rig.driver(i).sequencer().request(drivecom::Target::enabled, asked);
    ASSERT_TRUE(rig.until([&] { return rig.driver(0).sequencer().report().phase == drivecom::Phase::failed; }, 9000));
    EXPECT_EQ(rig.driver(0).sequencer().report().failure, drivecom::Failure::timeout);
    EXPECT_GT(rig.t - asked, 200ms);
    EXPECT_LE(rig.t - asked, 200ms + 2 * rig.period);
    rig.cycles(3);
    EXPECT_EQ(rig.driver(1).sequencer().report().failure, drivecom::Failure::timeout);
    EXPECT_NE(rig.seen(0), State::enabled);
    EXPECT_NE(rig.seen(1), State::enabled);
    shim::reset();  // the board at its own pace again for the shutdown
  }
}

// In real time: the board's thread cycles every 726 us, the master's loop every 242 us or 2.178 ms
// on its own deadlines. Both drives come up and every transaction of the default scenario's first
// second and a half gets the value it gets on the simulator.
TEST_F(Board, InRealTimeBothDrivesComeUpAndEveryTransactionEndsAsOnTheSimulator) {
  setenv("IBS_DDI_MODE", "realtime", 1);
  sim::Scenario s = sim::default_scenario();
  for (const Duration period : {242us, 2178us}) {
    board::RunOptions o;
    o.period = period;
    o.duration = 1500ms;
    const board::RunResult r = board::run(s, o);
    ASSERT_TRUE(r.started) << r.error.message;
    EXPECT_FALSE(r.error) << r.error.message;
    for (const sim::DeviceReport& d : r.summary.devices) {
      std::vector<std::string> states;
      for (const sim::StateRecord& x : d.states) states.push_back(x.what);
      EXPECT_EQ(states, (std::vector<std::string>{"START-UP INHIBIT", "READY", "ENABLED"})) << d.name;
    }
    std::vector<std::string> results;
    for (const sim::TransactionRecord& t : r.summary.transactions) results.push_back(t.device + ": " + t.result);
    EXPECT_EQ(results, (std::vector<std::string>{
                           "mc6000: value 1 (USIGN8)",
                           "vf1000: value 0001H",
                           "mc6000: written (PCP Write confirmed)",
                           "vf1000: written 03E8H",
                           "mc6000: value 100 (USIGN16)",
                           "vf1000: value 03E8H",
                           "mc6000: description IBCNF, USIGN8, EEPROM value, 0..4, default 2",
                           "vf1000: description VB2 [%], category 2, type 2, min 0000H, max 01F4H, default 00A0H",
                       }))
        << "period " << period.count() << " ns";
    EXPECT_TRUE(r.shutdown.drives_safe);
  }
}

}  // namespace
}  // namespace ibs::test
