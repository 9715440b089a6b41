// The DRIVECOM Profile 20 state machine as the drive executes it (INTERBUS manual 5.1.1-5.1.3), with
// the transition numbers of the profile. One call of sample() is one processing step of the
// drive; the drive's sampling period (1 ms MC6000, 8.2 ms VF1000) belongs to the device model.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "ibs/drivecom/control_word.hpp"
#include "ibs/drivecom/status_word.hpp"

namespace ibs::drivecom {

// How EMERGENCY STOP ACTIVE ends (transition 12).
enum class EmergencyStopExit : std::uint8_t {
  // VF1000 (5.2.1): falls to START-UP INHIBIT by itself once the stop ramp has been worked through
  // (or at once without a stop ramp); BLOCK POWER also ends it.
  automatic_when_stopped,
  // MC6000: stays until BLOCK POWER.
  on_block_power_only,
};

// What the drive knows besides the control word, sampled together with it.
struct DeviceInputs {
  Word control = 0;
  bool initialised = true;          // self-test done: NOT READY -> START-UP INHIBIT (1)
  bool fault_present = false;       // a fault condition: any state -> FAULT RESPONSE ACTIVE (13)
  bool fault_reaction_done = true;  // the fault reaction has finished (14)
  bool stopped = true;              // the motor has come to rest (VF1000 transition 12)
  // The drive may not be engaged: transition 4 (ON -> ENABLED) is not taken, ENABLE leaves it in
  // ON (the MC6000 during an 80-SLOAD download, LUSTBUS manual 11.4; a decision, docs/drivecom.md).
  bool enable_locked = false;
};

// One row of the transition table: `from` + `command` -> `to` with its profile number.
struct TransitionRow {
  State from;
  Command command;
  State to;
  std::uint8_t number;
};

// Transitions triggered by control commands (5.1.2, "Device Control Commands"). The automatic
// ones (0, 1, 12 on VF1000, 13, 14) and RESET FAULT (15) are handled beside the table.
inline constexpr std::array<TransitionRow, 14> kCommandTransitions{{
    {State::start_up_inhibit, Command::shutdown, State::ready, 2},
    {State::ready, Command::disable, State::on, 3},
    {State::ready, Command::enable, State::on, 3},
    {State::on, Command::enable, State::enabled, 4},
    {State::enabled, Command::disable, State::on, 5},
    {State::on, Command::shutdown, State::ready, 6},
    {State::ready, Command::block_power, State::start_up_inhibit, 7},
    {State::ready, Command::emergency_stop, State::start_up_inhibit, 7},
    {State::enabled, Command::shutdown, State::ready, 8},
    {State::enabled, Command::block_power, State::start_up_inhibit, 9},
    {State::on, Command::block_power, State::start_up_inhibit, 10},
    {State::on, Command::emergency_stop, State::start_up_inhibit, 10},
    {State::enabled, Command::emergency_stop, State::emergency_stop_active, 11},
    {State::emergency_stop_active, Command::block_power, State::start_up_inhibit, 12},
}};

// Transitions no command triggers (5.1.1): the end of the self-test, a fault and its reaction,
// RESET FAULT. With kCommandTransitions this names every numbered transition of the profile.
struct AutomaticTransition {
  std::uint8_t number;
  std::optional<State> from;  // nullopt: from every state but the two fault states
  State to;
};
inline constexpr std::array<AutomaticTransition, 4> kAutomaticTransitions{{
    {1, State::not_ready, State::start_up_inhibit},
    {13, std::nullopt, State::fault_response_active},
    {14, State::fault_response_active, State::fault},
    {15, State::fault, State::start_up_inhibit},
}};

// Where transition `number` leads from and to (from nullopt: any state); nullopt for a number
// the profile does not have.
struct TransitionEnds {
  std::optional<State> from;
  State to;
};
constexpr std::optional<TransitionEnds> transition_ends(std::uint8_t number) {
  for (const auto& row : kCommandTransitions) {
    if (row.number == number) return TransitionEnds{row.from, row.to};
  }
  for (const auto& row : kAutomaticTransitions) {
    if (row.number == number) return TransitionEnds{row.from, row.to};
  }
  return std::nullopt;
}

namespace detail {
// (state, command) -> transition, derived once from kCommandTransitions; number 0 = none.
struct Cell {
  State to;
  std::uint8_t number;
};
constexpr std::array<std::array<Cell, 5>, kStateCount> make_transition_lut() {
  std::array<std::array<Cell, 5>, kStateCount> lut{};
  for (std::size_t s = 0; s < kStateCount; ++s) {
    for (auto& c : lut[s]) c = {static_cast<State>(s), 0};
  }
  for (const auto& row : kCommandTransitions) {
    lut[static_cast<std::size_t>(row.from)][static_cast<std::size_t>(row.command)] = {row.to, row.number};
  }
  return lut;
}
inline constexpr auto kTransitionLut = make_transition_lut();
}  // namespace detail

// The transitions one sample performed, in order (at most a handful: the longest chain is
// 15, 2, 3, 4 or 1, 2, 3, 4). Packed four bits a transition so that it fits a register.
struct SampleResult {
  static constexpr std::size_t kMax = 8;
  std::uint32_t packed = 0;
  std::uint8_t count = 0;
  State state = State::not_ready;

