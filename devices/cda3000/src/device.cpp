#include "ibs/devices/cda3000/device.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "ibs/devices/cda3000/descriptor.hpp"
#include "ibs/devices/cda3000/description.hpp"

namespace ibs::devices::cda3000 {

namespace {

using namespace ibs::canlust;

std::size_t index_or_throw(std::uint16_t number) {
  const auto i = parameter_index(number);
  if (!i) throw std::invalid_argument("CDA3000: parameter " + std::to_string(number) + " is not in the table");
  return *i;
}

}  // namespace

std::vector<std::pair<std::uint16_t, std::uint32_t>> commissioned_for_bus(std::uint8_t address,
                                                                          std::uint8_t cacnf) {
  return {{kAstpr, kDataSetBus1}, {kAster, kDataSetBus1}, {kFisa0, kOptn2Code},
          {kClsel, kOptn2Code},   {kRssl1, kOptn2Code},   {kCladr, address},
          {kCacnf, cacnf}};
}

Cda3000::Cda3000(const DeviceConfig& config) : config_(config) {
  if (config_.connector_address > 7) {
    throw std::invalid_argument("CDA3000: connector address " + std::to_string(config_.connector_address) +
                                " is outside 0..7 (2.1)");
  }
  for (std::size_t i = 0; i < kParameters.size(); ++i) {
    saved_[i] = wire_of(kParameters[i], kParameters[i].factory);
  }
  name_saved_ = FixedString::from(kNameFactory);
  for (const auto& [number, v] : config_.saved) {
    const ParameterInfo* p = find_parameter(number);
    if (p == nullptr) {
      throw std::invalid_argument("CDA3000: saved parameter " + std::to_string(number) + " does not exist");
    }
    if (!p->writable() || p->is_string() || p->memory != Memory::flash) {
      throw std::invalid_argument("CDA3000: " + display_name(*p) + " is not a saved setting");
    }
    const ValueCheck c = check_value(*p, v);
    if (c != ValueCheck::ok) throw std::invalid_argument("CDA3000: " + describe_refusal(*p, v, c));
    if (number == kCamod && v != kCamodSlave) {
      throw std::invalid_argument("CDA3000: 570-CAMOD: only the CANLust slave (0) is emulated (decision D26)");
    }
    saved_[index_or_throw(number)] = v;
  }
  current_ = saved_;
  name_ = name_saved_;
}

std::uint32_t Cda3000::get(std::uint16_t number) const {
  const auto i = parameter_index(number);
  return i ? current_[*i] : 0U;
}

void Cda3000::set(std::uint16_t number, std::uint32_t value) {
  if (const auto i = parameter_index(number)) current_[*i] = value;
}

std::optional<std::uint32_t> Cda3000::value(std::uint16_t number) const {
  const auto i = parameter_index(number);
  if (!i || kParameters[*i].is_string()) return std::nullopt;
  return value_at(*i);
}

std::uint32_t Cda3000::value_at(std::size_t i) const {
  const std::uint16_t number = kParameters[i].number;
  if (number == kReff) return static_cast<std::uint32_t>(q16_from_double(reference_hz()));
  if (number == kErr1) return wire_from_err_struc(last_error_);
  if (number == kCawrn) return warnings();
  return current_[i];
}

std::optional<std::uint32_t> Cda3000::saved_value(std::uint16_t number) const {
  const auto i = parameter_index(number);
  if (!i || kParameters[*i].is_string() || kParameters[*i].memory != Memory::flash) return std::nullopt;
  return saved_[*i];
}

std::string_view Cda3000::text(std::uint16_t number) const {
  if (number == kName) return name_.view();
  if (number == kOptn2) return kOptn2Module;
  return {};
}

std::string_view Cda3000::saved_text(std::uint16_t number) const {
  if (number == kName) return name_saved_.view();
  return text(number);
}

bool Cda3000::bus_controls() const { return get(kClsel) == kOptn2Code; }

ErrorReaction Cda3000::response(std::uint8_t error) const {
  const auto p = response_parameter(error);
  return static_cast<ErrorReaction>(p ? get(*p) : kResponseDefault);
}

std::uint16_t Cda3000::warnings() const {
  // 6.3 0004H "warning message when I2t integrator of device is active": the integrator runs
  // while the power stage drives more than the rated torque (CAN-E17).
  const bool i2t = drivecom::power_stage_enabled(sm_.state()) && std::fabs(load_percent_) > 100.0;
  return static_cast<std::uint16_t>(warnings_raised_ | (i2t ? kWarningI2t : 0U));
}

bool Cda3000::warning() const {
  // 6.3: only the warnings 576-CAWMK selects are reported on the CAN (status bit 7).
  return warning_ || error_warning_ || (warnings() & get(kCawmk)) != 0;
}

void Cda3000::acknowledge_warnings() {
  error_warning_ = false;
  warnings_raised_ = 0;
}

double Cda3000::reference_hz() const {
  if (get(kRssl1) != kOptn2Code) return 0.0;  // the emulator has no terminals, MOP or tables
  const double r = std::clamp(reference_hz_, -config_.plant.fmax_hz, config_.plant.fmax_hz);
  if (layout_.mode != canlust::WordMode::easydrive) return r;
  // EasyDrive (D26): the start bit gives the direction, the reference its size.
  const bool str = bit(easy_word_, easydrive::kStr);
  const bool stl = bit(easy_word_, easydrive::kStl);
  return str == stl ? 0.0 : (str ? std::fabs(r) : -std::fabs(r));
}

ibs::Word Cda3000::easydrive_control(bool stopped) const {
  // EasyDrive's direct control walks the DRIVECOM machine inside the drive (D26): a start bit
  // enables (SHUTDOWN first from START-UP INHIBIT); without one the drive brings the frequency to
  // 0 Hz with its ramp and then shuts down (READY); the error reset bit is DRIVECOM's bit 7.
  const bool str = bit(easy_word_, easydrive::kStr);
  const bool stl = bit(easy_word_, easydrive::kStl);
  const drivecom::State st = sm_.state();
  ibs::Word w = bit(easy_word_, easydrive::kEres) ? ibs::Word{0x0080} : ibs::Word{0};
  if (str != stl) {
    w |= st == drivecom::State::start_up_inhibit ? drivecom::command_word(drivecom::Command::shutdown)
                                                  : drivecom::command_word(drivecom::Command::enable);
  } else if (st == drivecom::State::enabled && !stopped) {
    w |= drivecom::command_word(drivecom::Command::enable);
  } else {
    w |= drivecom::command_word(drivecom::Command::shutdown);
  }
  return w;
}

ibs::Word Cda3000::easydrive_status(Time now) const {
  namespace es = easydrive::status;
  const drivecom::State st = sm_.state();
  const double f = plant_.hz(now);
  const bool error = st == drivecom::State::fault || st == drivecom::State::fault_response_active;
  const bool active = drivecom::power_stage_enabled(st);
  ibs::Word w = 0;
  w = with_bit(w, es::kReady, !error && st != drivecom::State::not_ready);
  w = with_bit(w, es::kError, error);
  w = with_bit(w, es::kActiv, active);
  w = with_bit(w, es::kRot0, std::fabs(f) <= config_.plant.stop_threshold_hz);
  // BRK: the power stage takes the frequency towards 0 Hz (decelerating, or reversing).
  const double t = plant_.target();
  const bool braking = std::fabs(f) > config_.plant.stop_threshold_hz && ((f > 0.0 && t < f) || (f < 0.0 && t > f));
  w = with_bit(w, es::kBrk, active && braking);
  w = with_bit(w, es::kWarning, warning());
  w = with_bit(w, es::kCanStart, system_state() == canlust::SystemState::start);
  w = with_bit(w, es::kReferenceReached,
               st == drivecom::State::enabled && std::fabs(f - reference_hz()) <= config_.plant.reached_window_hz);
  return w;
}

canlust::SystemState Cda3000::system_state() const {
  return node_ ? node_->state() : canlust::SystemState::logon;
}

void Cda3000::power_on(Time now) {
  if (!first_power_on_) first_power_on_ = now;
  current_ = saved_;
  easy_word_ = 0;
  name_ = name_saved_;
  download_open_ = false;  // a download the mains reset cut is lost; the old set is in flash
  set(kSload, 0);
  const std::uint32_t cladr = get(kCladr);
  address_ = static_cast<Address>(cladr != 0 ? cladr : config_.connector_address);
  layout_ = process_layout_for_cacnf(static_cast<std::uint8_t>(get(kCacnf))).value_or(ProcessLayout{});
  bitrate_ = get(kClbdr) * 1000U;
  NodeConfig nc;
  nc.address = address_;
  nc.ids = config_.ids;
  nc.layout = layout_;
  nc.status_period = std::chrono::milliseconds(get(kCascy));
  nc.watchdog = std::chrono::milliseconds(get(kCawdg));
  nc.watchdog_reaction = response(kErrorOp2);  // 525-ROP2; watchdog_expired reads it again
  nc.outbox_capacity = config_.outbox_capacity;
  node_.reset();
  node_.emplace(nc, *this, *this);
  sm_.power_on();
  state_since_ = now;
  control_ = 0;
  reference_hz_ = 0.0;
  warning_ = false;
  acknowledge_warnings();
  fault_.reset();
  plant_.reset(now);
  sample(now);  // the self-test is instantaneous here: NOT READY -> START-UP INHIBIT (1)
  node_->power_on(now);
}

void Cda3000::power_off() { node_.reset(); }

bool Cda3000::awaiting_stop() const {
  const auto s = sm_.state();
  if (s == drivecom::State::emergency_stop_active) return true;
  return s == drivecom::State::fault_response_active && fault_ &&
         *fault_ != ErrorReaction::disable_power;
}

void Cda3000::advance(Time now) {
  if (awaiting_stop() && now >= plant_.stopped_at(config_.plant.stop_threshold_hz)) sample(now);
}

void Cda3000::sample(Time now) {
  const bool stopped = plant_.target() == 0.0
                           ? now >= plant_.stopped_at(config_.plant.stop_threshold_hz)
                           : std::fabs(plant_.hz(now)) <= config_.plant.stop_threshold_hz;
  if (layout_.mode == canlust::WordMode::easydrive) control_ = easydrive_control(stopped);
  drivecom::DeviceInputs in;
  // 2.3 Figure 2-5 / 3.1: without ENPO (X2-8) the power stage cannot be enabled; the drive
  // takes it as DRIVECOM's "block power" (bit 1 clear): START-UP INHIBIT, the motor coasts (D36).
  // 4.x: during a data set download the drive is disabled ("the drive is enabled again" after it).
  in.control = enpo_ && !download_open_ ? control_ : static_cast<ibs::Word>(control_ & ~ibs::Word{0x0002});
  in.fault_present = fault_.has_value();
  in.fault_reaction_done = !fault_ || *fault_ == ErrorReaction::disable_power || stopped;
  in.stopped = stopped;
  const drivecom::State before = sm_.state();
  sm_.sample(in);
  if (sm_.state() != before) state_since_ = now;
  drive_plant(now);
}

void Cda3000::drive_plant(Time now) {
  const auto& pc = config_.plant;
  double target = 0.0;
  Duration tau = pc.coast_time_constant;
  switch (sm_.state()) {
    case drivecom::State::enabled: {
      // D35: a load torque makes the motor slip below the output frequency (linear, rated slip
      // at 100 %); a load larger than the drive can turn holds the motor at 0 Hz.
      const double r = reference_hz();
      const double slipped = r - std::copysign(load_percent_ / 100.0 * pc.rated_slip_hz, r);
      target = r == 0.0 || (slipped > 0.0) != (r > 0.0) ? 0.0 : slipped;
      tau = pc.time_constant;
      break;
    }
    case drivecom::State::emergency_stop_active: tau = pc.quick_stop_time_constant; break;
    case drivecom::State::fault_response_active:
      if (fault_ == ErrorReaction::stop) tau = pc.time_constant;
      if (fault_ == ErrorReaction::quick_stop) tau = pc.quick_stop_time_constant;
      break;
    default: break;
  }
  plant_.set(target, tau, now);
}

void Cda3000::receive(const CanFrame& f, Time now) {
  if (!node_) return;
  advance(now);
  node_->receive(f, now);
}

void Cda3000::step(Time now) {
  if (!node_) return;
  advance(now);
  node_->step(now);
}

Time Cda3000::next_deadline() const {
  if (!node_) return Time::max();
  Time t = node_->next_deadline();
  if (awaiting_stop()) t = std::min(t, plant_.stopped_at(config_.plant.stop_threshold_hz));
  return t;
}

ibs::Word Cda3000::status_word() const {
  drivecom::StatusExtras x;
  x.alarm = warning();
  x.remote = bus_controls();
  x.limit_value = get(kRssl1) == kOptn2Code && std::fabs(reference_hz_) > config_.plant.fmax_hz;
  // Bit 10 needs the actual frequency at the time of asking: status(now) adds it.
  return drivecom::status_word(sm_.state(), sm_.last_control(), x);
}

// ---- plant and fault events ----------------------------------------------------------------

std::optional<Input> find_input(std::string_view name) {
  std::string up(name);
  for (char& c : up) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (up == "ENPO") return Input::enpo;
  if (up == "ISD00") return Input::isd00;
  return std::nullopt;
}

std::string_view to_string(Input i) { return i == Input::enpo ? "ENPO" : "ISD00"; }

bool Cda3000::inject_fault(std::uint8_t number, Time now) {
  if (!node_ || !canlust::find_error(number)) return false;
  advance(now);
  ++counters_.device_faults;
  // 6.1: "the error response is programmable for each error in four stages"; the default
  // disables the power stage (CAN-E16: the error's parameter, factory PWOFF).
  const ErrorReaction r = response(number);
  const auto hours = std::chrono::duration_cast<std::chrono::hours>(now - first_power_on_.value_or(now)).count();
  last_error_ = {number, 0, static_cast<std::uint16_t>(std::min<long long>(hours, 0xFFFF))};
  if (r == ErrorReaction::warning) {
    // 6.1 p. 67: with the response WRN "the device indicates the warning": status bit 7.
    error_warning_ = true;
  } else {
    // A second error never softens the reaction already running (the codes rise with severity).
    if (!fault_ || r > *fault_) fault_ = r;
    sample(now);
  }
  // 5.5 / 6.2: the error message (441 + address) carries the number of table 5.9 and (D6) the
  // reaction taken.
  node_->report_error({number, 0, static_cast<std::uint8_t>(r)}, now);
  return true;
}

const WarningInfo* find_warning(std::string_view text) {
  std::string up(text);
  for (char& c : up) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const auto& w : kWarnings) {
    char hex[16];
    std::snprintf(hex, sizeof hex, "%04XH", static_cast<unsigned>(w.mask));
    char cx[16];
    std::snprintf(cx, sizeof cx, "0X%04X", static_cast<unsigned>(w.mask));
    if (up == w.name || "W-" + up == w.name || up == hex || up == cx) return &w;
  }
  return nullptr;
}

