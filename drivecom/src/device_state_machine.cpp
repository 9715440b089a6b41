#include "ibs/drivecom/device_state_machine.hpp"

namespace ibs::drivecom {

detail::Cell DeviceStateMachine::next(const DeviceInputs& in, Command cmd, bool reset_edge) const {
  // 13: a fault takes every state except the two fault states to FAULT RESPONSE ACTIVE.
  if (in.fault_present && state_ != State::fault && state_ != State::fault_response_active) {
    return {State::fault_response_active, 13};
  }
  switch (state_) {
    case State::not_ready:
      if (in.initialised) return {State::start_up_inhibit, 1};
      return {state_, 0};
    case State::fault_response_active:
      if (in.fault_reaction_done) return {State::fault, 14};
      return {state_, 0};
    case State::fault:
      // 15: RESET FAULT on the 0 -> 1 edge of bit 7, once the cause has gone.
      if (reset_edge && !in.fault_present) return {State::start_up_inhibit, 15};
      return {state_, 0};
    case State::emergency_stop_active:
      if (estop_exit_ == EmergencyStopExit::automatic_when_stopped && in.stopped) {
        return {State::start_up_inhibit, 12};
      }
      break;
    case State::start_up_inhibit:
    case State::ready:
    case State::on:
    case State::enabled: break;
  }
  const detail::Cell cell = detail::kTransitionLut[static_cast<std::size_t>(state_)][static_cast<std::size_t>(cmd)];
  if (in.enable_locked && cell.number == 4) return {state_, 0};
  return cell;
}

SampleResult DeviceStateMachine::sample_transitions(const DeviceInputs& in) {
  SampleResult r;
  // RESET FAULT acts on an edge seen in FAULT; an edge during the fault reaction is not stored.
  bool reset_edge = state_ == State::fault && reset_fault_edge(last_control_, in.control);
  last_control_ = in.control;
  const Command cmd = decode_command(in.control);
  while (r.count < SampleResult::kMax) {
    const detail::Cell t = next(in, cmd, reset_edge);
    if (t.number == 0) break;
    state_ = t.to;
    r.add(t.number);
    // The edge is consumed by the one transition it can cause.
    if (t.number == 15) reset_edge = false;
  }
  r.state = state_;
  return r;
}

}  // namespace ibs::drivecom
