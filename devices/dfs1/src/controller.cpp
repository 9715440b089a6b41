#include "ibs/devices/dfs1/controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ibs::devices::dfs1 {

namespace proto = ::ibs::dfs1;
using proto::Command;
using proto::ErrorCode;
using proto::Reply;

namespace {

constexpr Duration kContactorStep = 25ms;  // parameter 62 (notes)

Duration turnaround_for(std::uint32_t p56) {
  return std::chrono::milliseconds(p56);
}  // D2

// D13: the fragment timeout follows the line rate the baud rate code (parameter 2) holds.
Duration fragment_timeout_for(std::uint32_t code) {
  return proto::fragment_timeout(baud_for_code(code).value_or(9600));
}

std::uint32_t value_in(const proto::Frame& f, std::size_t offset) {
  return f.value_at(offset);
}

}  // namespace

void SpeedPlant::step(Duration dt, double target_rpm) {
  if (dt <= Duration::zero()) return;
  const double ratio = std::chrono::duration<double>(dt) / std::chrono::duration<double>(tau_);
  speed_ += (target_rpm - speed_) * (1.0 - std::exp(-ratio));
}

Controller::Controller(const ControllerConfig& config)
    : receiver_(config.uid, Duration::zero()), plant_(config.plant_time_constant) {
  if (config.uid == proto::kGlobalUid) {
    throw std::invalid_argument(
        "dfs1 controller: UID 0 is the global address; a controller needs a UID of 1..255");
  }
  if (config.plant_time_constant <= Duration::zero()) {
    throw std::invalid_argument("dfs1 controller " + std::to_string(config.uid) +
                                ": the plant time constant must be positive");
  }
  for (std::size_t i = 0; i < kParameters.size(); ++i) values_[i] = kParameters[i].default_value;
  values_[index(kUnitId)] = config.uid;
  receiver_.set_turnaround(turnaround_for(values_[index(kTurnaroundDelay)]));
  receiver_.set_fragment_timeout(fragment_timeout_for(values_[index(kBaudCode)]));
  terminal_inputs_[kEstopInput - 1U] = true;  // E-stop closed: the drive may run
}

std::size_t Controller::index(std::uint8_t number) const {
  return static_cast<std::size_t>(find_parameter(number) - kParameters.data());
}

std::uint32_t Controller::parameter(std::uint8_t number) const {
  return find_parameter(number) != nullptr ? values_[index(number)] : 0;
}

bool Controller::remote(std::uint32_t functions) const {
  return (values_[index(kRemoteFunctions)] & functions) == functions;
}

void Controller::receive(std::uint8_t byte, Time now) {
  receiver_.receive(byte, now, *this);
}

void Controller::receive(std::span<const std::uint8_t> bytes, Time now) {
  receiver_.receive(bytes, now, *this);
}

void Controller::set_digital_input(std::uint8_t channel, bool closed) {
  if (channel < 1 || channel > kDigitalInputs) return;
  terminal_inputs_[channel - 1U] = closed;
  // D19: an E-stop ends the run; closing it again does not restart the motor by itself.
  if (channel == kEstopInput && !closed) running_ = false;
  settle();
}

void Controller::set_faults(std::uint8_t st1) {
  latched_st1_ = st1;
  if (st1 != 0) running_ = false;
  settle();
}

std::uint8_t Controller::st1() const {
  // D17: without mains the DC bus is not charged; the bit goes when the mains return.
  return static_cast<std::uint8_t>(latched_st1_ | (mains_on_ ? 0U : kSt1BusNotCharged));
}

bool Controller::cause_present(FaultCause cause) const {
  return now_ < cause_until_[static_cast<std::size_t>(cause)];
}

void Controller::settle() {
  if (estop_closed() || !fault_latched()) return;
  for (const FaultCauseInfo& f : fault_causes()) {
    if (cause_present(f.cause)) return;
  }
  latched_st1_ = 0;
  latched_micro_ = false;
}