bool Cda3000::raise_warning(std::uint16_t mask, Time now) {
  if (!node_) return false;
  advance(now);
  warnings_raised_ = static_cast<std::uint16_t>(warnings_raised_ | mask);
  return true;
}

void Cda3000::set_load(double percent, Time now) {
  advance(now);
  load_percent_ = std::clamp(percent, -kMaxLoadPercent, kMaxLoadPercent);
  if (node_) drive_plant(now);
}

void Cda3000::set_input(Input i, bool high, Time now) {
  if (i == Input::isd00) {
    isd00_ = high;  // CANLust manual names the terminal only (2.3.2: "X2 9 ISD00 digital input")
    return;
  }
  enpo_ = high;
  if (!node_) return;
  advance(now);
  sample(now);
}

// ---- DriveProcess ----------------------------------------------------------------------------

void Cda3000::execute(const ControlTelegram& t, Time now) {
  advance(now);
  if (!bus_controls()) {
    // 4.3.2: only with 260-CLSEL = OPTN2 is the control word formed from the control telegram.
    ++counters_.controls_ignored;
    return;
  }
  ++counters_.controls_executed;
  if (get(kRssl1) == kOptn2Code) reference_hz_ = hz_from_wire(layout_.reference, t.reference);
  warning_ = false;  // a control telegram again: the watchdog's warning is over
  // 6.5: the error reset bit acknowledges the error; the cause (no control telegram) is gone.
  // It acknowledges an error answered with WRN and the warnings of 6.3 too (CAN-E17).
  if (drivecom::reset_fault_edge(sm_.last_control(), t.word)) acknowledge_warnings();
  if (fault_ && sm_.state() == drivecom::State::fault && drivecom::reset_fault_edge(sm_.last_control(), t.word)) {
    fault_.reset();
  }
  control_ = t.word;
  easy_word_ = t.word;  // EasyDrive: sample() forms the DRIVECOM word from it (D26)
  sample(now);
}

