#include "ibs/devices/mc6000/drive.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/mc6000/layout.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/drivecom/control_word.hpp"

namespace ibs::devices::mc6000 {

namespace {

using drivecom::State;

constexpr Word kResetBit = 0x0080;     // INTERBUS manual 5.1.2: RESET FAULT
constexpr Word kOs00Bit = 0x4000;      // INTERBUS manual 5.3.1: bit 14, output OS00
constexpr Word kOs01Bit = 0x8000;      // bit 15, output OS01
// The longest silence the drive catches up on by itself: after a longer one only its last part is
// simulated (a speed loop has settled long before; 60 s x 1 ms samples are 60 000 samples).
constexpr Duration kCatchUp = std::chrono::seconds(60);
// The samples a serial command takes to walk DRIVECOM (reset edge, SHUTDOWN, ENABLE OPERATION).
constexpr int kSettleSamples = 6;

}  // namespace

Drive::Drive(const DriveConfig& config, DeviceStart start, Time now)
    : params_(drive_parameters_config(config.timing)), pd_(config.pd), boot_time_(config.pd.init_time) {
  last_cycle_ = last_telegram_ = sampled_until_ = now;
  switch (start) {
    case DeviceStart::power_on:
      power_on(now);
      break;
    case DeviceStart::initialised:
      pd_.start(DeviceStart::operational);
      break;
    case DeviceStart::operational:
      pd_.start(DeviceStart::operational);
      params_.read(now, kSerr);  // running for a while: 85-SERR has been read
      break;
    case DeviceStart::fault:
      pd_.start(DeviceStart::fault);
      break;
  }
  refresh_readings();
}

bool Drive::fault() const {
  return pd_.state() == State::fault || pd_.state() == State::fault_response_active;
}

bool Drive::serial_control() const {
  // 7.2 step 2: 402-CLSEL = SIO gives the serial interface the control -- where a serial face
  // serves the drive; a drive without a fieldbus face has no other master to listen to (MC-D4).
  if (!fieldbus_sampling_) return true;
  return serial_face_ && params_.raw(kClsel) == static_cast<std::uint32_t>(kClselSio);
}

double Drive::serial_reference_rpm() const {
  double rpm = 0.0;
  for (const std::uint16_t sel : {kRssl1, kRssl2, kRssl3, kRssl4}) {
    if (params_.raw(sel) == static_cast<std::uint32_t>(kRsslRsio)) {
      rpm += static_cast<double>(static_cast<std::int32_t>(params_.raw(kRsio))) / 65536.0;
    }
  }
  return rpm;
}

Word Drive::serial_word() const {
  // 7.2: 416-SCTL1 bit 0 starts with the control location on SIO; the plant is a speed loop, so
  // only 300-CFCON = SCON engages it (LB-D19). The drive walks DRIVECOM's sequence itself:
  // the reset edge of 8.1.2 first, SHUTDOWN before ENABLE OPERATION.
  if (reset_pending_) {
    return static_cast<Word>(drivecom::command_word(drivecom::Command::shutdown) | 0x0080U);
  }
  const bool start = params_.raw(kClsel) == static_cast<std::uint32_t>(kClselSio) &&
                     params_.raw(kCfcon) == static_cast<std::uint32_t>(kCfconScon) &&
                     (params_.raw(kSctl1) & kSctl1Start) != 0;
  if (start && pd_.state() != State::start_up_inhibit) return drivecom::command_word(drivecom::Command::enable);
  return drivecom::command_word(drivecom::Command::shutdown);
}

Duration Drive::bus_watchdog() const { return std::chrono::milliseconds(params_.raw(kButwd)); }

void Drive::refresh_readings() {
  // 408-IBSTA mirrors the status word (INTERBUS manual 4.2.1), 77-SPEED the motor speed as Q16 rpm
  // (LUSTBUS manual 6.1.1.2).
  params_.set_reading(kIbsta, status_word());
  params_.set_reading(kSpeed, static_cast<std::uint32_t>(to_q16(pd_.actual_rpm())));
}

void Drive::check_serial_watchdog(Time now) {
  // 5.2: no valid telegram within 84-SWDGT ms: the error state, 02H in 85-SERR; the drive stops.
  const auto swdgt = params_.raw(kSwdgt);
  if (!serial_fault_ && swdgt != 0 && now - quiet_since(last_telegram_, now) > std::chrono::milliseconds(swdgt)) {
    serial_fault_ = true;
    params_.set_serr(drive::SiofBit::watchdog);
  }
}

void Drive::clear_bus_fault(bool expired) {
  // The bus watchdog's fault ends once data flows again and DRIVECOM left FAULT (transition 15);
  // as a warning (510-REOP1 = WARN) once data flows again.
  if (bus_fault_ && !expired &&
      (pd_.state() == State::start_up_inhibit || reaction_of(kReop1) == ErrorReaction::warn)) {
    bus_fault_ = false;
  }
}

void Drive::serial_telegram(Time now) {
  advance(now);
  last_telegram_ = now;
}

void Drive::fieldbus_cycle(Time now) {
  armed_ = true;
  last_cycle_ = now;
}

ErrorReaction Drive::reaction_of(std::uint16_t number) const {
  // 510..512 take 1..5 only (the store refuses the rest with 80H).
  const auto r = params_.raw(number);
  return r >= 1 && r <= 5 ? static_cast<ErrorReaction>(r) : ErrorReaction::stop;
}

std::array<std::optional<ErrorReaction>, 3> Drive::present_errors() const {
  std::array<std::optional<ErrorReaction>, 3> e{};
  // A device fault numbered 16 is E-OP1 (INTERBUS manual 3.2.4), which 510-REOP1 programs like the
  // bus watchdog's; any other number, or none, 512-REDEV.
  if (external_fault_) e[0] = reaction_of(fault_cause_ == kWatchdogError ? kReop1 : kRedev);
  if (bus_expired_) e[1] = reaction_of(kReop1);
  if (serial_fault_) e[2] = reaction_of(kResio);
  return e;
}

std::optional<ErrorReaction> Drive::present_reaction() const {
  std::optional<ErrorReaction> worst;
  for (const auto& r : present_errors()) {
    if (r && (!worst || *r > *worst)) worst = r;
  }
  return worst;
}

void Drive::apply_reactions() {
  // LUSTBUS manual 8: each error's own reaction; with several the most severe acts, and the servo
  // holds to the most severe it has met until the reset or a power-on (MC-D7).
  const auto present = present_reaction();
  if (present && (!held_ || *present > *held_)) held_ = present;
  const bool fault = present && *present != ErrorReaction::warn;
  pd_.set_fault(fault, held_ && *held_ >= ErrorReaction::off);
}

Word Drive::fieldbus_word(Word control) const {
  return held_ == ErrorReaction::lock ? static_cast<Word>(control & ~kResetBit) : control;
}

bool Drive::digital_output(std::size_t output) const {
  // INTERBUS manual 5.3.1: "Bit 14 controls the reference state of output OS00 directly when parameter
  // 445-FOS00 = ROPT1", bit 15 OS01 with 446-FOS01.
  if (!powered_ || output > 1) return false;
  const std::uint16_t selector = output == 0 ? kFos00 : kFos01;
  const Word bit = output == 0 ? kOs00Bit : kOs01Bit;
  return (fieldbus_control_ & bit) != 0 && params_.raw(selector) == static_cast<std::uint32_t>(kFunctionRopt1);
}

ResetOutcome Drive::fault_reset(Time now) {
  std::optional<ErrorReaction> r = held_;
  const auto present = present_reaction();
  if (present && (!r || *present > *r)) r = present;
  // MC-D7: a reaction-4 error is ended by a power-on only.
  if (r == ErrorReaction::lock) return ResetOutcome::ignored;
  // 8.1.2: "Resetting an error, which has a 5 ("RESET") programmed for its reaction, makes the
  // servocontroller boot" -- from FAULT, where DRIVECOM takes a reset (PD4).
  if (r == ErrorReaction::reset && pd_.state() == State::fault) {
    reboot(now);
    return ResetOutcome::rebooted;
  }
  // 8.1.2: the reset clears the error; the serial watchdog's time runs again from the reset.
  serial_fault_ = false;
  last_telegram_ = now;
  reset_pending_ = true;
  held_.reset();
  return ResetOutcome::cleared;
}

void Drive::reboot(Time now) {
  // 8.1.2: the boot is a new start (LUSTBUS manual 9.2: the power-on bit tells the host "after a ...
  // reset of an error"); the serial connection is broken for the initialisation and self test.
  power_on(now);
  ++reboots_;
  boot_until_ = now + boot_time_;
}

void Drive::power_on(Time now) {
  params_.power_on(now);
  detect_interbus_card();
  card_until_ = Time::min();  // switched off: a SMARTCARD operation ends with it
  pd_.power_on();
  armed_ = false;
  bus_fault_ = false;
  bus_expired_ = false;
  serial_fault_ = false;
  reset_pending_ = false;
  held_.reset();
  fieldbus_control_ = 0;
  boot_until_ = now;
  last_telegram_ = sampled_until_ = now;
  refresh_readings();
}

void Drive::mains_off(Time now) {
  advance(now);
  powered_ = false;
  pd_.power_on();  // NOT READY: no power stage, nothing to show
  card_until_ = Time::min();
  external_fault_ = false;
  fieldbus_control_ = 0;
  fault_cause_.reset();
  refresh_readings();
}

void Drive::mains_on(Time now) {
  if (powered_) return;
  powered_ = true;
  power_on(now);  // LUSTBUS manual 9.2: the power-on bit tells the host of the power failure
}

bool Drive::apply(const PlantEvent& e, Time now) {
  switch (e.kind) {
    case PlantEvent::Kind::fault:
      set_external_fault(true, e.cause);
      return true;
    case PlantEvent::Kind::fault_clear:
      set_external_fault(false);
      return true;
    case PlantEvent::Kind::power_cycle:
      power_on(now);
      return true;
    case PlantEvent::Kind::mains_off:
      mains_off(now);
      return true;
    case PlantEvent::Kind::mains_on:
      mains_on(now);
      return true;
    case PlantEvent::Kind::load:
      set_load_torque(e.value);
      return true;
    case PlantEvent::Kind::input:
      set_input(e.input, e.level);
      return true;
    case PlantEvent::Kind::card_read:
    case PlantEvent::Kind::card_write:
      // Reading loads the card's parameter set, writing saves the servo's: the seeds give neither
      // set, so the values stay; the time is what either bus sees (MC-D9).
      smartcard(std::chrono::duration_cast<Duration>(std::chrono::duration<double>(e.value)), now);
      return true;
    case PlantEvent::Kind::option_withdrawn:
      withdraw_interbus_card();
      return true;
    case PlantEvent::Kind::option_inserted:
      insert_interbus_card();
      return true;
  }
  return false;
}

void Drive::smartcard(Duration how_long, Time now) {
  if (powered_ && how_long > Duration{0}) card_until_ = std::max(card_until_, now + how_long);
}

void Drive::detect_interbus_card() {
  // INTERBUS manual 3.2.1: "The first time it is detected the following parameters are changed ...
  // After the INTERBUS card has been withdrawn ... reset to their factory defaults the next time
  // the device is powered-up." A card found again after that is detected for the first time again.
  if (card_fitted_ == card_detected_) return;
  card_detected_ = card_fitted_;
  set_option_defaults(card_detected_);
}

void Drive::set_option_defaults(bool with_card) {
  for (const OptionDefault& d : kOptionDefaults) params_.preset(d.number, with_card ? d.with_card : d.without_card);
}

void Drive::set_input(std::size_t input, bool high) {
  if (input < 2) inputs_[input] = high;
  refresh_readings();
}

Word Drive::status_word() const {
  Word w = pd_.status_word();
  // INTERBUS manual 5.3.2: "Bit 14 reflects the actual state of input IS00 when parameter 439-FIS00 =
  // ROPT1", bit 15 likewise IS01 with 440-FIS01.
  if (inputs_[0] && params_.raw(kFis00) == static_cast<std::uint32_t>(kFunctionRopt1)) w |= 0x4000;
  if (inputs_[1] && params_.raw(kFis01) == static_cast<std::uint32_t>(kFunctionRopt1)) w |= 0x8000;
  // INTERBUS manual 5.1.3, bit 7 "Alarm": an error whose programmed reaction is a warning (MC-D7).
  for (const auto& r : present_errors()) {
    if (r == ErrorReaction::warn) w |= 0x0080;
  }
  return w;
}

void Drive::sample_one(Time now, Word control, double reference_rpm) {
  if (!powered_) {
    sampled_until_ = now;
    return;
  }
  params_.advance(now);
  check_serial_watchdog(now);
  // INTERBUS manual 3.2.4: monitoring time 409-BUTWD in ms, 0 deactivates; running out is error 16
  // (E-OP1), location 1, a device fault that stays until it is reset once data flows again.
  const Duration butwd = bus_watchdog();
  const bool expired = armed_ && butwd > Duration{0} && (now - quiet_since(last_cycle_, now)) > butwd;
  if (expired) bus_fault_ = true;
  bus_expired_ = expired;
  fieldbus_control_ = control;
  apply_reactions();
  pd_.set_enable_locked(params_.engage_locked());
  if (serial_control()) {
    pd_.step_held(serial_word(), serial_reference_rpm(), kSamplePeriod, 1);
  } else {
    // A reset given over another face reaches DRIVECOM as the RESET FAULT edge in this sample.
    const Word f = fieldbus_word(control);
    const Word w = reset_pending_ ? static_cast<Word>(f | kResetBit) : f;
    pd_.step_held(w, reference_rpm, kSamplePeriod, 1);
  }
  reset_pending_ = false;
  clear_bus_fault(expired);
  sampled_until_ = now;
}

void Drive::watch(Time now) {
  if (!powered_) {
    sampled_until_ = now;
    return;
  }
  params_.advance(now);
  check_serial_watchdog(now);
  const Duration butwd = bus_watchdog();
  const bool expired = armed_ && butwd > Duration{0} && (now - quiet_since(last_cycle_, now)) > butwd;
  if (expired) bus_fault_ = true;
  bus_expired_ = expired;
  clear_bus_fault(expired);
  sampled_until_ = now;
}

void Drive::sample(Time first, Duration period, std::uint32_t count, Word control, double reference_rpm) {
  if (count == 0) return;
  if (!powered_) {
    sampled_until_ = first + static_cast<std::int64_t>(count - 1) * period;
    return;
  }
  if (count == 1 || period <= Duration{0} || serial_control() || bus_fault_ || serial_fault_ ||
      params_.engage_locked() || params_.raw(kSwdgt) != 0 || reset_pending_ || external_fault_ || held_) {
    for (std::uint32_t k = 0; k < count; ++k) sample_one(first + static_cast<std::int64_t>(k) * period, control, reference_rpm);
    refresh_readings();
    return;
  }
  // A stretch with the same words: the monitoring time runs out at the first sample more than
  // 409-BUTWD after the last cycle; from there on every sample sees the watchdog fault.
  params_.advance(first);
  const Duration butwd = bus_watchdog();
  std::uint32_t in_time = count;
  if (armed_ && butwd > Duration{0}) {
    const Duration left = butwd - (first - quiet_since(last_cycle_, first));
    in_time = left < Duration{0} ? 0U : static_cast<std::uint32_t>(std::min<std::int64_t>(count, left / period + 1));
  }
  fieldbus_control_ = control;
  pd_.set_fault(false);
  pd_.set_enable_locked(false);
  pd_.step_held(control, reference_rpm, kSamplePeriod, in_time);
  // From the sample where 409-BUTWD runs out, the error's programmed reaction sample by sample.
  for (std::uint32_t k = in_time; k < count; ++k) {
    sample_one(first + static_cast<std::int64_t>(k) * period, control, reference_rpm);
  }
  sampled_until_ = first + static_cast<std::int64_t>(count - 1) * period;
  params_.advance(sampled_until_);
  refresh_readings();
}

void Drive::serial_samples(std::uint32_t count, Duration dt) {
  // The serial word follows the state: sample by sample until the machine holds, then the rest
  // with the word it holds on (Mc6000PdDevice::step_held moves the plant in one loop).
  for (std::uint32_t k = 0; k < count; ++k) {
    apply_reactions();
    pd_.set_enable_locked(params_.engage_locked());
    const Word w = serial_word();
    pd_.step_held(w, serial_reference_rpm(), dt, 1);
    reset_pending_ = false;
    if (pd_.last_sample().count == 0 && serial_word() == w && pd_.initialised() && k + 1 < count) {
      pd_.step_held(w, serial_reference_rpm(), dt, count - k - 1);
      break;
    }
  }
}

void Drive::advance(Time now) {
  params_.advance(now);
  check_serial_watchdog(now);
  if (fieldbus_sampling_) return;  // the fieldbus face samples (MC-D4)
  if (!powered_) {
    sampled_until_ = now;
    return;
  }
  // Without a fieldbus face the drive samples itself up to `now` (7.2: the plant under the
  // serial control location), then lets a command that just arrived take effect at once.
  if (now > sampled_until_) {
    if (now - sampled_until_ > kCatchUp) sampled_until_ = now - kCatchUp;
    const auto n = static_cast<std::uint32_t>((now - sampled_until_) / kSamplePeriod);
    serial_samples(n, kSamplePeriod);
    sampled_until_ += static_cast<std::int64_t>(n) * kSamplePeriod;
  }
  serial_samples(kSettleSamples, Duration{0});
  refresh_readings();
}

std::optional<pcp::Value> Drive::read(Time now, std::uint16_t number) {
  advance(now);
  refresh_readings();
  return params_.read(now, number);
}

WriteResult Drive::write(Time now, std::uint16_t number, std::optional<std::uint32_t> raw) {
  advance(now);
  WriteResult r = params_.write(now, number, raw, drivecom::power_stage_enabled(pd_.state()));
  if (!r.ok() || !raw) return r;
  if (number == kSwdgt) last_telegram_ = now;  // 5.2: the watchdog's own setting restarts it
  // 10 exception 1: 4-PROG = 1 loads the factory defaults of the servo as it stands: those of
  // 3.2.1 are "modified" by the INTERBUS card the servo detected; without it, its own (MC-D10).
  if (number == kProg && *raw == static_cast<std::uint32_t>(kProgFactoryDefaults) && !card_detected_) {
    set_option_defaults(false);
  }
  if (number == kSctl1 && (*raw & kSctl1Reset) != 0 && !params_.downloading() && serial_control()) {
    // 8.1.2: bit 7 resets the error -- like bit 0, only from the control location SIO (7.2 step
    // 2, MC-D4); it is a command, the stored word keeps the other bits. A reaction-5 error makes
    // it a boot: the store starts anew, the answer is cut.
    params_.set_reading(kSctl1, *raw & ~kSctl1Reset);
    if (fault_reset(now) == ResetOutcome::rebooted) {
      r.restarted = true;
      return r;
    }
  }
  if (!fieldbus_sampling_) serial_samples(kSettleSamples, Duration{0});
  refresh_readings();
  return r;
}

}  // namespace ibs::devices::mc6000
