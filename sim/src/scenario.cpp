// The scenario data model: errors, loading by extension, equality, the built-in default.
#include "ibs/sim/scenario.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>

#include "ibs/base/text_file.hpp"
#include "scenario_internal.hpp"

namespace ibs::sim {

ScenarioError::ScenarioError(const std::string& file, std::size_t line, const std::string& what)
    : std::runtime_error(file + ":" + std::to_string(line) + ": " + what),
      file_(file),
      line_(line) {}

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

detail::ScenarioText detail::read_scenario_file(const std::string& path) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext != ".toml" && ext != ".json") {
    throw ScenarioError(path, 0,
                        "unknown scenario format: the file name must end in .toml or .json");
  }
  ScenarioText s;
  s.format = ext == ".json" ? Format::json : Format::toml;
  try {
    s.text = read_text_file(path);
  } catch (const FileReadError& e) {
    throw ScenarioError(path, 0, e.what());
  }
  return s;
}

Scenario load_scenario(const std::string& path) {
  const detail::ScenarioText s = detail::read_scenario_file(path);
  return s.format == detail::Format::toml ? parse_scenario_toml(s.text, path) : parse_scenario_json(s.text, path);
}

void validate_scenario(const Scenario& s, const std::string& file) {
  detail::validate(s, detail::SourceMap{}, file);
}

devices::DeviceSettings device_settings(const DeviceConfig& d) {
  devices::DeviceSettings s;
  s.bus = d.bus;
  s.watchdog_ms = d.watchdog_ms;
  s.watchdog_reaction = d.watchdog_reaction;
  s.drive = d.settings;
  return s;
}

void set_device_settings(DeviceConfig& d, const devices::DeviceSettings& s) {
  d.bus = s.bus;
  d.watchdog_ms = s.watchdog_ms;
  d.watchdog_reaction = s.watchdog_reaction;
  d.settings = s.drive;
}

bool operator==(const DeviceConfig& a, const DeviceConfig& b) {
  // The kind's own settings compare by what the drive reads: one not given reads as its default,
  // and one the kind does not declare (a VF1000 holding an MC6000's setting, which the validator
  // refuses) is not read at all. Without a known kind, as given.
  const devices::DriveKind* k = devices::find_drive_kind(a.kind);
  bool settings_equal = a.settings == b.settings;
  if (k != nullptr) {
    settings_equal = true;
    for (const devices::SettingSpec& spec : (*k)->settings()) {
      settings_equal = settings_equal && a.settings.value(spec) == b.settings.value(spec);
    }
  }
  return a.name == b.name && a.kind == b.kind && settings_equal && a.bus == b.bus &&
         a.phase == b.phase && a.jitter == b.jitter && a.initialised == b.initialised &&
         a.watchdog_ms == b.watchdog_ms && a.watchdog_reaction == b.watchdog_reaction && a.lustbus == b.lustbus;
}

bool operator==(const TimelineEntry& a, const TimelineEntry& b) {
  if (a.at != b.at || a.device != b.device || a.action != b.action) return false;
  switch (a.action) {
    case Action::state:
      return a.value == b.value;
    case Action::wait_state:
      return a.value == b.value && a.duration == b.duration;
    case Action::speed:
    case Action::frequency:
      return a.number == b.number;
    case Action::read:
    case Action::describe:
      return a.parameter == b.parameter;
    case Action::write:
      return a.parameter == b.parameter && a.number == b.number;
    case Action::fault_corrupt:
      return a.count == b.count;
    case Action::fault_device:
      return a.duration == b.duration && a.cause == b.cause;
    case Action::fault_lost:
      return a.duration == b.duration;
    case Action::mains:
      return a.value == b.value;
    case Action::load:
      return a.number == b.number;
    case Action::input:
      return a.value == b.value && a.level == b.level;
    case Action::smartcard:
      return a.value == b.value && a.duration == b.duration;
    case Action::option_card:
      return a.value == b.value;
    case Action::emergency_stop:
    case Action::block_power:
    case Action::fault_power_cycle:
    case Action::master_restart:
      return true;
  }
  return false;
}

bool operator==(const Scenario& a, const Scenario& b) {
  return a.name == b.name && a.duration == b.duration && a.bus == b.bus && a.devices == b.devices &&
         a.timeline == b.timeline && a.random == b.random && a.lustbus == b.lustbus && a.controller_line == b.controller_line &&
         a.controllers == b.controllers;
}

Scenario default_scenario() {
  Scenario s;
  s.name = "default";
  s.duration = 8s;

  DeviceConfig mc;
  mc.name = "mc6000";
  mc.kind = "mc6000";
  mc.bus = interbus::BusKind::remote;
  mc.initialised = true;
  DeviceConfig vf;
  vf.name = "vf1000";
  vf.kind = "vf1000";
  vf.bus = interbus::BusKind::remote;
  vf.initialised = true;
  s.devices = {mc, vf};

  const auto entry = [](Time at, const char* device, Action action) {
    TimelineEntry e;
    e.at = at;
    e.device = device;
    e.action = action;
    return e;
  };
  const auto state = [&](Time at, const char* device, const char* target) {
    TimelineEntry e = entry(at, device, Action::state);
    e.value = target;
    return e;
  };
  const auto reference = [&](Time at, const char* device, Action action, double value) {
    TimelineEntry e = entry(at, device, action);
    e.number = value;
    return e;
  };
  const auto parameter = [&](Time at, const char* device, Action action, std::uint16_t number,
                             double value = 0.0) {
    TimelineEntry e = entry(at, device, action);
    e.parameter = number;
    e.number = value;
    return e;
  };
  // Commissioning first (parameters are written with the power stage off: EEPROM values refuse a
  // write while it is on), then both drives up, to speed, down and back to READY.
  s.timeline = {
      parameter(0ms, "mc6000", Action::read, 85),    // 85-SERR: clears the power-on bit
      parameter(0ms, "vf1000", Action::read, 85),    // 85-SIOF: clears the power-on bit (6.1)
      parameter(250ms, "mc6000", Action::write, 409, 100),  // 409-BUTWD = 100 ms (3.2.4)
      parameter(250ms, "vf1000", Action::write, 22, 1000),  // 22-FMAX1 = 50.00 Hz in 0.05 Hz
      parameter(450ms, "mc6000", Action::read, 409),
      parameter(450ms, "vf1000", Action::read, 22),
      parameter(650ms, "mc6000", Action::describe, 406),  // 406-IBCNF, Get-OV
      parameter(650ms, "vf1000", Action::describe, 45),   // 45-VB2, the example of 4.1.3.3.1
      state(1200ms, "mc6000", "enabled"),
      state(1200ms, "vf1000", "enabled"),
      reference(1400ms, "mc6000", Action::speed, 2500.25),
      reference(1400ms, "vf1000", Action::frequency, 50.0),
      reference(5s, "mc6000", Action::speed, 0.0),
      reference(5s, "vf1000", Action::frequency, 0.0),
      state(7600ms, "mc6000", "ready"),
      state(7600ms, "vf1000", "ready"),
  };
  return s;
}

}  // namespace ibs::sim
