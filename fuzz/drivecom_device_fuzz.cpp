// The drive's DRIVECOM state machine (drivecom::DeviceStateMachine, docs/drivecom.md "Device
// side") fed arbitrary control words and inputs, sample by sample, with power-ons and forced
// states in between.
//
// Asserts, after every sample:
// - the status word the drive shows (any last control word, any device bits 7-15) matches
//   exactly one row of the state table of 5.1.3, and that row is the machine's state;
// - the transitions reported form a chain of documented transitions from the state before to
//   the state after, each one allowed by the inputs: a command transition only for the command
//   the control word carries, 1 only when initialised, 13 only with a fault present and from a
//   non-fault state, 14 only when the reaction is done, 15 only on a reset edge (0 -> 1 of bit 7)
//   seen in FAULT with the cause gone, 12 without BLOCK POWER only on the VF1000 at standstill,
//   4 never while the drive may not be engaged (enable_locked);
// - a fault present always ends the sample in FAULT RESPONSE ACTIVE or FAULT;
// - the sample went on until the state was stable: the same inputs again take no transition;
// - holds() never says a sample holds that moves; without the enable lock (which makes it
//   conservative) it says so for every sample of a stable state that moves nothing.
//
// Input: byte 0 chooses the emergency-stop exit and the initial state; then per sample two bytes
// of control word, one byte of inputs (bits 0-3: initialised, fault present, reaction done,
// stopped; bits 4-5: 01 power-on, 10 force a state first; bit 6: enable locked), one byte of
// device status bits.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "ibs/drivecom/control_word.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/drivecom/status_word.hpp"

