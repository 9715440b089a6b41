// The CDA3000's CANLust face: the wing's Cda3000 and Driver behind the registry's drive-neutral
// CanlustDrive and CanlustMaster (ibs/devices/canlust_face.hpp), and its parameter table as the
// face looks parameters up. The frame path forwards to the wing's own allocation-free calls.
#include "ibs/devices/cda3000/bus_face.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "ibs/devices/cda3000/description.hpp"
#include "ibs/devices/cda3000/descriptor.hpp"
#include "ibs/devices/cda3000/device.hpp"
#include "ibs/devices/cda3000/driver.hpp"
#include "ibs/devices/cda3000/parameters.hpp"

namespace ibs::devices::cda3000 {

namespace {

// A fault's cause as table 5.9 writes it (6.2): "E-OTI", "OTI" or the number "8".
std::optional<std::uint8_t> find_cause(std::string_view text) {
  std::string up(text);
  for (char& c : up) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const auto& e : canlust::kErrorTable) {
    if (up == e.name || "E-" + up == e.name || up == std::to_string(e.number)) return e.number;
  }
  return std::nullopt;
}

std::string causes() {
  std::string list;
  for (const auto& e : canlust::kErrorTable) {
    list += (list.empty() ? "" : ", ") + std::to_string(e.number) + " " + std::string(e.name);
  }
  list += "; its warnings (6.3) are";
  for (const auto& w : kWarnings) {
    char b[48];
    std::snprintf(b, sizeof b, " %04XH %.*s,", static_cast<unsigned>(w.mask), static_cast<int>(w.name.size()),
                  w.name.data());
    list += b;
  }
  list.pop_back();
  return list;
}

std::string check(const CanlustEvent& e) {
  using K = CanlustEvent::Kind;
  if (e.kind == K::fault && !find_cause(e.cause) && find_warning(e.cause) == nullptr) {
    return "cause '" + e.cause + "': the CDA3000's errors (CANLust manual, table 5.9) are " + causes();
  }
  if (e.kind == K::input && !find_input(e.input)) {
    return "input '" + e.input + "': the CDA3000's terminals in the CANLust manual are ENPO (X2-8) and ISD00 (X2-9)";
  }
  if (e.kind == K::load && !(std::fabs(e.load) <= kMaxLoadPercent)) {
    return "load " + std::to_string(e.load) + " %: the CDA3000 takes -300 .. 300 % of the rated torque";
  }
  return {};
}

class EmulatedDrive final : public CanlustDrive {
 public:
  explicit EmulatedDrive(const DeviceConfig& c) : drive_(c) {}

  void power_on(Time now) override { drive_.power_on(now); }
  void power_off() override { drive_.power_off(); }
  void receive(const canlust::CanFrame& f, Time now) override { drive_.receive(f, now); }
  void step(Time now) override { drive_.step(now); }
  std::optional<canlust::CanFrame> take_frame() override { return drive_.take_frame(); }
  [[nodiscard]] Time next_deadline() const override { return drive_.next_deadline(); }

  [[nodiscard]] canlust::Address address() const override { return drive_.address(); }
  [[nodiscard]] canlust::SystemState system_state() const override { return drive_.system_state(); }
  [[nodiscard]] drivecom::State state() const override { return drive_.state(); }
  [[nodiscard]] double actual_hz(Time now) const override { return drive_.actual_hz(now); }
  [[nodiscard]] double reference_hz() const override { return drive_.reference_hz(); }
  [[nodiscard]] std::uint32_t watchdog_trips() const override { return drive_.counters().watchdog_trips; }
  [[nodiscard]] std::optional<std::uint32_t> value(std::uint16_t number) const override {
    return drive_.value(number);
  }

