// Sequencer::step takes two shortcuts (the held target shown again; a drive moving along the
// target's path, step_path) that must decide exactly as the general decisions do
// (Sequencer::step_general, docs/performance.md "Issue 26"). Two sequencers, one through step()
// and one through step_general(), get the same random status words, requests, stop requests,
// restarts, application bits and cycle times; every word sent and every field of the report
// must be the same, bit for bit.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/drivecom/sequencer.hpp"

namespace ibs::drivecom {
namespace {

std::string differs(const Report& a, const Report& b) {
  if (a.goal != b.goal) return "goal";
  if (a.target != b.target) return "target";
  if (a.phase != b.phase) return "phase";
  if (a.failure != b.failure) return "failure";
  if (a.state_seen != b.state_seen) return "state_seen";
  if (a.status_seen != b.status_seen) return "status_seen";
  if (a.command_sent != b.command_sent) return "command_sent";
  if (a.failed_command != b.failed_command) return "failed_command";
  if (a.transition != b.transition) return "transition";
  if (a.waited != b.waited) return "waited";
  if (a.timeout != b.timeout) return "timeout";
  if (a.since != b.since) return "since";
  return {};
}

// The status word of a drive in state `s` (the state bits of 5.1.3 plus bit 9) or, now and
// then, any word at all.
Word status_for(State s, Word last_control, std::mt19937& rng) {
  if (rng() % 16 == 0) return static_cast<Word>(rng());
  return static_cast<Word>(status_word(s, last_control, {}) | (rng() % 4 == 0 ? 0x0400U : 0U));
}

// A run: a DRIVECOM device answers the words sent through step() (so that the run spends its
// time on paths and holds, where the shortcuts are), with random faults, power cycles, foreign
// words, requests and cycle times.
void run(std::uint32_t seed, EmergencyStopExit exit) {
  std::mt19937 rng(seed);
  SequencerConfig cfg = SequencerConfig::defaults();
  if (seed % 3 == 0) cfg.transition_timeout.fill(5ms);  // timeouts on the path as well
  Sequencer fast(cfg), general(cfg);
  DeviceStateMachine dev(exit, State::not_ready);
  Time now{0};
  bool fault = false;
  for (int i = 0; i < 4000; ++i) {
    const auto r = static_cast<unsigned>(rng() % 100);
    if (r < 4) {
      const auto t = static_cast<Target>(rng() % 4);
      fast.request(t, now);
      general.request(t, now);
    } else if (r == 4) {
      fast.request_emergency_stop(now);
      general.request_emergency_stop(now);
    } else if (r == 5) {
      fast.request_block_power(now);
      general.request_block_power(now);
    } else if (r == 6) {
      fast.restart();
      general.restart();
    } else if (r == 7) {
      const auto bits = static_cast<Word>(rng());
      fast.set_application_bits(bits);
      general.set_application_bits(bits);
    } else if (r == 8) {
      dev.power_on();
    } else if (r < 12) {
      fault = !fault;
    }
    const Word status = status_for(dev.state(), dev.last_control(), rng);
    const Word a = fast.step(status, now);
    const Word b = general.step_general(status, now);
    ASSERT_EQ(a, b) << "seed " << seed << " step " << i << " status " << status;
    const std::string d = differs(fast.report(), general.report());
    ASSERT_TRUE(d.empty()) << "seed " << seed << " step " << i << ": report." << d << " differs";
    ASSERT_EQ(fast.last_control(), general.last_control());
    dev.sample({.control = a, .fault_present = fault});
    now += std::chrono::microseconds(rng() % 3 == 0 ? static_cast<std::int64_t>(100 + rng() % 20000) : 1000);
  }
}

TEST(SequencerShortcuts, StepDecidesAsTheGeneralDecisionsOverRandomRunsMc6000) {
  for (std::uint32_t seed = 1; seed <= 60; ++seed) run(seed, EmergencyStopExit::on_block_power_only);
}

TEST(SequencerShortcuts, StepDecidesAsTheGeneralDecisionsOverRandomRunsVf1000) {
  for (std::uint32_t seed = 1000; seed <= 1060; ++seed) run(seed, EmergencyStopExit::automatic_when_stopped);
}

// The shortcuts are taken in such runs at all: a start-up held at ENABLED sends ENABLE with the
// hold, and the path's words with step_path (the counts of the benchmark depend on both).
TEST(SequencerShortcuts, StartUpAndHoldGiveTheGeneralWords) {
  Sequencer fast, general;
  fast.request(Target::enabled, Time{0});
  general.request(Target::enabled, Time{0});
  for (const Word s : {Word{0x0240}, Word{0x0221}, Word{0x0637}, Word{0x0637}}) {
    EXPECT_EQ(fast.step(s, Time{0}), general.step_general(s, Time{0}));
  }
  EXPECT_EQ(fast.last_control(), 0x000F);
  EXPECT_EQ(fast.report().phase, Phase::reached);
}

}  // namespace
}  // namespace ibs::drivecom