void Controller::power_on_reset(Time now) {
  // D20: what a power cycle loses. The parameters are the controller's setup and stay (the
  // receiver already runs with their UID, turnaround and fragment timeout); terminals, mains,
  // load and the motor's own speed are outside the controller and stay too.
  receiver_.restart();
  preset_speed_ = 0;
  commanded_speed_ = 0;
  running_ = false;
  contactor_closes_at_ = now;
  operational_mode_ = 0;
  application_mode_ = 0;
  application_value_ = 0;
  analog_out_ = {};
  digital_out_ = {};
  // The fault memory is cleared; a cause still present trips the controller again at once.
  latched_st1_ = 0;
  latched_micro_ = false;
  for (const FaultCauseInfo& f : fault_causes()) {
    if (cause_present(f.cause)) {
      latched_st1_ |= f.st1_bit;
      if (f.st2_bit != 0) latched_micro_ = true;
    }
  }
}

EventReport Controller::apply(const Event& e, Time now) {
  step(now);
  switch (e.kind) {
    case Event::Kind::fault: {
      // D15, D16: the fault bit of the cause is latched and the motor coasts; the cause lasts
      // `duration` (the longer of two overlapping ones).
      const FaultCauseInfo& f = info(e.cause);
      auto& until = cause_until_[static_cast<std::size_t>(e.cause)];
      until = std::max(until, now_ + std::max(e.duration, Duration::zero()));
      latched_st1_ |= f.st1_bit;
      if (f.st2_bit != 0) latched_micro_ = true;
      running_ = false;
      break;
    }
    case Event::Kind::power_cycle:
      power_on_reset(now_);
      break;
    case Event::Kind::mains:
      mains_on_ = e.on;
      if (!e.on) running_ = false;  // D17: the motor coasts; it needs a new start
      break;
    case Event::Kind::input:
      set_digital_input(e.input, e.on);
      break;
    case Event::Kind::load:
      load_ = std::min(e.load_percent, kMaxLoadPercent);
      break;
  }
  settle();
  EventReport r;
  r.at = now_;
  r.event = e;
  r.st2 = st2();
  r.st1 = st1();
  r.load_percent = load_percent();
  r.latched = fault_latched();
  return r;
}

void Controller::set_analog_input(std::uint8_t channel, std::uint32_t value) {
  if (channel >= 1 && channel <= kAnalogInputs)
    analog_in_[channel - 1U] = std::min(value, kAnalogMax);
}

bool Controller::digital_input(std::uint8_t channel) const {
  if (channel < 1 || channel > kDigitalInputs) return false;
  // 8D: a set bit makes the input's function remote-on; the E-stop (bit 0) is never remote.
  const bool remote_on =
      channel != kEstopInput && ((operational_mode_ >> (channel - 1U)) & 1U) != 0;
  return terminal_inputs_[channel - 1U] || remote_on;
}

bool Controller::enabled() const {
  return estop_closed() && !faulted() && running_ && now_ >= contactor_closes_at_;
}

double Controller::target_speed(Time now) const {
  const bool on = estop_closed() && !faulted() && running_ && now >= contactor_closes_at_;
  return on ? static_cast<double>(commanded_speed_) : 0.0;
}

void Controller::step(Time now) {
  if (now <= now_) return;
  if (running_ && now_ < contactor_closes_at_ && contactor_closes_at_ < now) {
    plant_.step(contactor_closes_at_ - now_, 0.0);
    now_ = contactor_closes_at_;
  }
  plant_.step(now - now_, target_speed(now_));
  now_ = now;
  settle();  // a cause whose time is over may let an open E-stop reset the fault (D16)
}

