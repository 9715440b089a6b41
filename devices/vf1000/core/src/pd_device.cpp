#include "ibs/devices/vf1000/pd_device.hpp"

#include <algorithm>
#include <cmath>

namespace ibs::devices {

namespace {

using drivecom::State;

double seconds(Duration d) { return static_cast<double>(d.count()) / 1e9; }

// Moves `value` towards `target` by at most `step`; returns true when it had to limit.
bool approach(double& value, double target, double step) {
  const double diff = target - value;
  if (std::fabs(diff) <= step) {
    value = target;
    return false;
  }
  value += diff > 0 ? step : -step;
  return true;
}

drivecom::State initial_state(DeviceStart s) {
  return s == DeviceStart::fault ? State::fault : State::start_up_inhibit;
}

}  // namespace

Vf1000PdDevice::Vf1000PdDevice(const Vf1000PdConfig& config)
    : config_(config),
      machine_(drivecom::EmergencyStopExit::automatic_when_stopped, State::start_up_inhibit) {
  start(DeviceStart::operational);
}

void Vf1000PdDevice::power_on() {
  machine_.power_on();
  since_power_on_ = 0ns;
  boot_time_ = config_.init_time;
  initialised_ = false;
  setpoint_ = 0.0;
  frequency_ = 0.0;
  at_setpoint_ = false;
  zero_hz_off_ = false;
  status_ = machine_.state_bits();
  comm_ = 0x0000;
}

void Vf1000PdDevice::software_reset(Word control) {
  power_on();
  boot_time_ = config_.reset_time;
  machine_.force(State::not_ready, control);
  status_ = machine_.state_bits();
}

void Vf1000PdDevice::start(DeviceStart s) {
  machine_.force(initial_state(s));
  since_power_on_ = config_.init_time;
  initialised_ = true;
  setpoint_ = 0.0;
  frequency_ = 0.0;
  at_setpoint_ = false;
  zero_hz_off_ = false;
  status_ = drivecom::status_word(machine_.state(), 0, {});
  comm_ = 0x8000;
}

void Vf1000PdDevice::run_ramp(Word control, double dt_s) {
  const auto b = vf1000::decode_control_bits(control);
  const State s = machine_.state();
  if (s == State::emergency_stop_active || s == State::fault_response_active) {
    // EMERGENCY STOP brakes only with a stop ramp (36-RSTOP <> 0); otherwise the power stage is
    // switched off and the motor coasts (5.2.1).
    if (config_.stop_ramp_hz_per_s > 0 && s == State::emergency_stop_active) {
      approach(frequency_, 0.0, config_.stop_ramp_hz_per_s * dt_s);
    } else {
      frequency_ = 0.0;
    }
    at_setpoint_ = false;
    return;
  }
  if (s != State::enabled) {
    frequency_ = 0.0;
    at_setpoint_ = false;
    return;
  }
  if (!b.ramp_enable) {
    // Bit 4 = 0: the parameter-set stop function (36-RSTOP: stop ramp, or power stage off).
    if (config_.stop_ramp_hz_per_s > 0) {
      approach(frequency_, 0.0, config_.stop_ramp_hz_per_s * dt_s);
    } else {
      frequency_ = 0.0;
    }
    at_setpoint_ = false;
    return;
  }
  if (!b.ramp_run) {  // bit 5 = 0: the ramp stops at its current value
    at_setpoint_ = frequency_ == setpoint_;
    return;
  }
  const double target = b.ramp_follow ? setpoint_ : 0.0;  // bit 6 = 0: ramp to 0 Hz
  const bool up = std::fabs(target) > std::fabs(frequency_);
  const double rate = up ? config_.acceleration_hz_per_s : config_.deceleration_hz_per_s;
  approach(frequency_, target, rate * dt_s);
  at_setpoint_ = frequency_ == setpoint_;
}

void Vf1000PdDevice::sample(std::span<const Word> m2s, std::span<Word> s2m, Duration dt,
                            std::optional<Word> comm_out) {
  since_power_on_ += dt;
  if (!initialised_ && since_power_on_ >= boot_time_) initialised_ = true;
  const Word control = override_ ? *override_ : m2s[0];
  const auto b = vf1000::decode_control_bits(control);
  // STR runs clockwise, STL counter-clockwise; neither or both: no direction, 0 Hz.
  const double direction = b.str == b.stl ? 0.0 : (b.str ? 1.0 : -1.0);
  const double requested_hz = vf1000::reference_hz(m2s[1]);
  setpoint_ = std::min(requested_hz, config_.max_frequency_hz) * direction;

  drivecom::DeviceInputs in;
  in.control = control;
  in.initialised = initialised_;
  in.fault_present = fault_present_;
  in.fault_reaction_done = true;  // the VF1000 switches its power stage off at once
  in.stopped = frequency_ == 0.0 || config_.stop_ramp_hz_per_s <= 0;
  last_ = machine_.sample(in);
  run_ramp(control, seconds(dt));
  // 5.2.3: at a reference of 0 Hz the inverter shuts the motor down once its ramp has brought the
  // frequency there (unless DC-Stop holds it); a reference above 0 Hz starts it again from 0 Hz.
  // DRIVECOM's state is the master's command and stays ENABLED (VF-E19).
  zero_hz_off_ = machine_.state() == State::enabled && !config_.dc_stop && m2s[1] == 0 && frequency_ == 0.0;
  // The stop ramp has been worked through: START-UP INHIBIT by itself (5.2.1) in the same sample.
  if (machine_.state() == State::emergency_stop_active && frequency_ == 0.0) {
    in.stopped = true;
    const auto more = machine_.sample(in);
    for (std::uint8_t i = 0; i < more.count; ++i) last_.add(more.transition(i));
    last_.state = more.state;
  }

  drivecom::StatusExtras e;
  e.message = false;  // bit 8 is not implemented on the VF1000 (5.2.2)
  e.remote = initialised_;
  e.reference_reached = machine_.state() == State::enabled && at_setpoint_;
  // Bit 11: the reference is limited (above the maximum frequency 22-FMAX1).
  e.limit_value = requested_hz > config_.max_frequency_hz && direction != 0.0;
  e.bit14 = s2out_;
  e.bit15 = s1out_;
  status_ = drivecom::status_word(machine_.state(), machine_.last_control(), e);
  comm_ = comm_out ? *comm_out : (initialised_ ? Word{0x8000} : Word{0x0000});
  output(s2m);
}

void Vf1000PdDevice::output(std::span<Word> s2m) const {
  s2m[0] = status_;
  s2m[1] = vf1000::actual_word(frequency_);
  s2m[2] = comm_;
}

}  // namespace ibs::devices
