// INTERBUS manual 5.1.1-5.1.3: the drive's state machine, exhaustively against an independent table.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "ibs/drivecom/device_state_machine.hpp"

namespace ibs::drivecom {
namespace {

// --- The oracle, written from 5.1.2 and 5.1.3 without the production tables --------------------

struct Expected {
  State state;
  std::vector<int> transitions;
};

Expected oracle(State s, unsigned w, bool prev7, bool estop_automatic, bool stopped) {
  const bool block_power = (w & 0x2U) == 0;                    // X X X 0 X
  const bool estop = (w & 0x2U) != 0 && (w & 0x4U) == 0;       // X X 0 1 X
  const bool shutdown = (w & 0x7U) == 0x6U;                    // X X 1 1 0
  const bool power_on = (w & 0x7U) == 0x7U;                    // X X 1 1 1
  const bool enable = (w & 0xFU) == 0xFU;                      // X 1 1 1 1
  const bool disable = (w & 0xFU) == 0x7U;                     // X 0 1 1 1
  bool reset = s == State::fault && !prev7 && (w & 0x80U) != 0;  // 0 -> 1 of bit 7
  Expected e{s, {}};
  for (int guard = 0; guard < 10; ++guard) {
    State next = e.state;
    int t = 0;
    switch (e.state) {
      case State::not_ready: next = State::start_up_inhibit; t = 1; break;
      case State::start_up_inhibit:
        if (shutdown) { next = State::ready; t = 2; }
        break;
      case State::ready:
        if (power_on) { next = State::on; t = 3; }
        else if (block_power || estop) { next = State::start_up_inhibit; t = 7; }
        break;
      case State::on:
        if (enable) { next = State::enabled; t = 4; }
        else if (shutdown) { next = State::ready; t = 6; }
        else if (block_power || estop) { next = State::start_up_inhibit; t = 10; }
        break;
      case State::enabled:
        if (disable) { next = State::on; t = 5; }
        else if (shutdown) { next = State::ready; t = 8; }
        else if (block_power) { next = State::start_up_inhibit; t = 9; }
        else if (estop) { next = State::emergency_stop_active; t = 11; }
        break;
      case State::emergency_stop_active:
        if (block_power || (estop_automatic && stopped)) { next = State::start_up_inhibit; t = 12; }
        break;
      case State::fault_response_active: next = State::fault; t = 14; break;
      case State::fault:
        if (reset) { next = State::start_up_inhibit; t = 15; reset = false; }
        break;
    }
    if (t == 0) break;
    e.state = next;
    e.transitions.push_back(t);
  }
  return e;
}

// Bits 6 5 3 2 1 0 of each state from the table of 5.1.3, bits 4/5 from the control word.
Word oracle_bits(State s, unsigned w) {
  unsigned v = 0;
  switch (s) {
    case State::not_ready: v = 0x00; break;
    case State::start_up_inhibit: v = 0x40; break;
    case State::ready: v = 0x21; break;
    case State::on: v = 0x23; break;
    case State::enabled: v = 0x27; break;
    case State::fault: v = 0x08; break;
    case State::fault_response_active: v = 0x0F; break;
    case State::emergency_stop_active: v = 0x07; break;
  }
  v |= ((w >> 1U) & 1U) << 4U;                                              // bit 4 = 0: block power received
  if (s != State::emergency_stop_active) v |= ((w >> 2U) & 1U) << 5U;      // bit 5 = 0: e-stop received
  return static_cast<Word>(v);
}

constexpr std::array<State, kStateCount> kAllStates{
    State::not_ready, State::start_up_inhibit, State::ready, State::on, State::enabled,
    State::fault, State::fault_response_active, State::emergency_stop_active};

void exhaustive(EmergencyStopExit exit, bool stopped) {
  const bool automatic = exit == EmergencyStopExit::automatic_when_stopped;
  for (const State s : kAllStates) {
    for (unsigned w = 0; w <= 0xFFFF; ++w) {
      for (const bool prev7 : {false, true}) {
        DeviceStateMachine m(exit);
        m.force(s, prev7 ? Word{0x0080} : Word{0x0000});
        DeviceInputs in;
        in.control = static_cast<Word>(w);
        in.stopped = stopped;
        const SampleResult r = m.sample(in);
        const Expected e = oracle(s, w, prev7, automatic, stopped);
        ASSERT_EQ(r.state, e.state) << to_string(s) << " word " << std::hex << w << " prev7 " << prev7;
        ASSERT_EQ(r.count, e.transitions.size()) << to_string(s) << " word " << std::hex << w;
        for (std::size_t i = 0; i < e.transitions.size(); ++i) {
          ASSERT_EQ(r.transition(i), e.transitions[i]) << to_string(s) << " word " << std::hex << w;
        }
        ASSERT_EQ(m.state_bits(), oracle_bits(e.state, w)) << to_string(s) << " word " << std::hex << w;
      }
    }
  }
}

TEST(DeviceStateMachine, ExhaustiveMc6000EveryStateEveryWordBothBit7Histories) {
  exhaustive(EmergencyStopExit::on_block_power_only, false);
  exhaustive(EmergencyStopExit::on_block_power_only, true);
}

TEST(DeviceStateMachine, ExhaustiveVf1000EveryStateEveryWordBothBit7Histories) {
  exhaustive(EmergencyStopExit::automatic_when_stopped, false);
  exhaustive(EmergencyStopExit::automatic_when_stopped, true);
}

// --- Named behaviours ----------------------------------------------------------------------------

TEST(DeviceStateMachine, StartUpTableOf534) {
  DeviceStateMachine m(EmergencyStopExit::on_block_power_only, State::start_up_inhibit);
  EXPECT_EQ(m.sample({.control = 0x0000}).state, State::start_up_inhibit);
  EXPECT_EQ(m.state_bits(), 0x0040);
  auto r = m.sample({.control = 0x0006});
  EXPECT_EQ(r.state, State::ready);
  EXPECT_EQ(m.state_bits(), 0x0031);
  r = m.sample({.control = 0x000F});
  ASSERT_EQ(r.count, 2);  // READY + ENABLE reaches ENABLED in one sample
  EXPECT_EQ(r.transition(0), 3);
  EXPECT_EQ(r.transition(1), 4);
  EXPECT_EQ(m.state_bits(), 0x0037);
}

TEST(DeviceStateMachine, NotReadyUntilInitialised) {
  DeviceStateMachine m(EmergencyStopExit::automatic_when_stopped);
  DeviceInputs in{.control = 0x0006, .initialised = false};
  EXPECT_EQ(m.sample(in).state, State::not_ready);
  EXPECT_EQ(m.state_bits() & 0x4F, 0x00);
  in.initialised = true;
  const auto r = m.sample(in);
  EXPECT_EQ(r.state, State::ready);  // 1 then 2 with SHUTDOWN already waiting
  EXPECT_EQ(r.transition(0), 1);
}

TEST(DeviceStateMachine, FaultFromEveryStateThroughFaultResponseActive) {
  for (const State s : kAllStates) {
    if (s == State::fault || s == State::fault_response_active) continue;
    DeviceStateMachine m(EmergencyStopExit::on_block_power_only, s);
    DeviceInputs in{.control = 0x000F, .fault_present = true, .fault_reaction_done = false};
    auto r = m.sample(in);
    ASSERT_EQ(r.state, State::fault_response_active) << to_string(s);
    EXPECT_EQ(r.transition(0), 13);
    EXPECT_EQ(m.state_bits() & 0x4F, 0x0F);
    r = m.sample(in);  // the reaction is still running
    EXPECT_EQ(r.state, State::fault_response_active);
    EXPECT_EQ(r.count, 0);
    in.fault_reaction_done = true;
    r = m.sample(in);
    EXPECT_EQ(r.state, State::fault);
    EXPECT_EQ(r.transition(0), 14);
  }
}

TEST(DeviceStateMachine, ResetFaultNeedsAnEdgeAndTheCauseGone) {
  DeviceStateMachine m(EmergencyStopExit::on_block_power_only, State::fault);
  DeviceInputs in{.control = 0x0080, .fault_present = true};
  EXPECT_EQ(m.sample(in).state, State::fault);  // edge, but the cause is still there
  in.fault_present = false;
  EXPECT_EQ(m.sample(in).state, State::fault);  // cause gone, but bit 7 is only a level now
  in.control = 0x0000;
  EXPECT_EQ(m.sample(in).state, State::fault);
  in.control = 0x0080;
  const auto r = m.sample(in);
  EXPECT_EQ(r.state, State::start_up_inhibit);
  EXPECT_EQ(r.transition(0), 15);
}

TEST(DeviceStateMachine, Vf1000EmergencyStopFallsToStartUpInhibitOnceStopped) {
  DeviceStateMachine m(EmergencyStopExit::automatic_when_stopped, State::enabled);
  DeviceInputs in{.control = 0x000B, .stopped = false};
  EXPECT_EQ(m.sample(in).state, State::emergency_stop_active);
  EXPECT_EQ(m.sample(in).state, State::emergency_stop_active);  // still ramping down
  in.stopped = true;
  const auto r = m.sample(in);
  EXPECT_EQ(r.state, State::start_up_inhibit);
  EXPECT_EQ(r.transition(0), 12);
}

TEST(DeviceStateMachine, Mc6000EmergencyStopStaysUntilBlockPower) {
  DeviceStateMachine m(EmergencyStopExit::on_block_power_only, State::enabled);
  DeviceInputs in{.control = 0x000B, .stopped = true};
  EXPECT_EQ(m.sample(in).state, State::emergency_stop_active);
  in.control = 0x000F;  // even ENABLE does not leave it (no transition 16 in Profile 20)
  EXPECT_EQ(m.sample(in).state, State::emergency_stop_active);
  EXPECT_EQ(m.state_bits(), 0x0017);
  in.control = 0x0000;
  const auto r = m.sample(in);
  EXPECT_EQ(r.state, State::start_up_inhibit);
  EXPECT_EQ(r.transition(0), 12);
}

TEST(DeviceStateMachine, PowerOnClearsBit7History) {
  DeviceStateMachine m(EmergencyStopExit::on_block_power_only, State::fault);
  m.sample({.control = 0x0080});  // leaves FAULT
  m.power_on();
  EXPECT_EQ(m.state(), State::not_ready);
  EXPECT_EQ(m.last_control(), 0);
}

// sample()'s lookup (detail::kChainLut) against the general loop (sample_general): two machines,
// the same random inputs -- control words mostly the start-up's and the commands', sometimes any
// word; random faults, reactions, standstill, enable locks, power-ons and forced states -- the
// same result, state and last control word after every sample.
TEST(DeviceStateMachineShortcut, SampleEqualsTheGeneralLoop) {
  constexpr std::array<Word, 8> kWords{0x0000, 0x0002, 0x0006, 0x0007, 0x000F, 0x0080, 0x0086, 0x008F};
  for (const auto exit : {EmergencyStopExit::on_block_power_only, EmergencyStopExit::automatic_when_stopped}) {
    for (std::uint32_t seed = 1; seed <= 60; ++seed) {
      std::mt19937 rng(seed);
      const auto initial = static_cast<State>(rng() % kStateCount);
      DeviceStateMachine fast(exit, initial), general(exit, initial);
      for (int i = 0; i < 3000; ++i) {
        const auto r = static_cast<unsigned>(rng());
        if (r % 97 == 0) {
          fast.power_on();
          general.power_on();
        } else if (r % 89 == 0) {
          const auto s = static_cast<State>(rng() % kStateCount);
          const auto w = static_cast<Word>(rng());
          fast.force(s, w);
          general.force(s, w);
        }
        DeviceInputs in;
        in.control = (r >> 8) % 4 == 0 ? static_cast<Word>(rng()) : kWords[(r >> 10) % kWords.size()];
        in.initialised = (r >> 13) % 8 != 0;
        in.fault_present = (r >> 16) % 16 == 0;
        in.fault_reaction_done = (r >> 20) % 4 != 0;
        in.stopped = (r >> 22) % 3 != 0;
        in.enable_locked = (r >> 24) % 8 == 0;
        const SampleResult a = fast.sample(in);
        const SampleResult b = general.sample_general(in);
        ASSERT_EQ(a.packed, b.packed) << "seed " << seed << " sample " << i;
        ASSERT_EQ(a.count, b.count) << "seed " << seed << " sample " << i;
        ASSERT_EQ(a.state, b.state) << "seed " << seed << " sample " << i;
        ASSERT_EQ(fast.state(), general.state()) << "seed " << seed << " sample " << i;
        ASSERT_EQ(fast.last_control(), general.last_control()) << "seed " << seed << " sample " << i;
      }
    }
  }
}

}  // namespace
}  // namespace ibs::drivecom