StatusTelegram Cda3000::status(Time now) {
  advance(now);
  const double f = plant_.hz(now);
  if (layout_.mode == canlust::WordMode::easydrive) {
    return {easydrive_status(now), wire_from_hz(layout_.actual, std::clamp(f, -32767.0, 32767.0)).value_or(0)};
  }
  ibs::Word w = status_word();
  const bool reached = sm_.state() == drivecom::State::enabled &&
                       std::fabs(f - reference_hz()) <= config_.plant.reached_window_hz;
  w = with_bit(w, status_bits::kReferenceReached, reached);
  const double clamped = std::clamp(f, -32767.0, 32767.0);
  return {w, wire_from_hz(layout_.actual, clamped).value_or(0)};
}

std::optional<ErrorTelegram> Cda3000::watchdog_expired(const WatchdogEvent& e) {
  advance(e.now);
  ++counters_.watchdog_trips;
  // 6.1 / D15: the watchdog reports E-OP2; its reaction is 525-ROP2 as it is set now (CAN-E16),
  // not what the node was built with.
  const ErrorReaction r = response(e.error.number);
  if (r == ErrorReaction::warning) {
    warning_ = true;  // 6.1 WRN: a warning, the drive keeps running
  } else {
    if (!fault_ || r > *fault_) fault_ = r;
    sample(e.now);
  }
  ErrorTelegram t = e.error;
  t.reaction = static_cast<std::uint8_t>(r);
  return t;
}