namespace {

using namespace ibs;
using namespace ibs::drivecom;
using ibs::fuzz::fail;
using ibs::fuzz::hex4;

std::string name(State s) { return std::string(to_string(s)); }

bool is_fault(State s) { return s == State::fault || s == State::fault_response_active; }

// The status word shows exactly one state, and it is `s`.
void check_status(State s, Word last_control, const StatusExtras& extras) {
  const Word status = status_word(s, last_control, extras);
  int rows = 0;
  std::string matched;
  for (const StateRow& row : kStateTable) {
    if ((status & row.mask) == row.value) {
      ++rows;
      matched += " " + std::string(row.name);
    }
  }
  if (rows != 1 || decode_state(status) != s) {
    fail("status word " + hex4(status) + " for state " + name(s) + " (last control " + hex4(last_control) +
         ") matches " + std::to_string(rows) + " rows of the state table:" + matched);
  }
}

// Is command transition `number` from `from` allowed for the command `cmd`?
bool command_row_allows(std::uint8_t number, State from, Command cmd) {
  for (const TransitionRow& row : kCommandTransitions) {
    if (row.number == number && row.from == from && row.command == cmd) return true;
  }
  return false;
}

void check_sample(const DeviceStateMachine& before_machine, const DeviceInputs& in, EmergencyStopExit exit,
                  const SampleResult& r, const DeviceStateMachine& after) {
  const State before = before_machine.state();
  const Word prev_control = before_machine.last_control();
  const Command cmd = decode_command(in.control);
  const auto where = [&] {
    return "sample from " + name(before) + " with control " + hex4(in.control) + " (previous " +
                            hex4(prev_control) + "), initialised " + std::to_string(in.initialised) +
                            ", fault " + std::to_string(in.fault_present) + ", reaction done " +
                            std::to_string(in.fault_reaction_done) + ", stopped " + std::to_string(in.stopped) +
                            ", enable locked " + std::to_string(in.enable_locked);
  };
  if (r.state != after.state()) fail(where() + ": the result says " + name(r.state) + ", the machine " + name(after.state()));
  if (r.count > SampleResult::kMax) fail(where() + ": " + std::to_string(r.count) + " transitions reported");
  if (after.last_control() != in.control) fail(where() + ": last control " + hex4(after.last_control()));

  State s = before;
  bool edge = before == State::fault && reset_fault_edge(prev_control, in.control);
  bool saw13 = false;
  for (std::size_t i = 0; i < r.count; ++i) {
    const std::uint8_t n = r.transition(i);
    const auto ends = transition_ends(n);
    const auto t = [&] { return where() + ": transition " + std::to_string(n) + " (#" + std::to_string(i + 1) + ") from " + name(s); };
    if (!ends) fail(t() + ": no such transition in the profile");
    if (ends->from && *ends->from != s) fail(t() + ": it starts in " + name(*ends->from));
    bool allowed = false;
    switch (n) {
      case 1: allowed = in.initialised; break;
      case 13: allowed = in.fault_present && !is_fault(s); saw13 = true; break;
      case 14: allowed = in.fault_reaction_done; break;
      case 15:
        allowed = edge && !in.fault_present;
        edge = false;  // one edge, one reset
        break;
      case 12:
        allowed = command_row_allows(n, s, cmd) ||
                  (exit == EmergencyStopExit::automatic_when_stopped && in.stopped);
        break;
      case 4: allowed = command_row_allows(n, s, cmd) && !in.enable_locked; break;
      default: allowed = command_row_allows(n, s, cmd); break;
    }
    if (!allowed) fail(t() + ": not allowed by these inputs (command " + std::string(to_string(cmd)) + ")");
    // A fault present takes precedence over every other transition out of a healthy state.
    if (in.fault_present && !is_fault(s) && n != 13) fail(t() + ": a fault is present, 13 must come first");
    s = ends->to;
  }
  if (s != after.state()) fail(where() + ": the transitions lead to " + name(s) + ", the machine is in " + name(after.state()));
  if (in.fault_present && !is_fault(before) && !saw13) fail(where() + ": a fault is present but 13 was not taken");
  if (in.fault_present && !is_fault(after.state())) fail(where() + ": a fault is present and the sample ended in " + name(after.state()));
  if (r.count == 0 && after.state() != before) fail(where() + ": the state changed without a transition");
  // Stable: the same inputs again (no new edge) move nothing.
  if (r.count < SampleResult::kMax) {
    DeviceStateMachine again = after;
    const SampleResult r2 = again.sample(in);
    if (r2.count != 0 || again.state() != after.state()) {
      fail(where() + ": the sample stopped in " + name(after.state()) + " before the state was stable: the same inputs take transition " +
           std::to_string(r2.transition(0)) + " to " + name(again.state()));
    }
  } else {
    fail(where() + ": " + std::to_string(r.count) + " transitions in one sample (the longest chain is 4)");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ibs::fuzz::Input in(data, size);
  const std::uint8_t setup = in.ConsumeIntegral<std::uint8_t>();
  const EmergencyStopExit exit =
      (setup & 1U) != 0 ? EmergencyStopExit::automatic_when_stopped : EmergencyStopExit::on_block_power_only;
  DeviceStateMachine m(exit, static_cast<State>((setup >> 1U) % kStateCount));
  check_status(m.state(), m.last_control(), {});

  while (in.remaining_bytes() > 0) {
    DeviceInputs inputs;
    inputs.control = in.ConsumeIntegral<std::uint16_t>();
    const std::uint8_t flags = in.ConsumeIntegral<std::uint8_t>();
    const std::uint8_t extra = in.ConsumeIntegral<std::uint8_t>();
    inputs.initialised = (flags & 0x01U) != 0;
    inputs.fault_present = (flags & 0x02U) != 0;
    inputs.fault_reaction_done = (flags & 0x04U) != 0;
    inputs.stopped = (flags & 0x08U) != 0;
    inputs.enable_locked = (flags & 0x40U) != 0;
    switch ((flags >> 4U) & 3U) {
      case 1: m.power_on(); break;
      case 2: m.force(static_cast<State>(extra % kStateCount), static_cast<Word>(extra << 8U | extra)); break;
      default: break;
    }
    check_status(m.state(), m.last_control(), {});

    const DeviceStateMachine before = m;
    const bool holds = m.holds(inputs);
    const SampleResult r = m.sample(inputs);
    check_sample(before, inputs, exit, r, m);
    if (holds && (r.count != 0 || m.state() != before.state())) {
      fail("holds() said " + name(before.state()) + " holds with control " + hex4(inputs.control) +
           ", the sample took transition " + std::to_string(r.transition(0)));
    }
    if (!holds && r.count == 0 && !(inputs.fault_present || inputs.enable_locked || before.state() == State::not_ready ||
                                    is_fault(before.state()) || before.state() == State::emergency_stop_active)) {
      fail("holds() said " + name(before.state()) + " does not hold with control " + hex4(inputs.control) +
           ", but nothing moved");
    }

    StatusExtras e;
    e.alarm = (extra & 0x01U) != 0;
    e.message = (extra & 0x02U) != 0;
    e.remote = (extra & 0x04U) != 0;
    e.reference_reached = (extra & 0x08U) != 0;
    e.limit_value = (extra & 0x10U) != 0;
    e.bit14 = (extra & 0x20U) != 0;
    e.bit15 = (extra & 0x40U) != 0;
    check_status(m.state(), m.last_control(), e);
    check_status(m.state(), inputs.control, e);
    if (decode_state(m.state_bits()) != m.state()) {
      fail("state_bits() " + hex4(m.state_bits()) + " does not decode to " + name(m.state()));
    }
  }
  return 0;
}
