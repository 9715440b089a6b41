// Writing scenarios: one list of fields per part, rendered as TOML or JSON.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "ibs/sim/scenario.hpp"
#include "scenario_internal.hpp"

namespace ibs::sim {

namespace detail {

namespace {

OutField text(std::string key, std::string_view value) {
  return {std::move(key), quote(value), {}};
}
OutField time(std::string key, Duration d) {
  return text(std::move(key), format_time(d));
}
OutField integer(std::string key, std::int64_t v) {
  return {std::move(key), std::to_string(v), {}};
}
OutField number(std::string key, double v) {
  return {std::move(key), format_number(v), {}};
}
OutField yes(std::string key) {
  return {std::move(key), "true", {}};
}

// A drive's own setting, as its declaration's type writes it.
OutField setting(const devices::SettingSpec& spec, std::int64_t v) {
  const std::string key(spec.name);
  switch (spec.kind) {
    case devices::SettingKind::integer: return integer(key, v);
    case devices::SettingKind::boolean: return {key, v != 0 ? "true" : "false", {}};
    case devices::SettingKind::duration: return time(key, Duration{v});
    case devices::SettingKind::choice:
      if (v >= 0 && static_cast<std::size_t>(v) < spec.choices.size()) {
        return text(key, spec.choices[static_cast<std::size_t>(v)]);
      }
      return integer(key, v);
  }
  return integer(key, v);
}

// A raw value: an integer where it is one (every valid write value is).
OutField raw(std::string key, double v) {
  if (std::trunc(v) == v && std::abs(v) < 9007199254740992.0) {
    return integer(std::move(key), static_cast<std::int64_t>(v));
  }
  return number(std::move(key), v);
}

}  // namespace

std::vector<OutField> top_fields(const Scenario& s) {
  return {text("name", s.name), time("duration", s.duration)};
}

std::vector<OutField> bus_fields(const BusSettings& b) {
  std::vector<OutField> f;
  if (b.cycle_time) f.push_back(time("cycle_time", *b.cycle_time));
  f.push_back(text("baud", b.baud_2mbit ? "2M" : "500k"));
  f.push_back(time("software_time", b.software_time));
  f.push_back(integer("recovery_cycles", b.recovery_cycles));
  return f;
}

std::vector<OutField> device_fields(const DeviceConfig& d) {
  std::vector<OutField> f{text("name", d.name), text("type", d.kind)};
  // The kind's own settings (devices/settings.hpp), in its declarations' order: those that place
  // the device on the ring always (even at their default) and next to its bus side, the others
  // when given, after the generic ones.
  const devices::DriveKind* k = devices::find_drive_kind(d.kind);
  const auto own = [&](bool ring) {
    if (k == nullptr) return;
    for (const devices::SettingSpec& spec : (*k)->settings()) {
      if (spec.places_device != ring) continue;
      if (ring || d.settings.given(spec.name)) f.push_back(setting(spec, d.settings.value(spec)));
    }
  };
  own(true);
  f.push_back(text("bus", bus_text(d.bus)));
  if (d.phase != Duration::zero()) f.push_back(time("phase", d.phase));
  if (d.jitter != Duration::zero()) f.push_back(time("jitter", d.jitter));
  f.push_back({"initialised", d.initialised ? "true" : "false", {}});
  if (d.watchdog_ms) f.push_back(integer("watchdog_ms", *d.watchdog_ms));
  if (d.watchdog_reaction) f.push_back(integer("watchdog_reaction", *d.watchdog_reaction));
  if (d.lustbus) f.push_back(integer("lustbus", *d.lustbus));
  own(false);
  return f;
}

std::vector<OutField> entry_fields(const TimelineEntry& e) {
  std::vector<OutField> f{time("at", e.at)};
  if (!e.device.empty()) f.push_back(text("device", e.device));
  switch (e.action) {
    case Action::state:
      f.push_back(text("state", e.value));
      break;
    case Action::wait_state:
      f.push_back(text("wait_state", e.value));
      if (e.duration != Duration::zero()) f.push_back(time("timeout", e.duration));
      break;
    case Action::emergency_stop:
      f.push_back(yes("emergency_stop"));
      break;
    case Action::block_power:
      f.push_back(yes("block_power"));
      break;
    case Action::master_restart:
      f.push_back(yes("master_restart"));
      break;
    case Action::speed:
      f.push_back(number("speed", e.number));
      break;
    case Action::frequency:
      f.push_back(number("frequency", e.number));
      break;
    case Action::read:
      f.push_back(integer("read", e.parameter));
      break;
    case Action::describe:
      f.push_back(integer("describe", e.parameter));
      break;
    case Action::write:
      f.push_back({"write", {}, {integer("parameter", e.parameter), raw("value", e.number)}});
      break;
    case Action::fault_corrupt:
      f.push_back(text("fault", fault_name(e.action)));
      if (e.count != 1) f.push_back(integer("count", e.count));
      break;
    case Action::fault_power_cycle:
      f.push_back(text("fault", fault_name(e.action)));
      break;
    case Action::fault_device:
      f.push_back(text("fault", fault_name(e.action)));
      if (e.duration != Duration::zero()) f.push_back(time("duration", e.duration));
      if (!e.cause.empty()) f.push_back(text("cause", e.cause));
      break;
    case Action::mains:
      f.push_back(text("mains", e.value));
      break;
    case Action::load:
      f.push_back(number("load", e.number));
      break;
    case Action::input:
      f.push_back(text("input", e.value));
      f.push_back(text("level", e.level ? "high" : "low"));
      break;
    case Action::smartcard:
      f.push_back(text("smartcard", e.value));
      f.push_back(time("duration", e.duration));
      break;
    case Action::option_card:
      f.push_back(text("option_card", e.value));
      break;
    case Action::fault_lost:
      f.push_back(text("fault", fault_name(e.action)));
      f.push_back(time("duration", e.duration));
      break;
  }
  return f;
}

std::vector<OutField> line_fields(const ServedLine& l) {
  std::vector<OutField> f;
  if (l.pty) f.push_back(yes("pty"));
  if (!l.port.empty()) f.push_back(text("port", l.port));
  f.push_back(integer("baud", l.baud));
  return f;
}

std::vector<OutField> controller_fields(const LineController& c) {
  return {text("name", c.name), integer("uid", c.uid)};
}

std::vector<OutField> random_fields(const RandomFaults& r) {
  if (r == RandomFaults{}) return {};
  return {integer("seed", static_cast<std::int64_t>(r.seed)),
          number("corrupt_per_s", r.corrupt_per_s),
          number("power_cycle_per_s", r.power_cycle_per_s),
          number("device_fault_per_s", r.device_fault_per_s),
          number("lost_per_s", r.lost_per_s),
          number("master_restart_per_s", r.master_restart_per_s)};
}

}  // namespace detail

namespace {

using detail::OutField;

// key = value lines; inline tables as { a = 1, b = 2 }.
std::string toml_value(const OutField& f) {
  if (f.table.empty()) return f.scalar;
  std::string out = "{ ";
  for (std::size_t i = 0; i < f.table.size(); ++i) {
    out += (i == 0 ? "" : ", ") + f.table[i].key + " = " + toml_value(f.table[i]);
  }
  return out + " }";
}

std::string toml_lines(const std::vector<OutField>& fields) {
  std::string out;
  for (const OutField& f : fields) out += f.key + " = " + toml_value(f) + "\n";
  return out;
}

std::string json_object(const std::vector<OutField>& fields) {
  std::string out = "{";
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const OutField& f = fields[i];
    out += (i == 0 ? "" : ", ") + detail::quote(f.key) + ": " +
           (f.table.empty() ? f.scalar : json_object(f.table));
  }
  return out + "}";
}

template <typename T, typename F>
std::string json_array(const std::vector<T>& items, F&& fields) {
  if (items.empty()) return "[]";
  std::string out = "[\n";
  for (std::size_t i = 0; i < items.size(); ++i) {
    out += "    " + json_object(fields(items[i])) + (i + 1 < items.size() ? ",\n" : "\n");
  }
  return out + "  ]";
}

}  // namespace

