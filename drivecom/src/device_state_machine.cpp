#include "ibs/drivecom/device_state_machine.hpp"

namespace ibs::drivecom {

std::optional<TransitionRow> DeviceStateMachine::next(const DeviceInputs& in,
                                                      bool reset_edge) const {
  const Command cmd = decode_command(in.control);
  // 13: a fault takes every state except the two fault states to FAULT RESPONSE ACTIVE.
  if (in.fault_present && state_ != State::fault && state_ != State::fault_response_active) {
    return TransitionRow{state_, cmd, State::fault_response_active, 13};
  }
  switch (state_) {
    case State::not_ready:
      if (in.initialised) return TransitionRow{state_, cmd, State::start_up_inhibit, 1};
      return std::nullopt;
    case State::fault_response_active:
      if (in.fault_reaction_done) return TransitionRow{state_, cmd, State::fault, 14};
      return std::nullopt;
    case State::fault:
      // 15: RESET FAULT on the 0 -> 1 edge of bit 7, once the cause has gone.
      if (reset_edge && !in.fault_present) {
        return TransitionRow{state_, cmd, State::start_up_inhibit, 15};
      }
      return std::nullopt;
    case State::emergency_stop_active:
      if (estop_exit_ == EmergencyStopExit::automatic_when_stopped && in.stopped) {
        return TransitionRow{state_, cmd, State::start_up_inhibit, 12};
      }
      break;
    case State::start_up_inhibit:
    case State::ready:
    case State::on:
    case State::enabled: break;
  }
  for (const auto& row : kCommandTransitions) {
    if (row.from == state_ && row.command == cmd) return row;
  }
  return std::nullopt;
}

SampleResult DeviceStateMachine::sample(const DeviceInputs& in) {
  SampleResult r;
  bool reset_edge = reset_fault_edge(last_control_, in.control);
  last_control_ = in.control;
  while (r.count < SampleResult::kMax) {
    const auto t = next(in, reset_edge);
    if (!t) break;
    state_ = t->to;
    r.transitions[r.count++] = t->number;
    // The edge is consumed by the one transition it can cause.
    if (t->number == 15) reset_edge = false;
  }
  r.state = state_;
  return r;
}

}  // namespace ibs::drivecom