  [[nodiscard]] constexpr std::uint8_t transition(std::size_t i) const {
    return static_cast<std::uint8_t>((packed >> (4 * i)) & 0xFU);
  }
  constexpr void add(std::uint8_t number) {
    if (count >= kMax) return;
    packed |= (number & 0xFU) << (4U * count);
    ++count;
  }
};

namespace detail {
// A state the command table alone moves (5.1.2): no automatic transition leaves it.
constexpr bool commanded_state(State s) { return s >= State::start_up_inhibit && s <= State::enabled; }

// What one sample does in a commanded state under one command with no fault and no enable lock:
// the transitions of kTransitionLut taken until the state moves no more (READY + ENABLE takes
// 3 then 4, 5.3.4), and where they end. Derived once from the table, so that such a sample -- the
// whole start-up, every hold (no transition: count 0, the state itself) -- is one lookup instead
// of the general loop of sample_transitions. `settles` is false where the chain ends outside the
// commanded states (ENABLED + EMERGENCY STOP -> EMERGENCY STOP ACTIVE, whose exit depends on the
// drive's other inputs) and for every state that is no commanded state (NOT READY, the fault
// states, EMERGENCY STOP ACTIVE: automatic transitions leave them): the loop decides. Eight bytes
// a cell, so that the lookup is one load of one cell.
struct alignas(8) Chain {
  std::uint32_t packed = 0;  // as SampleResult::packed
  std::uint8_t count = 0;
  State state = State::not_ready;
  bool settles = false;
  [[nodiscard]] constexpr SampleResult result() const {
    SampleResult r;
    r.packed = packed;
    r.count = count;
    r.state = state;
    return r;
  }
};
static_assert(sizeof(Chain) == 8);
constexpr std::array<std::array<Chain, 5>, kStateCount> make_chain_lut() {
  std::array<std::array<Chain, 5>, kStateCount> lut{};
  for (std::size_t s = 0; s < kStateCount; ++s) {
    for (std::size_t c = 0; c < 5; ++c) {
      SampleResult r;
      State at = static_cast<State>(s);
      while (r.count < SampleResult::kMax && commanded_state(at)) {
        const Cell t = kTransitionLut[static_cast<std::size_t>(at)][c];
        if (t.number == 0) break;
        r.add(t.number);
        at = t.to;
      }
      // settles: started and ended in the commanded states (a state that is none takes no step
      // of the loop above, so it must be excluded here).
      lut[s][c] = {r.packed, r.count, at, commanded_state(static_cast<State>(s)) && commanded_state(at)};
    }
  }
  return lut;
}
inline constexpr auto kChainLut = make_chain_lut();
static_assert(kChainLut[static_cast<std::size_t>(State::ready)][static_cast<std::size_t>(Command::enable)].packed == 0x43,
              "READY + ENABLE: 3 then 4 in one sample (5.3.4)");
// The lookup replaces the hold of kTransitionLut too (sample() and holds()): in a commanded state
// a command the table does not move on is a settled chain of no transition that stays where it
// is, and a settled chain of no transition is such a hold; a settled chain starts in a commanded
// state.
constexpr bool chain_lut_consistent() {
  for (std::size_t s = 0; s < kStateCount; ++s) {
    for (std::size_t c = 0; c < 5; ++c) {
      const Chain& ch = kChainLut[s][c];
      const auto st = static_cast<State>(s);
      if (ch.settles && !commanded_state(st)) return false;
      const bool table_holds = commanded_state(st) && kTransitionLut[s][c].number == 0;
      if (table_holds != (ch.settles && ch.count == 0)) return false;
      if (table_holds && !(ch.packed == 0 && ch.state == st)) return false;
    }
  }
  return true;
}
static_assert(chain_lut_consistent(), "kChainLut holds where kTransitionLut takes no transition");
// kChainLut indexed by the control word's bits 0-3 instead of its command (decode_command folded
// in), so that sample() finds its chain with one load rather than two in a row: in a closed loop
// every cycle waits for the last one's status word, and each dependent load adds to that wait.
constexpr std::array<std::array<Chain, 16>, kStateCount> make_chain_by_control() {
  std::array<std::array<Chain, 16>, kStateCount> lut{};
  for (std::size_t s = 0; s < kStateCount; ++s) {
    for (std::size_t bits = 0; bits < 16; ++bits) {
      lut[s][bits] = kChainLut[s][static_cast<std::size_t>(decode_command(static_cast<Word>(bits)))];
    }
  }
  return lut;
}
alignas(64) inline constexpr auto kChainByControl = make_chain_by_control();
static_assert(kChainByControl[static_cast<std::size_t>(State::ready)][0x0F].packed == 0x43,
              "READY + 000FH: 3 then 4 in one sample (5.3.4)");
}  // namespace detail

// True where the power stage drives the motor.
constexpr bool power_stage_enabled(State s) {
  return s == State::enabled || s == State::emergency_stop_active ||
         s == State::fault_response_active;
}

class DeviceStateMachine {
 public:
  explicit DeviceStateMachine(EmergencyStopExit estop_exit, State initial = State::not_ready)
      : estop_exit_(estop_exit), state_(initial) {}

