// The meaning of a scenario: ranges, names, device kinds and layouts, the INTERBUS limits and the
// timeline. One validator for both file formats and for scenarios built in code.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ibs/devices/registry.hpp"
#include "ibs/interbus/bus_config.hpp"
#include "ibs/sim/scenario.hpp"
#include "scenario_internal.hpp"

namespace ibs::sim::detail {

namespace {

constexpr Duration kMaxRunTime = 24h;
constexpr Duration kMaxBusTime = 1s;  // cycle and software time: more is a unit typo
constexpr int kMaxRecoveryCycles = 100;
constexpr std::size_t kMaxNameLength = 32;
constexpr int kMaxCorruptCount = 10'000;
constexpr double kMaxRatePerS = 1000.0;

std::size_t pick(std::size_t line, std::size_t fallback) {
  return line != 0 ? line : fallback;
}

std::string action_text(const TimelineEntry& e) {
  const std::string_view fault = fault_name(e.action);
  if (!fault.empty()) return "fault = \"" + std::string(fault) + "\"";
  return "'" + std::string(to_string(e.action)) + "'";
}

bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

bool one_of(std::string_view v, std::span<const std::string_view> names) {
  return std::find(names.begin(), names.end(), v) != names.end();
}

std::string list(std::span<const std::string_view> names) {
  std::string out;
  for (const std::string_view n : names) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

std::string kind_text(const devices::DriveDescriptor& k) { return std::string(k.facts().title); }
std::string a_kind(const devices::DriveDescriptor& k) {
  return std::string(k.facts().article) + " " + std::string(k.facts().title);
}


// Numbers in messages: integers without a fraction ("40000", not "40000.0").
std::string number_text(double v) {
  if (std::isfinite(v) && std::trunc(v) == v && std::abs(v) < 1e15) {
    return std::to_string(static_cast<std::int64_t>(v));
  }
  return format_number(v);
}

struct Known {
  const DeviceConfig* config = nullptr;
  std::size_t line = 0;
  const devices::DriveDescriptor* kind = nullptr;
  devices::Configuration configuration;
};

class Validator {
 public:
  Validator(const Scenario& s, const SourceMap& m, const std::string& file)
      : s_(s), m_(m), file_(file) {}

  void run() {
    check_top();
    check_bus();
    check_devices();
    check_bench();
    check_random();
    check_timeline();
  }

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& what) const {
    throw ScenarioError(file_, line, what);
  }

  DeviceLines device_lines(std::size_t i) const {
    return i < m_.devices.size() ? m_.devices[i] : DeviceLines{};
  }
  EntryLines entry_lines(std::size_t i) const {
    if (i < m_.entries.size()) return m_.entries[i];
    const std::size_t l = s_.timeline[i].source_line;
    return {l, l, l, l, l, l, l, l, l};
  }

  void check_top() const {
    if (s_.name.empty()) fail(pick(m_.name, m_.root), "'name' must not be empty");
    if (std::any_of(s_.name.begin(), s_.name.end(),
                    [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7F; })) {
      fail(pick(m_.name, m_.root), "'name' must not hold control characters");
    }
    if (s_.duration <= Duration::zero()) {
      fail(pick(m_.duration, m_.root), "'duration' must be longer than 0 s");
    }
    if (s_.duration > kMaxRunTime) {
      fail(pick(m_.duration, m_.root),
           "'duration' " + format_time(s_.duration) + " is longer than 24 h");
    }
  }

  void check_bus() const {
    const BusSettings& b = s_.bus;
    if (b.cycle_time) {
      const std::size_t line = pick(m_.cycle_time, m_.bus);
      if (*b.cycle_time <= Duration::zero()) fail(line, "'cycle_time' must be longer than 0 s");
      if (*b.cycle_time > kMaxBusTime) {
        fail(line, "'cycle_time' " + format_time(*b.cycle_time) +
                       " is longer than 1 s (INTERBUS cycles take milliseconds)");
      }
    }
    const std::size_t sw = pick(m_.software_time, m_.bus);
    if (b.software_time < Duration::zero()) fail(sw, "'software_time' must not be negative");
    if (b.software_time > kMaxBusTime) {
      fail(sw, "'software_time' " + format_time(b.software_time) + " is longer than 1 s");
    }
    if (b.recovery_cycles < 0 || b.recovery_cycles > kMaxRecoveryCycles) {
      fail(pick(m_.recovery_cycles, m_.bus),
           "'recovery_cycles' = " + std::to_string(b.recovery_cycles) + " is out of range (0.." +
               std::to_string(kMaxRecoveryCycles) + ")");
    }
  }

  void check_devices() {
    if (s_.devices.empty()) {
      fail(pick(m_.device_array, m_.root),
           "a scenario needs at least one device ([[device]] in TOML, \"device\": [...] in JSON)");
    }
    for (std::size_t i = 0; i < s_.devices.size(); ++i) check_device(i);
    check_bus_limits();
  }

  void check_device(std::size_t i) {
    const DeviceConfig& d = s_.devices[i];
    const DeviceLines l = device_lines(i);
    const std::size_t table = l.table;
    const std::size_t name_line = pick(l.name, table);
    if (d.name.empty()) fail(name_line, "a device name must not be empty");
    if (d.name.size() > kMaxNameLength ||
        !std::all_of(d.name.begin(), d.name.end(), is_name_char)) {
      fail(name_line, "device name '" + d.name + "' must be 1.." + std::to_string(kMaxNameLength) +
                          " letters, digits, '_' or '-'");
    }
    for (const Known& k : known_) {
      if (k.config->name == d.name) {
        fail(name_line,
             "device name '" + d.name + "' is already used (line " + std::to_string(k.line) + ")");
      }
    }
    const std::string who = "device '" + d.name + "': ";
    const devices::DriveKind* kind = devices::find_drive_kind(d.kind);
    if (kind == nullptr) {
      fail(table, who + "unknown type '" + d.kind + "' (" + devices::drive_kind_names(", ", " or ", "\"") + ")");
    }
    const devices::DriveDescriptor& k = **kind;
    // The line a setting the drive refuses was given on (the table's when it was not given).
    const auto line_of = [&l](std::string_view setting) -> std::size_t { return l.line_of(setting); };
    const auto refuse = [&](const devices::SettingsError& e) {
      fail(pick(line_of(e.setting()), pick(line_of(e.fallback()), table)), who + e.what());
    };
    const devices::DeviceSettings settings = device_settings(d);
    Known known{&d, table, &k, {}};
    try {
      known.configuration = k.configure(settings);
    } catch (const devices::SettingsError& e) {
      refuse(e);
    }
    const Duration period = k.facts().sample_period;
    if (d.phase < Duration::zero() || d.phase >= period) {
      fail(pick(l.phase, table), who + "'phase' " + format_time(d.phase) +
                                     " must be at least 0 s and shorter than the " +
                                     kind_text(k) + "'s sample period " + format_time(period));
    }
    if (d.jitter < Duration::zero() || d.jitter * 2 >= period) {
      fail(pick(l.jitter, table), who + "'jitter' " + format_time(d.jitter) +
                                      " must be at least 0 s and shorter than half the " +
                                      kind_text(k) + "'s sample period (" +
                                      format_time(period / 2) + ")");
    }
    try {
      k.check_watchdog(settings);
      // Whatever the wing's own checks leave: the drive's settings against its declarations (a
      // scenario built in code may give a VF1000 an MC6000's setting; a file's reader refused it).
      ibs::detail::require<devices::SettingsError>(devices::check_settings(*kind, settings.drive));
    } catch (const devices::SettingsError& e) {
      refuse(e);
    }
    if (d.lustbus) {
      const std::size_t line = pick(l.lustbus, table);
      if (!s_.lustbus) {
        fail(line, who + "'lustbus' = " + std::to_string(*d.lustbus) +
                       " needs the line it answers on: a [lustbus] table with pty = true or port = \"PATH\"");
      }
      if (*d.lustbus < 1 || *d.lustbus > 30) {
        fail(line, who + "'lustbus' = " + std::to_string(*d.lustbus) +
                       " is not a drive's LUSTBUS address (1..30, LUSTBUS manual 9.1)");
      }
      for (const Known& o : known_) {
        if (o.config->lustbus == d.lustbus) {
          fail(line, who + "LUSTBUS address " + std::to_string(*d.lustbus) + " is already device '" +
                         o.config->name + "''s (line " + std::to_string(o.line) +
                         "): both would answer at once (LUSTBUS manual 9.1)");
        }
      }
    }
    known_.push_back(known);
  }

  // The test bench's lines (docs/testbench.md): each serves somebody, on a pty or a named port at a
  // rate its protocol runs at; the DFS-1 controllers have names of their own and unit ids once.
  void check_bench() const {
    const auto check_line = [&](const std::optional<ServedLine>& line, const SourceMap::Line& l, std::string_view key) {
      if (!line) return;
      const std::size_t table = pick(l.table, m_.root);
      if (line->pty == !line->port.empty()) {
        fail(table, "[" + std::string(key) + "] needs either pty = true (a new pseudo-terminal) or port = \"PATH\" "
                        "(a serial port), not " + (line->pty ? "both" : "neither"));
      }
      // Which rates a drive runs at is its own (LUSTBUS manual 4: the VF1000 up to 9600, the MC6000 up
      // to 57600); the bench asks each drive's face when it makes it.
      if (line->baud == 0) fail(pick(l.baud, table), "[" + std::string(key) + "] baud must not be 0");
    };
    check_line(s_.lustbus, m_.lustbus, "lustbus");
    check_line(s_.controller_line, m_.controller_line, "dfs1");
    if (s_.lustbus && std::none_of(s_.devices.begin(), s_.devices.end(), [](const DeviceConfig& d) { return d.lustbus.has_value(); })) {
      fail(pick(m_.lustbus.table, m_.root),
           "[lustbus] serves no device: give the devices that answer on it their address (lustbus = 1..30)");
    }
    if (!s_.controller_line && !s_.controllers.empty()) {
      fail(pick(s_.controllers.front().source_line, m_.root),
           "DFS-1 controllers need their line: [dfs1] with pty = true or port = \"PATH\"");
    }
    if (s_.controller_line && s_.controllers.empty()) {
      fail(pick(m_.controller_line.table, m_.root),
           "[dfs1] serves no controller: list them as [[dfs1.controller]] with a name and a uid (1..255)");
    }
    for (std::size_t i = 0; i < s_.controllers.size(); ++i) {
      const LineController& c = s_.controllers[i];
      const std::size_t line = pick(c.source_line, m_.root);
      if (c.name.empty() || c.name.size() > kMaxNameLength || !std::all_of(c.name.begin(), c.name.end(), is_name_char)) {
        fail(line, "controller name '" + c.name + "' must be 1.." + std::to_string(kMaxNameLength) +
                       " letters, digits, '_' or '-'");
      }
      if (const Known* k = find(c.name)) {
        fail(line, "controller name '" + c.name + "' is already a device's (line " + std::to_string(k->line) + ")");
      }
      if (c.uid < 1 || c.uid > 255) {
        fail(i < m_.controller_uids.size() ? m_.controller_uids[i] : line,
             "controller '" + c.name + "': uid " + std::to_string(c.uid) + " is not a unit id (1..255, DFS-1 manual)");
      }
      for (std::size_t j = 0; j < i; ++j) {
        const LineController& o = s_.controllers[j];
        if (o.name == c.name) {
          fail(line, "controller name '" + c.name + "' is already used (line " + std::to_string(o.source_line) + ")");
        }
        if (o.uid == c.uid) {
          fail(i < m_.controller_uids.size() ? m_.controller_uids[i] : line,
               "controller '" + c.name + "': uid " + std::to_string(c.uid) + " is already controller '" + o.name +
                   "''s (line " + std::to_string(o.source_line) + "): both would answer at once");
        }
      }
    }
  }

  const LineController* find_controller(const std::string& name) const {
    for (const LineController& c : s_.controllers) {
      if (c.name == name) return &c;
    }
    return nullptr;
  }

  // The INTERBUS limits (devices, remote bus devices, local bus segments, PCP devices, process
  // data words) are make_bus_config's; to name the line, find the first device that breaks one.
  // Every limit only grows with the ring, so the shortest refused prefix ends at that device.
  void check_bus_limits() const {
    std::vector<interbus::DeviceSpec> ring;
    ring.reserve(s_.devices.size());
    for (const Known& k : known_) {
      ring.push_back({k.config->name, k.configuration.id_code, k.configuration.bus});
    }
    const auto refused = [&](std::size_t n) -> std::optional<std::string> {
      try {
        (void)interbus::make_bus_config(std::span(ring).first(n));
        return std::nullopt;
      } catch (const interbus::ConfigError& e) {
        return std::string(e.what());
      }
    };
    if (!refused(ring.size())) return;
    std::size_t lo = 1;
    std::size_t hi = ring.size();
    while (lo < hi) {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (refused(mid)) {
        hi = mid;
      } else {
        lo = mid + 1;
      }
    }
    fail(known_[lo - 1].line, *refused(lo));
  }

  void check_random() const {
    const RandomFaults& r = s_.random;
    if (r.seed > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
      fail(pick(m_.seed, m_.random), "'seed' must be 0..2^63-1 (a TOML integer)");
    }
    const std::pair<double, std::string_view> rates[] = {
        {r.corrupt_per_s, "corrupt_per_s"},
        {r.power_cycle_per_s, "power_cycle_per_s"},
        {r.device_fault_per_s, "device_fault_per_s"},
        {r.lost_per_s, "lost_per_s"},
        {r.master_restart_per_s, "master_restart_per_s"}};
    for (std::size_t i = 0; i < std::size(rates); ++i) {
      const auto [rate, key] = rates[i];
      if (!std::isfinite(rate) || rate < 0.0 || rate > kMaxRatePerS) {
        fail(pick(m_.rates[i], m_.random), "'" + std::string(key) + "' = " + number_text(rate) +
                                               " is out of range (0..1000 per second)");
      }
    }
  }

  const Known* find(std::string_view name) const {
    const auto it = std::find_if(known_.begin(), known_.end(),
                                 [&](const Known& k) { return k.config->name == name; });
    return it == known_.end() ? nullptr : &*it;
  }

  std::string device_list() const {
    std::string out;
    for (const Known& k : known_) out += (out.empty() ? "" : ", ") + k.config->name;
    return out;
  }

  void check_timeline() const {
    for (std::size_t i = 0; i < s_.timeline.size(); ++i) {
      const TimelineEntry& e = s_.timeline[i];
      const EntryLines l = entry_lines(i);
      const std::size_t at_line = pick(l.at, l.table);
      if (e.at < Duration::zero()) fail(at_line, "'at' must not be negative");
      if (e.at > s_.duration) {
        fail(at_line, "'at' = " + format_time(e.at) + " is after the end of the run ('duration' " +
                          format_time(s_.duration) + ")");
      }
      if (i > 0 && e.at < s_.timeline[i - 1].at) {
        fail(at_line, "'at' = " + format_time(e.at) + " is earlier than the entry before it (" +
                          format_time(s_.timeline[i - 1].at) + ", line " +
                          std::to_string(entry_lines(i - 1).table) +
                          "): the timeline is written in time order");
      }
      check_entry(e, l);
    }
  }

  void check_entry(const TimelineEntry& e, const EntryLines& l) const {
    const std::size_t action_line = pick(l.action, l.table);
    const std::string what = action_text(e);
    const bool bus_wide = e.action == Action::fault_corrupt || e.action == Action::master_restart;
    if (bus_wide) {
      if (!e.device.empty()) {
        fail(pick(l.device, l.table), what + " is bus-wide: it takes no 'device'");
      }
    } else if (e.device.empty()) {
      fail(l.table, what + " needs a 'device'");
    }
    // A DFS-1 controller of the bench takes the events of a drive without a master here.
    if (!bus_wide && find(e.device) == nullptr && find_controller(e.device) != nullptr) {
      // Its causes, inputs and load range are the DFS-1 wing's: the bench checks them against the
      // wing's own reader when it is made (tools/ibs/bench.hpp), with this entry's line.
      if (e.action != Action::fault_device && e.action != Action::fault_power_cycle && e.action != Action::mains &&
          e.action != Action::load && e.action != Action::input) {
        fail(action_line, "'" + e.device + "' is a DFS-1 controller of the bench, not on the INTERBUS ring: " + what +
                              " is not for it (it takes fault = \"device\" or \"power-cycle\", mains, load, input)");
      }
      return;
    }
    const Known* k = bus_wide ? nullptr : find(e.device);
    if (!bus_wide && k == nullptr) {
      fail(pick(l.device, l.table),
           "unknown device '" + e.device + "' (devices: " + device_list() + ")");
    }
    const std::string who = "device '" + e.device + "'";
    // What the device lacks for this entry, in the drive's words ("has no PCP channel (405-SUPI
    // 12)"); bus-wide entries need nothing.
    const auto lacks = [&](devices::Capability c) -> std::optional<std::string> {
      return k != nullptr ? k->kind->lacks(c, k->configuration) : std::nullopt;
    };
    const auto need_control_word = [&] {
      if (const auto why = lacks(devices::Capability::control_word)) {
        fail(action_line, who + " " + *why + ", so " + what + " cannot reach it");
      }
    };
    const auto need_parameter_channel = [&] {
      if (const auto why = lacks(devices::Capability::parameter_channel)) {
        fail(action_line, who + " " + *why + ", so " + what + " cannot reach it");
      }
      const devices::DriveFacts& f = k->kind->facts();
      if (e.parameter > f.max_parameter) {
        fail(pick(l.parameter, action_line),
             "parameter " + std::to_string(e.parameter) + " is out of range for the " +
                 kind_text(*k->kind) + " " + who + " (0.." + std::to_string(f.max_parameter) +
                 std::string(f.parameter_range) + ")");
      }
    };
    // A reference action (speed, frequency) is the one of the drives whose reference it is.
    const auto reference = [&] {
      const devices::DriveDescriptor& kind = *k->kind;
      const std::string_view action = to_string(e.action);
      if (kind.facts().reference_action != action) {
        const devices::DriveDescriptor* wanted = nullptr;
        for (const devices::DriveKind& d : devices::drive_kinds()) {
          if (d->facts().reference_action == action) wanted = d.descriptor;
        }
        fail(action_line, what + " is " + (wanted != nullptr ? a_kind(*wanted) : std::string("another drive's")) +
                              " action, but " + who + " is " + a_kind(kind) + " (use '" +
                              std::string(kind.facts().reference_action) + "')");
      }
      if (!std::isfinite(e.number)) fail(action_line, what + " needs a finite number");
      if (const auto why = lacks(devices::Capability::reference)) fail(action_line, who + " " + *why);
      const devices::DriveFacts& f = kind.facts();
      if (e.number < f.reference_min || e.number > f.reference_max) {
        fail(action_line, "'" + std::string(action) + "' = " + number_text(e.number) + " " +
                              std::string(f.unit) + " is out of range (" + std::string(f.reference_range) + ")");
      }
    };
    const auto finite = [&](double v, std::size_t line) {
      if (!std::isfinite(v)) fail(line, what + " needs a finite number");
    };

    switch (e.action) {
      case Action::state:
        need_control_word();
        if (!one_of(e.value, kTargetStates)) {
          fail(action_line,
               "'state' = \"" + e.value + "\" is not a target state (" + list(kTargetStates) + ")");
        }
        break;
      case Action::wait_state:
        need_control_word();
        if (!one_of(e.value, kWaitStates)) {
          fail(action_line, "'wait_state' = \"" + e.value + "\" is not a DRIVECOM state (" +
                                list(kWaitStates) + ")");
        }
        if (e.duration < Duration::zero()) {
          fail(pick(l.modifier, action_line), "'timeout' must not be negative");
        }
        break;
      case Action::emergency_stop:
      case Action::block_power:
        need_control_word();
        break;
      case Action::speed:
      case Action::frequency:
        reference();
        break;
      case Action::read:
      case Action::describe:
        need_parameter_channel();
        break;
      case Action::write: {
        need_parameter_channel();
        const std::size_t value_line = pick(l.value, action_line);
        finite(e.number, value_line);
        const devices::DriveFacts& f = k->kind->facts();
        if (e.number != std::trunc(e.number)) {
          fail(value_line, "write's 'value' = " + number_text(e.number) +
                               " must be an integer (the raw value)");
        }
        if (e.number < f.write_min || e.number > f.write_max) {
          fail(value_line, "write's 'value' = " + number_text(e.number) +
                               " is out of range for the " + kind_text(*k->kind) + std::string(f.write_range));
        }
        break;
      }
      case Action::fault_corrupt:
        if (e.count < 1 || e.count > kMaxCorruptCount) {
          fail(pick(l.modifier, action_line), "'count' = " + std::to_string(e.count) +
                                                  " is out of range (1.." +
                                                  std::to_string(kMaxCorruptCount) + ")");
        }
        break;
      case Action::fault_device:
        if (e.duration < Duration::zero()) {
          fail(pick(l.modifier, action_line), "'duration' must not be negative");
        }
        if (!e.cause.empty()) {
          // The drive's own error list (its descriptor's EventFacts).
          const devices::CauseCheck c = devices::check_cause(k->kind->facts().events, kind_text(*k->kind), e.cause);
          if (!c.number) fail(pick(l.cause, action_line), "'cause' of " + who + ": " + c.error);
        }
        break;
      case Action::mains:
        break;
      case Action::load: {
        const devices::EventFacts& f = k->kind->facts().events;
        if (f.load_unit.empty()) {
          fail(action_line, "'load' is not for " + who + ", " + a_kind(*k->kind) + ": " +
                                std::string(f.no_load.empty() ? "its manuals give it no load" : f.no_load));
        }
        finite(e.number, action_line);
        break;
      }
      case Action::input: {
        const devices::EventFacts& f = k->kind->facts().events;
        if (f.inputs.empty()) {
          fail(action_line, "'input' is not for " + who + ", " + a_kind(*k->kind) + ": " +
                                std::string(f.no_inputs.empty() ? "its manuals name no input" : f.no_inputs));
        }
        if (!devices::find_input(f, e.value)) {
          fail(action_line, "'input' = \"" + e.value + "\" is not an input of the " + kind_text(*k->kind) + " " +
                                who + " (" + devices::input_names(f) + ")");
        }
        break;
      }
      case Action::smartcard: {
        // The drive's own card (its descriptor's EventFacts): how long an operation may last.
        const devices::EventFacts& f = k->kind->facts().events;
        if (f.card_max_s <= 0.0) {
          fail(action_line, "'smartcard' is not for " + who + ", " + a_kind(*k->kind) + ": " +
                                std::string(f.no_card.empty() ? "its manuals name no SMARTCARD operation" : f.no_card));
        } else if (e.duration <= Duration::zero() ||
                   e.duration > std::chrono::duration_cast<Duration>(std::chrono::duration<double>(f.card_max_s))) {
          char most[32];
          std::snprintf(most, sizeof most, "%g", f.card_max_s);
          fail(pick(l.modifier, action_line), "'duration' of a SMARTCARD operation of " + who +
                                                  " must be above 0 s and at most " + most + " s (" +
                                                  std::string(f.card_source) + ")");
        }
        break;
      }
      case Action::option_card: {
        // The drive's own option card (its descriptor's EventFacts): one its manual says it detects.
        const devices::EventFacts& f = k->kind->facts().events;
        if (f.option_card.empty()) {
          fail(action_line, "'option_card' is not for " + who + ", " + a_kind(*k->kind) + ": " +
                                std::string(f.no_option.empty() ? "its manuals give no option card an effect"
                                                                : f.no_option));
        }
        break;
      }
      case Action::fault_lost:
        if (e.duration <= Duration::zero()) {
          fail(pick(l.modifier, action_line),
               "fault = \"lost\" needs a 'duration' longer than 0 s");
        }
        break;
      case Action::fault_power_cycle:
      case Action::master_restart:
        break;
    }
  }

  const Scenario& s_;
  const SourceMap& m_;
  const std::string& file_;
  std::vector<Known> known_;
};

}  // namespace

void validate(const Scenario& s, const SourceMap& lines, const std::string& file) {
  Validator(s, lines, file).run();
}

}  // namespace ibs::sim::detail
