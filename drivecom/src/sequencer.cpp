#include "ibs/drivecom/sequencer.hpp"

#include <cstdio>

namespace ibs::drivecom {

namespace {

constexpr bool is_fault_state(State s) {
  return s == State::fault || s == State::fault_response_active;
}

constexpr Word kResetBit = 1U << cw::kResetFault;

// The state a transition leads from and to, for reports.
struct Edge {
  std::string_view from;
  std::string_view to;
};
constexpr Edge transition_edge(std::uint8_t n) {
  switch (n) {
    case 1: return {"NOT READY", "START-UP INHIBIT"};
    case 2: return {"START-UP INHIBIT", "READY"};
    case 3: return {"READY", "ON"};
    case 4: return {"ON", "ENABLED"};
    case 5: return {"ENABLED", "ON"};
    case 6: return {"ON", "READY"};
    case 7: return {"READY", "START-UP INHIBIT"};
    case 8: return {"ENABLED", "READY"};
    case 9: return {"ENABLED", "START-UP INHIBIT"};
    case 10: return {"ON", "START-UP INHIBIT"};
    case 11: return {"ENABLED", "EMERGENCY STOP ACTIVE"};
    case 12: return {"EMERGENCY STOP ACTIVE", "START-UP INHIBIT"};
    case 13: return {"any", "FAULT RESPONSE ACTIVE"};
    case 14: return {"FAULT RESPONSE ACTIVE", "FAULT"};
    case 15: return {"FAULT", "START-UP INHIBIT"};
    default: return {"?", "?"};
  }
}

}  // namespace

std::string_view to_string(Target t) { return state_row(target_state(t)).name; }

std::string_view to_string(Failure f) {
  switch (f) {
    case Failure::none: return "none";
    case Failure::timeout: return "timeout";
    case Failure::fault: return "fault";
    case Failure::left_target: return "left target";
    case Failure::invalid_status: return "invalid status word";
  }
  return "?";
}

SequencerConfig SequencerConfig::defaults() {
  SequencerConfig c;
  c.transition_timeout.fill(200ms);
  c.transition_timeout[0] = 0ms;
  c.transition_timeout[13] = 0ms;
  c.transition_timeout[1] = 10s;   // the VF1000 initialises for about 4 s after power-on (6.1)
  c.transition_timeout[14] = 10s;  // the drive's fault reaction (braking) may take seconds
  return c;
}

Sequencer::Sequencer(const SequencerConfig& config)
    : config_(config), app_bits_(static_cast<Word>(config.application_bits & ~kOwnedBits)) {}

void Sequencer::restart() {
  report_ = Report{};
  last_control_ = 0;
  prev_state_.reset();
  pulse_started_ = false;
}

void Sequencer::begin(Goal g, Time now) {
  report_.goal = g;
  report_.phase = Phase::moving;
  report_.failure = Failure::none;
  report_.transition = 0;
  report_.since = now;
  report_.waited = 0ns;
  report_.timeout = 0ns;
  pulse_started_ = false;
}

void Sequencer::request(Target t, Time now) {
  report_.target = t;
  begin(Goal::target, now);
}

void Sequencer::request_emergency_stop(Time now) { begin(Goal::emergency_stop, now); }
void Sequencer::request_block_power(Time now) { begin(Goal::block_power, now); }

Word Sequencer::emit(Word drivecom_bits) {
  last_control_ = static_cast<Word>((drivecom_bits & cw::kDrivecomMask) | app_bits_);
  report_.command_sent = last_control_;
  return last_control_;
}

void Sequencer::wait_for(std::uint8_t transition, Time now) {
  if (transition != report_.transition || report_.state_seen != prev_state_) {
    report_.since = now;
  }
  report_.transition = transition;
  report_.timeout = config_.transition_timeout[transition & 0x0FU];
  report_.waited = now - report_.since;
  if (report_.waited > report_.timeout) fail(Failure::timeout);
}

void Sequencer::fail(Failure f) {
  report_.phase = Phase::failed;
  report_.failure = f;
}

Sequencer::Move Sequencer::reset_pulse(Time now) {
  // 15: a real rising edge of bit 7, repeated as a pulse while the drive stays in FAULT.
  const bool high = (last_control_ & kResetBit) != 0;
  if (!pulse_started_) {
    pulse_started_ = true;
    pulse_edge_ = now;
    // Coming from a word with bit 7 high there is no edge yet: drop it first.
    return {high ? Word{0} : kResetBit, 15};
  }
  if (now - pulse_edge_ >= config_.reset_pulse) {
    pulse_edge_ = now;
    return {high ? Word{0} : kResetBit, 15};
  }
  return {high ? kResetBit : Word{0}, 15};
}

Sequencer::Move Sequencer::plan(State s, Time now) {
  const Word bp = command_word(Command::block_power);
  const Word sd = command_word(Command::shutdown);
  const Word dis = command_word(Command::disable);
  const Word en = command_word(Command::enable);
  // States every target leaves the same way.
  switch (s) {
    case State::fault: return reset_pulse(now);
    case State::fault_response_active: return {bp, 14};  // wait, bit 7 low
    case State::emergency_stop_active: return {bp, 12};
    default: break;
  }
  pulse_started_ = false;
  switch (report_.target) {
    case Target::enabled:
      switch (s) {
        case State::not_ready: return {sd, 1};
        case State::start_up_inhibit: return {sd, 2};
        case State::ready: return {en, 3};  // LUST drives take 3 and 4 in one sample (5.3.4)
        case State::on: return {en, 4};
        case State::enabled: return {en, 0};
        default: break;
      }
      break;
    case Target::on:
      switch (s) {
        case State::not_ready: return {sd, 1};
        case State::start_up_inhibit: return {sd, 2};
        case State::ready: return {dis, 3};
        case State::on: return {dis, 0};
        case State::enabled: return {dis, 5};
        default: break;
      }
      break;
    case Target::ready:
      switch (s) {
        case State::not_ready: return {sd, 1};
        case State::start_up_inhibit: return {sd, 2};
        case State::ready: return {sd, 0};
        case State::on: return {sd, 6};
        case State::enabled: return {sd, 8};
        default: break;
      }
      break;
    case Target::start_up_inhibit:
      switch (s) {
        case State::not_ready: return {bp, 1};
        case State::start_up_inhibit: return {bp, 0};
        case State::ready: return {bp, 7};
        case State::on: return {bp, 10};
        case State::enabled: return {bp, 9};
        default: break;
      }
      break;
  }
  return {bp, 0};
}

Word Sequencer::step(Word status, Time now) {
  const std::optional<State> st = decode_state(status);
  report_.status_seen = status;
  report_.state_seen = st;
  // The common case of every cycle: holding a reached target.
  if (report_.goal == Goal::target && report_.phase == Phase::reached &&
      st == target_state(report_.target)) {
    prev_state_ = st;
    return emit(last_control_);
  }
  struct Remember {
    std::optional<State>& prev;
    const std::optional<State>& now;
    ~Remember() { prev = now; }
  } remember{prev_state_, st};

  const Word bp = command_word(Command::block_power);
  switch (report_.goal) {
    case Goal::idle: return emit(bp);

    case Goal::emergency_stop:
    case Goal::block_power: {
      const bool estop = report_.goal == Goal::emergency_stop;
      const Word word = estop ? command_word(Command::emergency_stop) : bp;
      if (!st) {
        wait_for(report_.transition, now);
        return emit(word);
      }
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
      } else if (report_.phase != Phase::failed) {
        report_.phase = Phase::moving;
        wait_for(t, now);
      }
      return emit(word);
    }

    case Goal::target: break;
  }