  // Processes one sample: transitions are taken until the state is stable, so READY + ENABLE
  // reaches ENABLED in one sample (5.3.4). Never allocates, never throws.
  SampleResult sample(const DeviceInputs& in) {
    // The common cases of every sample, inline: a commanded state, no fault, no enable lock.
    // Its transitions follow from the state and the command alone: a hold (the most common) or
    // a move, one lookup in detail::kChainByControl (kChainLut by bits 0-3; `settles` is false
    // outside the commanded states, so the state needs no check of its own).
    if (!in.fault_present && !in.enable_locked) {
      const detail::Chain c = detail::kChainByControl[static_cast<std::size_t>(state_)][in.control & 0x0FU];
      if (c.settles) {
        last_control_ = in.control;
        // A hold (no transition) writes no state: a drive that holds then does not wait each
        // sample for the state stored by the last (store to load).
        if (c.count != 0) state_ = c.state;
        return c.result();
      }
    }
    return sample_transitions(in);
  }
  // sample() without its lookup (detail::kChainByControl): every sample through the general loop.
  // The same result and the same state as sample(); DeviceStateMachineShortcut.* compares the
  // two over random runs.
  SampleResult sample_general(const DeviceInputs& in) { return sample_transitions(in); }
  // True when a sample with these inputs takes no transition and changes nothing but the last
  // control word: a stable state (START-UP INHIBIT .. ENABLED), no fault, and a command that
  // does not move it. The same inputs again then hold it again.
  // The same lookup as sample()'s: a settled chain of no transition (chain_lut_consistent()).
  [[nodiscard]] bool holds(const DeviceInputs& in) const {
    if (in.fault_present || in.enable_locked) return false;
    const detail::Chain c = detail::kChainByControl[static_cast<std::size_t>(state_)][in.control & 0x0FU];
    return c.settles && c.count == 0;
  }

  [[nodiscard]] State state() const { return state_; }
  [[nodiscard]] Word last_control() const { return last_control_; }
  // Bits 0-6 of the status word (state + bits 4/5 from the last control word).
  [[nodiscard]] Word state_bits() const { return drivecom::state_bits(state_, last_control_); }

  // Power-on (transition 0): NOT READY, no control word seen, bit 7 history cleared.
  void power_on() {
    state_ = State::not_ready;
    last_control_ = 0;
  }
  // Puts the machine in a state directly (trace `init`, tests).
  void force(State s, Word last_control = 0) {
    state_ = s;
    last_control_ = last_control;
  }

 private:
  // A sample that takes at least one transition (or may: the fault and e-stop states).
  SampleResult sample_transitions(const DeviceInputs& in);
  // The transition the state machine takes next (number 0: none).
  detail::Cell next(const DeviceInputs& in, Command cmd, bool reset_edge) const;

  EmergencyStopExit estop_exit_;
  State state_;
  Word last_control_ = 0;
};

}  // namespace ibs::drivecom