void Cda3000::system_state_changed(SystemState s, Time now) {
  advance(now);
  if (s != SystemState::stop) return;
  // 6.5: the transition SYSTEM START -> SYSTEM STOP acknowledges the error: transition 15.
  warning_ = false;
  acknowledge_warnings();
  if (fault_) {
    fault_.reset();
    if (sm_.state() == drivecom::State::fault) {
      sm_.force(drivecom::State::start_up_inhibit, sm_.last_control());
      state_since_ = now;
    }
    drive_plant(now);
  }
}

// ---- ParameterAccess -------------------------------------------------------------------------

ValueResult Cda3000::read(std::uint16_t number, std::uint8_t index, Time now) {
  (void)now;
  // The table's row looked up once (issue 26), for the checks and the value.
  const auto i = parameter_index(number);
  if (!i) return {kStatusUnknownParameter, DataType::usign32, 0, {}};
  const ParameterInfo& p = kParameters[*i];
  // A STRING goes by mode 11 (D24); no CDA3000 parameter here is a field (index 0 only).
  if (p.is_string()) return {kStatusReadNotPermitted, DataType::usign32, 0, {}};
  if (index != 0) return {kStatusImpermissibleValue, p.type, 0, {}};
  return {kStatusOk, p.type, value_at(*i), {}};
}