  // The outcome in words; the caller names the event ("left: device fault E-OTI: ...").
  CanlustEventResult apply(const CanlustEvent& e, Time now) override {
    using K = CanlustEvent::Kind;
    if (const std::string why = check(e); !why.empty()) return {false, why};
    switch (e.kind) {
      case K::fault: {
        if (const WarningInfo* w = find_warning(e.cause)) {
          // 6.3: a warning, reported on the CAN (status bit 7) when 576-CAWMK selects it.
          if (!drive_.raise_warning(w->mask, now)) return {false, "the drive is off (mains)"};
          char b[16];
          std::snprintf(b, sizeof b, "%04XH ", static_cast<unsigned>(w->mask));
          const bool shown = (*drive_.value(kCawmk) & w->mask) != 0;
          return {true, b + std::string(w->name) + " (" + std::string(w->text) + "), warning, " +
                            (shown ? "status bit 7" : "not reported on the CAN (576-CAWMK)")};
        }
        const std::uint8_t n = *find_cause(e.cause);
        if (!drive_.inject_fault(n, now)) return {false, "the drive is off (mains)"};
        const auto info = canlust::find_error(n);
        // 6.1: the response is the error's parameter; WRN leaves the state as it was.
        const auto r = static_cast<canlust::ErrorReaction>(*drive_.value(*response_parameter(n)));
        const std::string what = r == canlust::ErrorReaction::warning
                                     ? "WRN, status bit 7"
                                     : std::string(drivecom::to_string(drive_.state()));
        return {true, std::to_string(n) + " " + std::string(info->name) + " (" + std::string(info->cause) + "), " +
                          what + ", error telegram sent"};
      }
      case K::mains_off:
        drive_.power_off();
        return {true, "off"};
      case K::mains_on:
        if (drive_.powered()) return {true, "already on"};
        drive_.power_on(now);
        return {true, "on, System Logon"};
      case K::power_cycle:
        drive_.power_off();
        drive_.power_on(now);
        return {true, "restarted from its stored settings, System Logon"};
      case K::load: {
        drive_.set_load(e.load, now);
        char b[96];
        std::snprintf(b, sizeof b, "set: the motor slips %.2f Hz below the output frequency",
                      std::fabs(e.load) / 100.0 * drive_.config().plant.rated_slip_hz);
        return {true, b};
      }
      case K::input: {
        const Input i = *find_input(e.input);
        drive_.set_input(i, e.level, now);
        if (i == Input::isd00) return {true, "kept (CANLust manual gives the terminal no function)"};
        return {true, e.level ? "the power stage may be enabled"
                              : "the power stage is blocked, " + std::string(drivecom::to_string(drive_.state()))};
      }
    }
    return {false, "unknown event"};
  }

 private:
  Cda3000 drive_;
};

std::unique_ptr<CanlustDrive> make(const CanlustFaceOptions& o) {
  DeviceConfig c;
  c.ids = o.ids;
  if (o.factory) {
    c.connector_address = o.address;
  } else {
    c.saved = commissioned_for_bus(o.address, o.cacnf);
  }
  // 6.1 / CAN-E16: the watchdog's reaction is the drive's stored 525-ROP2.
  if (o.watchdog_reaction != static_cast<canlust::ErrorReaction>(kResponseDefault) || !o.factory) {
    c.saved.push_back({kRop2, static_cast<std::uint32_t>(o.watchdog_reaction)});
  }
  // 4.3.1: the bus settings are parameters; the constructor checks them like a write.
  if (o.bitrate) c.saved.push_back({kClbdr, *o.bitrate / 1000});  // 489-CLBDR in kBaud
  if (o.watchdog_ms) c.saved.push_back({kCawdg, *o.watchdog_ms});
  if (o.status_ms) c.saved.push_back({kCascy, *o.status_ms});
  return std::make_unique<EmulatedDrive>(c);
}

class Master final : public CanlustMaster {
 public:
  explicit Master(const DriverConfig& c) : driver_(c) {}

  void receive(const canlust::CanFrame& f, Time now) override { driver_.receive(f, now); }
  void cycle(Time now) override { driver_.cycle(now); }
  std::optional<canlust::CanFrame> take_frame() override { return driver_.take_frame(); }
  [[nodiscard]] Time next_deadline() const override { return driver_.next_deadline(); }
  std::optional<canlust::ErrorEvent> take_error() override { return driver_.take_error(); }

  void system_start(Time now) override { driver_.system_start(now); }
  void system_stop(Time now) override { driver_.system_stop(now); }
  bool request(canlust::Address a, drivecom::Target t, Time now) override { return driver_.request(a, t, now); }
  bool set_easydrive(canlust::Address a, Word bits) override { return driver_.set_easydrive(a, bits); }
  std::optional<std::string_view> set_reference_hz(canlust::Address a, double hz) override {
    const ReferenceError e = driver_.set_reference_hz(a, hz);
    if (e == ReferenceError::none) return std::nullopt;
    return to_string(e);
  }

