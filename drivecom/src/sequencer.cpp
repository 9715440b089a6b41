#include "ibs/drivecom/sequencer.hpp"

#include <cstdio>

namespace ibs::drivecom {

namespace {

using detail::is_fault_state;

constexpr Word kResetBit = 1U << cw::kResetFault;
constexpr std::size_t kTargets = 4;
constexpr std::size_t kCommands = kCommandTable.size();
constexpr std::uint8_t kFar = 0xFF;

// ---------------------------------------------------------------------------------------------
// The master's paths, derived at compile time from the one DRIVECOM table (kCommandTransitions,
// 5.1.2) plus the automatic transition 1: for each state and target, the command to send and the
// transition it waits for. The fault states are left the same way for every target (see plan()).

struct PathStep {
  Command command = Command::block_power;
  std::uint8_t transition = 0;  // 0: holding the target
};

constexpr std::size_t idx(State s) { return static_cast<std::size_t>(s); }

// Steps from each state to each target state along command transitions (and 1 from NOT READY).
constexpr std::array<std::array<std::uint8_t, kStateCount>, kTargets> make_distances() {
  std::array<std::array<std::uint8_t, kStateCount>, kTargets> dist{};
  for (std::size_t t = 0; t < kTargets; ++t) {
    for (auto& d : dist[t]) d = kFar;
    dist[t][idx(target_state(static_cast<Target>(t)))] = 0;
    for (std::size_t round = 0; round < kStateCount; ++round) {
      for (const auto& row : kCommandTransitions) {
        const std::uint8_t via = dist[t][idx(row.to)];
        if (via != kFar && via + 1 < dist[t][idx(row.from)]) dist[t][idx(row.from)] = static_cast<std::uint8_t>(via + 1);
      }
      const std::uint8_t via = dist[t][idx(State::start_up_inhibit)];
      if (via != kFar && via + 1 < dist[t][idx(State::not_ready)]) dist[t][idx(State::not_ready)] = static_cast<std::uint8_t>(via + 1);
    }
  }
  return dist;
}
inline constexpr auto kDistance = make_distances();

// The command that holds a target: one that moves nothing there and leads into it from a
// neighbour (first in the command table's order): BLOCK POWER, SHUTDOWN, DISABLE, ENABLE.
constexpr Command hold_command(State target) {
  for (const auto& c : kCommandTable) {
    if (detail::kTransitionLut[idx(target)][static_cast<std::size_t>(c.command)].number != 0) continue;
    for (const auto& row : kCommandTransitions) {
      if (row.to == target && row.command == c.command) return c.command;
    }
  }
  return Command::block_power;
}

// The first step of a shortest path. Among equally short ones the step whose command is also the
// next state's command wins, so that a drive taking several transitions in one sample (READY +
// ENABLE -> ON -> ENABLED, 5.3.4) gets one word for all of them; then the command table's order.
constexpr std::array<std::array<PathStep, kStateCount>, kTargets> make_paths() {
  std::array<std::array<PathStep, kStateCount>, kTargets> paths{};
  for (std::size_t t = 0; t < kTargets; ++t) {
    const State target = target_state(static_cast<Target>(t));
    paths[t][idx(target)] = {hold_command(target), 0};
    // Nearer states first, so that a step can look at its successor's command.
    for (std::uint8_t d = 1; d < kStateCount; ++d) {
      for (std::size_t s = 0; s < kStateCount; ++s) {
        if (kDistance[t][s] != d) continue;
        if (static_cast<State>(s) == State::not_ready) {
          // 1 happens by itself; the word already is what START-UP INHIBIT will need.
          paths[t][s] = {paths[t][idx(State::start_up_inhibit)].command, 1};
          continue;
        }
        bool found = false;
        PathStep best{};
        bool best_matches = false;
        for (const auto& row : kCommandTransitions) {
          if (idx(row.from) != s || kDistance[t][idx(row.to)] + 1 != d) continue;
          const bool matches = paths[t][idx(row.to)].command == row.command;
          const bool earlier = static_cast<std::size_t>(row.command) < static_cast<std::size_t>(best.command);
          if (!found || (matches && !best_matches) || (matches == best_matches && earlier)) {
            best = {row.command, row.number};
            best_matches = matches;
            found = true;
          }
        }
        paths[t][s] = best;
      }
    }
  }
  return paths;
}
inline constexpr auto kPaths = make_paths();

constexpr PathStep path(State s, Target t) { return kPaths[static_cast<std::size_t>(t)][idx(s)]; }

// kPaths by the status word seen (detail::kStatusMoves): the state each value of bits 0-6 shows
// and, for a state, its path step as the word sent.
constexpr std::array<std::array<detail::StatusMove, 128>, kTargets> make_status_moves() {
  std::array<std::array<detail::StatusMove, 128>, kTargets> moves{};
  for (std::size_t t = 0; t < kTargets; ++t) {
    for (std::size_t bits = 0; bits < 128; ++bits) {
      const std::uint8_t code = detail::kStateLut[bits];
      moves[t][bits] = {0, 0, code};
      if (code == detail::kNoState) continue;
      moves[t][bits].word = command_word(kPaths[t][code].command);
      moves[t][bits].transition = kPaths[t][code].transition;
    }
  }
  return moves;
}

// The table of docs/drivecom.md, pinned where the manual is explicit: the start-up of 5.3.4
// (0006H in START-UP INHIBIT, 000FH in READY taking 3 and 4) and every state's way out.
static_assert(path(State::start_up_inhibit, Target::enabled).command == Command::shutdown);
static_assert(path(State::ready, Target::enabled).command == Command::enable);
static_assert(path(State::ready, Target::enabled).transition == 3);
static_assert(path(State::ready, Target::on).command == Command::disable);
static_assert(path(State::enabled, Target::on).transition == 5);
static_assert(path(State::enabled, Target::start_up_inhibit).transition == 9);
static_assert(path(State::not_ready, Target::start_up_inhibit).command == Command::block_power);
static_assert(path(State::not_ready, Target::ready).command == Command::shutdown);
static_assert(path(State::emergency_stop_active, Target::enabled).transition == 12);
static_assert(path(State::enabled, Target::enabled).command == Command::enable);
static_assert(path(State::enabled, Target::enabled).transition == 0);
static_assert(kCommands == 5);

}  // namespace

// kPaths by the status word seen (declared in the header for Sequencer::step).
alignas(64) constexpr std::array<std::array<detail::StatusMove, 128>, 4> detail::kStatusMoves = make_status_moves();
// step_path takes a plain path state with nothing to wait for as the target reached and held.
constexpr bool plain_states_hold_only_at_target() {
  for (std::size_t t = 0; t < 4; ++t) {
    for (const detail::StatusMove& m : detail::kStatusMoves[t]) {
      if (m.code == detail::kNoState || ((detail::kPlainPathStates >> m.code) & 1U) == 0) continue;
      const bool at_target = static_cast<State>(m.code) == target_state(static_cast<Target>(t));
      if ((m.transition == 0) != at_target) return false;
    }
  }
  return true;
}
// Every value of bits 0-6 carries kStateLut's state and, for a state, kPaths' step as a word.
constexpr bool status_moves_follow_the_paths() {
  for (std::size_t t = 0; t < 4; ++t) {
    for (std::size_t bits = 0; bits < 128; ++bits) {
      const detail::StatusMove& m = detail::kStatusMoves[t][bits];
      if (m.code != detail::kStateLut[bits]) return false;
      if (m.code == detail::kNoState) continue;
      const PathStep p = path(static_cast<State>(m.code), static_cast<Target>(t));
      if (m.word != command_word(p.command) || m.transition != p.transition) return false;
    }
  }
  return true;
}
static_assert(status_moves_follow_the_paths());
// The start-up of 5.3.4 as step() sees it: 0240H (START-UP INHIBIT) answered with 0006H, waiting
// for 2; 0231H (READY) with 000FH, waiting for 3.
constexpr auto kToEnabled = static_cast<std::size_t>(Target::enabled);
static_assert(detail::kStatusMoves[kToEnabled][0x40].word == 0x0006 && detail::kStatusMoves[kToEnabled][0x40].transition == 2);
static_assert(detail::kStatusMoves[kToEnabled][0x31].word == 0x000F && detail::kStatusMoves[kToEnabled][0x31].transition == 3);
static_assert(plain_states_hold_only_at_target());
static_assert(detail::kPlainPathStates == ((1U << idx(State::start_up_inhibit)) | (1U << idx(State::ready)) |
                                           (1U << idx(State::on)) | (1U << idx(State::enabled)) |
                                           (1U << idx(State::emergency_stop_active))));

std::string_view to_string(Target t) { return state_row(target_state(t)).name; }

std::string_view to_string(Failure f) {
  switch (f) {
    case Failure::none: return "none";
    case Failure::timeout: return "timeout";
    case Failure::fault: return "fault";
    case Failure::left_target: return "left target";
    case Failure::restarted: return "restarted";
    case Failure::invalid_status: return "invalid status word";
  }
  return "?";
}

void Sequencer::restart() {
  report_ = Report{};
  last_control_ = 0;
  track_ = Track{};
  hold_code_ = kNotHolding;
  update_path_mask();
}

void Sequencer::request_emergency_stop(Time now) { begin(Goal::emergency_stop, now); }
void Sequencer::request_block_power(Time now) { begin(Goal::block_power, now); }

void Sequencer::wait_for(std::uint8_t transition, Time now) {
  if (transition != report_.transition || report_.state_seen != prev_state()) {
    report_.since = now;
  }
  report_.transition = transition;
  report_.timeout = transition_timeout(transition);
  report_.waited = now - report_.since;
  if (report_.waited > report_.timeout) fail(Failure::timeout);
}

Word Sequencer::fail(Failure f) {
  if (report_.phase != Phase::failed) report_.failed_command = last_control_;
  report_.phase = Phase::failed;
  report_.failure = f;
  set(kPulseStarted, false);
  return emit(command_word(Command::block_power));
}

Sequencer::Move Sequencer::reset_pulse(Time now) {
  // 15: a real rising edge of bit 7, repeated as a pulse while the drive stays in FAULT.
  const bool high = (last_control_ & kResetBit) != 0;
  if (!has(kPulseStarted)) {
    set(kPulseStarted, true);
    pulse_edge_ = now;
    // Coming from a word with bit 7 high there is no edge yet: drop it first.
    return {high ? Word{0} : kResetBit, 15};
  }
  if (now - pulse_edge_ >= reset_pulse_) {
    pulse_edge_ = now;
    return {high ? Word{0} : kResetBit, 15};
  }
  return {high ? kResetBit : Word{0}, 15};
}

Sequencer::Move Sequencer::plan(State s, Time now) {
  // States every target leaves the same way.
  switch (s) {
    case State::fault: return reset_pulse(now);
    case State::fault_response_active: return {command_word(Command::block_power), 14};  // wait, bit 7 low
    default: break;
  }
  set(kPulseStarted, false);
  const PathStep p = path(s, report_.target);
  return {command_word(p.command), p.transition};
}

Word Sequencer::step_moving(std::uint8_t code, Time now) {
  // step() took the plain moves along a target's path (step_path); everything else decides here.
  const std::optional<State> st = detail::state_of_code(code);
  report_.state_seen = st;
  Word w = 0;
  switch (report_.goal) {
    case Goal::idle: w = emit(command_word(Command::block_power)); break;
    case Goal::emergency_stop:
    case Goal::block_power: w = step_stop(st, now); break;
    case Goal::target: w = step_target(st, now); break;
  }
  track_.prev_seen = code;
  if (st) track_.known = code;
  if (st && *st != State::fault) set(kEdgeOut, false);
  hold_code_ = report_.goal == Goal::target && report_.phase == Phase::reached && st == target_state(report_.target)
                   ? static_cast<std::uint8_t>(*st)
                   : kNotHolding;
  update_path_mask();
  return w;
}

Word Sequencer::step_stop(std::optional<State> st, Time now) {
  const bool estop = report_.goal == Goal::emergency_stop;
  const Word word = command_word(estop ? Command::emergency_stop : Command::block_power);
  if (report_.phase == Phase::failed) return fail(report_.failure);
  if (!st) {
    wait_for(report_.transition, now);
    return report_.phase == Phase::failed ? fail(Failure::invalid_status) : emit(word);
  }
  // The transition the request waits for, from the seen state (0: there already).
  std::uint8_t t = 0;
  switch (*st) {
    case State::ready: t = 7; break;
    case State::on: t = 10; break;
    case State::enabled: t = estop ? 11 : 9; break;
    case State::emergency_stop_active: t = estop ? 0 : 12; break;
    case State::fault_response_active: t = 14; break;
    case State::not_ready:
    case State::start_up_inhibit:
    case State::fault: t = 0; break;
  }
  if (t == 0) {
    report_.phase = Phase::reached;
    report_.transition = 0;
    return emit(word);
  }
  report_.phase = Phase::moving;
  wait_for(t, now);
  return report_.phase == Phase::failed ? fail(Failure::timeout) : emit(word);
}

Word Sequencer::step_target(std::optional<State> st, Time now) {
  // Once failed, BLOCK POWER until a new request: never a reset, never a power-on.
  if (report_.phase == Phase::failed) return fail(report_.failure);
  if (!st) {
    // An unreadable status word erases nothing: the command stays the one for the last state
    // seen (a new request may have changed it), and the transition's timeout decides.
    const Move m = plan(known_state().value_or(State::not_ready), now);
    wait_for(m.transition, now);
    if (report_.phase == Phase::failed) return fail(Failure::invalid_status);
    return emit(m.word);
  }
  if (is_fault_state(*st)) {
    // A fault the request did not cover: it appeared after the drive was seen in another state.
    if (!has(kResetAllowed)) return fail(Failure::fault);
  } else {
    set(kResetAllowed, false);
  }
  if (report_.phase == Phase::reached && *st != target_state(report_.target)) return fail(Failure::left_target);
  if (*st == State::not_ready) {
    // NOT READY straight after the RESET FAULT this request sent is the drive booting from it
    // (the VF1000 performs a software reset, INTERBUS manual 5.2.1), not a restart: the request goes on
    // as after power-on. The fault was reset; one that comes back ends the request (above).
    const std::optional<State> known = known_state();
    const bool booting_from_reset = known == State::fault && has(kResetEdgeSent);
    // A drive last seen up and now NOT READY has restarted, perhaps during an outage in which
    // the request was made: the master cannot tell whether the power cycle came before the
    // request or after it, and takes it as after -- the request ends rather than enable a drive
    // that was switched off and on since somebody asked (docs/errata.md DC-D1).
    const bool restarted_unseen = known && *known != State::not_ready;
    if ((has(kUpSinceRequest) || restarted_unseen) && !booting_from_reset) return fail(Failure::restarted);
    set(kUpSinceRequest, false);
    set(kResetEdgeSent, false);
  } else {
    // Out of FAULT RESPONSE ACTIVE or FAULT into a healthy state without a reset edge from this
    // master: only a power-on leaves a fault state that way (5.1.2: FAULT is left by transition
    // 15 alone), its NOT READY between two samples -- a restart, as above (DC-D1).
    if (!is_fault_state(*st) && detail::is_fault_code(track_.known) && !has(kEdgeOut)) return fail(Failure::restarted);
    set(kUpSinceRequest, true);
  }
  const Move m = plan(*st, now);
  if (*st == State::fault && (m.word & kResetBit) != 0 && (last_control_ & kResetBit) == 0) {
    set(kResetEdgeSent, true);
    set(kEdgeOut, true);
  }
  if (*st != State::fault) set(kResetEdgeSent, false);
  if (m.transition == 0) {
    report_.phase = Phase::reached;
    report_.transition = 0;
    report_.waited = 0ns;
    return emit(m.word);
  }
  report_.phase = Phase::moving;
  wait_for(m.transition, now);
  if (report_.phase == Phase::failed) return fail(Failure::timeout);
  return emit(m.word);
}

std::string describe(const Report& r) {
  std::string s;
  char buf[32];
  const auto hex = [&buf](Word w) {
    std::snprintf(buf, sizeof buf, "%04X", static_cast<unsigned>(w));
    return std::string(buf);
  };
  const auto ms = [&buf](Duration d) {
    std::snprintf(buf, sizeof buf, "%.1f ms", to_ms(d));
    return std::string(buf);
  };
  const std::string seen =
      (r.state_seen ? std::string(to_string(*r.state_seen)) : std::string("no valid state")) +
      " (status " + hex(r.status_seen) + ")";
  const std::string sent = hex(r.command_sent) + " " + std::string(to_string(decode_command(r.command_sent)));
  const std::string goal = r.goal == Goal::target ? std::string(to_string(r.target))
                           : r.goal == Goal::emergency_stop ? std::string("EMERGENCY STOP")
                           : r.goal == Goal::block_power    ? std::string("BLOCK POWER")
                                                            : std::string("idle");
  switch (r.phase) {
    case Phase::idle: return "idle, sending " + sent;
    case Phase::reached: return goal + " reached: state " + seen + ", sending " + sent;
    case Phase::moving:
    case Phase::failed: break;
  }
  const auto ends = transition_ends(r.transition);
  const std::string from = !ends ? "?" : ends->from ? std::string(to_string(*ends->from)) : "any";
  const std::string to = ends ? std::string(to_string(ends->to)) : "?";
  const std::string wait = "transition " + std::to_string(r.transition) + " (" + from + " -> " + to + ")";
  if (r.phase == Phase::moving) {
    return "moving to " + goal + ": waiting for " + wait + " for " + ms(r.waited) + " of " +
           ms(r.timeout) + "; state " + seen + ", sending " + sent;
  }
  const std::string was = hex(r.failed_command) + " " + std::string(to_string(decode_command(r.failed_command)));
  const std::string then = "; sending " + sent + " until a new request";
  switch (r.failure) {
    case Failure::timeout:
    case Failure::invalid_status:
      return wait + " did not happen: state seen " + seen + ", command sent " + was + ", waited " +
             ms(r.waited) + " (timeout " + ms(r.timeout) + ")" +
             (r.failure == Failure::invalid_status ? "; the status word matches no DRIVECOM state" : "") + then;
    case Failure::fault:
      return "the drive faulted (target " + goal + "): state seen " + seen + ", command sent " + was + then +
             "; request a target again to reset the fault";
    case Failure::left_target:
      return "the drive left " + goal + " on its own: state seen " + seen + ", command sent " + was + then;
    case Failure::restarted:
      return "the drive restarted on the way to " + goal + " (NOT READY again): state seen " + seen +
             ", command sent " + was + then + "; request a target again once it is up";
    case Failure::none: break;
  }
  return "failed: " + seen;
}

}  // namespace ibs::drivecom
