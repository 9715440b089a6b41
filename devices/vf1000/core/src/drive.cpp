#include "ibs/devices/vf1000/drive.hpp"

#include <algorithm>
#include <cmath>

#include "ibs/devices/vf1000/descriptor.hpp"

namespace ibs::devices::vf1000 {

namespace {

// LUSTBUS manual 7.1: 1-MODE = 0 and 2-CSEL = 3 put control on the serial interface; 4-FSSEL = 8 takes
// the reference from 5-FSSIO; 3-CNTL 80H starts clockwise (7.1.1), 40H counter-clockwise (LB-D19).
constexpr Word kModeSio = 0;
constexpr Word kCselSio = 3;
// INTERBUS manual 6.1: "During operation on the INTERBUS-S (01-MODE = 4) the serial interface of the
// inverter cannot be used" (decision VF-E16).
constexpr Word kModeInterbus = 4;
constexpr Word kFsselFssio = 8;
constexpr Word kStartClockwise = 0x80;
constexpr Word kStartCounterClockwise = 0x40;
// After a longer silence only this much of the inverter's own sampling is run (the ramp has long
// ended): 60 s are about 7 300 samples of 8.2 ms.
constexpr Duration kCatchUp = std::chrono::seconds(60);
// INTERBUS manual 5.2.1: bit 12 S2IND, bit 13 S1IND.
constexpr Word kS2indBit = 0x1000;
constexpr Word kS1indBit = 0x2000;
constexpr Word kInputFunctionBits = kS2indBit | kS1indBit;

// Transition 15 (FAULT -> START-UP INHIBIT on RESET FAULT) among those of a sample.
bool reset_fault_taken(const drivecom::SampleResult& r) {
  for (std::uint8_t i = 0; i < r.count; ++i) {
    if (r.transition(i) == 15) return true;
  }
  return false;
}

bool one_byte(drive::DataType t) {
  return t == drive::DataType::binary8 || t == drive::DataType::usign8;
}

}  // namespace

Drive::Drive(const DriveConfig& config, DeviceStart start, Time now)
    : config_(config),
      params_(config.interbus_software ? parameters() : standalone_parameters(), pnr::kProg),
      slots_{params_.table().slot(pnr::kIbWd),  params_.table().slot(pnr::kIbcod),
             params_.table().slot(pnr::kIcntl), params_.table().slot(pnr::kIbsta),
             params_.table().slot(pnr::kFdriv), params_.table().slot(pnr::kFist)},
      pd_(config.pd),
      serial_last_(now),
      sample_time_(now) {
  params_.power_on();  // a factory-fresh store, power-on bit set
  ready_at_ = now;
  switch (start) {
    case DeviceStart::power_on:
      // 6.1: about four seconds of initialisation and self-test.
      ready_at_ = now + config_.pd.init_time;
      starting_ = true;
      pd_.power_on();
      break;
    case DeviceStart::initialised:
      pd_.start(DeviceStart::operational);
      break;
    case DeviceStart::operational:
    case DeviceStart::fault:
      params_.clear_siof(0xFF);
      pd_.start(start);
      break;
  }
  apply_parameters();
}

// --- Parameters ---------------------------------------------------------------------------------

Word Drive::read(std::size_t slot) const {
  switch (params_.table().params()[slot].number) {
    case pnr::kStat:
      return status();
    case pnr::kFout:
      // LUSTBUS manual 6.1.1.1: the rotary-field frequency, the ramp generator's output, in 0.05 Hz.
      return static_cast<Word>(std::lround(std::fabs(pd_.frequency_hz()) / kHzPerBit));
    default:
      return params_.read(slot);
  }
}

drive::WriteCheck Drive::check_write(const drive::ParameterInfo* p, Word raw,
                                     bool power_stage_enabled) const {
  const drive::WriteCheck c = drive::check_write(p, raw, power_stage_enabled);
  // 8.1.1: 000FH is the reset; 11-STAT is otherwise the inverter's status (LB-D19).
  if (c == drive::WriteCheck::ok && p->number == pnr::kStat && raw != kStatReset) {
    return drive::WriteCheck::invalid_value;
  }
  // LUSTBUS manual 4: the rate "in steps ranging from 2400 Baud to 9600 Baud" (LB-E18).
  if (c == drive::WriteCheck::ok && p->number == pnr::kSioc && !drive::is_baud_step(raw, kHighestBaud)) {
    return drive::WriteCheck::invalid_value;
  }
  return c;
}

drive::WriteEffect Drive::write(std::size_t slot, Word raw, bool power_stage_enabled, Time now) {
  unsettle();
  const drive::ParameterInfo& p = params_.table().params()[slot];
  if (p.number == pnr::kStat) {
    // 8.1.1: "the reset happens immediately after the receipt": with an error the inverter boots
    // (self-test); without one 000FH resets nothing. 11-STAT keeps no written value.
    if ((status() & kStatError) != 0) {
      starting_ = true;  // the serial control word is void from now on
      software_reset(serial_has_control() ? serial_control_word() : last_control_, now);
    }
    return {};
  }
  const bool defaults = params_.loads_defaults(slot, raw);
  // LUSTBUS manual 11.1, kind '3': FSEL/ISEL variables are RAM variables while the serial interface
  // controls (2-CSEL = 3); otherwise INTERBUS manual 4.1.3.3's rule: RAM while the power stage runs,
  // EEPROM too while it is off (decision VF-E18). The store keeps them in RAM alone when told the
  // power stage runs.
  const bool ram_only = power_stage_enabled || (drive::storage(p.category) == drive::Storage::eeprom_ram &&
                                                value(pnr::kCsel) == kCselSio);
  drive::WriteEffect e = params_.write(slot, raw, ram_only, now);
  // 5.2: a new watchdog time counts from its setting.
  if (p.number == pnr::kSiot) serial_last_ = now;
  apply_parameters();
  e.storing = storing_time(p, e.eeprom_changed, defaults);
  return e;
}

Duration Drive::storing_time(const drive::ParameterInfo& p, bool eeprom_changed,
                             bool defaults) const {
  // LUSTBUS manual 3: "SMARTDRIVE inverters delay the answer telegram until the parameter value is
  // stored"; 10 exceptions 1 and 4: the factory defaults, a changed EEPROM value by its length.
  if (defaults) return config_.storing.factory_defaults;
  if (!eeprom_changed) return Duration{0};
  return one_byte(p.type) ? config_.storing.eeprom_one_byte : config_.storing.eeprom_two_bytes;
}

Word Drive::value(std::uint16_t number) const {
  const int s = params_.table().slot(number);
  return s < 0 ? Word{0} : params_.store().value(static_cast<std::size_t>(s));
}

Word Drive::reading(std::uint16_t number) const {
  const int s = params_.table().slot(number);
  return s < 0 ? Word{0} : read(static_cast<std::size_t>(s));
}

Word Drive::eeprom_value(std::uint16_t number) const {
  const int s = params_.table().slot(number);
  return s < 0 ? Word{0} : params_.store().eeprom_value(static_cast<std::size_t>(s));
}

std::uint8_t Drive::read_siof() {
  unsettle();
  const std::uint8_t bits = siof();
  clear_siof(bits);
  return bits;
}

// --- Faces --------------------------------------------------------------------------------------

void Drive::attach(Face f) {
  unsettle();
  ++(f == Face::interbus ? faces_.interbus : faces_.serial);
}

void Drive::detach(Face f) {
  unsettle();
  int& n = f == Face::interbus ? faces_.interbus : faces_.serial;
  if (n > 0) --n;
}

bool Drive::serial_locked() const {
  return attached(Face::interbus) && value(pnr::kMode) == kModeInterbus;
}

bool Drive::serial_has_control() const {
  return attached(Face::serial) && value(pnr::kMode) == kModeSio && value(pnr::kCsel) == kCselSio;
}

Word Drive::serial_control_word() const {
  const Word cntl = serial_has_control() && !starting_ ? value(pnr::kCntl) : Word{0};
  ControlBits b;
  b.ramp_enable = b.ramp_run = b.ramp_follow = true;  // the ramp generator runs freely
  b.str = (cntl & kStartClockwise) != 0;
  b.stl = (cntl & kStartCounterClockwise) != 0;
  Word w = encode_control_bits(b);
  const drivecom::State s = pd_.state();
  // The inverter walks DRIVECOM itself: SHUTDOWN before ENABLE OPERATION; without a start bit
  // the ramp brings the frequency down first, then SHUTDOWN (READY TO SWITCH ON).
  if (b.str || b.stl) {
    w |= s == drivecom::State::start_up_inhibit ? drivecom::command_word(drivecom::Command::shutdown)
                                                : drivecom::command_word(drivecom::Command::enable);
  } else if (s == drivecom::State::enabled && pd_.frequency_hz() != 0.0) {
    w |= drivecom::command_word(drivecom::Command::enable);
  } else {
    w |= drivecom::command_word(drivecom::Command::shutdown);
  }
  return w;
}

Word Drive::serial_reference() const {
  // 7.1: the reference of 5-FSSIO in 0.05 Hz steps, with 4-FSSEL = 8.
  return value(pnr::kFssel) == kFsselFssio ? value(pnr::kFssio) : Word{0};
}

// --- Time ---------------------------------------------------------------------------------------

void Drive::advance(Time now) {
  // Advanced to `now` already, nothing changed since (advance_fully says when it leaves the drive
  // settled): the watchdog has not run out (5.2), no sample is due, the start's end has been seen.
  // Only the fault input is set again, as the general path would.
  if (settled_.on && now == settled_.to) {
    if (!attached(Face::interbus) && now > sample_time_) {
      pd_.set_fault(external_fault_ || ib_fault_ || serial_fault_);
    }
    return;
  }
  advance_fully(now);
}

void Drive::advance_fully(Time now) {
  if (!attached(Face::interbus)) {
    // The inverter samples up to the moment its serial watchdog ran out, so that the fault acts
    // from then.
    const Word siot = value(pnr::kSiot);
    if (attached(Face::serial) && !starting_ && !serial_fault_ && siot != 0 &&
        now - serial_last_ > std::chrono::milliseconds(siot)) {
      const Time expiry = serial_last_ + std::chrono::milliseconds(siot) + Duration{1};
      if (expiry < now) advance_fully(expiry);
    }
    if (now > sample_time_) {
      if (now - sample_time_ > kCatchUp) sample_time_ = now - kCatchUp;
      pd_.set_fault(external_fault_ || ib_fault_ || serial_fault_);
      while (now - sample_time_ >= kSamplePeriod) {
        sample_time_ += kSamplePeriod;
        own_sample(kSamplePeriod, sample_time_);
      }
    }
  }
  finish_start(now);
  // 5.2: no valid telegram within 84-SIOT ms; 8: the power stage blocks at once.
  const bool tripped = check_serial_watchdog(now);
  if (tripped && !attached(Face::interbus)) sample_now(now);
  // Settled when the watchdog did not run out here: the last steps were then the start's end and
  // a check that changed nothing, so a second call at `now` would find the same state and do
  // nothing but set the fault input again (as advance() does). After a trip, not settled.
  settled_.on = !tripped;
  settled_.to = now;
}

void Drive::interbus_cycle(Time now) {
  unsettle();
  ib_armed_ = true;
  ib_last_cycle_ = now;
}

void Drive::serial_telegram(Time now) {
  // 5.2: the telegram feeds 84-SIOT. At the time the drive was advanced to, advance() there still
  // has nothing to do: the watchdog then sees 0 ms since the telegram (it runs out only after more
  // than 84-SIOT ms), and nothing else advance() does reads serial_last_. So the drive stays
  // settled; at any other time it does not.
  if (now != settled_.to) unsettle();
  serial_last_ = now;
}

void Drive::begin_sample(Time now) {
  unsettle();
  finish_start(now);
  run_interbus_watchdog(now);
  check_serial_watchdog(now);
  pd_.set_fault(external_fault_ || ib_fault_ || serial_fault_);
}

void Drive::sample(std::span<const Word> m2s, std::span<Word> s2m, Time now,
                   std::optional<Word> comm) {
  unsettle();
  // The interface that controls gives words 1 and 2 (LUSTBUS manual 7.1; INTERBUS manual 6.1).
  const bool serial = serial_has_control();
  const Word control = serial ? serial_control_word() : m2s[0];
  const Word reference = serial ? serial_reference() : m2s[1];
  const std::array<Word, Vf1000PdDevice::kWords> in{control, reference, 0};
  pd_.sample(in, s2m, kSamplePeriod, comm);
  sample_time_ = now;
  after_sample(control, s2m[1], now);
}

void Drive::own_sample(Duration dt, Time now) {
  // Words 1 and 2 as 7.1 forms them from 3-CNTL and 5-FSSIO; no communication word.
  const Word control = serial_control_word();
  const std::array<Word, Vf1000PdDevice::kWords> in{control, serial_reference(), 0};
  std::array<Word, Vf1000PdDevice::kWords> out{};
  pd_.sample(in, out, dt);
  after_sample(control, out[1], now);
}

void Drive::sample_now(Time now) {
  pd_.set_fault(external_fault_ || ib_fault_ || serial_fault_);
  own_sample(Duration{0}, now);
}

// `actual`: word 2 of the sample's answer, the actual frequency as 912-FIST holds it.
void Drive::after_sample(Word control, Word actual, Time now) {
  if (reset_fault_taken(pd_.last_sample())) {
    software_reset(control, now);
    return;
  }
  if (ib_fault_ && !ib_tripped_ && pd_.state() == drivecom::State::start_up_inhibit) {
    ib_fault_ = false;  // reset by the master after the data came back
  }
  last_control_ = control;
  input_bits_ = control & kInputFunctionBits;
  mirror(control, actual);
}

void Drive::mirror(Word control, Word actual) {
  // 901-ICNTL and 911-IBSTA mirror the DRIVECOM words, 905-FDRIV and 912-FIST the frequencies
  // (INTERBUS manual 4.1.1; signed 0.05 Hz, a modelling choice). 912 is the word the sample answered
  // with (actual_word of the frequency), not formed a second time.
  set_slot(slots_.icntl, control);
  set_slot(slots_.ibsta, pd_.status_word());
  set_slot(slots_.fdriv, actual_word(pd_.setpoint_hz()));
  set_slot(slots_.fist, actual);
}

void Drive::run_interbus_watchdog(Time now) {
  // 906-IB-WD: monitoring time in 50 ms steps, 65535 = off; 907-IBCOD: the reaction (4.1.1).
  const auto limit = ib_wd_monitoring_time(slot_value(slots_.ib_wd, 0xFFFF));
  const bool expired = ib_armed_ && limit && (now - ib_last_cycle_) > *limit;
  if (expired && !ib_tripped_) {
    ib_tripped_ = true;
    switch (static_cast<IbCod>(slot_value(slots_.ibcod, 0))) {
      case IbCod::no_action: break;
      case IbCod::shutdown_e_ibs: ib_fault_ = true; break;
      case IbCod::block_power: pd_.override_control(Word{0x0000}); break;
      case IbCod::emergency_stop: pd_.override_control(Word{0x0002}); break;
    }
  } else if (!expired && ib_tripped_) {
    // Data flows again: the master's words count again; an E-IBS fault stays latched until the
    // master resets it (its cause, the missing data, has gone).
    ib_tripped_ = false;
    pd_.override_control(std::nullopt);
  }
}

bool Drive::check_serial_watchdog(Time now) {
  // LUSTBUS manual 5.2: 84-SIOT in ms, 0 = off; it monitors the serial link, so only while a serial
  // face is attached, and not through a self-test (the timer starts again at its end).
  if (!attached(Face::serial) || starting_ || serial_fault_) return false;
  const Word siot = value(pnr::kSiot);
  if (siot == 0 || now - serial_last_ <= std::chrono::milliseconds(siot)) return false;
  // The error state, bit 02H in 85-SIOF (9.2).
  serial_fault_ = true;
  raise_siof(drive::siof_mask(drive::SiofBit::watchdog));
  pd_.set_fault(true);
  return true;
}

void Drive::apply_parameters() {
  // 36-RSTOP: stop ramp in 0.05 Hz/s (0: the power stage is switched off, 5.2.1); 22-FMAX1.
  pd_.set_stop_ramp(static_cast<double>(params_.value(pnr::kRstop).value_or(0)) * kHzPerBit);
  pd_.set_max_frequency(static_cast<double>(params_.value(pnr::kFmax1).value_or(8000)) * kHzPerBit);
}

// --- Events -------------------------------------------------------------------------------------

void Drive::new_start(Time now, Duration init) {
  // LUSTBUS manual 6 and 9.2: after every new start only the power-on bit; EEPROM values back.
  params_.power_on();
  input_bits_ = 0;  // the bus's bits count again from the first word after the start
  ready_at_ = now + init;
  starting_ = true;
  ++starts_;
}

void Drive::finish_start(Time now) {
  if (!starting_ || now < ready_at_) return;
  starting_ = false;
  serial_last_ = now;  // 5.2: the serial watchdog counts from the end of the self-test
}

void Drive::software_reset(Word control, Time now) {
  // INTERBUS manual 5.2.1, bit 7: "The inverter performs a software reset !"; LUSTBUS manual 8.1.1: the
  // boot-up (self test) after 11-STAT = 000FH, the connection broken meanwhile; 9.2: the
  // power-on bit afterwards. One model for both triggers (VF-E13): the self-test lasts
  // config().pd.reset_time, the store starts anew at once (nothing can read it meanwhile).
  new_start(now, config_.pd.reset_time);
  pd_.software_reset(control);
  // Faults are reset with it; the firmware starts again: 906-IB-WD monitors the bus from the
  // first data cycle after the self-test (no data reach an inverter that shows a module error).
  ib_fault_ = false;
  ib_armed_ = false;
  if (ib_tripped_) pd_.override_control(std::nullopt);
  ib_tripped_ = false;
  serial_fault_ = false;
  pd_.set_fault(external_fault_);
  ++software_resets_;
  apply_parameters();
}

void Drive::power_cycle(Time now) {
  unsettle();
  new_start(now, config_.pd.init_time);
  card_until_ = Time{0};  // switched off: the card operation ends with it
  pd_.power_on();
  pd_.override_control(std::nullopt);
  ib_armed_ = false;
  ib_tripped_ = false;
  ib_fault_ = false;
  serial_fault_ = false;
  apply_parameters();
}

void Drive::restart(Time now) {
  unsettle();
  new_start(now, Duration{0});
  finish_start(now);
  pd_.override_control(std::nullopt);
  pd_.start(DeviceStart::operational);
  ib_armed_ = false;
  ib_tripped_ = false;
  ib_fault_ = false;
  serial_fault_ = false;
  sample_time_ = now;
  apply_parameters();
}

void Drive::mains_off(Time now) {
  unsettle();
  power_cycle(now);
  ready_at_ = Time::max();  // no end of the start until the mains return
  powered_ = false;
  external_fault_ = false;
  fault_cause_.reset();
}

void Drive::mains_on(Time now) {
  unsettle();
  if (powered_) return;
  powered_ = true;
  power_cycle(now);
}

bool Drive::apply(const PlantEvent& e, Time now) {
  unsettle();
  switch (e.kind) {
    case PlantEvent::Kind::fault:
    case PlantEvent::Kind::fault_clear:
      set_fault(e.kind == PlantEvent::Kind::fault, now, e.cause);
      return true;
    case PlantEvent::Kind::power_cycle:
      power_cycle(now);
      return true;
    case PlantEvent::Kind::mains_off:
      mains_off(now);
      return true;
    case PlantEvent::Kind::mains_on:
      mains_on(now);
      return true;
    case PlantEvent::Kind::card_read:
    case PlantEvent::Kind::card_write:
      // Reading loads the card's parameter set, writing saves the drive's: the seeds give neither
      // set, so the values stay; the time is what either bus sees (VF-E21).
      smartcard(std::chrono::duration_cast<Duration>(std::chrono::duration<double>(e.value)), now);
      return true;
    case PlantEvent::Kind::input:
      if (e.input >= vf1000::kTerminalCount) return false;
      set_terminal(static_cast<vf1000::Terminal>(e.input), e.level);
      return true;
    case PlantEvent::Kind::load:
    case PlantEvent::Kind::option_withdrawn:  // no seed gives the inverter's option an effect
    case PlantEvent::Kind::option_inserted:
      return false;
  }
  return false;
}

void Drive::set_terminal(vf1000::Terminal t, bool high) {
  unsettle();
  terminals_[static_cast<std::size_t>(t)] = high;
  // 5.2.2: bit 14 S2OUT, bit 15 S1OUT, in the status word of the next sample (and so in 911).
  pd_.set_outputs(terminals_[static_cast<std::size_t>(vf1000::Terminal::s2out)],
                  terminals_[static_cast<std::size_t>(vf1000::Terminal::s1out)]);
}

bool Drive::terminal(vf1000::Terminal t) const {
  const bool output = t == vf1000::Terminal::s1out || t == vf1000::Terminal::s2out;
  return terminals_[static_cast<std::size_t>(t)] && (powered_ || !output);
}

bool Drive::input_function_active(vf1000::Terminal input) const {
  if (!powered_) return false;
  switch (input) {
    case vf1000::Terminal::s1ind: return terminal(input) || (input_bits_ & kS1indBit) != 0;
    case vf1000::Terminal::s2ind: return terminal(input) || (input_bits_ & kS2indBit) != 0;
    default: return false;
  }
}

void Drive::smartcard(Duration how_long, Time now) {
  unsettle();
  if (how_long > Duration{0}) card_until_ = std::max(card_until_, now + how_long);
}

void Drive::set_fault(bool present, Time now, std::optional<int> cause) {
  unsettle();
  external_fault_ = present;
  fault_cause_ = present ? cause : std::nullopt;
  // Without an INTERBUS face the drive samples itself: the fault acts at once (8). With one, at
  // its next sample.
  if (!attached(Face::interbus)) sample_now(now);
}

Word Drive::status() const {
  Word w = 0;
  if (pd_.initialised() && !starting_) w |= kStatReady;
  if (power_stage_enabled()) w |= kStatRunning;
  if (pd_.frequency_hz() < 0.0) w |= kStatCounterClockwise;
  const drivecom::State s = pd_.state();
  if (external_fault_ || ib_fault_ || serial_fault_ || s == drivecom::State::fault ||
      s == drivecom::State::fault_response_active) {
    w |= kStatError;
  }
  return w;
}

}  // namespace ibs::devices::vf1000