std::uint8_t Controller::st2() const {
  const double actual = plant_.speed();
  const double band = std::max(1.0, 0.01 * static_cast<double>(values_[index(kMaxSpeed)]));
  std::uint8_t s = 0;
  if (values_[index(kRemoteFunctions)] != 0) s |= kSt2Remote;
  if (application_mode_ == 1) s |= kSt2Slave;
  // At speed means at the commanded speed the same reply carries (issue 25.12, DFS1-D21): not at
  // the plant's momentary target, which is 0 while the contactor closes, a fault is latched or the
  // E-stop is open; a start from rest is not at speed until the motor gets there.
  if (std::abs(actual - static_cast<double>(commanded_speed_)) <= band) s |= kSt2AtSpeed;
  if (commanded_speed_ >= 0) s |= kSt2Forward;
  if (faulted()) s |= kSt2Fault;
  if (enabled()) s |= kSt2Enabled;
  if (latched_micro_) s |= kSt2MicroFault;
  if (std::abs(actual) < 1.0) s |= kSt2ZeroSpeed;
  return s;
}

std::uint32_t Controller::load_percent() const {
  // Invented (D3): the share of the maximum speed still to go, as a stand-in for the current.
  const double max = static_cast<double>(values_[index(kMaxSpeed)]);
  // D18: only a driven motor takes current: a coasting one (fault, E-stop, stop) shows none.
  if (!enabled()) return 0;
  const double gap = std::abs(target_speed(now_) - plant_.speed());
  const double accelerating = std::min(100.0, 100.0 * gap / max);
  // D18: the speed loop holds the speed against the load; the current it takes shows as load %.
  return static_cast<std::uint32_t>(
      std::lround(std::min(static_cast<double>(kMaxLoadPercent), accelerating + static_cast<double>(load_))));
}

Reply Controller::status_reply() const {
  // Decision D3: commanded speed, actual speed, load %, 00 00 ST2 ST1, four 4-byte values.
  std::array<std::uint8_t, 16> d{};
  const auto at = [&d](std::size_t off) { return std::span<std::uint8_t, 4>(d.data() + off, 4); };
  proto::put_u32(at(0), proto::to_unsigned(commanded_speed_));
  proto::put_u32(at(4), proto::to_unsigned(static_cast<std::int32_t>(std::lround(plant_.speed()))));
  proto::put_u32(at(8), load_percent());
  proto::put_u32(at(12), (std::uint32_t{st2()} << 8) | st1());
  return Reply::ack(d);
}

Reply Controller::speed_command(Command c, std::int32_t rpm, Time now) {
  std::uint32_t needs = 0;
  if (c != Command::execute_speed) needs |= kRemoteSpeedReference;
  if (c != Command::set_speed) needs |= kRemoteStartStop;
  if (!remote(needs)) return Reply::nak(ErrorCode::not_in_remote);
  if (c != Command::execute_speed) {
    const auto max = static_cast<std::int64_t>(values_[index(kMaxSpeed)]);
    if (std::abs(static_cast<std::int64_t>(rpm)) > max) return Reply::nak(ErrorCode::illegal_speed);
    preset_speed_ = rpm;
  }
  if (c != Command::set_speed) {
    commanded_speed_ = preset_speed_;
    // D16, D17, D19: a start is taken (the seed has no error for it) but does not run the motor
    // while the E-stop is open, a fault is latched or the bus is not charged.
    const bool run = commanded_speed_ != 0 && estop_closed() && !faulted();
    if (run && !running_) {
      contactor_closes_at_ = now + values_[index(kContactorDelay)] * kContactorStep;
    }
    running_ = run;
  }
  return Reply::ack();
}

Reply Controller::write_parameter(std::uint8_t number, std::uint32_t value) {
  const ParameterInfo* p = find_parameter(number);
  if (p == nullptr) return Reply::nak(ErrorCode::illegal_parameter_number);
  if (value < p->min || value > p->max) return Reply::nak(ErrorCode::illegal_parameter_value);
  values_[index(number)] = value;
  // Decision D5: a new UID and a new turnaround delay apply from the next request on (the
  // receiver answers this one as it was asked).
  if (number == kUnitId) receiver_.set_uid(static_cast<std::uint8_t>(value));
  if (number == kTurnaroundDelay) receiver_.set_turnaround(turnaround_for(value));
  if (number == kBaudCode) receiver_.set_fragment_timeout(fragment_timeout_for(value));
  return Reply::ack();
}

