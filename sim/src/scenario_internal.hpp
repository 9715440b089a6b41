// Internals of the scenario reader and writers. Both file formats are first turned into one small
// document tree that carries a source line on every key and value; one schema reader turns the
// tree into a Scenario, and one validator checks the meaning. So TOML and JSON files obey the same
// rules and get the same messages, and a scenario built in code is checked by the same validator.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ibs/devices/registry.hpp"
#include "ibs/drivecom/sequencer.hpp"
#include "ibs/sim/scenario.hpp"

namespace ibs::sim::detail {

enum class Format : std::uint8_t { toml, json };

// A scenario file's format and text, whichever bus it is for: .toml or .json by the extension
// (either case), a regular file of bounded size (base/text_file.hpp); a ScenarioError naming the
// file otherwise.
struct ScenarioText {
  Format format = Format::toml;
  std::string text;
};
ScenarioText read_scenario_file(const std::string& path);

// A value of either format with the line it starts on (1-based).
struct Node {
  enum class Kind : std::uint8_t {
    table,
    array,
    string,
    integer,
    floating,
    boolean,
    null,
    datetime
  };
  Kind kind = Kind::table;
  std::size_t line = 0;
  std::string text;  // string
  std::int64_t integer = 0;
  double floating = 0.0;
  bool boolean = false;
  std::vector<Node> children;          // a table's values (in source order) or an array's items
  std::vector<std::string> keys;       // table: the key of each child
  std::vector<std::size_t> key_lines;  // table: the line of each key
};

// Syntax only; throw ScenarioError with the line of the syntax error.
Node toml_tree(const std::string& text, const std::string& file);
Node json_tree(const std::string& text, const std::string& file);

// Where each setting was read from; 0 = not in the file (the validator then falls back to the
// enclosing table's line, and for a scenario built in code to the entry's source_line or 0).
struct DeviceLines {
  std::size_t table = 0;
  std::size_t name = 0;
  std::size_t bus = 0;
  std::size_t phase = 0;
  std::size_t jitter = 0;
  std::size_t watchdog_ms = 0;
  std::size_t watchdog_reaction = 0;
  std::size_t lustbus = 0;
  std::vector<std::pair<std::string, std::size_t>> settings;  // the drive's own, by name

  // The line of a setting by its name, generic or the drive's own; 0 when not in the file.
  [[nodiscard]] std::size_t line_of(std::string_view setting) const {
    if (setting == "name") return name;
    if (setting == "bus") return bus;
    if (setting == "phase") return phase;
    if (setting == "jitter") return jitter;
    if (setting == "watchdog_ms") return watchdog_ms;
    if (setting == "watchdog_reaction") return watchdog_reaction;
    if (setting == "lustbus") return lustbus;
    for (const auto& [key, line] : settings) {
      if (key == setting) return line;
    }
    return 0;
  }
};
struct EntryLines {
  std::size_t table = 0;
  std::size_t at = 0;
  std::size_t device = 0;
  std::size_t action = 0;
  std::size_t parameter = 0;
  std::size_t value = 0;     // write's value
  std::size_t modifier = 0;  // timeout, count or duration
  std::size_t cause = 0;     // fault = "device"'s cause
  std::size_t level = 0;     // input's level
};
struct SourceMap {
  std::size_t root = 0;
  std::size_t name = 0;
  std::size_t duration = 0;
  std::size_t bus = 0;
  std::size_t cycle_time = 0;
  std::size_t software_time = 0;
  std::size_t recovery_cycles = 0;
  std::size_t device_array = 0;
  std::size_t random = 0;
  std::size_t seed = 0;
  std::size_t rates[5] = {};  // corrupt, power_cycle, device_fault, lost, master_restart
  std::vector<DeviceLines> devices;
  std::vector<EntryLines> entries;
  // The test bench's tables: [lustbus] and [dfs1] and their keys.
  struct Line {
    std::size_t table = 0;
    std::size_t pty = 0;
    std::size_t port = 0;
    std::size_t baud = 0;
  } lustbus, controller_line;
  std::vector<std::size_t> controller_uids;  // the line of each controller's uid
};

// The schema: tree -> Scenario, refusing unknown keys, wrong types and values the data model
// cannot hold. `name` defaults to the file name's stem.
Scenario read_tree(const Node& root, Format format, const std::string& file, SourceMap& lines);

// One control line's tree (a JSON object) as an entry without `at` (parse_control_line).
TimelineEntry read_control_entry(const Node& n, const std::string& file, EntryLines& lines);

// The meaning: ranges, device names and kinds, layouts, bus limits, the timeline.
void validate(const Scenario& s, const SourceMap& lines, const std::string& file);

// --- names and text shared by the reader, the validator and the writers ---------------------

// The DRIVECOM states' names as the files write them: drivecom's state table is their only source.
inline constexpr const auto& kTargetStates = drivecom::kTargetKeys;
inline constexpr const auto& kWaitStates = drivecom::kStateKeys;

// The `fault = "..."` names.
std::string_view fault_name(Action a);  // empty for a non-fault action

// Numbers as text that both formats read back to the same double ("2500.25", "50.0", "1e-05").
std::string format_number(double v);
// A basic string literal with the escapes both formats share, in double quotes.
std::string quote(std::string_view s);

// Typing "cycletime" for "cycle_time": the closest known name within two edits, or empty.
std::string_view closest_name(std::string_view given, const std::vector<std::string_view>& known);

// --- writing ---------------------------------------------------------------------------------

// One key of the output: a scalar already written as text (strings, numbers and booleans read
// the same in TOML and JSON), or an inline table.
struct OutField {
  std::string key;
  std::string scalar;
  std::vector<OutField> table;  // inline table when not empty
};
std::vector<OutField> top_fields(const Scenario& s);  // name, duration
std::vector<OutField> bus_fields(const BusSettings& b);
std::vector<OutField> device_fields(const DeviceConfig& d);
std::vector<OutField> entry_fields(const TimelineEntry& e);
std::vector<OutField> random_fields(const RandomFaults& r);  // empty for the defaults
std::vector<OutField> line_fields(const ServedLine& l);          // [lustbus], [dfs1] (docs/testbench.md)
std::vector<OutField> controller_fields(const LineController& c);

}  // namespace ibs::sim::detail