AccessResult Cda3000::write(std::uint16_t number, std::uint8_t index, std::uint32_t v, Time now) {
  const ParameterInfo* p = find_parameter(number);
  if (p == nullptr) return {kStatusUnknownParameter, {}};
  if (download_open_ && number != kSload) {
    // 4.x: the data set "is transferred to the drive controller without individual checking of
    // the parameter values"; only Card Writeable parameters belong to it (D39).
    if (!card_writeable(*p)) return {kStatusChangeNotPermitted, {}};
    if (index != 0) return {kStatusImpermissibleValue, {}};
    pending_[*parameter_index(number)] = v;
    ++counters_.writes;
    return {};
  }
  if (!p->writable() || p->is_string()) return {kStatusChangeNotPermitted, {}};
  if (index != 0) return {kStatusImpermissibleValue, {}};
  if (check_value(*p, v) != ValueCheck::ok) return {kStatusImpermissibleValue, {}};
  // D26: what the emulator does not model it refuses, rather than pretend.
  if (number == kCamod && v != kCamodSlave) return {kStatusChangeNotPermitted, {}};
  ++counters_.writes;
  switch (number) {
    case kProg:
      if (v == 1) {
        // p. 13: every setting back to its factory value; the reply once that is done.
        for (std::size_t i = 0; i < kParameters.size(); ++i) {
          if (kParameters[i].writable()) current_[i] = wire_of(kParameters[i], kParameters[i].factory);
        }
        name_ = FixedString::from(kNameFactory);
        apply_live(kCawdg, now);
        apply_live(kCascy, now);
        return {kStatusOk, config_.prog_time};
      }
      return {};
    case kSave:
      if (v == 1) {
        // 3.5.1 / 4.3.3: "a few hundred milliseconds"; RAM values (80-SLOAD, D39) stay out.
        for (std::size_t i = 0; i < kParameters.size(); ++i) {
          if (kParameters[i].memory == Memory::flash) saved_[i] = current_[i];
        }
        name_saved_ = name_;
        return {kStatusOk, config_.save_time};
      }
      return {};
    case kAstpr:
      load_preset(v, now);
      return {};
    case kSload:
      return download(v, now);
    default:
      set(number, v);
      apply_live(number, now);
      return {};
  }
}