std::optional<ErrorCode> Controller::set_parameter(std::uint8_t number, std::uint32_t value) {
  const Reply r = write_parameter(number, value);
  if (r.kind == Reply::Kind::nak) return r.error;
  return std::nullopt;
}

Reply Controller::handle(const proto::Frame& f, bool global, Time now) {
  step(now);
  const auto command = static_cast<Command>(f.code);
  const std::uint8_t channel = f.size >= 1 ? f.data[0] : 0;
  switch (command) {
    case Command::status:
      return status_reply();
    case Command::set_speed:
    case Command::set_and_execute_speed:
      return speed_command(command, proto::to_signed(value_in(f, 0)), now);
    case Command::execute_speed: {
      Reply r = speed_command(command, 0, now);
      return global ? Reply::none() : r;
    }
    case Command::read_parameter: {
      if (find_parameter(channel) == nullptr)
        return Reply::nak(ErrorCode::illegal_parameter_number);
      return Reply::ack_value(values_[index(channel)]);
    }
    case Command::write_parameter:
      return write_parameter(channel, value_in(f, 1));
    case Command::read_analog_input:
      if (channel < 1 || channel > kAnalogInputs) return Reply::nak(ErrorCode::illegal_channel);
      return Reply::ack_value(analog_in_[channel - 1U]);
    case Command::read_analog_output:
      if (channel < 1 || channel > kAnalogOutputs) return Reply::nak(ErrorCode::illegal_channel);
      return Reply::ack_value(analog_out_[channel - 1U]);
    case Command::write_analog_output: {
      if (!remote(kRemoteAnalogOutputs)) return Reply::nak(ErrorCode::not_in_remote);
      if (channel < 1 || channel > kAnalogOutputs) return Reply::nak(ErrorCode::illegal_channel);
      const std::uint32_t v = value_in(f, 1);
      if (v > kAnalogMax) return Reply::nak(ErrorCode::illegal_channel_value);
      analog_out_[channel - 1U] = v;
      return Reply::ack();
    }
    case Command::read_digital_input:
      if (channel < 1 || channel > kDigitalInputs) return Reply::nak(ErrorCode::illegal_channel);
      return Reply::ack_value(digital_input(channel) ? 1U : 0U);
    case Command::read_digital_output:
      if (channel < 1 || channel > kDigitalOutputs) return Reply::nak(ErrorCode::illegal_channel);
      return Reply::ack_value(digital_out_[channel - 1U] ? 1U : 0U);
    case Command::write_digital_output: {
      if (!remote(kRemoteDigitalOutputs)) return Reply::nak(ErrorCode::not_in_remote);
      if (channel < 1 || channel > kDigitalOutputs) return Reply::nak(ErrorCode::illegal_channel);
      const std::uint32_t v = value_in(f, 1);
      if (v > 1) return Reply::nak(ErrorCode::illegal_channel_value);
      digital_out_[channel - 1U] = v != 0;
      return Reply::ack();
    }
    case Command::set_operational_mode: {
      // Notes: 00 00 SMH SML; input 1 is the E-stop and must be 0 (at most 00 00 FF FE).
      const std::uint32_t mask = value_in(f, 0);
      if (mask > 0xFFFEU || (mask & 1U) != 0) return Reply::nak(ErrorCode::illegal_parameter_value);
      operational_mode_ = static_cast<std::uint16_t>(mask);
      return Reply::ack();
    }
    case Command::read_operational_mode:
      return Reply::ack_value(operational_mode_);
    case Command::application_mode: {
      // Decision D8 (invented): AMD 0 master, 1 slave; the value is kept and read by no one.
      if (channel > 1) return Reply::nak(ErrorCode::illegal_parameter_value);
      application_mode_ = channel;
      application_value_ = value_in(f, 1);
      return Reply::ack();
    }
  }
  return Reply::nak(ErrorCode::illegal_command);
}

}  // namespace ibs::devices::dfs1
