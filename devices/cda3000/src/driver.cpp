#include "ibs/devices/cda3000/driver.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ibs/devices/cda3000/descriptor.hpp"

namespace ibs::devices::cda3000 {

namespace {

using namespace ibs::canlust;

MasterConfig master_config(const DriverConfig& c) {
  MasterConfig m;
  m.ids = c.ids;
  m.client = c.client;
  // Every drive's control telegram in one cycle, the broadcasts, and room to spare.
  m.outbox_capacity = std::max<std::size_t>(128, 2 * c.drives.size() + 16);
  return m;
}

drivecom::SequencerConfig sequencer_config(const DriverConfig& c) {
  drivecom::SequencerConfig s = c.sequencer;
  // A transition shows in the next status telegram (575-CASCY) after the control telegram that
  // caused it (sent within a control period): wait for at least two of each.
  const Duration floor = 2 * c.status_period + c.control_period + 20ms;
  for (auto& t : s.transition_timeout) {
    if (t > Duration::zero()) t = std::max(t, floor);
  }
  return s;
}

}  // namespace

std::string_view to_string(SystemPhase p) {
  switch (p) {
    case SystemPhase::logon: return "System Logon";
    case SystemPhase::started: return "System Start";
    case SystemPhase::stopped: return "System Stop";
  }
  return "?";
}

std::string_view to_string(ReferenceError e) {
  switch (e) {
    case ReferenceError::none: return "ok";
    case ReferenceError::unknown_drive: return "not a configured drive";
    case ReferenceError::not_finite: return "not a number";
    case ReferenceError::above_limit: return "beyond the drive's maximum reference";
    case ReferenceError::does_not_fit: return "does not fit the drive's reference format (492-CACNF)";
  }
  return "?";
}

std::string_view to_string(ParameterError e) {
  switch (e) {
    case ParameterError::none: return "ok";
    case ParameterError::unknown_drive: return "not a configured drive";
    case ParameterError::unknown_parameter: return "not a CDA3000 parameter";
    case ParameterError::read_only: return "read-only";
    case ParameterError::string_parameter: return "a STRING parameter: write it as text";
    case ParameterError::not_a_string: return "not a STRING parameter";
    case ParameterError::value: return "value refused";
    case ParameterError::text_too_long: return "text longer than 99 characters";
    case ParameterError::queue_full: return "the request queue is full";
  }
  return "?";
}

std::string describe(const ParameterSubmission& s, std::uint16_t number, std::uint32_t value) {
  const ParameterInfo* p = find_parameter(number);
  const std::string who = p != nullptr ? display_name(*p) : "parameter " + std::to_string(number);
  if (s.error == ParameterError::value && p != nullptr) return describe_refusal(*p, value, s.value_check);
  return who + ": " + std::string(to_string(s.error));
}

Driver::Driver(const DriverConfig& config)
    : config_(config), settings_(config.drives), master_(master_config(config)) {
  if (config_.control_period <= Duration::zero()) {
    throw std::invalid_argument("CDA3000 driver: control_period must be positive");
  }
  if (config_.status_period <= Duration::zero()) {
    throw std::invalid_argument("CDA3000 driver: status_period must be positive");
  }
  if (!config_.ids.unambiguous()) {
    throw std::invalid_argument("CDA3000 driver: the identifier map is ambiguous (step " +
                                std::to_string(config_.ids.step) + ", addresses 0.." +
                                std::to_string(config_.ids.max_address) + ")");
  }
  slot_of_.assign(static_cast<std::size_t>(config_.ids.max_address) + 1, -1);
  const auto seq = sequencer_config(config_);
  slots_.reserve(settings_.size());
  for (const auto& d : settings_) {
    const std::string who = "CDA3000 driver: drive " + std::to_string(d.address) + ": ";
    if (d.address > config_.ids.max_address) {
      throw std::invalid_argument(who + "address above " + std::to_string(config_.ids.max_address));
    }
    if (slot_of_[d.address] >= 0) throw std::invalid_argument(who + "configured twice");
    if (d.cacnf < 1 || d.cacnf > 4) {
      throw std::invalid_argument(who + "492-CACNF " + std::to_string(d.cacnf) +
                                  " is not a layout of 4.3.2 (1..3 DRIVECOM, 4 EasyDrive)");
    }
    if (!(d.max_reference_hz > 0.0) || !std::isfinite(d.max_reference_hz)) {
      throw std::invalid_argument(who + "max_reference_hz must be positive");
    }
    Slot s{d.address, *process_layout_for_cacnf(d.cacnf), d.max_reference_hz, drivecom::Sequencer(seq)};
    slot_of_[d.address] = static_cast<std::int16_t>(slots_.size());
    slots_.push_back(s);
    master_.set_layout(d.address, s.layout);
  }
}

Driver::Slot* Driver::slot(Address a) {
  if (a >= slot_of_.size() || slot_of_[a] < 0) return nullptr;
  return &slots_[static_cast<std::size_t>(slot_of_[a])];
}

const Driver::Slot* Driver::slot(Address a) const {
  if (a >= slot_of_.size() || slot_of_[a] < 0) return nullptr;
  return &slots_[static_cast<std::size_t>(slot_of_[a])];
}

bool Driver::configured(Address a) const { return slot(a) != nullptr; }

Time Driver::sequencer_time(Time now) const {
  if (phase_ != SystemPhase::started || !cycled_ || now < last_cycle_) return seq_now_;
  return seq_now_ + (now - last_cycle_);
}

void Driver::receive(const CanFrame& f, Time now) {
  master_.receive(f, now);
  const auto c = config_.ids.classify(f.id);
  if (c && c->kind == TelegramKind::status && slot(c->address) != nullptr) fresh_status_ = true;
}

Time Driver::next_deadline() const {
  if (fresh_status_) return Time::min();
  Time t = master_.next_deadline();
  if (phase_ == SystemPhase::logon) return t;
  for (const auto& s : slots_) {
    if (s.sent) t = std::min(t, s.next_send);
  }
  return t;
}

void Driver::cycle(Time now) {
  if (cycled_ && phase_ == SystemPhase::started && now > last_cycle_) seq_now_ += now - last_cycle_;
  last_cycle_ = now;
  cycled_ = true;
  fresh_status_ = false;
  master_.step(now);
  for (auto& s : slots_) {
    const DriveView& v = master_.drive(s.address);
    // D31: a configured drive that logs on after the Start is in System Logon: Start again.
    if (config_.restart_late_logons && phase_ == SystemPhase::started && v.logged_on &&
        v.last_logon > started_at_ + config_.late_logon_grace) {
      master_.system_start();
      started_at_ = now;
    }
    // The drive's state is known from its status telegrams only (sent from System Start on).
    // Before its own first Start or Stop the driver sends no control telegram: the bus may have
    // been started by another master (D30).
    if (!v.has_status || phase_ == SystemPhase::logon) continue;
    // EasyDrive (492-CACNF = 4): the caller's direct-control bits, no sequencer (D26).
    const ibs::Word w = s.layout.mode == WordMode::easydrive ? s.easy_word : s.sequencer.step(v.status.word, seq_now_);
    const bool due = !s.sent || w != s.sent_word || s.reference != s.sent_reference || now >= s.next_send;
    if (!due) continue;
    if (master_.send_control(s.address, {w, s.reference})) {
      s.sent = true;
      s.sent_word = w;
      s.sent_reference = s.reference;
      s.next_send = now + config_.control_period;
    }
  }
}

void Driver::system_start(Time now) {
  master_.system_start();
  if (phase_ != SystemPhase::started) {
    // The sequencers' clock goes on from here (it stood still since the Stop).
    last_cycle_ = now;
    cycled_ = true;
  }
  phase_ = SystemPhase::started;
  started_at_ = now;
  // Presets go out again right after the broadcast, ahead of the next period.
  for (auto& s : slots_) s.next_send = now;
}

void Driver::system_stop(Time now) {
  if (phase_ == SystemPhase::started && cycled_ && now > last_cycle_) seq_now_ += now - last_cycle_;
  last_cycle_ = now;
  master_.system_stop();
  phase_ = SystemPhase::stopped;
}

bool Driver::all_logged_on() const {
  return std::all_of(slots_.begin(), slots_.end(),
                     [this](const Slot& s) { return master_.drive(s.address).logged_on; });
}

bool Driver::set_easydrive(Address a, ibs::Word bits) {
  Slot* s = slot(a);
  if (s == nullptr || s->layout.mode != WordMode::easydrive) return false;
  s->easy_word = bits;
  return true;
}

bool Driver::request(Address a, drivecom::Target t, Time now) {
  Slot* s = slot(a);
  if (s == nullptr || s->layout.mode == WordMode::easydrive) return false;
  s->sequencer.request(t, sequencer_time(now));
  return true;
}

bool Driver::emergency_stop(Address a, Time now) {
  Slot* s = slot(a);
  if (s == nullptr) return false;
  s->sequencer.request_emergency_stop(sequencer_time(now));
  return true;
}

bool Driver::block_power(Address a, Time now) {
  Slot* s = slot(a);
  if (s == nullptr) return false;
  s->sequencer.request_block_power(sequencer_time(now));
  return true;
}

ReferenceError Driver::set_reference_hz(Address a, double hz) {
  Slot* s = slot(a);
  if (s == nullptr) return ReferenceError::unknown_drive;
  if (!std::isfinite(hz)) return ReferenceError::not_finite;
  if (std::fabs(hz) > s->max_reference_hz) return ReferenceError::above_limit;
  const auto w = wire_from_hz(s->layout.reference, hz);
  if (!w) return ReferenceError::does_not_fit;
  s->reference = *w;
  return ReferenceError::none;
}

DriveReport Driver::drive(Address a) const {
  DriveReport r;
  r.address = a;
  if (a > config_.ids.max_address) return r;
  const DriveView& v = master_.drive(a);
  r.logged_on = v.logged_on;
  r.has_status = v.has_status;
  r.status_word = v.status.word;
  r.errors = v.errors;
  const Slot* own = slot(a);
  r.easydrive = own != nullptr && own->layout.mode == WordMode::easydrive;
  if (v.has_status) {
    if (!r.easydrive) r.state = drivecom::decode_state(v.status.word);
    r.actual_hz = hz_from_wire(v.layout.actual, v.status.actual);
  }
  if (const Slot* s = slot(a)) {
    r.reference_hz = hz_from_wire(s->layout.reference, s->reference);
    r.sequencer = s->sequencer.report();
  }
  return r;
}

const drivecom::Report* Driver::sequencer_report(Address a) const {
  const Slot* s = slot(a);
  return s != nullptr ? &s->sequencer.report() : nullptr;
}

ParameterSubmission Driver::submit(Address a, const Request& r) {
  ParameterSubmission out;
  const auto sub = master_.parameters().submit(r);
  if (!sub) {
    out.error = sub.error == SubmitError::text_too_long ? ParameterError::text_too_long
                : sub.error == SubmitError::invalid_address ? ParameterError::unknown_drive
                                                            : ParameterError::queue_full;
    return out;
  }
  (void)a;
  out.id = sub.id;
  return out;
}

ParameterSubmission Driver::read(Address a, std::uint16_t number) {
  if (slot(a) == nullptr) return {0, ParameterError::unknown_drive};
  const ParameterInfo* p = find_parameter(number);
  if (p == nullptr) return {0, ParameterError::unknown_parameter};
  return submit(a, p->is_string() ? canlust::read_string(a, number) : canlust::read(a, number));
}

ParameterSubmission Driver::write(Address a, std::uint16_t number, std::uint32_t value) {
  if (slot(a) == nullptr) return {0, ParameterError::unknown_drive};
  const ParameterInfo* p = find_parameter(number);
  if (p == nullptr) return {0, ParameterError::unknown_parameter};
  if (p->is_string()) return {0, ParameterError::string_parameter};
  if (!p->writable()) return {0, ParameterError::read_only};
  const ValueCheck c = check_value(*p, value);
  if (c != ValueCheck::ok) return {0, ParameterError::value, c};
  Request r = canlust::write(a, number, value);
  // 150-SAVE and 04-PROG answer when their work is done (4.3.3: a few hundred ms; p. 13).
  if (number == kSave || number == kProg) r.timeout = std::max<Duration>(config_.client.timeout, 2s);
  return submit(a, r);
}

ParameterSubmission Driver::write_text(Address a, std::uint16_t number, std::string_view text) {
  if (slot(a) == nullptr) return {0, ParameterError::unknown_drive};
  const ParameterInfo* p = find_parameter(number);
  if (p == nullptr) return {0, ParameterError::unknown_parameter};
  if (!p->is_string()) return {0, ParameterError::not_a_string};
  if (!p->writable()) return {0, ParameterError::read_only};
  if (text.size() > kMaxStringChars) return {0, ParameterError::text_too_long};
  return submit(a, canlust::write_string(a, number, text));
}

ParameterSubmission Driver::describe(Address a, std::uint16_t number, std::uint8_t item) {
  if (slot(a) == nullptr) return {0, ParameterError::unknown_drive};
  if (find_parameter(number) == nullptr) return {0, ParameterError::unknown_parameter};
  return submit(a, canlust::describe(a, number, item));
}

}  // namespace ibs::devices::cda3000