AccessResult Cda3000::download(std::uint32_t code, Time now) {
  advance(now);
  if (code == kSloadStart) {
    // Opened only with the power stage off and the motor at rest: the drive is disabled for the
    // download (D39); a second -1 starts again.
    if (drivecom::power_stage_enabled(sm_.state()) || std::fabs(plant_.hz(now)) > config_.plant.stop_threshold_hz) {
      return {kStatusChangeNotPermitted, {}};
    }
    download_open_ = true;
    pending_ = current_;  // the parameters the set leaves out keep their values
    set(kSload, kSloadStart);
    sample(now);
    return {};
  }
  if (code == kSloadCancel) {
    download_open_ = false;
    set(kSload, 0);
    sample(now);
    return {};
  }
  if (code != kSloadEnd || !download_open_) return {kStatusImpermissibleValue, {}};
  // 4.x: "the drive controller checks the now complete new data set for plausibility": every
  // Card Writeable value against its row, in the table's order; the first one refused is named.
  std::uint16_t implausible = 0;
  for (std::size_t i = 0; i < kParameters.size() && implausible == 0; ++i) {
    const ParameterInfo& p = kParameters[i];
    if (!card_writeable(p)) continue;
    const bool camod_master = p.number == kCamod && pending_[i] != kCamodSlave;  // D26
    if (check_value(p, pending_[i]) != ValueCheck::ok || camod_master) implausible = p.number;
  }
  download_open_ = false;
  if (implausible != 0) {
    set(kSload, implausible);  // nothing taken: the old data set stays
  } else {
    // "If the data set is valid the parameters are accepted with the attribute Card Writeable
    // into the EEPROM": settings and flash alike; 574 / 575 act at once (D21).
    for (std::size_t i = 0; i < kParameters.size(); ++i) {
      if (card_writeable(kParameters[i])) current_[i] = saved_[i] = pending_[i];
    }
    set(kSload, 0);
    apply_live(kCawdg, now);
    apply_live(kCascy, now);
  }
  sample(now);  // "The drive is enabled again"
  return {kStatusOk, config_.download_check_time};
}