  if (report_.phase == Phase::failed) {
    // Hold still. Out of a fault only a new request moves on, and never with ENABLE.
    if (st && is_fault_state(*st)) return emit(bp);
    return emit(last_control_);
  }
  if (!st) {
    // An unreadable status word: keep the command, let the transition's timeout decide.
    wait_for(report_.transition, now);
    if (report_.phase == Phase::failed) report_.failure = Failure::invalid_status;
    return emit(last_control_);
  }
  const bool was_fault = prev_state_ && is_fault_state(*prev_state_);
  if (is_fault_state(*st) && prev_state_ && !was_fault) {
    fail(Failure::fault);
    return emit(bp);
  }
  if (report_.phase == Phase::reached && *st != target_state(report_.target)) {
    fail(Failure::left_target);
    return emit(last_control_);
  }
  const Move m = plan(*st, now);
  if (m.transition == 0) {
    report_.phase = Phase::reached;
    report_.transition = 0;
    report_.waited = 0ns;
  } else {
    report_.phase = Phase::moving;
    wait_for(m.transition, now);
  }
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
  const Edge e = transition_edge(r.transition);
  const std::string wait = "transition " + std::to_string(r.transition) + " (" + std::string(e.from) +
                           " -> " + std::string(e.to) + ")";
  if (r.phase == Phase::moving) {
    return "moving to " + goal + ": waiting for " + wait + " for " + ms(r.waited) + " of " +
           ms(r.timeout) + "; state " + seen + ", sending " + sent;
  }
  switch (r.failure) {
    case Failure::timeout:
    case Failure::invalid_status:
      return wait + " did not happen: state seen " + seen + ", command sent " + sent + ", waited " +
             ms(r.waited) + " (timeout " + ms(r.timeout) + ")" +
             (r.failure == Failure::invalid_status ? "; the status word matches no DRIVECOM state"
                                                   : "");
    case Failure::fault:
      return "the drive faulted on the way to " + goal + ": state seen " + seen + ", command sent " +
             sent + "; request a target again to reset the fault";
    case Failure::left_target:
      return "the drive left " + goal + " on its own: state seen " + seen + ", command sent " + sent;
    case Failure::none: break;
  }
  return "failed: " + seen;
}

}  // namespace ibs::drivecom
