// ibs's master on a controller board (docs/board.md): the DDI bus adapter (master/ddi) and the
// runner of `ibs master --board` (board/) against ibs's virtual board, stepped (one bus cycle per
// exchange) unless a test says otherwise. What the virtual board never does by itself -- plug &
// play on, a lost or misaddressed PCP confirmation -- the tests make it do through the wrapped DDI
// calls (ddi_shim.hpp).
#include "rig.hpp"

namespace ibs::test {
namespace {

// ---------------------------------------------------------------------------------------------
// Bring-up and shutdown

TEST_F(Board, BringsTheBoardUpAndDownAsABoardExpects) {
  {
    Rig rig(scenario_file("board_up.toml", kServo + kFan, "", ""));
    ASSERT_TRUE(rig.up());
    EXPECT_EQ(rig.board->cycle_time(), 726us);  // Read_Value 2231H: the formula's, as `ibs run`
    EXPECT_EQ(rig.board->device_number(0), 0x0100);
    EXPECT_EQ(rig.board->device_number(1), 0x0200);
    rig.cycle();
    EXPECT_EQ(rig.board->bus().diagnostic_status(), DIAG_RUN | DIAG_ACTIVE | DIAG_READY);
    EXPECT_TRUE(rig.last.data_valid);
    EXPECT_FALSE(rig.board->close());
    EXPECT_FALSE(rig.board->close());  // once
  }
  EXPECT_TRUE(fresh_board());  // both nodes closed: the board stopped
}

TEST_F(Board, NoBoardOrANodeThatWillNotOpenIsAClearErrorAndNothingStaysOpen) {
  const board::MasterRing ring = board::make_master_ring(sim::default_scenario());
  const struct {
    const char* board;
    const char* message;
  } cases[] = {
      {"IBB2N1", "DDI_DevOpenNode(IBB2N1_D): ERR_INVLD_BOARD_NUM (0080H): no such board"},
      {"IBB1N3", "DDI_DevOpenNode(IBB1N3_D): ERR_INVLD_NODE_NUM (0081H)"},
      {"COM1", "DDI_DevOpenNode(COM1_D): ERR_INVLD_PARAM (008DH): not a node name"},
  };
  for (const auto& c : cases) {
    master::DdiBoardOptions o;
    o.board = c.board;
    auto b = DdiBoard::open(ring.config, o);
    ASSERT_FALSE(b) << c.board;
    EXPECT_EQ(b.error().code, ErrorCode::board_call_failed);
    EXPECT_EQ(b.error().message.rfind(c.message, 0), 0U) << b.error().message;
  }
  // A board that cannot start (its scenario is missing): ERR_NODE_NOT_READY.
  board_runs("/nonexistent/board.toml");
  auto b = DdiBoard::open(ring.config);
  ASSERT_FALSE(b);
  EXPECT_NE(b.error().message.find("DDI_DevOpenNode(IBB1N1_D): ERR_NODE_NOT_READY (0087H)"), std::string::npos);
  unsetenv("IBS_DDI_SCENARIO");
  EXPECT_TRUE(fresh_board());
  // Through the runner: the error, no summary.
  board::RunOptions o;
  o.board = "IBB2N1";
  o.clock = board::Clock::stepped;
  const board::RunResult r = board::run(sim::default_scenario(), o);
  EXPECT_FALSE(r.started);
  EXPECT_EQ(r.error.code, ErrorCode::board_call_failed);
}

TEST_F(Board, PlugAndPlayOnIsRefusedAndTheNodesAreClosed) {
  // The board answers Read_Value 2240H with 1: [8351][count][result][1][2240][value].
  shim::hooks().receive = [](IBDDIHND h, T_DDI_MXI_ACCESS* a) {
    const IBDDIRET r = __real_DDI_MXI_RcvMessage(h, a);
    if (r == ERR_OK && a->msgLength == 12 && a->msgBlk[0] == 0x83 && a->msgBlk[1] == 0x51 && a->msgBlk[8] == 0x22 &&
        a->msgBlk[9] == 0x40) {
      a->msgBlk[11] = 1;
    }
    return r;
  };
  auto b = DdiBoard::open(board::make_master_ring(sim::default_scenario()).config);
  ASSERT_FALSE(b);
  EXPECT_EQ(b.error().code, ErrorCode::board_plug_and_play);
  EXPECT_NE(b.error().message.find("plug & play mode (Read_Value 2240H = 1)"), std::string::npos)
      << b.error().message;
  shim::reset();
  EXPECT_TRUE(fresh_board());
}

TEST_F(Board, AConfigurationMismatchNamesTheDeviceAndIsRefused) {
  board_runs(scenario_file("board_ring.toml", kServo + kFan, ""));
  // The master's ring: two servos where the board has a servo and an inverter.
  const std::string two_servos =
      scenario_file("board_two_servos.toml", kServo + "[[device]]\nname = \"servo2\"\ntype = \"mc6000\"\n", "");
  auto b = DdiBoard::open(board::make_master_ring(sim::load_scenario(two_servos)).config);
  ASSERT_FALSE(b);
  EXPECT_EQ(b.error().code, ErrorCode::board_configuration_mismatch);
  EXPECT_NE(b.error().message.find("configuration mismatch at ring position 2 (device 0200H): the board has ID code "
                                   "33BH"),
            std::string::npos)
      << b.error().message;
  EXPECT_NE(b.error().message.find("the master's 'servo2' 4DBH"), std::string::npos) << b.error().message;
  EXPECT_TRUE(fresh_board());
  // A device more on the board's ring.
  board_runs(scenario_file("board_three.toml", kServo + kFan + "[[device]]\nname = \"pump\"\ntype = \"vf1000\"\n", ""));
  auto c = DdiBoard::open(board::make_master_ring(sim::load_scenario(two_servos)).config);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().message.find("the board's active configuration has 3 devices, the master's 2 (servo, servo2)"),
            std::string::npos)
      << c.error().message;
}

// ---------------------------------------------------------------------------------------------
// Faults the board reports: the master reacts as on the simulator, and enables nothing by itself

TEST_F(Board, ABoardThatFailsMidRunEndsTheRunEveryDeviceLostNothingReEnabled) {
  // The board's controller fails at 1.5 s (a master restart in the board's own file, which no
  // ibs master runs: SysFail); the master brings both drives up before.
  board_runs(scenario_file("board_sysfail.toml", kServo + kFan, R"(
[[timeline]]
at = "1500 ms"
master_restart = true
)"));
  const std::string path = scenario_file("board_sysfail_master.toml", kServo + kFan, R"(
[[timeline]]
at = "0 s"
device = "servo"
state = "enabled"

[[timeline]]
at = "0 s"
device = "fan"
state = "enabled"
)");
  board::RunOptions o;
  o.clock = board::Clock::stepped;
  o.duration = 3s;
  const board::RunResult r = board::run(sim::load_scenario(path), o);
  ASSERT_TRUE(r.started);
  EXPECT_EQ(r.error.code, ErrorCode::board_call_failed);
  EXPECT_NE(r.error.message.find("ERR_IBS_SYSFAIL (00A2H)"), std::string::npos) << r.error.message;
  const auto& f = r.summary.faults;
  EXPECT_TRUE(std::any_of(f.begin(), f.end(), [](const sim::FaultRecord& x) { return x.kind == "sysfail"; }));
  // The run ended at the failure.
  EXPECT_LT(r.summary.simulated, 1600ms);
  for (const sim::DeviceReport& d : r.summary.devices) {
    ASSERT_GE(d.states.size(), 2U) << d.name;
    // ENABLED before, NOT READY (every device lost) and the request failed: nothing enabled again.
    EXPECT_EQ(d.states[d.states.size() - 2].what, "NOT READY") << d.name;
    EXPECT_EQ(d.states.back().what.rfind("master: request failed", 0), 0U) << d.name;
    EXPECT_EQ(d.final_state, "NOT READY");
  }
  EXPECT_FALSE(r.shutdown.drives_safe);  // the bus was gone: nothing to stop it with
  EXPECT_TRUE(fresh_board());
}

TEST_F(Board, ASegmentSwitchedOffIsBypassedAndItsDriveIsNotReEnabledBehindTheUsersBack) {
  // The fan's bus watchdog: E-IBS (907-IBCOD 1) after 50 ms without a cycle.
  Rig rig(scenario_file("board_bsa.toml", kServo + kFan, "watchdog_ms = 50\nwatchdog_reaction = 1\n"));
  ASSERT_TRUE(rig.up());
  ASSERT_TRUE(rig.enable_all());
  ASSERT_TRUE(rig.board->bus().switch_segment(1, false));
  EXPECT_FALSE(rig.board->bus().switch_segment(2, false));  // no such device
  rig.cycles(3);
  EXPECT_TRUE(rig.saw(BoardEvent::Kind::segment_off));
  EXPECT_TRUE(rig.last.data_valid);            // the cycle is the servo's as ever
  EXPECT_FALSE(rig.last.link(1).data_valid);   // the fan's data is not there
  EXPECT_EQ(rig.board->bus().diagnostic_status() & DIAG_BSA, DIAG_BSA);
  rig.cycles(200);  // the fan's watchdog runs out meanwhile
  EXPECT_EQ(rig.seen(0), State::enabled);
  ASSERT_TRUE(rig.board->bus().switch_segment(1, true));
  rig.cycles(200);
  EXPECT_TRUE(rig.saw(BoardEvent::Kind::segment_on));
  // The fan comes back in FAULT; the master's request failed and it sends BLOCK POWER, no reset,
  // no ENABLE: the fan stays off until the user asks again.
  EXPECT_EQ(rig.driver(1).sequencer().report().phase, drivecom::Phase::failed);
  for (int k = 0; k < 500; ++k) {
    rig.cycle();
    const Word control = interbus::out_slice(rig.image, rig.ring.config.devices[1])[0];
    ASSERT_EQ(control & 0x0080U, 0U) << "fault reset at cycle " << k;
    ASSERT_NE(rig.seen(1), State::enabled) << "cycle " << k;
  }
  EXPECT_EQ(rig.seen(0), State::enabled);
}

TEST_F(Board, APeripheralFaultOfOneDriveIsItsModuleError) {
  Rig rig(scenario_file("board_pf.toml", kServo + kFan, R"(
[[timeline]]
at = "2 s"
device = "fan"
fault = "lost"
duration = "300 ms"
)"));
  ASSERT_TRUE(rig.up());
  ASSERT_TRUE(rig.enable_all(1900));
  ASSERT_TRUE(rig.until([&] { return rig.last.link(1).module_error; }, 2000));
  EXPECT_FALSE(rig.last.link(0).module_error);
  EXPECT_TRUE(rig.saw(BoardEvent::Kind::peripheral_fault));
  EXPECT_EQ(interbus::in_slice(rig.image, rig.ring.config.devices[1])[0], 0);  // a lost device reads 0
  ASSERT_TRUE(rig.until([&] { return !rig.last.link(1).module_error; }, 1000));
  EXPECT_TRUE(rig.saw(BoardEvent::Kind::peripheral_ok));
  rig.cycles(1000);
  // The fan vanished while ENABLED: the request failed and nothing brings it back on its own.
  EXPECT_EQ(rig.driver(1).sequencer().report().phase, drivecom::Phase::failed);
  EXPECT_NE(rig.seen(1), State::enabled);
  EXPECT_EQ(rig.seen(0), State::enabled);
}

TEST_F(Board, ABusErrorBurstMakesItsCyclesInvalid) {
  Rig rig(scenario_file("board_bus.toml", kServo + kFan, R"(
[[timeline]]
at = "1500 ms"
fault = "corrupt"
count = 4
)"));
  ASSERT_TRUE(rig.up());
  ASSERT_TRUE(rig.enable_all(1400));
  ASSERT_TRUE(rig.until([&] { return rig.t >= Time{1400ms}; }, 1500));
  int invalid = 0;
  for (int k = 0; k < 600; ++k) {
    rig.cycle();
    if (!rig.last.data_valid) ++invalid;
  }
  // 4 corrupted cycles and 5 of recovery (the scenario's default) at least; BUS then cleared.
  EXPECT_GE(invalid, 9);
  EXPECT_LE(invalid, 12);
  EXPECT_TRUE(rig.saw(BoardEvent::Kind::bus_error));
  EXPECT_TRUE(rig.saw(BoardEvent::Kind::bus_ok));
  EXPECT_TRUE(rig.last.data_valid);
  EXPECT_EQ(rig.seen(0), State::enabled);
  EXPECT_EQ(rig.seen(1), State::enabled);
}

// ---------------------------------------------------------------------------------------------
// PCP through the board's mailbox: the MC6000 driver's transactions, and how each fault ends one

TEST_F(Board, TheServosTransactionsRunThroughTheMailbox) {
  Rig rig(scenario_file("board_pcp.toml", kServo + kFan, ""));
  ASSERT_TRUE(rig.up());
  using devices::ParamKind;
  using devices::ParamOp;
  EXPECT_EQ(rig.transact(0, ParamOp::read, 85).kind, ParamKind::value);  // clears the power-on bit
  EXPECT_EQ(rig.transact(0, ParamOp::write, 409, 100).kind, ParamKind::written);
  const devices::ParamStatus read = rig.transact(0, ParamOp::read, 409);
  EXPECT_EQ(read.kind, ParamKind::value);
  EXPECT_EQ(read.value, 100);
  EXPECT_EQ(rig.transact(0, ParamOp::describe, 406).kind, ParamKind::description);
  EXPECT_EQ(rig.describe_last(0), "description IBCNF, USIGN8, EEPROM value, 0..4, default 2");
  // The PCP words of the master's image are not the board's: nothing went there.
  const auto pcp = interbus::pcp_out_slice(rig.image, rig.ring.config.devices[0]);
  EXPECT_TRUE(std::all_of(pcp.begin(), pcp.end(), [](Word w) { return w == 0; }));
}

TEST_F(Board, ANegativeConfirmationEndsTheTransactionAndTheNextWorks) {
  Rig rig(scenario_file("board_nak.toml", kServo, ""));
  ASSERT_TRUE(rig.up());
  using devices::ParamKind;
  using devices::ParamOp;
  ASSERT_EQ(rig.transact(0, ParamOp::read, 85).kind, ParamKind::value);
  EXPECT_EQ(rig.transact(0, ParamOp::write, 406, 99).kind, ParamKind::nak);  // 406-IBCNF 0..4
  EXPECT_EQ(rig.describe_last(0).rfind("negative confirmation: ", 0), 0U) << rig.describe_last(0);
  const devices::ParamStatus next = rig.transact(0, ParamOp::read, 406);
  EXPECT_EQ(next.kind, ParamKind::value);
  EXPECT_EQ(next.value, 2);
}

TEST_F(Board, AnAbortIndicationEndsTheTransactionAndTheNextWorks) {
  // The servo is away from 1 s to 2.5 s: the board resets the channel and says so (Abort
  // indication, reason 2) instead of confirming.
  Rig rig(scenario_file("board_abort.toml", kServo, R"(
[[timeline]]
at = "1 s"
device = "servo"
fault = "lost"
duration = "1500 ms"
)"));
  ASSERT_TRUE(rig.up());
  using devices::ParamKind;
  using devices::ParamOp;
  ASSERT_EQ(rig.transact(0, ParamOp::read, 406).kind, ParamKind::value);
  ASSERT_TRUE(rig.until([&] { return rig.t >= Time{1050ms}; }, 2000));
  EXPECT_EQ(rig.transact(0, ParamOp::read, 406).kind, ParamKind::aborted);
  EXPECT_EQ(rig.describe_last(0), "aborted (link reset)");
  rig.cycles(1600);  // back
  const devices::ParamStatus next = rig.transact(0, ParamOp::read, 406);
  EXPECT_EQ(next.kind, ParamKind::value);
  EXPECT_EQ(next.value, 2);
}

TEST_F(Board, AConfirmationThatNeverComesTimesOutAndTheNextWorks) {
  Rig rig(scenario_file("board_timeout.toml", kServo, ""));
  ASSERT_TRUE(rig.up());
  using devices::ParamKind;
  using devices::ParamOp;
  ASSERT_EQ(rig.transact(0, ParamOp::read, 85).kind, ParamKind::value);
  edit_next_read_confirmation([](T_DDI_MXI_ACCESS*) { return true; });
  const Time submitted = rig.t;
  EXPECT_EQ(rig.transact(0, ParamOp::read, 406).kind, ParamKind::timeout);
  EXPECT_EQ(rig.describe_last(0), "timeout (timeout)");
  EXPECT_GE(rig.t - submitted, 500ms);  // the driver's: 500 ms, or 240 bus cycles when longer
  const devices::ParamStatus next = rig.transact(0, ParamOp::read, 406);
  EXPECT_EQ(next.kind, ParamKind::value);
  EXPECT_EQ(next.value, 2);
}

TEST_F(Board, AConfirmationForAnUnknownInvokeIdEndsTheTransactionAndTheNextWorks) {
  Rig rig(scenario_file("board_invoke.toml", kServo, ""));
  ASSERT_TRUE(rig.up());
  using devices::ParamKind;
  using devices::ParamOp;
  ASSERT_EQ(rig.transact(0, ParamOp::read, 85).kind, ParamKind::value);
  edit_next_read_confirmation([](T_DDI_MXI_ACCESS* a) {
    a->msgBlk[4] ^= 0x5A;  // [8081][count][InvokeID, CR]...: another invoke ID
    return false;
  });
  EXPECT_EQ(rig.transact(0, ParamOp::read, 406).kind, ParamKind::timeout);
  EXPECT_EQ(rig.describe_last(0), "timeout (protocol error)");
  const devices::ParamStatus next = rig.transact(0, ParamOp::read, 406);
  EXPECT_EQ(next.kind, ParamKind::value);
  EXPECT_EQ(next.value, 2);
}

}  // namespace
}  // namespace ibs::test
