#include "ibs/devices/mc6000/pd_device.hpp"

#include <algorithm>
#include <cmath>

#include "ibs/devices/mc6000/descriptor.hpp"

namespace ibs::devices {

namespace {

using drivecom::State;

drivecom::State initial_state(DeviceStart s) {
  return s == DeviceStart::fault ? State::fault : State::start_up_inhibit;
}

}  // namespace

Mc6000PdDevice::Mc6000PdDevice(const Mc6000PdConfig& config)
    : config_(config),
      machine_(drivecom::EmergencyStopExit::on_block_power_only, State::start_up_inhibit),
      plant_(config.plant, mc6000::kSamplePeriod) {
  start(DeviceStart::operational);
}

void Mc6000PdDevice::power_on() {
  machine_.power_on();
  since_power_on_ = 0ns;
  initialised_ = false;
  reset_motion();
  status_ = machine_.state_bits();
}

void Mc6000PdDevice::start(DeviceStart s) {
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
  step_held(m2s.empty() ? Word{0} : m2s[0],
            mc6000::decode_reference(l, m2s.subspan(1, static_cast<std::size_t>(l.reference_words))), dt,
            count);
}

void Mc6000PdDevice::step_held(Word word, double reference_rpm, Duration dt, std::uint32_t count) {
  if (count == 0) return;
  const Word control = override_ ? *override_ : word;
  reference_ = reference_rpm;
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
  const drivecom::DeviceInputs in{control, initialised_, fault_present_, standstill || coast_, standstill, enable_locked_};
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
  write_pd_words(config_.layout, status_, actual_, torque_percent(), s2m);
}

void write_pd_words(const mc6000::Layout& l, Word status, double actual_rpm, double torque_percent,
                    std::span<Word> s2m) {
  if (s2m.empty()) return;
  if (!l.exchanges_data) {
    std::fill(s2m.begin(), s2m.end(), Word{0});  // SUPI 0 (3.2.2)
    return;
  }
  s2m[0] = status;
  // The actual words, and 0 in a word the layout leaves unused (SUPI 12 with IBCNF 2). IBCNF 3
  // sends the torque in its second word, in % of the rated torque (a modelling choice: the
  // manual gives no scaling).
  const double torque = l.ibcnf == mc6000::Ibcnf::speed_torque ? torque_percent : 0.0;
  mc6000::encode_actual(l, {actual_rpm, torque}, s2m.subspan(1));
}

}  // namespace ibs::devices
