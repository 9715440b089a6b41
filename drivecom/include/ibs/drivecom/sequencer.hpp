// The master side of DRIVECOM Profile 20: given a target state, reads the status word every
// cycle and writes the control word that moves the drive along the shortest documented path
// (INTERBUS manual 5.1.2 command table; 5.3.4 start-up sequence 0000H, 0006H, 000FH).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "ibs/drivecom/control_word.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/drivecom/status_word.hpp"
#include "ibs/base/time.hpp"

namespace ibs::drivecom {

// The states a master may ask for; names and keys are their states' (kStateTable).
enum class Target : std::uint8_t { start_up_inhibit, ready, on, enabled };
inline constexpr std::array<Target, 4> kTargets{Target::start_up_inhibit, Target::ready, Target::on,
                                                Target::enabled};
std::string_view to_string(Target t);
constexpr State target_state(Target t) {
  switch (t) {
    case Target::start_up_inhibit: return State::start_up_inhibit;
    case Target::ready: return State::ready;
    case Target::on: return State::on;
    case Target::enabled: return State::enabled;
  }
  return State::start_up_inhibit;
}
constexpr std::string_view key(Target t) { return key(target_state(t)); }
// The target a file names by its state's key ("enabled"); nullopt for a state that is no target.
constexpr std::optional<Target> target_named(std::string_view key) {
  for (const Target t : kTargets) {
    if (drivecom::key(t) == key) return t;
  }
  return std::nullopt;
}
// Every target's key, in kTargets' order.
inline constexpr std::array<std::string_view, kTargets.size()> kTargetKeys = [] {
  std::array<std::string_view, kTargets.size()> keys{};
  for (std::size_t i = 0; i < kTargets.size(); ++i) keys[i] = key(kTargets[i]);
  return keys;
}();

// What the sequencer is doing.
enum class Goal : std::uint8_t {
  idle,            // no request yet: sends BLOCK POWER
  target,          // moving to / holding a target state
  emergency_stop,  // EMERGENCY STOP requested: sent at once, until a new target
  block_power,     // BLOCK POWER requested: sent at once, until a new target
};

enum class Phase : std::uint8_t { idle, moving, reached, failed };

enum class Failure : std::uint8_t {
  none,
  timeout,        // the expected transition did not happen in its time
  fault,          // the drive went to FAULT / FAULT RESPONSE ACTIVE on its own
  left_target,    // the drive left the reached target state without being told
  restarted,      // the drive showed NOT READY again after the request: it was switched off and on
  invalid_status, // the status word matches no DRIVECOM state (counts against the timeout)
};
std::string_view to_string(Failure f);

struct SequencerConfig {
  // Timeout of each transition, indexed by its profile number 0-15 (0 and 13 are never waited
  // for). Defaults suit both drives on a healthy bus; device drivers may tighten them.
  std::array<Duration, 16> transition_timeout{};
  // Bits the application owns (device bits 4-6, 11-15), ORed into every control word. Bits 0-3,
  // 7 (state machine) and 8-10 (reserved, 5.1.2) are masked off.
  Word application_bits = 0;
  // RESET FAULT is a pulse on bit 7: high this long, then low this long, repeated while the drive
  // stays in FAULT. Longer than two VF1000 samples (8.2 ms) so that a sampling drive sees the edge.
  Duration reset_pulse = 50ms;