void Cda3000::load_preset(std::uint32_t data_set, Time now) {
  // D23: the application data set BUS_1 puts control location, reference and the analog input's
  // function on the bus module (4.2 table: FISA0 OFF -> OPTN2); DRV_1 back to the factory's.
  const bool bus = data_set == kDataSetBus1;
  set(kAstpr, data_set);
  set(kAster, data_set);
  set(kFisa0, bus ? kOptn2Code : kFunctionOff);
  set(kClsel, bus ? kOptn2Code : kClselTerm);
  set(kRssl1, bus ? kOptn2Code : static_cast<std::uint32_t>(find_parameter(kRssl1)->factory));
  (void)now;
}

void Cda3000::apply_live(std::uint16_t number, Time now) {
  if (!node_) return;
  // 574-CAWDG and 575-CASCY act at once (decision D21); the address, layout and baud rate after a
  // mains reset (7.1.1 steps 4-5).
  if (number == kCawdg) node_->set_watchdog(std::chrono::milliseconds(get(kCawdg)), now);
  if (number == kCascy) node_->set_status_period(std::chrono::milliseconds(get(kCascy)));
}

ValueResult Cda3000::describe(std::uint16_t number, std::uint8_t item, Time now) {
  (void)now;
  const ParameterInfo* p = find_parameter(number);
  if (p == nullptr) return {kStatusUnknownParameter, DataType::usign32, 0, {}};
  std::uint32_t v = 0;
  switch (item) {
    case 0: v = static_cast<std::uint32_t>(p->type); break;
    case 1: v = wire_of(*p, p->min); break;
    case 2: v = wire_of(*p, p->max); break;
    case 3: v = wire_of(*p, p->factory); break;
    case 4:
      v = (p->writable() ? kAttrWritable : 0U) | (p->memory == Memory::flash ? kAttrFlash : 0U) |
          (p->effect == Effect::after_mains_reset ? kAttrAfterMainsReset : 0U) |
          (p->choices.empty() ? 0U : kAttrChoices);
      break;
    case 5: v = pack4(p->name); break;
    case 6: v = pack4(p->name.size() > 4 ? p->name.substr(4) : std::string_view{}); break;
    case 7: v = pack4(p->unit); break;
    default: return {kStatusListEnd, DataType::usign32, 0, {}};
  }
  return {kStatusOk, DataType::usign32, v, {}};
}

StringResult Cda3000::read_string(std::uint16_t number, std::span<char> out, Time now) {
  (void)now;
  const ParameterInfo* p = find_parameter(number);
  if (p == nullptr) return {kStatusUnknownParameter, 0, {}};
  if (!p->is_string()) return {kStatusReadNotPermitted, 0, {}};
  const std::string_view s = text(number);
  const std::size_t n = std::min(s.size(), out.size());
  std::copy_n(s.data(), n, out.data());
  return {kStatusOk, static_cast<std::uint8_t>(n), {}};
}

AccessResult Cda3000::begin_string_write(std::uint16_t number, Time now) {
  (void)now;
  const ParameterInfo* p = find_parameter(number);
  if (p == nullptr) return {kStatusUnknownParameter, {}};
  if (!p->is_string() || !p->writable()) return {kStatusChangeNotPermitted, {}};
  return {};
}

AccessResult Cda3000::write_string(std::uint16_t number, std::string_view s, Time now) {
  const AccessResult a = begin_string_write(number, now);
  if (a.status != kStatusOk) return a;
  if (s.size() > kMaxStringChars || s.find('\0') != std::string_view::npos) return {kStatusImpermissibleValue, {}};
  name_ = FixedString::from(s);
  ++counters_.writes;
  return {};
}

}  // namespace ibs::devices::cda3000
