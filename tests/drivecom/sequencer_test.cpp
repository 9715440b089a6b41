// The master side of DRIVECOM Profile 20 against the device side, cycle by cycle.
#include <gtest/gtest.h>

#include <vector>

#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/drivecom/sequencer.hpp"

namespace ibs::drivecom {
namespace {

constexpr std::array<State, kStateCount> kAllStates{
    State::not_ready, State::start_up_inhibit, State::ready, State::on, State::enabled,
    State::fault, State::fault_response_active, State::emergency_stop_active};
constexpr std::array<Target, 4> kAllTargets{Target::start_up_inhibit, Target::ready, Target::on,
                                            Target::enabled};

// A drive on a perfect bus: the master's word reaches it in the next sample, its status word
// reaches the master in the next cycle (the trace timing convention).
struct Loop {
  explicit Loop(EmergencyStopExit exit, State initial, SequencerConfig cfg = SequencerConfig::defaults())
      : device(exit, initial), seq(cfg) {
    status = status_word(initial, 0, {});
  }
  // Returns the control word sent this cycle.
  Word cycle() {
    const State seen_state = decode_state(status).value_or(State::not_ready);
    const Word control = seq.step(status, now);
    // Invariants every cycle: ENABLE/DISABLE (POWER-ON) never while START-UP INHIBIT or NOT READY
    // is seen (SHUTDOWN is never skipped), and never ENABLE out of FAULT.
    const Command c = decode_command(control);
    if (seen_state == State::start_up_inhibit || seen_state == State::not_ready) {
      EXPECT_TRUE(c != Command::enable && c != Command::disable) << "skipped SHUTDOWN, sent " << std::hex << control;
    }
    if (seen_state == State::fault || seen_state == State::fault_response_active) {
      EXPECT_NE(c, Command::enable) << "ENABLE out of FAULT";
    }
    sent.push_back(control);
    DeviceInputs in = inputs;
    in.control = control;
    device.sample(in);
    status = status_word(device.state(), device.last_control(), {});
    now += 1ms;
    return control;
  }
  void run(int cycles) {
    for (int i = 0; i < cycles; ++i) cycle();
  }
  DeviceStateMachine device;
  Sequencer seq;
  DeviceInputs inputs{};
  Word status = 0;
  Time now{0};
  std::vector<Word> sent;
};

TEST(Sequencer, StartUpSequenceOf534) {
  Sequencer seq;
  seq.request(Target::enabled, 0ms);
  EXPECT_EQ(seq.step(0x0240, 1ms), 0x0006);  // START-UP INHIBIT: SHUTDOWN
  EXPECT_EQ(seq.step(0x0240, 2ms), 0x0006);
  EXPECT_EQ(seq.step(0x0231, 3ms), 0x000F);  // READY: ENABLE
  EXPECT_EQ(seq.step(0x0231, 4ms), 0x000F);
  EXPECT_EQ(seq.report().phase, Phase::moving);
  EXPECT_EQ(seq.step(0x0237, 5ms), 0x000F);
  EXPECT_EQ(seq.report().phase, Phase::reached);
}

TEST(Sequencer, IdleSendsBlockPower) {
  Sequencer seq;
  EXPECT_EQ(seq.step(0x0240, 0ms), 0x0000);
  EXPECT_EQ(seq.report().phase, Phase::idle);
}

TEST(Sequencer, ReachesEveryTargetFromEveryStateIncludingFault) {
  for (const auto exit : {EmergencyStopExit::on_block_power_only, EmergencyStopExit::automatic_when_stopped}) {
    for (const State from : kAllStates) {
      for (const Target target : kAllTargets) {
        Loop loop(exit, from);
        loop.inputs.stopped = false;  // e-stop exits only through BLOCK POWER
        loop.seq.request(target, loop.now);
        int cycles = 0;
        while (loop.seq.report().phase != Phase::reached && cycles < 500) {
          loop.cycle();
          ++cycles;
        }
        ASSERT_EQ(loop.seq.report().phase, Phase::reached)
            << to_string(from) << " -> " << to_string(target) << ": " << describe(loop.seq.report());
        EXPECT_EQ(loop.device.state(), target_state(target));
        // The shortest documented path: never more than 4 transitions, bounded by the reset pulse.
        EXPECT_LE(cycles, 60) << to_string(from) << " -> " << to_string(target);
        // It holds the state afterwards.
        loop.run(20);
        EXPECT_EQ(loop.device.state(), target_state(target));
        EXPECT_EQ(loop.seq.report().phase, Phase::reached);
      }
    }
  }
}

TEST(Sequencer, ResetFaultIsARisingEdgeRepeatedAsAPulse) {
  Loop loop(EmergencyStopExit::on_block_power_only, State::fault);
  loop.inputs.fault_present = true;  // the cause is still there: the drive stays in FAULT
  loop.seq.request(Target::enabled, loop.now);
  loop.run(200);
  EXPECT_EQ(loop.device.state(), State::fault);
  EXPECT_EQ(loop.seq.report().transition, 15);
  // bit 7: high 50 cycles, low 50, high 50 ... starting with a rising edge from 0.
  int edges = 0;
  Word prev = 0;
  for (const Word w : loop.sent) {
    if (reset_fault_edge(prev, w)) ++edges;
    EXPECT_EQ(w & 0x000FU, 0U);  // nothing but bit 7 while in FAULT
    prev = w;
  }
  EXPECT_EQ(edges, 2);
  loop.inputs.fault_present = false;
  for (int i = 0; i < 200 && loop.seq.report().phase != Phase::reached; ++i) loop.cycle();
  EXPECT_EQ(loop.device.state(), State::enabled);
}

TEST(Sequencer, ResetPulseIsHighThenLowThenANewEdge) {
  Sequencer seq;
  SequencerConfig cfg = SequencerConfig::defaults();
  seq.request(Target::enabled, 0ms);
  Word w = seq.step(0x0208, 0ms);
  EXPECT_EQ(w, 0x0080);  // edge from the previous 0
  w = seq.step(0x0208, 1ms);
  EXPECT_EQ(w, 0x0080);  // held high for the pulse length
  w = seq.step(0x0208, cfg.reset_pulse + 1ms);
  EXPECT_EQ(w, 0x0000);  // then low
  w = seq.step(0x0208, 2 * cfg.reset_pulse + 2ms);
  EXPECT_EQ(w, 0x0080);  // and a new rising edge
}

TEST(Sequencer, EmergencyStopWhileEnabledIsSentAtOnce) {
  for (const auto exit : {EmergencyStopExit::on_block_power_only, EmergencyStopExit::automatic_when_stopped}) {
    Loop loop(exit, State::start_up_inhibit);
    loop.seq.request(Target::enabled, loop.now);
    loop.run(10);
    ASSERT_EQ(loop.device.state(), State::enabled);
    loop.inputs.stopped = false;
    loop.seq.request_emergency_stop(loop.now);
    const Word w = loop.cycle();
    EXPECT_EQ(decode_command(w), Command::emergency_stop);
    EXPECT_EQ(loop.device.state(), State::emergency_stop_active);
    loop.run(3);
    EXPECT_EQ(loop.seq.report().phase, Phase::reached);
    EXPECT_EQ(loop.device.state(), State::emergency_stop_active);
    loop.inputs.stopped = true;  // the motor has come to rest
    loop.run(3);
    EXPECT_EQ(loop.device.state(), exit == EmergencyStopExit::automatic_when_stopped
                                       ? State::start_up_inhibit
                                       : State::emergency_stop_active);
    EXPECT_EQ(loop.seq.report().phase, Phase::reached);
    EXPECT_EQ(decode_command(loop.sent.back()), Command::emergency_stop);
    // A new target leaves it through BLOCK POWER (12) and SHUTDOWN.
    loop.seq.request(Target::enabled, loop.now);
    loop.run(10);
    EXPECT_EQ(loop.device.state(), State::enabled);
  }
}

TEST(Sequencer, BlockPowerIsSentAtOnceFromEveryState) {
  for (const State from : {State::ready, State::on, State::enabled, State::emergency_stop_active}) {
    Loop loop(EmergencyStopExit::on_block_power_only, from);
    loop.seq.request(Target::enabled, loop.now);
    loop.seq.request_block_power(loop.now);
    const Word w = loop.cycle();
    EXPECT_EQ(decode_command(w), Command::block_power);
    EXPECT_EQ(loop.device.state(), State::start_up_inhibit) << to_string(from);
    loop.cycle();
    EXPECT_EQ(loop.seq.report().phase, Phase::reached);
  }
}

struct StuckCase {
  State stuck;
  Goal goal;
  Target target;
  std::uint8_t transition;
  Word command;
};

TEST(Sequencer, DeviceThatNeverAnswersTimesOutOnEachTransitionAndSaysWhich) {
  const std::vector<StuckCase> cases{
      {State::not_ready, Goal::target, Target::enabled, 1, 0x0006},
      {State::start_up_inhibit, Goal::target, Target::enabled, 2, 0x0006},
      {State::ready, Goal::target, Target::enabled, 3, 0x000F},
      {State::on, Goal::target, Target::enabled, 4, 0x000F},
      {State::enabled, Goal::target, Target::on, 5, 0x0007},
      {State::on, Goal::target, Target::ready, 6, 0x0006},
      {State::ready, Goal::target, Target::start_up_inhibit, 7, 0x0000},
      {State::enabled, Goal::target, Target::ready, 8, 0x0006},
      {State::enabled, Goal::target, Target::start_up_inhibit, 9, 0x0000},
      {State::on, Goal::target, Target::start_up_inhibit, 10, 0x0000},
      {State::enabled, Goal::emergency_stop, Target::enabled, 11, 0x0002},
      {State::emergency_stop_active, Goal::target, Target::enabled, 12, 0x0000},
      {State::fault_response_active, Goal::target, Target::enabled, 14, 0x0000},
  };
  // A separate timeout for every transition: 10 ms times its number.
  SequencerConfig cfg = SequencerConfig::defaults();
  for (std::size_t i = 0; i < cfg.transition_timeout.size(); ++i) {
    cfg.transition_timeout[i] = std::chrono::milliseconds(10 * static_cast<int>(i));
  }
  for (const auto& c : cases) {
    Sequencer seq(cfg);
    const Word status = status_word(c.stuck, c.command, {});
    if (c.goal == Goal::emergency_stop) {
      seq.request_emergency_stop(0ms);
    } else {
      seq.request(c.target, 0ms);
    }
    const Duration limit = cfg.transition_timeout[c.transition];
    Time now{0};
    for (; now <= limit; now += 1ms) {
      EXPECT_EQ(seq.step(status, now), c.command) << "transition " << int(c.transition);
      ASSERT_EQ(seq.report().phase, Phase::moving) << "transition " << int(c.transition) << " failed early at "
                                                   << now.count();
    }
    seq.step(status, now);
    const Report& r = seq.report();
    ASSERT_EQ(r.phase, Phase::failed) << int(c.transition);
    EXPECT_EQ(r.failure, Failure::timeout);
    EXPECT_EQ(r.transition, c.transition);
    EXPECT_EQ(r.state_seen, c.stuck);
    EXPECT_EQ(r.failed_command, c.command);
    EXPECT_EQ(r.command_sent, 0x0000) << "BLOCK POWER once failed";
    EXPECT_GT(r.waited, limit);
    EXPECT_EQ(r.timeout, limit);
    const std::string why = describe(r);
    EXPECT_NE(why.find("transition " + std::to_string(c.transition) + " ("), std::string::npos) << why;
    EXPECT_NE(why.find("did not happen"), std::string::npos) << why;
    EXPECT_NE(why.find(std::string(to_string(c.stuck))), std::string::npos) << why;
  }
}

TEST(Sequencer, StuckInFaultTimesOutOnTransition15) {
  SequencerConfig cfg = SequencerConfig::defaults();
  cfg.transition_timeout[15] = 300ms;
  Sequencer seq(cfg);
  seq.request(Target::enabled, 0ms);
  Time now{0};
  while (seq.report().phase != Phase::failed && now < 1s) {
    seq.step(0x0208, now);
    now += 1ms;
  }
  EXPECT_EQ(seq.report().failure, Failure::timeout);
  EXPECT_EQ(seq.report().transition, 15);
  EXPECT_EQ(now, 302ms);
  EXPECT_NE(describe(seq.report()).find("transition 15 (FAULT -> START-UP INHIBIT) did not happen"),
            std::string::npos)
      << describe(seq.report());
}

TEST(Sequencer, TimerRestartsForEachTransition) {
  SequencerConfig cfg = SequencerConfig::defaults();
  cfg.transition_timeout[2] = 50ms;
  cfg.transition_timeout[3] = 50ms;
  Sequencer seq(cfg);
  seq.request(Target::enabled, 0ms);
  Time now{0};
  for (; now < 40ms; now += 1ms) seq.step(0x0240, now);  // 40 ms on transition 2
  for (; now < 80ms; now += 1ms) seq.step(0x0231, now);  // 40 ms on transition 3
  EXPECT_EQ(seq.report().phase, Phase::moving) << describe(seq.report());
  EXPECT_EQ(seq.report().transition, 3);
}

TEST(Sequencer, FaultWhileEnabledIsReportedAndNotResetBehindTheUsersBack) {
  Loop loop(EmergencyStopExit::on_block_power_only, State::start_up_inhibit);
  loop.seq.request(Target::enabled, loop.now);
  loop.run(10);
  ASSERT_EQ(loop.seq.report().phase, Phase::reached);
  loop.inputs.fault_present = true;
  loop.run(3);
  EXPECT_EQ(loop.device.state(), State::fault);
  EXPECT_EQ(loop.seq.report().phase, Phase::failed);
  EXPECT_EQ(loop.seq.report().failure, Failure::fault);
  EXPECT_NE(describe(loop.seq.report()).find("faulted"), std::string::npos);
  loop.inputs.fault_present = false;
  const std::size_t before = loop.sent.size();
  loop.run(200);
  for (std::size_t i = before; i < loop.sent.size(); ++i) {
    EXPECT_EQ(loop.sent[i] & 0x008FU, 0U) << "no reset and no command without a new request";
  }
  EXPECT_EQ(loop.device.state(), State::fault);
  loop.seq.request(Target::enabled, loop.now);
  loop.run(10);
  EXPECT_EQ(loop.device.state(), State::enabled);
  EXPECT_EQ(loop.seq.report().phase, Phase::reached);
}

TEST(Sequencer, DriveLeavingTheTargetIsReported) {
  Sequencer seq;
  seq.request(Target::enabled, 0ms);
  seq.step(0x0237, 0ms);
  ASSERT_EQ(seq.report().phase, Phase::reached);
  seq.step(0x0270, 1ms);  // dropped to START-UP INHIBIT
  EXPECT_EQ(seq.report().phase, Phase::failed);
  EXPECT_EQ(seq.report().failure, Failure::left_target);
}

TEST(Sequencer, InvalidStatusWordCountsAgainstTheTimeout) {
  Sequencer seq;
  seq.request(Target::enabled, 0ms);
  seq.step(0x0240, 0ms);
  Time now = 1ms;
  for (; now < 1s && seq.report().phase != Phase::failed; now += 1ms) seq.step(0x0001, now);
  EXPECT_EQ(seq.report().failure, Failure::invalid_status);
  EXPECT_NE(describe(seq.report()).find("matches no DRIVECOM state"), std::string::npos);
}

TEST(Sequencer, ApplicationBitsRideAlongButNeverTheStateMachineBits) {
  SequencerConfig cfg = SequencerConfig::defaults();
  cfg.application_bits = 0xFFFF;  // tries to set every bit
  Sequencer seq(cfg);
  seq.request(Target::ready, 0ms);
  const Word w = seq.step(0x0240, 0ms);
  EXPECT_EQ(w & 0x008FU, 0x0006U);  // SHUTDOWN, bit 7 low
  EXPECT_EQ(w & 0x0700U, 0U);       // reserved bits 8-10 stay 0 (5.1.2)
  EXPECT_EQ(w & 0xF870U, 0xF870U);
}

TEST(Sequencer, RestartForgetsEverything) {
  Sequencer seq;
  seq.request(Target::enabled, 0ms);
  seq.step(0x0240, 0ms);
  seq.restart();
  EXPECT_EQ(seq.report().phase, Phase::idle);
  EXPECT_EQ(seq.step(0x0240, 1ms), 0x0000);
}

TEST(Sequencer, TargetsAreNamedByTheirStatesKeys) {
  for (const Target t : kTargets) {
    EXPECT_EQ(key(t), key(target_state(t)));
    EXPECT_EQ(target_named(key(t)), t);
  }
  EXPECT_EQ(kTargetKeys, (std::array<std::string_view, 4>{"start-up-inhibit", "ready", "on", "enabled"}));
  EXPECT_EQ(target_named("fault"), std::nullopt) << "a state, but no target";
}

// A sequencer keeps the timeouts it was built with, whether they are the defaults (which it does
// not copy) or its own (one table that copies share).
TEST(SequencerConfigured, EveryTransitionHasTheTimeoutItWasBuiltWith) {
  SequencerConfig own = SequencerConfig::defaults();
  for (std::size_t i = 0; i < own.transition_timeout.size(); ++i) {
    own.transition_timeout[i] = std::chrono::milliseconds(7 * static_cast<int>(i) + 1);
  }
  const SequencerConfig defaults = SequencerConfig::defaults();
  const Sequencer built_plain;
  const Sequencer built_with_defaults(defaults);
  const Sequencer built_with_own(own);
  for (std::uint8_t n = 0; n < 16; ++n) {
    EXPECT_EQ(built_plain.transition_timeout(n), defaults.transition_timeout[n]) << int(n);
    EXPECT_EQ(built_with_defaults.transition_timeout(n), defaults.transition_timeout[n]) << int(n);
    EXPECT_EQ(built_with_own.transition_timeout(n), own.transition_timeout[n]) << int(n);
  }
}

// Steps START-UP INHIBIT (0240H) until the request to ENABLED fails; returns when it failed.
Time time_out_on_transition_2(Sequencer& seq) {
  seq.request(Target::enabled, 0ms);
  Time now{0};
  for (; now < 20s && seq.report().phase != Phase::failed; now += 1ms) seq.step(0x0240, now);
  EXPECT_EQ(seq.report().failure, Failure::timeout);
  EXPECT_EQ(seq.report().transition, 2);
  return now;
}

TEST(SequencerConfigured, ACopyKeepsItsTimeoutsAfterTheOriginalIsGone) {
  SequencerConfig cfg = SequencerConfig::defaults();
  cfg.transition_timeout[2] = 30ms;
  Sequencer copy;
  {
    const Sequencer original(cfg);
    copy = original;
  }
  // Failed in the step after 30 ms had been waited for (the last step's `now` is 31 ms, the loop
  // stops one later).
  EXPECT_EQ(time_out_on_transition_2(copy), 32ms);
  Sequencer copied_again(copy);
  EXPECT_EQ(time_out_on_transition_2(copied_again), 32ms);
  // A plain sequencer assigned over it brings the defaults back.
  copied_again = Sequencer{};
  EXPECT_EQ(time_out_on_transition_2(copied_again), SequencerConfig::defaults().transition_timeout[2] + 2ms);
}

TEST(SequencerConfigured, AResetPulseOfItsOwnWithTheDefaultTimeouts) {
  SequencerConfig cfg = SequencerConfig::defaults();
  cfg.reset_pulse = 20ms;
  Sequencer seq(cfg);
  seq.request(Target::enabled, 0ms);
  EXPECT_EQ(seq.step(0x0208, 0ms), 0x0080);   // the edge
  EXPECT_EQ(seq.step(0x0208, 19ms), 0x0080);  // high for 20 ms, not the default's 50
  EXPECT_EQ(seq.step(0x0208, 20ms), 0x0000);  // then low
  EXPECT_EQ(seq.step(0x0208, 40ms), 0x0080);  // and a new edge
  EXPECT_EQ(seq.transition_timeout(15), SequencerConfig::defaults().transition_timeout[15]);
}

}  // namespace
}  // namespace ibs::drivecom