  // At compile time, so that a sequencer built with the defaults copies a constant.
  static constexpr SequencerConfig defaults() {
    SequencerConfig c;
    c.transition_timeout.fill(200ms);
    c.transition_timeout[0] = 0ms;
    c.transition_timeout[13] = 0ms;
    c.transition_timeout[1] = 10s;   // the VF1000 initialises for about 4 s after power-on (6.1)
    c.transition_timeout[14] = 10s;  // the drive's fault reaction (braking) may take seconds
    return c;
  }
};

namespace detail {
constexpr bool is_fault_state(State s) { return s == State::fault || s == State::fault_response_active; }
// is_fault_state for a state code (kNoState: no state, no fault state).
constexpr bool is_fault_code(std::uint8_t code) {
  const std::optional<State> s = state_of_code(code);
  return s && is_fault_state(*s);
}
// A target's path by the status word seen: for each target and each value of status bits 0-6,
// the state code the word shows (kStateLut: kNoState for none) and, for a state, the word of the
// path's command and the transition it waits for (0: holding the target). Derived in
// sequencer.cpp from kCommandTransitions (5.1.2); declared here for Sequencer::step. One load
// gives step() both the state and the move, where a lookup of the state and then of its move
// would be two in a row on the path from one cycle's status word to the next control word.
struct StatusMove {
  Word word;                // bits 0-3 and 7 of the path's command
  std::uint8_t transition;  // waited for; 0: none (holding, or no state)
  std::uint8_t code;        // kStateLut's state code
};
extern const std::array<std::array<StatusMove, 128>, kTargets.size()> kStatusMoves;
// The states on a target's path in which step_target decides nothing beyond the path: START-UP
// INHIBIT, READY, ON, ENABLED, EMERGENCY STOP ACTIVE (neither a fault state, with its reset or
// refusal, nor NOT READY, with its start or restart). A bit per state code; checked in the .cpp.
inline constexpr unsigned kPlainPathStates = 0x9EU;
}  // namespace detail

// Why the sequencer is where it is; also the answer to "why did the transition not happen".
struct Report {
  Goal goal = Goal::idle;
  Target target = Target::start_up_inhibit;
  Phase phase = Phase::idle;
  Failure failure = Failure::none;
  std::optional<State> state_seen;  // nullopt: the status word matched no state
  Word status_seen = 0;
  Word command_sent = 0;            // the word sent last (BLOCK POWER once failed)
  Word failed_command = 0;          // failed: the word that was being sent when it failed
  std::uint8_t transition = 0;      // the transition waited for (0: none)
  Duration waited{0};               // how long it has been waited for
  Duration timeout{0};
  Time since{0};                    // when the current wait started
};

// "transition 2 (START-UP INHIBIT -> READY) did not happen: ..." (not for the cycle path).
std::string describe(const Report& r);

class Sequencer {
 public:
  // The default configuration (SequencerConfig::defaults()). Inline and written out rather than
  // defaulted, so that a sequencer is built with a few stores of constants (a defaulted one is
  // zero-filled as a block first, which costs more than the rest of a start-up); it stores no
  // timeout table: the defaults' is a constant (transition_timeout).
  Sequencer() noexcept {}  // NOLINT(modernize-use-equals-default)
  // A configuration of one's own. Timeouts other than the defaults are kept in one immutable
  // table that copies of this sequencer share (allocated here, so this may throw std::bad_alloc;
  // never on the cycle path). Timeouts equal to the defaults allocate nothing.
  explicit Sequencer(const SequencerConfig& config)
      : reset_pulse_(config.reset_pulse), app_bits_(static_cast<Word>(config.application_bits & ~kOwnedBits)) {
    if (config.transition_timeout != kDefaultConfig.transition_timeout) {
      own_timeouts_ = std::make_shared<const std::array<Duration, 16>>(config.transition_timeout);
    }
  }
  // The timeout of transition `number` (0-15) as configured: the defaults' constant table, or
  // the one of its own (own_timeouts_).
  [[nodiscard]] Duration transition_timeout(std::uint8_t number) const {
    return (own_timeouts_ ? own_timeouts_->data() : kDefaultConfig.transition_timeout.data())[number & 0x0FU];
  }

  // Requests a target state; clears an emergency-stop or block-power request. A fault the drive
  // is in (or shows first, when its state is not known yet) is reset on the way; a fault that
  // appears after the drive has been seen in another state ends the request as failed.
  // Inline, so that a sequencer built and asked at once (a master starting) is a few stores.
  void request(Target t, Time now) {
    report_.target = t;
    begin(Goal::target, now);
    const std::optional<State> known = known_state();
    set(kResetAllowed, !known || detail::is_fault_state(*known));
    set(kUpSinceRequest, false);
    set(kResetEdgeSent, false);
  }
  // Sends EMERGENCY STOP from the next step on, whatever the state, until the next request().
  void request_emergency_stop(Time now);
  // Sends BLOCK POWER from the next step on, whatever the state, until the next request().
  void request_block_power(Time now);

  // One master cycle: reads the status word, returns the control word to send. Never allocates,
  // never throws. After any failure it sends BLOCK POWER with bit 7 low until the next request.
  Word step(Word status, Time now) {
    // The common case of every cycle, one compare: the reached target shown again.
    const detail::StatusMove p = detail::kStatusMoves[static_cast<std::size_t>(report_.target)][status & 0x7FU];
    report_.status_seen = status;
    if (p.code == hold_code_) return emit(last_control_);
    // The next common case, a drive moving along the target's path, inline too (step_path).
    // path_mask_ is kPlainPathStates or 0; kNoState (0xFF) & 31 is bit 31, never set.
    if (((path_mask_ >> (p.code & 31U)) & 1U) != 0) return step_path(p, now);
    return step_moving(p.code, now);
  }

