// The scenario schema (docs/scenarios.md): a document tree of either format -> Scenario. Refuses
// unknown keys, wrong types and values the data model cannot hold; the meaning is checked
// afterwards by validate() (scenario_validate.cpp).
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/sim/scenario.hpp"
#include "scenario_internal.hpp"

namespace ibs::sim::detail {

namespace {

using Kind = Node::Kind;

const std::vector<std::string_view> kTopKeys = {"name",     "duration",      "bus",     "device",
                                                "timeline", "random_faults", "lustbus", "dfs1"};
// The test bench's served lines (docs/testbench.md).
const std::vector<std::string_view> kLineKeys = {"pty", "port", "baud"};
const std::vector<std::string_view> kControllerLineKeys = {"pty", "port", "baud", "controller"};
const std::vector<std::string_view> kControllerKeys = {"name", "uid"};
const std::vector<std::string_view> kBusKeys = {"cycle_time", "baud", "software_time",
                                                "recovery_cycles"};
// A device's keys every kind takes; each kind's own settings come from its declarations
// (devices/settings.hpp), read by device_keys().
const std::vector<std::string_view> kGenericDeviceKeys = {"name",        "type",        "bus",
                                                          "phase",       "jitter",      "initialised",
                                                          "watchdog_ms", "watchdog_reaction", "lustbus"};
const std::vector<std::string_view>& device_keys() {
  static const std::vector<std::string_view> keys = [] {
    std::vector<std::string_view> k = kGenericDeviceKeys;
    for (const std::string_view name : devices::declared_setting_names()) k.push_back(name);
    return k;
  }();
  return keys;
}
const std::vector<std::string_view> kActionKeys = {
    "state", "emergency_stop", "block_power", "speed", "frequency",     "read",
    "write", "describe",       "wait_state",  "fault", "master_restart", "mains", "load", "input",
    "smartcard", "option_card"};
const std::vector<std::string_view> kEntryKeys = [] {
  std::vector<std::string_view> keys{"at", "device"};
  keys.insert(keys.end(), kActionKeys.begin(), kActionKeys.end());
  keys.insert(keys.end(), {"timeout", "count", "duration", "cause", "level"});
  return keys;
}();
const std::vector<std::string_view> kWriteKeys = {"parameter", "value"};
const std::vector<std::string_view> kRandomKeys = {
    "seed",       "corrupt_per_s",       "power_cycle_per_s", "device_fault_per_s",
    "lost_per_s", "master_restart_per_s"};

std::string join(const std::vector<std::string_view>& names) {
  std::string out;
  for (const std::string_view n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

class Reader {
 public:
  Reader(Format format, const std::string& file) : format_(format), file_(file) {}

  [[noreturn]] void fail(std::size_t line, const std::string& what) const {
    throw ScenarioError(file_, line, what);
  }

  std::string kind_name(const Node& n) const {
    switch (n.kind) {
      case Kind::table:
        return format_ == Format::json ? "an object" : "a table";
      case Kind::array:
        return "an array";
      case Kind::string:
        return "a string";
      case Kind::integer:
        return "an integer";
      case Kind::floating:
        return "a fractional number";
      case Kind::boolean:
        return n.boolean ? "true" : "false";
      case Kind::null:
        return "null";
      case Kind::datetime:
        return "a date/time";
    }
    return "?";
  }
  std::string table_word() const { return format_ == Format::json ? "an object" : "a table"; }

  // Calls `each(key, key_line, value)` for every member of a table, after refusing keys not in
  // `known` (with a suggestion for a near miss).
  template <typename F>
  void members(const Node& table, const std::vector<std::string_view>& known,
               std::string_view where, F&& each) const {
    for (std::size_t i = 0; i < table.children.size(); ++i) {
      const std::string& key = table.keys[i];
      bool found = false;
      for (const std::string_view k : known) found = found || k == key;
      if (!found) {
        const std::string_view near = closest_name(key, known);
        fail(table.key_lines[i],
             "unknown key '" + key + "' " + std::string(where) +
                 (near.empty() ? " (known: " + join(known) + ")"
                               : " (did you mean '" + std::string(near) + "'?)"));
      }
      each(key, table.key_lines[i], table.children[i]);
    }
  }

  void expect_table(const Node& n, std::string_view key) const {
    if (n.kind != Kind::table) {
      fail(n.line, "'" + std::string(key) + "' must be " + table_word() + ", not " + kind_name(n));
    }
  }

  std::string string(const Node& n, std::string_view key) const {
    if (n.kind != Kind::string) {
      fail(n.line, "'" + std::string(key) + "' must be a string, not " + kind_name(n));
    }
    return n.text;
  }

  bool boolean(const Node& n, std::string_view key) const {
    if (n.kind != Kind::boolean) {
      fail(n.line, "'" + std::string(key) + "' must be true or false, not " + kind_name(n));
    }
    return n.boolean;
  }

  // An action flag: only `true` makes sense (leaving the key out is the "no").
  void flag(const Node& n, std::string_view key) const {
    if (!boolean(n, key)) {
      fail(n.line, "'" + std::string(key) + "' can only be true (leave the entry out instead)");
    }
  }

  std::int64_t integer(const Node& n, std::string_view key, std::int64_t min,
                       std::int64_t max) const {
    if (n.kind != Kind::integer) {
      fail(n.line, "'" + std::string(key) + "' must be an integer, not " + kind_name(n));
    }
    if (n.integer < min || n.integer > max) {
      fail(n.line, "'" + std::string(key) + "' = " + std::to_string(n.integer) +
                       " is out of range (" + std::to_string(min) + ".." + std::to_string(max) +
                       ")");
    }
    return n.integer;
  }

  // An integer for an `int` field. The documented range [lo, hi] is what a message quotes for a
  // number no `int` holds; inside that, the validator judges the value with its own reasons.
  int int_value(const Node& n, std::string_view key, std::int64_t lo, std::int64_t hi) const {
    if (n.kind == Kind::integer &&
        (n.integer < std::numeric_limits<int>::min() || n.integer > std::numeric_limits<int>::max())) {
      fail(n.line, "'" + std::string(key) + "' = " + std::to_string(n.integer) + " is out of range (" +
                       std::to_string(lo) + ".." + std::to_string(hi) + ")");
    }
    return static_cast<int>(
        integer(n, key, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
  }

  double number(const Node& n, std::string_view key) const {
    if (n.kind == Kind::integer) return static_cast<double>(n.integer);
    if (n.kind == Kind::floating) return n.floating;
    fail(n.line, "'" + std::string(key) + "' must be a number, not " + kind_name(n));
  }

  Duration time(const Node& n, std::string_view key) const {
    if (n.kind != Kind::string) {
      fail(n.line, "'" + std::string(key) +
                       "' must be a time string with a unit, e.g. \"250 ms\", not " + kind_name(n));
    }
    try {
      return parse_time(n.text);
    } catch (const std::invalid_argument& e) {
      fail(n.line, "'" + std::string(key) + "': " + e.what());
    }
  }

  std::uint16_t parameter(const Node& n, std::string_view key) const {
    return static_cast<std::uint16_t>(integer(n, key, 0, 0xFFFF));
  }

 private:
  Format format_;
  const std::string& file_;
};

void read_bus(const Reader& r, const Node& n, BusSettings& bus, SourceMap& lines) {
  r.expect_table(n, "bus");
  lines.bus = n.line;
  r.members(n, kBusKeys, "in bus", [&](const std::string& key, std::size_t, const Node& v) {
    if (key == "cycle_time") {
      bus.cycle_time = r.time(v, key);
      lines.cycle_time = v.line;
    } else if (key == "baud") {
      const std::string baud = r.string(v, key);
      if (baud != "500k" && baud != "2M") {
        r.fail(v.line, "'baud' must be \"500k\" or \"2M\", not \"" + baud + "\"");
      }
      bus.baud_2mbit = baud == "2M";
    } else if (key == "software_time") {
      bus.software_time = r.time(v, key);
      lines.software_time = v.line;
    } else if (key == "recovery_cycles") {
      bus.recovery_cycles = r.int_value(v, key, 0, 100);
      lines.recovery_cycles = v.line;
    }
  });
}

// One of a drive's own settings by its declaration's type. An integer's range is the
// validator's (the wing words it); here only what the value type cannot hold.
void read_setting(const Reader& r, const Node& v, const devices::SettingSpec& spec, devices::SettingValues& out) {
  const std::string key(spec.name);
  switch (spec.kind) {
    case devices::SettingKind::integer:
      out.set_integer(key, r.int_value(v, key, spec.min, spec.max));
      return;
    case devices::SettingKind::boolean:
      out.set_boolean(key, r.boolean(v, key));
      return;
    case devices::SettingKind::duration:
      out.set_duration(key, r.time(v, key));
      return;
    case devices::SettingKind::choice: {
      const std::string given = r.string(v, key);
      std::string names;
      for (std::size_t i = 0; i < spec.choices.size(); ++i) {
        if (spec.choices[i] == given) {
          out.set(key, devices::SettingKind::choice, static_cast<std::int64_t>(i));
          return;
        }
        names += std::string(i == 0 ? "" : i + 1 == spec.choices.size() ? " or " : ", ") + "\"" +
                 std::string(spec.choices[i]) + "\"";
      }
      r.fail(v.line, "'" + key + "' must be " + names + ", not \"" + given + "\"");
    }
  }
}

void read_device(const Reader& r, const Node& n, DeviceConfig& d, DeviceLines& l) {
  if (n.kind != Kind::table) {
    r.fail(n.line, "each 'device' must be " + r.table_word() + ", not " + r.kind_name(n));
  }
  l.table = n.line;
  bool has_type = false;
  r.members(n, device_keys(), "in a device", [&](const std::string& key, std::size_t, const Node& v) {
    if (key == "name") {
      d.name = r.string(v, key);
      l.name = v.line;
    } else if (key == "type") {
      const std::string type = r.string(v, key);
      if (devices::find_drive_kind(type) == nullptr) {
        r.fail(v.line, "'type' must be " + devices::drive_kind_names(", ", " or ", "\"") + ", not \"" + type + "\"");
      }
      d.kind = type;
      has_type = true;
    } else if (key == "bus") {
      const std::string bus = r.string(v, key);
      if (bus != "local" && bus != "remote") {
        r.fail(v.line, "'bus' must be \"local\" or \"remote\", not \"" + bus + "\"");
      }
      d.bus = bus == "local" ? interbus::BusKind::local : interbus::BusKind::remote;
      l.bus = v.line;
    } else if (key == "phase") {
      d.phase = r.time(v, key);
      l.phase = v.line;
    } else if (key == "jitter") {
      d.jitter = r.time(v, key);
      l.jitter = v.line;
    } else if (key == "initialised") {
      d.initialised = r.boolean(v, key);
    } else if (key == "watchdog_ms") {
      d.watchdog_ms = r.int_value(v, key, 0, 65535);
      l.watchdog_ms = v.line;
    } else if (key == "watchdog_reaction") {
      d.watchdog_reaction = r.int_value(v, key, 0, 3);
      l.watchdog_reaction = v.line;
    } else if (key == "lustbus") {
      // LUSTBUS manual 9.1: a drive's LUSTBUS address is 1..30 (0 is the broadcast, 31 not used).
      d.lustbus = r.int_value(v, key, 1, 30);
      if (*d.lustbus < 1 || *d.lustbus > 30) {
        r.fail(v.line, "'lustbus' = " + std::to_string(*d.lustbus) +
                           " is not a drive's LUSTBUS address (1..30, LUSTBUS manual 9.1)");
      }
      l.lustbus = v.line;
    } else {
      // A drive's own setting: read by the device's kind's declaration when the type came first,
      // else by the first kind's that declares it; whether the kind has it is checked below.
      const devices::DriveKind* kind = has_type ? devices::find_drive_kind(d.kind) : nullptr;
      const devices::SettingSpec* spec = kind != nullptr ? (*kind)->setting(key) : nullptr;
      if (spec == nullptr) spec = devices::any_declaration(key);
      read_setting(r, v, *spec, d.settings);
      l.settings.emplace_back(key, v.line);
    }
  });
  if (l.name == 0) r.fail(n.line, "a device needs a 'name'");
  if (!has_type)
    r.fail(n.line, "device '" + d.name + "' needs a 'type' (" + devices::drive_kind_names(", ", " or ", "\"") + ")");
  // A setting the kind does not declare (a VF1000 has no 405-SUPI, INTERBUS manual 3.1.2): refused on
  // its line, in the words of the kind that declares it.
  const devices::DriveKind& kind = *devices::find_drive_kind(d.kind);
  for (const auto& [key, line] : l.settings) {
    if (const auto refusal = devices::refuse_setting_name(kind, key)) r.fail(line, refusal->message);
  }
}

// `control`: a line of the control channel, which applies at once and so has no `at`.
void read_entry(const Reader& r, const Node& n, TimelineEntry& e, EntryLines& l, bool control = false) {
  if (n.kind != Kind::table) {
    r.fail(n.line, control ? "a control line must be a JSON object (a timeline entry without 'at'), not " +
                                 r.kind_name(n)
                           : "each 'timeline' entry must be " + r.table_word() + ", not " + r.kind_name(n));
  }
  l.table = n.line;
  e.source_line = n.line;
  std::string action_key;
  std::string modifier_key;
  bool has_at = false;
  r.members(
      n, kEntryKeys, "in a timeline entry",
      [&](const std::string& key, std::size_t key_line, const Node& v) {
        if (key == "at") {
          if (control) r.fail(key_line, "control entries apply at once: no 'at'");
          e.at = r.time(v, key);
          l.at = v.line;
          has_at = true;
          return;
        }
        if (key == "device") {
          e.device = r.string(v, key);
          l.device = v.line;
          return;
        }
        if (key == "cause") {
          // The drive's error as its manual writes it: a name ("E-IBS") or a number; checked
          // against the drive's list by the validator.
          if (v.kind == Kind::integer) {
            e.cause = std::to_string(v.integer);
          } else if (v.kind == Kind::string) {
            e.cause = v.text;
            if (e.cause.empty()) r.fail(v.line, "'cause' must not be empty (leave it out for a generic fault)");
          } else {
            r.fail(v.line, "'cause' must be the drive's error number or name, not " + r.kind_name(v));
          }
          l.cause = v.line;
          return;
        }
        if (key == "level") {
          const std::string level = r.string(v, key);
          if (level != "high" && level != "low") {
            r.fail(v.line, "'level' must be \"high\" or \"low\", not \"" + level + "\"");
          }
          e.level = level == "high";
          l.level = v.line;
          return;
        }
        if (key == "timeout" || key == "count" || key == "duration") {
          if (!modifier_key.empty()) {
            r.fail(key_line, "'" + key + "' and '" + modifier_key + "' (line " +
                                 std::to_string(l.modifier) + ") do not go together in one entry");
          }
          modifier_key = key;
          l.modifier = v.line;
          if (key == "count") {
            e.count = r.int_value(v, key, 1, 10000);
          } else {
            e.duration = r.time(v, key);
          }
          return;
        }
        // An action key.
        if (!action_key.empty()) {
          r.fail(key_line, "a timeline entry holds one action: this one already has '" +
                               action_key + "' (line " + std::to_string(l.action) + "), so '" +
                               key + "' needs an entry of its own");
        }
        action_key = key;
        l.action = v.line;
        if (key == "state" || key == "wait_state") {
          e.action = key == "state" ? Action::state : Action::wait_state;
          e.value = r.string(v, key);
        } else if (key == "emergency_stop" || key == "block_power" || key == "master_restart") {
          r.flag(v, key);
          e.action = key == "emergency_stop" ? Action::emergency_stop
                     : key == "block_power"  ? Action::block_power
                                             : Action::master_restart;
        } else if (key == "speed" || key == "frequency") {
          e.action = key == "speed" ? Action::speed : Action::frequency;
          e.number = r.number(v, key);
        } else if (key == "read" || key == "describe") {
          e.action = key == "read" ? Action::read : Action::describe;
          e.parameter = r.parameter(v, key);
          l.parameter = v.line;
        } else if (key == "write") {
          e.action = Action::write;
          r.expect_table(v, key);
          bool has_parameter = false;
          bool has_value = false;
          r.members(v, kWriteKeys, "in write",
                    [&](const std::string& k, std::size_t, const Node& w) {
                      if (k == "parameter") {
                        e.parameter = r.parameter(w, k);
                        l.parameter = w.line;
                        has_parameter = true;
                      } else {
                        e.number = r.number(w, k);
                        l.value = w.line;
                        has_value = true;
                      }
                    });
          if (!has_parameter) r.fail(v.line, "'write' needs a 'parameter' (its number)");
          if (!has_value) r.fail(v.line, "'write' needs a 'value' (the raw value)");
        } else if (key == "mains") {
          e.action = Action::mains;
          e.value = r.string(v, key);
          if (e.value != "off" && e.value != "on") {
            r.fail(v.line, "'mains' must be \"off\" or \"on\", not \"" + e.value + "\"");
          }
        } else if (key == "load") {
          e.action = Action::load;
          e.number = r.number(v, key);
        } else if (key == "input") {
          e.action = Action::input;
          e.value = r.string(v, key);
        } else if (key == "smartcard") {
          e.action = Action::smartcard;
          e.value = r.string(v, key);
          if (e.value != "read" && e.value != "write") {
            r.fail(v.line, "'smartcard' must be \"read\" or \"write\", not \"" + e.value + "\"");
          }
        } else if (key == "option_card") {
          e.action = Action::option_card;
          e.value = r.string(v, key);
          if (e.value != "withdrawn" && e.value != "inserted") {
            r.fail(v.line, "'option_card' must be \"withdrawn\" or \"inserted\", not \"" + e.value + "\"");
          }
        } else if (key == "fault") {
          const std::string fault = r.string(v, key);
          if (fault == "corrupt") {
            e.action = Action::fault_corrupt;
          } else if (fault == "power-cycle") {
            e.action = Action::fault_power_cycle;
          } else if (fault == "device") {
            e.action = Action::fault_device;
          } else if (fault == "lost") {
            e.action = Action::fault_lost;
          } else {
            r.fail(v.line,
                   "'fault' must be \"corrupt\", \"power-cycle\", \"device\" or \"lost\", not \"" +
                       fault + "\"");
          }
        }
      });
  if (!has_at && !control) r.fail(n.line, "a timeline entry needs 'at' (its time, e.g. at = \"250 ms\")");
  if (action_key.empty()) {
    r.fail(n.line, std::string(control ? "a control line" : "a timeline entry") +
                       " needs an action (one of: " + join(kActionKeys) + ")");
  }
  if (l.cause != 0 && e.action != Action::fault_device) {
    r.fail(l.cause, "'cause' goes with fault = \"device\" only");
  }
  if (e.action == Action::input && l.level == 0) {
    r.fail(l.action, "'input' needs 'level' (\"high\" or \"low\")");
  }
  if (l.level != 0 && e.action != Action::input) r.fail(l.level, "'level' goes with 'input' only");
  // Which modifier belongs to which action.
  std::string_view wanted;  // the modifier this action takes, if any
  switch (e.action) {
    case Action::wait_state:
      wanted = "timeout";
      break;
    case Action::fault_corrupt:
      wanted = "count";
      break;
    case Action::fault_device:
    case Action::fault_lost:
    case Action::smartcard:
      wanted = "duration";
      break;
    default:
      break;
  }
  const std::string what = !fault_name(e.action).empty()
                               ? "fault = \"" + std::string(fault_name(e.action)) + "\""
                               : "'" + action_key + "'";
  if (!modifier_key.empty() && modifier_key != wanted) {
    r.fail(l.modifier, "'" + modifier_key + "' does not go with " + what +
                           (wanted.empty() ? "" : " (it takes '" + std::string(wanted) + "')"));
  }
  if (e.action == Action::fault_lost && modifier_key.empty()) {
    r.fail(l.action, "fault = \"lost\" needs 'duration': how long the device stays off the bus");
  }
  if (e.action == Action::smartcard && modifier_key.empty()) {
    r.fail(l.action, "'smartcard' needs 'duration': how long the card is read or written");
  }
}

void read_random(const Reader& r, const Node& n, RandomFaults& rf, SourceMap& lines) {
  r.expect_table(n, "random_faults");
  lines.random = n.line;
  r.members(n, kRandomKeys, "in random_faults",
            [&](const std::string& key, std::size_t, const Node& v) {
              if (key == "seed") {
                rf.seed = static_cast<std::uint64_t>(
                    r.integer(v, key, 0, std::numeric_limits<std::int64_t>::max()));
                lines.seed = v.line;
                return;
              }
              double* rate = nullptr;
              std::size_t index = 0;
              if (key == "corrupt_per_s") {
                rate = &rf.corrupt_per_s;
                index = 0;
              } else if (key == "power_cycle_per_s") {
                rate = &rf.power_cycle_per_s;
                index = 1;
              } else if (key == "device_fault_per_s") {
                rate = &rf.device_fault_per_s;
                index = 2;
              } else if (key == "lost_per_s") {
                rate = &rf.lost_per_s;
                index = 3;
              } else {
                rate = &rf.master_restart_per_s;
                index = 4;
              }
              *rate = r.number(v, key);
              lines.rates[index] = v.line;
            });
}

// [lustbus] / [dfs1]: a new pty or a named port, and its rate; [dfs1] also lists its controllers.
void read_line(const Reader& r, const Node& n, std::string_view key, ServedLine& line, SourceMap::Line& lines,
               Scenario* controllers, SourceMap* map) {
  r.expect_table(n, key);
  lines.table = n.line;
  const std::string where = "in [" + std::string(key) + "]";
  r.members(n, controllers != nullptr ? kControllerLineKeys : kLineKeys, where, [&](const std::string& k, std::size_t, const Node& v) {
    if (k == "pty") {
      line.pty = r.boolean(v, k);
      lines.pty = v.line;
    } else if (k == "port") {
      line.port = r.string(v, k);
      lines.port = v.line;
    } else if (k == "baud") {
      line.baud = static_cast<std::uint32_t>(r.integer(v, k, 1, 4'000'000));
      lines.baud = v.line;
    } else {
      if (v.kind != Kind::array) {
        r.fail(v.line, "'controller' must be an array ([[dfs1.controller]] in TOML, [ ... ] in JSON), not " +
                           r.kind_name(v));
      }
      for (const Node& c : v.children) {
        if (c.kind != Kind::table) {
          r.fail(c.line, "each 'controller' must be " + r.table_word() + ", not " + r.kind_name(c));
        }
        LineController ctl;
        ctl.source_line = c.line;
        bool has_name = false;
        bool has_uid = false;
        std::size_t uid_line = c.line;
        r.members(c, kControllerKeys, "in a DFS-1 controller", [&](const std::string& ck, std::size_t, const Node& cv) {
          if (ck == "name") {
            ctl.name = r.string(cv, ck);
            has_name = true;
          } else {
            // DFS-1 manual: a controller's unit id is 1..255 (0 is nobody's).
            ctl.uid = static_cast<int>(r.integer(cv, ck, 1, 255));
            uid_line = cv.line;
            has_uid = true;
          }
        });
        if (!has_name) r.fail(c.line, "a DFS-1 controller needs a 'name'");
        if (!has_uid) r.fail(c.line, "DFS-1 controller '" + ctl.name + "' needs a 'uid' (1..255, its unit id)");
        controllers->controllers.push_back(std::move(ctl));
        map->controller_uids.push_back(uid_line);
      }
    }
  });
  if (line.pty == !line.port.empty()) {
    r.fail(n.line, "[" + std::string(key) + "] needs either pty = true (a new pseudo-terminal) or port = \"PATH\" "
                       "(a serial port), not " + (line.pty ? "both" : "neither"));
  }
}

template <typename T, typename L, typename F>
void read_array(const Reader& r, const Node& n, std::string_view key, std::string_view toml_form,
                std::vector<T>& out, std::vector<L>& lines, F&& read_one) {
  if (n.kind != Kind::array) {
    r.fail(n.line, "'" + std::string(key) + "' must be an array (" + std::string(toml_form) +
                       " in TOML, [ ... ] in JSON), not " + r.kind_name(n));
  }
  out.resize(n.children.size());
  lines.resize(n.children.size());
  for (std::size_t i = 0; i < n.children.size(); ++i) read_one(n.children[i], out[i], lines[i]);
}

}  // namespace

TimelineEntry read_control_entry(const Node& n, const std::string& file, EntryLines& lines) {
  const Reader r(Format::json, file);
  TimelineEntry e;
  read_entry(r, n, e, lines, true);
  return e;
}

Scenario read_tree(const Node& root, Format format, const std::string& file, SourceMap& lines) {
  const Reader r(format, file);
  Scenario s;
  s.name = std::filesystem::path(file).stem().string();
  if (s.name.empty()) s.name = "scenario";
  lines.root = root.line;
  if (root.kind != Kind::table) {
    r.fail(root.line,
           "a scenario must be " + r.table_word() + " at the top, not " + r.kind_name(root));
  }
  bool has_duration = false;
  r.members(
      root, kTopKeys, "at the top level", [&](const std::string& key, std::size_t, const Node& v) {
        if (key == "name") {
          s.name = r.string(v, key);
          lines.name = v.line;
        } else if (key == "duration") {
          s.duration = r.time(v, key);
          lines.duration = v.line;
          has_duration = true;
        } else if (key == "bus") {
          read_bus(r, v, s.bus, lines);
        } else if (key == "device") {
          lines.device_array = v.line;
          read_array(
              r, v, key, "[[device]]", s.devices, lines.devices,
              [&](const Node& n, DeviceConfig& d, DeviceLines& l) { read_device(r, n, d, l); });
        } else if (key == "timeline") {
          read_array(
              r, v, key, "[[timeline]]", s.timeline, lines.entries,
              [&](const Node& n, TimelineEntry& e, EntryLines& l) { read_entry(r, n, e, l); });
        } else if (key == "random_faults") {
          read_random(r, v, s.random, lines);
        } else if (key == "lustbus") {
          read_line(r, v, key, s.lustbus.emplace(), lines.lustbus, nullptr, nullptr);
        } else if (key == "dfs1") {
          read_line(r, v, key, s.controller_line.emplace(), lines.controller_line, &s, &lines);
        }
      });
  if (!has_duration) {
    r.fail(root.line, "a scenario needs 'duration' (the simulated time to run, e.g. \"6 s\")");
  }
  return s;
}

}  // namespace ibs::sim::detail