  CanlustSubmission read(canlust::Address a, std::uint16_t number) override {
    return submitted(driver_.read(a, number), number);
  }
  CanlustSubmission write(canlust::Address a, std::uint16_t number, std::string_view value) override {
    const ParameterInfo* p = find_parameter(number);
    if (p != nullptr && p->is_string()) return submitted(driver_.write_text(a, number, value), number);
    if (p == nullptr) return submitted(driver_.write(a, number, 0), number);  // refused: unknown_parameter
    const ParsedValue v = parse_value(*p, value);
    if (!v.wire) return {0, v.error};
    return submitted(driver_.write(a, number, *v.wire), number);
  }
  [[nodiscard]] canlust::Poll poll(canlust::RequestId id) const override { return driver_.parameters().poll(id); }

  [[nodiscard]] std::optional<std::string> status_text(canlust::Address a) const override {
    const DriveReport seen = driver_.drive(a);
    if (!seen.has_status) return std::nullopt;
    return seen.easydrive ? "EasyDrive " + explain_easydrive_status(seen.status_word)
                          : explain_status_word(seen.status_word);
  }

 private:
  static CanlustSubmission submitted(const ParameterSubmission& s, std::uint16_t number) {
    if (!s) return {0, describe(s, number)};
    return {s.id, {}};
  }

  Driver driver_;
};

std::unique_ptr<CanlustMaster> make_master(const CanlustMasterOptions& o) {
  DriverConfig c;
  c.ids = o.ids;
  c.control_period = o.control_period;
  c.status_period = o.status_period;
  for (const CanlustMasterDrive& d : o.drives) c.drives.push_back({d.address, d.cacnf, d.max_reference_hz});
  return std::make_unique<Master>(c);
}

std::optional<CanlustParameter> as_face(const ParameterInfo* p) {
  if (p == nullptr) return std::nullopt;
  return CanlustParameter{p->number, display_name(*p), p->writable(), p->is_string(), p->type, card_writeable(*p)};
}

std::optional<CanlustParameter> find_by_text(std::string_view text) { return as_face(find_parameter(text)); }
std::optional<CanlustParameter> find_by_number(std::uint16_t number) { return as_face(find_parameter(number)); }

CanlustValue parse(std::uint16_t number, std::string_view text) {
  const ParameterInfo* p = find_parameter(number);
  if (p == nullptr) return {std::nullopt, "parameter " + std::to_string(number) + " is not in the CDA3000's table"};
  ParsedValue v = parse_value(*p, text);
  return {v.wire, std::move(v.error)};
}

std::string format(std::uint16_t number, std::uint32_t wire) {
  const ParameterInfo* p = find_parameter(number);
  return p != nullptr ? format_value(*p, wire) : std::to_string(wire);
}

std::int64_t number(std::uint16_t n, std::uint32_t wire) {
  const ParameterInfo* p = find_parameter(n);
  return p != nullptr ? number_of(*p, wire) : static_cast<std::int64_t>(wire);
}

// 4.3.3 / 1.x: SAVE backs the settings up in flash and PROG resets them to the factory's before
// the drive answers, longer than the client's default for a parameter request.
std::optional<Duration> write_timeout(std::uint16_t n) {
  if (n == kSave || n == kProg) return Duration(2s);
  return std::nullopt;
}

// D29 (docs/canlust.md "Descriptions"): the items this drive answers.
std::optional<CanlustDescription> description(std::span<const std::uint32_t> items) {
  const std::optional<Description> d = read_description(items);
  if (!d) return std::nullopt;
  return CanlustDescription{d->type,       d->min,   d->max,      d->factory, d->writable(), d->flash(),
                            d->after_mains_reset(), d->short_name, d->unit};
}

std::string status_word(Word status) { return explain_status_word(status); }

double hz(canlust::ValueWidth w, std::int32_t raw) { return hz_from_wire(w, raw); }

CanlustFrameText frame_text(const canlust::CanFrame& f, const canlust::IdentifierMap& ids,
                            const canlust::ProcessLayout& layout) {
  FrameExplanation e = explain_frame(f, ids, layout);
  return {e.id, std::move(e.text)};
}

// D39: 80-SLOAD -1 opens, -2 closes (the answer after the check, 200 ms), 0 drops.
constexpr canlust::DownloadHandshake kDownload{kSload, kSloadStart, kSloadEnd, kSloadCancel, 2s};

}  // namespace

const CanlustFace& bus_face() {
  static const CanlustFace face{"CDA3000", &make,   &make_master,   &find_by_text, &find_by_number, &parse,
                                &format,   &check,  "CDA",          &number,       &write_timeout,  &description,
                                &status_word,       &hz,            &frame_text,    &kDownload};
  return face;
}

}  // namespace ibs::devices::cda3000