  // step() without its two shortcuts (the hold, step_path): every status word through the
  // general decisions. The same words and the same report as step(), by construction (see
  // step_path); SequencerShortcuts.* compares the two over random runs.
  Word step_general(Word status, Time now) {
    report_.status_seen = status;
    return step_moving(detail::kStateLut[status & 0x7FU], now);
  }

  // step() for a status word that shows the held target again: true, `control` the word step()
  // returns, with step()'s effects. For any other status word false, and nothing changes (a
  // caller then calls step()). Lets a driver keep its common case free of calls.
  bool step_holding(Word status, Word& control) {
    if (detail::kStateLut[status & 0x7FU] != hold_code_) return false;
    report_.status_seen = status;
    control = emit(last_control_);
    return true;
  }

  [[nodiscard]] const Report& report() const { return report_; }
  [[nodiscard]] Word last_control() const { return last_control_; }
  // New application bits end a hold: the next step sends them through the general decisions and
  // holds again. A master loop that skips a holding driver (DeviceDriver::skip_while_holding)
  // sees the hold end and calls the driver again.
  void set_application_bits(Word bits) {
    const auto b = static_cast<Word>(bits & ~kOwnedBits);
    if (b == app_bits_) return;
    app_bits_ = b;
    hold_code_ = kNotHolding;
  }
  // The state code a reached target holds (step_holding), kNotHolding when none (no state code:
  // detail::kStateLut gives 0..7 or kNoState). Only a step
  // sets it; every request, stop request, restart and change of the application bits clears it.
  static constexpr std::uint8_t kNotHolding = 0xFE;
  [[nodiscard]] std::uint8_t hold_code() const { return hold_code_; }
  // After a master restart: forget everything, send BLOCK POWER with bit 7 low.
  void restart();

 private:
  static constexpr Word kOwnedBits = static_cast<Word>(cw::kDrivecomMask | cw::kReservedMask);
  struct Move {
    Word word;               // bits 0-3 and 7
    std::uint8_t transition; // waited for; 0 = nothing to wait for (holding)
  };
  Move plan(State s, Time now);
  Move reset_pulse(Time now);
  void begin(Goal g, Time now) {
    hold_code_ = kNotHolding;
    report_.goal = g;
    report_.phase = Phase::moving;
    report_.failure = Failure::none;
    report_.transition = 0;
    report_.since = now;
    report_.waited = 0ns;
    report_.timeout = 0ns;
    set(kPulseStarted, false);
    update_path_mask();
  }
  // path_mask_ from the goal, the phase and the last state seen: kPlainPathStates while the
  // sequencer moves to a target and the drive was not last seen in a fault state, else 0.
  void update_path_mask() {
    path_mask_ = report_.goal == Goal::target && report_.phase == Phase::moving &&
                         !detail::is_fault_code(track_.known)
                     ? detail::kPlainPathStates
                     : 0U;
  }
  Word step_stop(std::optional<State> st, Time now);
  Word step_target(std::optional<State> st, Time now);
  void wait_for(std::uint8_t transition, Time now);
  Word fail(Failure f);
  Word emit(Word drivecom_bits) {
    last_control_ = static_cast<Word>((drivecom_bits & cw::kDrivecomMask) | app_bits_);
    report_.command_sent = last_control_;
    return last_control_;
  }
  Word step_moving(std::uint8_t code, Time now);
  // step_target for a drive on the target's path (goal a target, phase moving, `code` a plain
  // path state, the last state seen no fault state): the same decisions in a straight line.
  // step_target's other checks cannot fire there: a reset's cover is only ended by a healthy
  // state; the restart check needs a fault state seen last; NOT READY is no plain path state; a
  // moving phase has left no reached target. SequencerSafety.* and the exhaustive monitors
  // (tests/support/sequencer_monitor.hpp) check both paths against the rules.
  Word step_path(detail::StatusMove m, Time now) {
    const std::uint8_t code = m.code;
    const auto s = static_cast<State>(code);
    report_.state_seen = s;
    Word w = 0;
    if (m.transition == 0) {
      report_.phase = Phase::reached;
      report_.transition = 0;
      report_.waited = 0ns;
      w = emit(m.word);
      // A plain path state holds only at its target (checked on kStatusMoves in the .cpp).
      hold_code_ = code;
      path_mask_ = 0;
    } else {
      // wait_for: the timer restarts when the transition waited for or the state changes.
      if (m.transition != report_.transition || track_.prev_seen != code) report_.since = now;
      report_.transition = m.transition;
      report_.timeout = transition_timeout(m.transition);
      report_.waited = now - report_.since;
      if (report_.waited > report_.timeout) {
        w = fail(Failure::timeout);
        path_mask_ = 0;
      } else {
        w = emit(m.word);
      }
      // hold_code_ stays kNotHolding: path_mask_ is non-zero only while the phase is moving, and
      // every function that sets a hold code (a reached phase) clears path_mask_ with it.
    }
    // The state seen and known; a healthy state ends a reset's cover, counts as up since the
    // request, ends any reset pulse and any edge's credit (step_target, plan). All in one
    // assignment of four bytes, not six stores of single bytes.
    track_ = Track{code, code, kUpSinceRequest, 0};
    return w;
  }

