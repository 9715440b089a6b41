#include "ibs/devices/dfs1/events.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "ibs/base/time_text.hpp"
#include "ibs/devices/dfs1/bus_face.hpp"
#include "ibs/devices/dfs1/controller.hpp"
#include "ibs/devices/dfs1/status.hpp"

namespace ibs::devices::dfs1 {

namespace {

// The status list of command 81 (public notes, "Status (81)"): ST1 bit 7 down, then ST2's uP fault.
constexpr std::array<FaultCauseInfo, kFaultCauses> kCauses = {{
    {FaultCause::bus_not_charged, "Bus not charged", "bus-not-charged", kSt1BusNotCharged, 0},
    {FaultCause::ioc, "IOC", "IOC", kSt1Ioc, 0},
    {FaultCause::stall, "Stall", "stall", kSt1Stall, 0},
    {FaultCause::i2t, "I2t", "I2t", kSt1I2t, 0},
    {FaultCause::heatsink_overtemp, "Heatsink OT", "heatsink-overtemp", kSt1HeatsinkOvertemp, 0},
    {FaultCause::commutation, "Commutation", "commutation", kSt1Commutation, 0},
    {FaultCause::overvolt, "Overvolt", "overvolt", kSt1Overvolt, 0},
    {FaultCause::undervolt, "Undervolt", "undervolt", kSt1Undervolt, 0},
    {FaultCause::micro_fault, "uP fault", "uP-fault", 0, kSt2MicroFault},
}};

char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

bool same_letters(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

std::string hex2(unsigned v) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  return {kHex[(v >> 4) & 0xF], kHex[v & 0xF]};
}

std::string names(const std::vector<std::string_view>& v) {
  std::string s;
  for (const auto& x : v) s += " " + std::string(x);
  return s.empty() ? " none" : s;
}

std::string quoted(std::string_view s) { return "\"" + std::string(s) + "\""; }

std::string shown(const ControlValue& v) {
  switch (v.type) {
    case ControlValue::Type::string:
      return quoted(v.text);
    case ControlValue::Type::number: {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.15g", v.number);
      return buf;
    }
    case ControlValue::Type::other:
      break;
  }
  return v.text;
}

std::string cause_list() {
  std::string s;
  for (const FaultCauseInfo& f : kCauses) s += (s.empty() ? "" : ", ") + quoted(f.seed_name);
  return s;
}

constexpr std::string_view kKeys =
    "device, fault, cause, duration, mains, input, level, load";
constexpr std::string_view kInputForms =
    "1..7 (digital inputs #1-#7, as a number or a string), \"DI1\"..\"DI7\" or \"E-stop\" (input 1)";

// A whole number in [lo, hi] from a number value; nullopt otherwise.
std::optional<long long> whole(const ControlValue& v, long long lo, long long hi) {
  if (v.type != ControlValue::Type::number) return std::nullopt;
  if (v.number != std::floor(v.number) || v.number < static_cast<double>(lo) ||
      v.number > static_cast<double>(hi)) {
    return std::nullopt;
  }
  return static_cast<long long>(v.number);
}

std::optional<long long> whole_text(std::string_view t, long long lo, long long hi) {
  if (t.empty() || t.size() > 6) return std::nullopt;
  long long n = 0;
  for (char c : t) {
    if (c < '0' || c > '9') return std::nullopt;
    n = n * 10 + (c - '0');
  }
  if (n < lo || n > hi) return std::nullopt;
  return n;
}

std::optional<std::uint8_t> input_channel(const ControlValue& v) {
  if (v.type == ControlValue::Type::number) {
    if (auto n = whole(v, 1, kDigitalInputs)) return static_cast<std::uint8_t>(*n);
    return std::nullopt;
  }
  if (v.type != ControlValue::Type::string) return std::nullopt;
  std::string_view t = v.text;
  if (same_letters(t, "E-stop") || same_letters(t, "estop")) return kEstopInput;
  if (t.size() >= 2 && same_letters(t.substr(0, 2), "DI")) t.remove_prefix(2);
  if (auto n = whole_text(t, 1, kDigitalInputs)) return static_cast<std::uint8_t>(*n);
  return std::nullopt;
}

}  // namespace

const std::array<FaultCauseInfo, kFaultCauses>& fault_causes() { return kCauses; }

const FaultCauseInfo& info(FaultCause cause) { return kCauses[static_cast<std::size_t>(cause)]; }

std::optional<FaultCause> find_fault_cause(std::string_view name) {
  for (const FaultCauseInfo& f : kCauses) {
    if (same_letters(name, f.seed_name) || same_letters(name, f.flag_name)) return f.cause;
  }
  return std::nullopt;
}

std::string to_string(const Event& e) {
  switch (e.kind) {
    case Event::Kind::fault: {
      std::string s = "fault " + std::string(info(e.cause).seed_name);
      s += e.duration > Duration::zero() ? ", its cause lasting " + format_time(e.duration)
                                         : ", its cause gone at once";
      return s;
    }
    case Event::Kind::power_cycle:
      return "power cycle";
    case Event::Kind::mains:
      return e.on ? "mains on" : "mains off";
    case Event::Kind::input:
      return "input " + std::to_string(e.input) + (e.input == kEstopInput ? " (E-stop) " : " ") +
             (e.on ? "high" : "low");
    case Event::Kind::load:
      return "load " + std::to_string(e.load_percent) + " %";
  }
  return "event";
}

std::string to_string(const EventReport& r) {
  std::string s = to_string(r.event);
  switch (r.event.kind) {
    case Event::Kind::fault:
      s += r.latched ? "; the motor coasts, the fault is latched until the E-stop input opens with "
                       "the cause gone, or a power cycle"
                     : "; reset at once: the E-stop input is open and the cause gone";
      break;
    case Event::Kind::power_cycle:
      s += "; restarted as at power-on, parameters kept";
      if (r.latched) s += ", a cause still present tripped it again";
      break;
    case Event::Kind::mains:
      s += r.event.on ? "; the bus is charged, the motor waits for a start"
                      : "; the bus is not charged, the motor coasts";
      break;
    case Event::Kind::input:
      if (r.event.input == kEstopInput && !r.event.on) s += "; the motor stops";
      break;
    case Event::Kind::load:
      break;
  }
  s += "; status ST2 " + hex2(r.st2) + "H" + names(st2_flags(r.st2)) + ", ST1 " + hex2(r.st1) + "H" +
       names(st1_flags(r.st1)) + ", load " + std::to_string(r.load_percent) + " %";
  return s;
}

ParsedControl parse_event(const ControlFields& fields) {
  ParsedControl out;
  const auto fail = [&out](std::string what) {
    out.event.reset();
    out.error = std::move(what);
    return out;
  };
  const ControlValue* device = nullptr;
  const ControlValue* fault = nullptr;
  const ControlValue* cause = nullptr;
  const ControlValue* duration = nullptr;
  const ControlValue* mains = nullptr;
  const ControlValue* input = nullptr;
  const ControlValue* level = nullptr;
  const ControlValue* load = nullptr;
  std::vector<std::string_view> events;
  for (const auto& [key, value] : fields) {
    const ControlValue** slot = nullptr;
    if (key == "device") slot = &device;
    if (key == "fault") slot = &fault;
    if (key == "cause") slot = &cause;
    if (key == "duration") slot = &duration;
    if (key == "mains") slot = &mains;
    if (key == "input") slot = &input;
    if (key == "level") slot = &level;
    if (key == "load") slot = &load;
    if (slot == nullptr) return fail("unknown key " + quoted(key) + "; a DFS-1 control line takes " + std::string(kKeys));
    if (*slot != nullptr) return fail("key " + quoted(key) + " given twice");
    *slot = &value;
    if (key == "fault" || key == "mains" || key == "input" || key == "load") events.push_back(key);
  }
  if (events.empty()) {
    return fail("no event: give one of \"fault\", \"mains\", \"input\", \"load\"");
  }
  if (events.size() > 1) {
    return fail(quoted(events[0]) + " and " + quoted(events[1]) + " in one line: give one event per line");
  }

  ControlEvent ev;
  if (device != nullptr) {
    const std::string forms = "a unit ID 1..255 or \"" + std::string(kDriveName) + "@UID\"";
    if (device->type == ControlValue::Type::number) {
      const auto n = whole(*device, 1, 255);
      if (!n) return fail("\"device\": " + shown(*device) + " is no unit ID; give " + forms);
      ev.uid = static_cast<std::uint8_t>(*n);
    } else if (device->type == ControlValue::Type::string) {
      const std::string_view t = device->text;
      const auto at = t.find('@');
      const auto n = at == std::string_view::npos ? std::nullopt : whole_text(t.substr(at + 1), 1, 255);
      if (at == std::string_view::npos || !same_letters(t.substr(0, at), kDriveName) || !n) {
        return fail("\"device\": " + shown(*device) + " names no DFS-1 controller; give " + forms);
      }
      ev.uid = static_cast<std::uint8_t>(*n);
    } else {
      return fail("\"device\": expected " + forms + ", got " + device->text);
    }
  }

  const auto only_with = [&](const ControlValue* v, std::string_view key, std::string_view with) {
    return v == nullptr ? std::string{} : quoted(key) + " belongs to " + std::string(with) + " only";
  };
  const auto string_value = [&](const ControlValue* v, std::string_view key, std::string_view allowed,
                                std::string& error) -> std::optional<std::string_view> {
    if (v->type != ControlValue::Type::string) {
      error = quoted(key) + ": expected a string (" + std::string(allowed) + "), got " +
              (v->type == ControlValue::Type::number ? "the number " + shown(*v) : v->text);
      return std::nullopt;
    }
    return std::string_view(v->text);
  };

  std::string error;
  if (fault != nullptr) {
    if (level != nullptr) return fail(only_with(level, "level", "an input event"));
    const auto what = string_value(fault, "fault", "\"device\" or \"power-cycle\"", error);
    if (!what) return fail(error);
    if (*what == "power-cycle") {
      if (cause != nullptr || duration != nullptr) {
        return fail(std::string(cause != nullptr ? "\"cause\"" : "\"duration\"") +
                    " belongs to \"fault\": \"device\"; a power cycle takes none");
      }
      ev.event = Event::power_cycle();
    } else if (*what == "device") {
      if (cause == nullptr) return fail("\"fault\": \"device\" needs \"cause\", one of " + cause_list());
      const auto name = string_value(cause, "cause", "a DFS-1 fault", error);
      if (!name) return fail(error);
      const auto c = find_fault_cause(*name);
      if (!c) {
        return fail("\"cause\": " + shown(*cause) + " is no DFS-1 fault; allowed: " + cause_list() +
                    " (or the names `ibs dfs1 status` prints)");
      }
      Duration d{};
      if (duration != nullptr) {
        const auto text = string_value(duration, "duration", "a time with its unit, e.g. \"0.5 s\"", error);
        if (!text) return fail(error);
        try {
          d = parse_time(*text);
        } catch (const std::invalid_argument& e) {
          return fail("\"duration\": " + shown(*duration) + ": " + e.what());
        }
      }
      ev.event = Event::fault(*c, d);
    } else {
      return fail("\"fault\": " + shown(*fault) + " is no DFS-1 fault event; allowed: \"device\", \"power-cycle\"");
    }
    out.event = ev;
    return out;
  }
  for (const auto& e : {only_with(cause, "cause", "\"fault\": \"device\""),
                        only_with(duration, "duration", "\"fault\": \"device\"")}) {
    if (!e.empty()) return fail(e);
  }
  if (mains != nullptr) {
    if (level != nullptr) return fail(only_with(level, "level", "an input event"));
    const auto what = string_value(mains, "mains", "\"off\" or \"on\"", error);
    if (!what) return fail(error);
    if (*what != "off" && *what != "on") return fail("\"mains\": " + shown(*mains) + "; allowed: \"off\", \"on\"");
    ev.event = Event::mains(*what == "on");
    out.event = ev;
    return out;
  }
  if (input != nullptr) {
    const auto channel = input_channel(*input);
    if (!channel) {
      if (input->type == ControlValue::Type::other) return fail("\"input\": expected " + std::string(kInputForms) + ", got " + input->text);
      return fail("\"input\": " + shown(*input) + " is no DFS-1 digital input; allowed: " + std::string(kInputForms));
    }
    if (level == nullptr) return fail("\"input\" needs \"level\": \"high\" or \"low\"");
    const auto what = string_value(level, "level", "\"high\" or \"low\"", error);
    if (!what) return fail(error);
    if (*what != "high" && *what != "low") return fail("\"level\": " + shown(*level) + "; allowed: \"high\", \"low\"");
    ev.event = Event::input_level(*channel, *what == "high");
    out.event = ev;
    return out;
  }
  // load
  if (level != nullptr) return fail(only_with(level, "level", "an input event"));
  const auto percent = whole(*load, 0, kMaxLoadPercent);
  if (!percent) {
    const std::string allowed = "a whole number of percent of the drive's rating, 0.." + std::to_string(kMaxLoadPercent);
    if (load->type == ControlValue::Type::number) return fail("\"load\": " + shown(*load) + "; allowed: " + allowed);
    return fail("\"load\": expected " + allowed + ", got " +
                (load->type == ControlValue::Type::string ? "the string " + shown(*load) : load->text));
  }
  ev.event = Event::load(static_cast<std::uint32_t>(*percent));
  out.event = ev;
  return out;
}

}  // namespace ibs::devices::dfs1
