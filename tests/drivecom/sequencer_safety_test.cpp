// The master sequencer's safety promises (docs/drivecom.md) over arbitrary status-word sequences:
// BLOCK POWER after a failure, SHUTDOWN never skipped, no power-on out of FAULT without a reset
// edge, no reset of a fault the request did not cover, stop requests in the next cycle. A monitor
// written from the promises alone (not from the sequencer's code) checks every word: exhaustively
// over every sequence of state classes up to a depth, and at random over arbitrary words,
// requests and cycle times.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../support/sequencer_monitor.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/drivecom/sequencer.hpp"

namespace ibs::drivecom {
namespace {

using test_support::Monitor;

std::string hex(Word w) {
  char b[8];
  std::snprintf(b, sizeof b, "%04X", static_cast<unsigned>(w));
  return b;
}

// Runs `words` against a fresh sequencer asked for `target` at the start; returns the words sent.
std::vector<Word> run(Target target, const std::vector<Word>& words, Failure* failure = nullptr) {
  Sequencer seq;
  Monitor mon;
  seq.request(target, Time{0});
  mon.on_request(target);
  std::vector<Word> sent;
  Time now{0};
  for (const Word s : words) {
    const Word w = seq.step(s, now);
    const std::string why = mon.check(s, w, seq.report());
    EXPECT_EQ(why, "") << "status " << hex(s) << " answered with " << hex(w);
    sent.push_back(w);
    now += 8200us;
  }
  if (failure != nullptr) *failure = seq.report().failure;
  return sent;
}

std::string words_text(const std::vector<Word>& v) {
  std::string s;
  for (const Word w : v) s += (s.empty() ? "" : " ") + hex(w);
  return s;
}

// Issue 9, defect 1: one undecodable word between READY and FAULT made the sequencer forget that
// the drive had been healthy, and it reset the fault and re-enabled the drive.
TEST(SequencerSafety, UndecodableWordDoesNotEraseWhatTheSequencerKnows) {
  Failure f = Failure::none;
  const auto sent = run(Target::enabled, {0x0240, 0x0231, 0x0001, 0x0208, 0x0208, 0x0240, 0x0231, 0x0237}, &f);
  EXPECT_EQ(words_text(sent), "0006 000F 000F 0000 0000 0000 0000 0000");
  EXPECT_EQ(f, Failure::fault);
  // Without the undecodable word: the same outcome.
  const auto plain = run(Target::enabled, {0x0240, 0x0231, 0x0208, 0x0208, 0x0240, 0x0231, 0x0237}, &f);
  EXPECT_EQ(words_text(plain), "0006 000F 0000 0000 0000 0000 0000");
  EXPECT_EQ(f, Failure::fault);
}

// Issue 9, defect 2: after the drive left ENABLED the sequencer went on sending ENABLE.
TEST(SequencerSafety, LeavingTheTargetEndsInBlockPower) {
  Failure f = Failure::none;
  const auto sent = run(Target::enabled, {0x0240, 0x0231, 0x0237, 0x0237, 0x0240, 0x0240, 0x0233, 0x0237}, &f);
  EXPECT_EQ(words_text(sent), "0006 000F 000F 000F 0000 0000 0000 0000");
  EXPECT_EQ(f, Failure::left_target);
}

TEST(SequencerSafety, FaultAfterAnUndecodableWordIsAFaultNotLeftTarget) {
  Failure f = Failure::none;
  const auto sent = run(Target::enabled, {0x0240, 0x0231, 0x0237, 0x0001, 0x0208, 0x0208}, &f);
  EXPECT_EQ(words_text(sent), "0006 000F 000F 000F 0000 0000");
  EXPECT_EQ(f, Failure::fault);
}

// Found by the fault campaign (docs/robustness.md, defect A): a drive switched off and on while
// the master was still on its way to ENABLED was brought up to ENABLED after its restart. NOT
// READY comes only from power-on (5.1.1): the request does not carry across it.
TEST(SequencerSafety, ADriveThatRestartsOnTheWayEndsTheRequest) {
  Failure f = Failure::none;
  const auto sent = run(Target::enabled, {0x0240, 0x0231, 0x0233, 0x0000, 0x0000, 0x0240, 0x0231, 0x0233}, &f);
  EXPECT_EQ(words_text(sent), "0006 000F 000F 0000 0000 0000 0000 0000");
  EXPECT_EQ(f, Failure::restarted);
  // A drive still initialising when the request is made is brought up as before.
  const auto up = run(Target::enabled, {0x0000, 0x0000, 0x0240, 0x0231, 0x0237});
  EXPECT_EQ(words_text(up), "0006 0006 0006 000F 000F");
}

// Found by the 10-million campaign of docs/robustness.md (seed 1 after the drive-core change): a
// drive seen up, then an outage in which ENABLED was requested and the drive was switched off and
// on, then NOT READY. The master cannot tell whether the power cycle came before the request or
// after it; it takes it as after and ends the request (docs/errata.md DC-D1).
TEST(SequencerSafety, ARestartHiddenInAnOutageEndsARequestMadeInIt) {
  Sequencer seq;
  EXPECT_EQ(seq.step(0x0240, Time{0}), 0x0000);  // idle, drive in START-UP INHIBIT
  EXPECT_EQ(seq.step(0x0001, 1ms), 0x0000);       // the status word unreadable
  seq.request(Target::enabled, 2ms);
  EXPECT_EQ(seq.step(0x0001, 3ms), 0x0006) << "the command for the last state seen";
  EXPECT_EQ(seq.step(0x0000, 4ms), 0x0000) << "NOT READY: switched off and on in the outage";
  EXPECT_EQ(seq.report().failure, Failure::restarted);
  EXPECT_EQ(seq.step(0x0240, 5ms), 0x0000);
  EXPECT_EQ(seq.step(0x0231, 6ms), 0x0000) << "never brought up to ENABLED";
  // A drive never seen up (a master that starts while the drive boots) is brought up as before.
  Sequencer fresh;
  fresh.request(Target::enabled, Time{0});
  EXPECT_EQ(fresh.step(0x0001, 1ms), 0x0006);
  EXPECT_EQ(fresh.step(0x0000, 2ms), 0x0006);
  EXPECT_EQ(fresh.step(0x0240, 3ms), 0x0006);
  EXPECT_EQ(fresh.report().failure, Failure::none);
}

// Issue 14: RESET FAULT makes the VF1000 boot (INTERBUS manual 5.2.1, "a software reset"): NOT READY
// right after the request's own reset edge is the drive coming up again, not a restart.
TEST(SequencerSafety, NotReadyAfterTheRequestsOwnResetEdgeIsTheDriveBooting) {
  Failure f = Failure::none;
  const auto sent = run(Target::enabled, {0x0208, 0x0000, 0x0000, 0x0240, 0x0231, 0x0237}, &f);
  EXPECT_EQ(words_text(sent), "0080 0006 0006 0006 000F 000F");
  EXPECT_EQ(f, Failure::none);
  // The fault back after the boot ends the request: the master never resets it a second time.
  const auto again = run(Target::enabled, {0x0208, 0x0000, 0x0240, 0x0208, 0x0208, 0x0208}, &f);
  EXPECT_EQ(words_text(again), "0080 0006 0006 0000 0000 0000");
  EXPECT_EQ(f, Failure::fault);
  // A restart after the drive came up from the boot is a restart again.
  const auto restart = run(Target::enabled, {0x0208, 0x0000, 0x0240, 0x0231, 0x0000, 0x0000}, &f);
  EXPECT_EQ(words_text(restart), "0080 0006 0006 000F 0000 0000");
  EXPECT_EQ(f, Failure::restarted);
}

// Found by the 10-million campaign of docs/robustness.md (seed 1, after issue 25): a servo
// switched off and on in FAULT RESPONSE ACTIVE, its self-test's NOT READY between two of the
// master's samples. FAULT is left by transition 15 alone (5.1.2); a drive out of a fault state
// without this master's reset edge has restarted, and a request made in the fault does not carry
// across that (docs/errata.md DC-D1).
TEST(SequencerSafety, ADriveOutOfAFaultWithoutTheResetEdgeHasRestarted) {
  Failure f = Failure::none;
  const auto fra = run(Target::enabled, {0x020F, 0x020F, 0x0240, 0x0231, 0x0233}, &f);
  EXPECT_EQ(words_text(fra), "0000 0000 0000 0000 0000");
  EXPECT_EQ(f, Failure::restarted);
  const auto fault = run(Target::enabled, {0x020F, 0x0208, 0x0240, 0x0231}, &f);
  EXPECT_EQ(words_text(fault), "0000 0080 0006 000F") << "after the reset edge: the reset done";
  EXPECT_EQ(f, Failure::none);
  // The edge a previous request sent is out: the drive leaving FAULT on it is no restart.
  Sequencer seq;
  seq.request(Target::enabled, Time{0});
  EXPECT_EQ(seq.step(0x0208, 1ms), 0x0080);
  seq.request(Target::on, 2ms);
  EXPECT_EQ(seq.step(0x0208, 3ms), 0x0000) << "bit 7 dropped: no second edge";
  EXPECT_EQ(seq.step(0x0240, 4ms), 0x0006);
  EXPECT_EQ(seq.report().failure, Failure::none);
  // The same drive back in FAULT later, then out of it with no edge since: a restart.
  Sequencer later;
  later.request(Target::enabled, Time{0});
  EXPECT_EQ(later.step(0x0208, 1ms), 0x0080);
  EXPECT_EQ(later.step(0x0240, 2ms), 0x0006);
  later.request_block_power(3ms);
  EXPECT_EQ(later.step(0x0208, 4ms), 0x0000);
  later.request(Target::enabled, 5ms);
  EXPECT_EQ(later.step(0x020F, 6ms), 0x0000);
  EXPECT_EQ(later.step(0x0240, 7ms), 0x0000) << "out of FAULT RESPONSE ACTIVE with no edge";
  EXPECT_EQ(later.report().failure, Failure::restarted);
}

TEST(SequencerSafety, FaultPresentAtTheRequestIsResetOnTheWay) {
  // The request covers a fault the drive is in when it is made (or shows first).
  const auto sent = run(Target::enabled, {0x0208, 0x0208, 0x0240, 0x0231, 0x0237});
  EXPECT_EQ(words_text(sent), "0080 0080 0006 000F 000F");
}

TEST(SequencerSafety, FaultSeenBeforeTheRequestIsCoveredAFaultAfterItIsNot) {
  Sequencer seq;
  EXPECT_EQ(seq.step(0x0208, Time{0}), 0x0000);  // idle, drive in FAULT
  seq.request(Target::enabled, 1ms);
  EXPECT_EQ(seq.step(0x0208, 2ms), 0x0080);  // the user asked with the fault in view
  Sequencer other;
  EXPECT_EQ(other.step(0x0237, Time{0}), 0x0000);  // idle, drive ENABLED
  other.request(Target::enabled, 1ms);
  EXPECT_EQ(other.step(0x0208, 2ms), 0x0000);  // the fault came after the request
  EXPECT_EQ(other.report().failure, Failure::fault);
}

// Every sequence of status words, up to a depth, as state classes: one word for each of the
// eight states and one that decodes to none. The sequencer decodes a status word only through
// decode_state, so one representative per class stands for all 65536 words.
constexpr std::array<Word, 9> kClasses{0x0000, 0x0240, 0x0231, 0x0233, 0x0237, 0x0208, 0x020F, 0x0217, 0x0001};

struct Node {
  Sequencer seq;
  Monitor mon;
  Time now{0};
};

void explore(const Node& node, int depth, Duration dt, std::vector<Word>& path, std::uint64_t& visited,
             std::string& first_failure) {
  if (depth == 0 || !first_failure.empty()) return;
  for (const Word s : kClasses) {
    Node next = node;
    const Word w = next.seq.step(s, next.now);
    ++visited;
    path.push_back(s);
    const std::string why = next.mon.check(s, w, next.seq.report());
    if (!why.empty() && first_failure.empty()) {
      first_failure = why + " after status words " + words_text(path) + " (answered " + hex(w) + ")";
    }
    next.now += dt;
    explore(next, depth - 1, dt, path, visited, first_failure);
    path.pop_back();
  }
}

TEST(SequencerSafety, EveryStatusSequenceUpToSixCyclesKeepsThePromises) {
  std::uint64_t visited = 0;
  for (const Target target : {Target::start_up_inhibit, Target::ready, Target::on, Target::enabled}) {
    for (const bool short_timeouts : {false, true}) {
      SequencerConfig cfg = SequencerConfig::defaults();
      // Short timeouts make failures by timeout happen inside the sequences too.
      if (short_timeouts) cfg.transition_timeout.fill(1ms);
      // The request before any word, or after one word of each class seen while idle.
      for (int prefix = -1; prefix < static_cast<int>(kClasses.size()); ++prefix) {
        Node root{Sequencer(cfg), Monitor{}, Time{0}};
        std::vector<Word> path;
        if (prefix >= 0) {
          const Word s = kClasses[static_cast<std::size_t>(prefix)];
          const Word w = root.seq.step(s, root.now);
          ASSERT_EQ(root.mon.check(s, w, root.seq.report()), "");
          root.now += 1ms;
        }
        root.seq.request(target, root.now);
        root.mon.on_request(target);
        std::string failure;
        explore(root, prefix >= 0 ? 5 : 6, 1ms, path, visited, failure);
        ASSERT_EQ(failure, "") << "target " << to_string(target) << (short_timeouts ? ", 1 ms timeouts" : "");
      }
    }
  }
  EXPECT_GT(visited, 9'000'000U);
}

// Arbitrary words (most of them near the valid states), requests of every kind, stop requests,
// restarts and cycle times from 0 to 20 ms, over long runs.
TEST(SequencerSafety, RandomRunsWithArbitraryWordsAndRequestsKeepThePromises) {
  std::mt19937_64 rng(20261123);
  for (int run_no = 0; run_no < 300; ++run_no) {
    SequencerConfig cfg = SequencerConfig::defaults();
    std::uniform_int_distribution<int> timeout_ms(1, 300);
    for (auto& t : cfg.transition_timeout) t = std::chrono::milliseconds(timeout_ms(rng));
    Sequencer seq(cfg);
    Monitor mon;
    Time now{0};
    std::optional<State> drive = State::not_ready;  // a drive that mostly follows, sometimes not
    for (int k = 0; k < 3000; ++k) {
      const int event = static_cast<int>(rng() % 1000);
      if (event < 8) {
        const auto t = static_cast<Target>(rng() % 4);
        seq.request(t, now);
        mon.on_request(t);
      } else if (event < 10) {
        seq.request_emergency_stop(now);
        mon.on_emergency_stop();
      } else if (event < 12) {
        seq.request_block_power(now);
        mon.on_block_power();
      } else if (event < 13) {
        seq.restart();
        mon.on_restart();
      }
      Word status = 0;
      const int kind = static_cast<int>(rng() % 100);
      if (kind < 10) {
        status = static_cast<Word>(rng());  // anything at all
      } else {
        if (kind < 25) drive = static_cast<State>(rng() % kStateCount);  // a jump the profile may not have
        status = static_cast<Word>(status_word(*drive, static_cast<Word>(rng()), {}) | (rng() & 0xFF80U));
      }
      const Word w = seq.step(status, now);
      const std::string why = mon.check(status, w, seq.report());
      ASSERT_EQ(why, "") << "run " << run_no << " step " << k << ": status " << hex(status) << " answered "
                         << hex(w) << "; " << describe(seq.report());
      // The drive follows the command most of the time.
      if (rng() % 4 != 0) {
        DeviceStateMachine m(EmergencyStopExit::on_block_power_only, *drive);
        drive = m.sample({w, true, false, true, true}).state;
      }
      now += std::chrono::microseconds(rng() % 20'000);
    }
  }
}

}  // namespace
}  // namespace ibs::drivecom