  static constexpr SequencerConfig kDefaultConfig = SequencerConfig::defaults();
  // The configured transition timeouts when they differ from the defaults', else null.
  std::shared_ptr<const std::array<Duration, 16>> own_timeouts_;
  Duration reset_pulse_ = kDefaultConfig.reset_pulse;
  Word app_bits_ = 0;
  Report report_;
  Word last_control_ = 0;
  // What the sequencer keeps of the drive from step to step, in four bytes, so that a step along
  // the path (step_path) writes all of it in one assignment.
  struct Track {
    // The state code of the previous status word (kNoState: it matched no state); a change
    // restarts the transition timer.
    std::uint8_t prev_seen = detail::kNoState;
    // The state code the last decodable status word showed: an undecodable word does not erase it.
    std::uint8_t known = detail::kNoState;
    std::uint8_t flags = 0;  // the k* flags below
    std::uint8_t unused = 0;
  };
  // The request covers resetting a fault: the drive was in a fault state (or its state was not
  // known) when the target was requested, and no other state has been seen since. A fault that
  // appears after the drive was seen healthy is never reset without a new request.
  static constexpr std::uint8_t kResetAllowed = 1U << 0U;
  // A state other than NOT READY has been seen since the request: NOT READY now means the drive
  // restarted (only power-on leads there, 5.1.1), and the request does not carry across that.
  static constexpr std::uint8_t kUpSinceRequest = 1U << 1U;
  // This request sent a rising edge of bit 7 while the drive showed FAULT: NOT READY next is the
  // drive booting from RESET FAULT (the VF1000's software reset, INTERBUS manual 5.2.1), not a restart.
  static constexpr std::uint8_t kResetEdgeSent = 1U << 2U;
  // A rising edge of bit 7 went out (this request's or an earlier one's) since the drive showed
  // FAULT: a healthy state next is the reset done; without it a drive out of a fault state has
  // restarted unseen (DC-D1).
  static constexpr std::uint8_t kEdgeOut = 1U << 3U;
  // A RESET FAULT pulse is running; its last edge went out at pulse_edge_.
  static constexpr std::uint8_t kPulseStarted = 1U << 4U;
  [[nodiscard]] bool has(std::uint8_t flag) const { return (track_.flags & flag) != 0; }
  void set(std::uint8_t flag, bool on) {
    track_.flags = static_cast<std::uint8_t>(on ? (track_.flags | flag) : (track_.flags & ~flag));
  }
  [[nodiscard]] std::optional<State> prev_state() const { return detail::state_of_code(track_.prev_seen); }
  [[nodiscard]] std::optional<State> known_state() const { return detail::state_of_code(track_.known); }
  Track track_;
  Time pulse_edge_{0};
  // The state code of the reached target while the sequencer holds it, else kNotHolding. Set
  // only at the end of a step that reached or held the target, with report_.state_seen,
  // track_.prev_seen and track_.known all that state; cleared by every request and restart. A
  // step whose status word shows that state again changes none of them: it sends the last word
  // again.
  std::uint8_t hold_code_ = kNotHolding;
  // The states step() hands to step_path, a bit per state code: kPlainPathStates while the goal
  // is a target, the phase moving and the last state seen no fault state, else 0. Kept by every
  // function that changes those (begin, restart, step_moving, step_path: update_path_mask).
  std::uint32_t path_mask_ = 0;
};

}  // namespace ibs::drivecom
