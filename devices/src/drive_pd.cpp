#include "ibs/devices/drive_pd.hpp"

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

drivecom::State initial_state(InitState s) {
  return s == InitState::fault ? State::fault : State::start_up_inhibit;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

Mc6000PdDevice::Mc6000PdDevice(const Mc6000PdConfig& config)
    : config_(config),
      machine_(drivecom::EmergencyStopExit::on_block_power_only, State::start_up_inhibit),
      plant_(config.plant, kMc6000SamplePeriod) {
  start(InitState::operational);
}

void Mc6000PdDevice::power_on() {
  machine_.power_on();
  since_power_on_ = 0ns;
  initialised_ = false;
  reset_motion();
  status_ = machine_.state_bits();
}

void Mc6000PdDevice::start(InitState s) {
  machine_.force(initial_state(s));
  since_power_on_ = config_.init_time;
  initialised_ = true;
  reset_motion();
  status_ = drivecom::status_word(machine_.state(), 0, {});
}

void Mc6000PdDevice::reset_motion() {
  reference_ = 0.0;
  actual_ = 0.0;
  plant_.reset();
}

PlantInput Mc6000PdDevice::plant_input() const {
  // ENABLED follows the reference; EMERGENCY STOP ACTIVE and FAULT RESPONSE ACTIVE brake to 0 at
  // the torque limit (quick stop); with the power stage off the load coasts.
  const State s = machine_.state();
  PlantInput in{0.0, load_nm_, drivecom::power_stage_enabled(s)};
  if (s == State::enabled) in.speed_reference_rpm = std::clamp(reference_, -config_.max_speed_rpm, config_.max_speed_rpm);
  return in;
}

void Mc6000PdDevice::move_actual(Duration dt) {
  plant_.advance(dt, plant_input());
  actual_ = plant_.speed_rpm();
}

void Mc6000PdDevice::step_held(std::span<const Word> m2s, Duration dt, std::uint32_t count) {
  const auto& l = config_.layout;
  // SUPI 0: the INTERBUS CPU loops without exchanging data with the servo (3.2.2).
  if (!l.exchanges_data || count == 0) return;
  const Word control = override_ ? *override_ : (m2s.empty() ? Word{0} : m2s[0]);
  reference_ = interbus::mc6000::decode_reference(
      l, m2s.subspan(1, static_cast<std::size_t>(l.reference_words)));
  for (std::uint32_t k = 0; k < count; ++k) {
    sample_held(control, dt);
    if (initialised_ && machine_.holds({control, initialised_, fault_present_, true, true, enable_locked_})) {
      // The state machine holds its state with these words for the rest of the stretch (what
      // decides that does not change in it): the other samples only move the plant, with the
      // same input each time.
      plant_.advance_held(dt, plant_input(), count - k - 1);
      actual_ = plant_.speed_rpm();
      break;
    }
  }

  // The status word after the last sample (nothing reads it in between).
  const State state = machine_.state();
  drivecom::StatusExtras e;
  e.remote = initialised_;
  e.reference_reached =
      state == State::enabled && std::fabs(reference_ - actual_) <= config_.plant.reference_window_rpm;
  // Bit 11 "a limitation is active" (5.1.3): here the reference is beyond the speed limit. The
  // torque limit during acceleration does not set it: 5.3.4 shows 0237H while accelerating.
  e.limit_value = std::fabs(reference_) > config_.max_speed_rpm;
  e.bit14 = is00_;
  e.bit15 = is01_;
  status_ = drivecom::status_word(state, machine_.last_control(), e);
}

void Mc6000PdDevice::sample_held(Word control, Duration dt) {
  if (!initialised_) {
    since_power_on_ += dt;
    initialised_ = since_power_on_ >= config_.init_time;
  }
  const bool standstill = std::fabs(actual_) < config_.standstill_rpm;
  const drivecom::DeviceInputs in{control, initialised_, fault_present_, standstill, standstill, enable_locked_};
  last_ = machine_.sample(in);
  move_actual(dt);
  // A fault reaction that ends within this sample shows FAULT at once.
  if (machine_.state() == State::fault_response_active && std::fabs(actual_) < config_.standstill_rpm) {
    drivecom::DeviceInputs done = in;
    done.fault_reaction_done = true;
    const auto more = machine_.sample(done);
    for (std::uint8_t i = 0; i < more.count; ++i) last_.add(more.transition(i));
    last_.state = more.state;
  }
}

void Mc6000PdDevice::output(std::span<Word> s2m) const {
  const auto& l = config_.layout;
  if (s2m.empty()) return;
  if (!l.exchanges_data) {
    std::fill(s2m.begin(), s2m.end(), Word{0});  // SUPI 0 (3.2.2)
    return;
  }
  s2m[0] = status_;
  // The actual words, and 0 in a word the layout leaves unused (SUPI 12 with IBCNF 2). IBCNF 3
  // sends the torque in its second word, in % of the rated torque (a modelling choice: the
  // manual gives no scaling).
  const double torque = l.ibcnf == interbus::mc6000::Ibcnf::speed_torque ? torque_percent() : 0.0;
  interbus::mc6000::encode_actual(l, {actual_, torque}, s2m.subspan(1));
}

// ---------------------------------------------------------------------------------------------

Word vf1000_reference_word(double hz) {
  const double bits = std::clamp(std::round(std::fabs(hz) / kVf1000HzPerBit), 0.0, 65535.0);
  return static_cast<Word>(bits);
}
double vf1000_reference_hz(Word w) { return static_cast<double>(w) * kVf1000HzPerBit; }
Word vf1000_actual_word(double hz) {
  const double bits = std::clamp(std::round(hz / kVf1000HzPerBit), -32768.0, 32767.0);
  return static_cast<Word>(static_cast<std::int16_t>(bits));
}
double vf1000_actual_hz(Word w) {
  return static_cast<double>(static_cast<std::int16_t>(w)) * kVf1000HzPerBit;
}

Vf1000PdDevice::Vf1000PdDevice(const Vf1000PdConfig& config)
    : config_(config),
      machine_(drivecom::EmergencyStopExit::automatic_when_stopped, State::start_up_inhibit) {
  start(InitState::operational);
}

void Vf1000PdDevice::power_on() {
  machine_.power_on();
  since_power_on_ = 0ns;
  initialised_ = false;
  setpoint_ = 0.0;
  frequency_ = 0.0;
  at_setpoint_ = false;
  status_ = machine_.state_bits();
  comm_ = 0x0000;
}

void Vf1000PdDevice::start(InitState s) {
  machine_.force(initial_state(s));
  since_power_on_ = config_.init_time;
  initialised_ = true;
  setpoint_ = 0.0;
  frequency_ = 0.0;
  at_setpoint_ = false;
  status_ = drivecom::status_word(machine_.state(), 0, {});
  comm_ = 0x8000;
}

void Vf1000PdDevice::run_ramp(Word control, double dt_s) {
  const auto b = drivecom::decode_vf1000_bits(control);
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
  if (!initialised_ && since_power_on_ >= config_.init_time) initialised_ = true;
  const Word control = override_ ? *override_ : m2s[0];
  const auto b = drivecom::decode_vf1000_bits(control);
  // STR runs clockwise, STL counter-clockwise; neither or both: no direction, 0 Hz.
  const double direction = b.str == b.stl ? 0.0 : (b.str ? 1.0 : -1.0);
  const double requested_hz = vf1000_reference_hz(m2s[1]);
  setpoint_ = std::min(requested_hz, config_.max_frequency_hz) * direction;

  drivecom::DeviceInputs in;
  in.control = control;
  in.initialised = initialised_;
  in.fault_present = fault_present_;
  in.fault_reaction_done = true;  // the VF1000 switches its power stage off at once
  in.stopped = frequency_ == 0.0 || config_.stop_ramp_hz_per_s <= 0;
  last_ = machine_.sample(in);
  run_ramp(control, seconds(dt));
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
  s2m[1] = vf1000_actual_word(frequency_);
  s2m[2] = comm_;
}

// ---------------------------------------------------------------------------------------------

Mc6000PdMaster::Mc6000PdMaster(const interbus::mc6000::Layout& layout,
                               const drivecom::SequencerConfig& config)
    : layout_(layout), sequencer_(config) {}

void Mc6000PdMaster::initial(std::span<Word> m2s) const {
  std::fill(m2s.begin(), m2s.end(), Word{0});
}

void Mc6000PdMaster::cycle(std::span<const Word> s2m, std::span<Word> m2s, Time now) {
  if (m2s.empty() || s2m.empty()) return;
  const auto actual_words = static_cast<std::size_t>(layout_.actual_words);
  actual_ = interbus::mc6000::decode_actual(layout_, s2m.subspan(1, actual_words));
  m2s[0] = sequencer_.step(s2m[0], now);
  const auto ref_words = static_cast<std::size_t>(layout_.reference_words);
  if (reference_ != encoded_reference_) {
    interbus::mc6000::encode_reference(layout_, reference_, std::span<Word>(reference_words_.data(), ref_words));
    encoded_reference_ = reference_;
  }
  // Control word, reference, and 0 in any word the layout leaves unused (SUPI 12 with IBCNF 2).
  std::size_t w = 1;
  for (; w <= ref_words && w < m2s.size(); ++w) m2s[w] = reference_words_[w - 1];
  for (; w < m2s.size(); ++w) m2s[w] = 0;
}

Vf1000PdMaster::Vf1000PdMaster(const drivecom::SequencerConfig& config) : sequencer_(config) {
  sequencer_.set_application_bits(drivecom::kVf1000RampRun);
}

void Vf1000PdMaster::set_frequency_hz(double hz) {
  setpoint_ = hz;
  drivecom::Vf1000ControlBits b = drivecom::decode_vf1000_bits(drivecom::kVf1000RampRun);
  b.str = hz > 0;
  b.stl = hz < 0;
  sequencer_.set_application_bits(drivecom::encode_vf1000_bits(b));
}

void Vf1000PdMaster::initial(std::span<Word> m2s) const {
  std::fill(m2s.begin(), m2s.end(), Word{0});
}

void Vf1000PdMaster::cycle(std::span<const Word> s2m, std::span<Word> m2s, Time now, Word comm) {
  actual_ = vf1000_actual_hz(s2m[1]);
  m2s[0] = sequencer_.step(s2m[0], now);
  m2s[1] = vf1000_reference_word(setpoint_);
  m2s[2] = comm;
}

}  // namespace ibs::devices