std::string write_scenario_toml(const Scenario& s) {
  std::string out = "# ibs scenario (docs/scenarios.md)\n";
  out += toml_lines(detail::top_fields(s));
  out += "\n[bus]\n" + toml_lines(detail::bus_fields(s.bus));
  for (const DeviceConfig& d : s.devices)
    out += "\n[[device]]\n" + toml_lines(detail::device_fields(d));
  for (const TimelineEntry& e : s.timeline) {
    out += "\n[[timeline]]\n" + toml_lines(detail::entry_fields(e));
  }
  const std::vector<OutField> random = detail::random_fields(s.random);
  if (!random.empty()) out += "\n[random_faults]\n" + toml_lines(random);
  if (s.lustbus) out += "\n[lustbus]\n" + toml_lines(detail::line_fields(*s.lustbus));
  if (s.controller_line) out += "\n[dfs1]\n" + toml_lines(detail::line_fields(*s.controller_line));
  for (const LineController& c : s.controllers) {
    out += "\n[[dfs1.controller]]\n" + toml_lines(detail::controller_fields(c));
  }
  return out;
}

std::string write_control_line(const TimelineEntry& e) {
  std::vector<OutField> fields = detail::entry_fields(e);
  fields.erase(fields.begin());  // `at`: a control entry applies when it arrives
  return json_object(fields);
}

std::string write_scenario_json(const Scenario& s) {
  std::string out = "{\n";
  for (const OutField& f : detail::top_fields(s)) {
    out += "  " + detail::quote(f.key) + ": " + f.scalar + ",\n";
  }
  out += "  \"bus\": " + json_object(detail::bus_fields(s.bus)) + ",\n";
  out += "  \"device\": " + json_array(s.devices, detail::device_fields) + ",\n";
  out += "  \"timeline\": " + json_array(s.timeline, detail::entry_fields);
  const std::vector<OutField> random = detail::random_fields(s.random);
  if (!random.empty()) out += ",\n  \"random_faults\": " + json_object(random);
  if (s.lustbus) out += ",\n  \"lustbus\": " + json_object(detail::line_fields(*s.lustbus));
  if (s.controller_line) {
    std::string line = json_object(detail::line_fields(*s.controller_line));
    line.pop_back();  // the closing brace: the controllers go inside
    out += ",\n  \"dfs1\": " + line + ", \"controller\": " + json_array(s.controllers, detail::controller_fields) + "}";
  }
  return out + "\n}\n";
}

}  // namespace ibs::sim
