// A simulation scenario: the bus (devices and configuration) and a timeline of commands and
// faults. `ibs run` runs the built-in default scenario or one read from a TOML or JSON file
// (docs/scenarios.md). Plain data; reading and writing files is configuration-time work.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/devices/descriptor.hpp"
#include "ibs/interbus/id_code.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/time_text.hpp"

namespace ibs::sim {

struct DeviceConfig {
  std::string name;                 // unique in the scenario, 1..32 of [A-Za-z0-9_-]
  std::string kind;                 // the drive kind's name, the files' `type` (devices/registry.hpp)
  interbus::BusKind bus = interbus::BusKind::remote;  // the VF1000 is always a remote-bus device
  Duration phase{0};                // first sample after start (0 <= phase < sample period)
  Duration jitter{0};               // each sample happens up to +-jitter from its nominal time
  bool initialised = true;          // false: the run starts at the device's power-on (NOT READY,
                                    // VF1000 ~4 s initialisation); true: initialisation finished,
                                    // power-on bit still set in 85-SIOF/SERR
  std::optional<int> watchdog_ms;   // MC6000 409-BUTWD (ms, 0 = off); VF1000 906-IB-WD (ms)
  std::optional<int> watchdog_reaction;  // VF1000 907-IBCOD (0..3)
  // The test bench (docs/testbench.md): the drive's address on the scenario's LUSTBUS line
  // (Scenario::lustbus), 1..30 (LUSTBUS manual 9.1); the drive then answers there too, one drive
  // core behind both faces. Only for a kind that speaks LUSTBUS.
  std::optional<int> lustbus;
  // The drive's own settings, as its wing declares them (devices/settings.hpp); one not given
  // holds the declaration's default.
  devices::SettingValues settings;
};

// The settings the device's drive kind reads (devices/descriptor.hpp).
devices::DeviceSettings device_settings(const DeviceConfig& d);
// The other way: `s` into the device's fields (device_settings(d) == s afterwards).
void set_device_settings(DeviceConfig& d, const devices::DeviceSettings& s);

struct BusSettings {
  std::optional<Duration> cycle_time;  // fixed bus cycle time; default: the cycle-time formula
  bool baud_2mbit = false;             // 2 Mbit/s instead of 500 kbit/s (formula only)
  Duration software_time = 200us;      // the formula's SW term
  int recovery_cycles = 5;             // cycles without valid data after a corrupted cycle

  friend bool operator==(const BusSettings&, const BusSettings&) = default;
};

// A line the test bench serves while the scenario runs in real time (docs/testbench.md): a new
// pseudo-terminal, or a serial port the user names, at a rate.
struct ServedLine {
  bool pty = false;        // a new pseudo-terminal (its path is printed before the run)
  std::string port;        // else: this serial port
  std::uint32_t baud = 9600;

  friend bool operator==(const ServedLine&, const ServedLine&) = default;
};

// A stand-alone controller the bench serves on the scenario's controller line (the file's
// [dfs1] table and its [[dfs1.controller]] entries: the controllers of the DFS-1 manual): not on the
// INTERBUS ring, reached by the timeline's and the control channel's events by name. Which drive
// it is, is the registry's (the one that speaks that bus); the scenario names none.
struct LineController {
  std::string name;  // unique among the scenario's devices and controllers
  int uid = 1;       // 1..255 (DFS-1 manual)
  std::size_t source_line = 0;

  friend bool operator==(const LineController& a, const LineController& b) {
    return a.name == b.name && a.uid == b.uid;
  }
};

// What a timeline entry does.
enum class Action : std::uint8_t {
  state,          // value: start-up-inhibit | ready | on | enabled (the DRIVECOM target)
  emergency_stop, // EMERGENCY STOP now
  block_power,    // BLOCK POWER now
  speed,          // MC6000 reference in rpm (number)
  frequency,      // VF1000 reference in Hz, signed: negative = counter-clockwise (number)
  read,           // parameter read: parameter
  write,          // parameter write: parameter, number (raw value)
  describe,       // parameter description: parameter
  wait_state,     // the timeline pauses until the device reports the state in `value` (or timeout)
  fault_corrupt,  // corrupted bus cycles: count (default 1)
  fault_power_cycle,  // the device is switched off and on again
  fault_device,   // a device fault (FAULT RESPONSE ACTIVE -> FAULT); duration: how long the cause stays
  fault_lost,     // the device drops off the bus (module error) for `duration`
  master_restart, // the master restarts: drivers and channels start over
  // Plant events (devices/plant_event.hpp), each as the drive's descriptor allows it:
  mains,          // value: "off" | "on" (mains lost / back)
  load,           // load torque in the drive's unit (number; DriveFacts::events.load_unit)
  input,          // digital input `value` (its manual's name) to `level`
  smartcard,      // value: "read" | "write": a SMARTCARD operation lasting `duration`
  option_card,    // value: "withdrawn" | "inserted": the drive's option card (EventFacts::option_card)
};

struct TimelineEntry {
  Time at{0};                 // when, from the start of the run
  std::string device;         // the device's name; empty for bus-wide entries (fault_corrupt,
                              // master_restart)
  Action action = Action::state;
  std::string value;          // state / wait_state: the state's name as in the files (lower case,
                              // hyphens: "start-up-inhibit", "ready", "on", "enabled"; wait_state
                              // also "not-ready", "fault", "fault-response-active",
                              // "emergency-stop-active")
  double number = 0.0;        // speed, frequency, write value
  std::uint16_t parameter = 0;
  int count = 1;              // fault_corrupt
  Duration duration{0};       // fault_device: how long the cause stays (0: it clears at once);
                              // fault_lost: how long the device is off the bus (> 0);
                              // wait_state: timeout (0: wait up to the end of the run);
                              // smartcard: how long the card is read or written (> 0)
  std::string cause;          // fault_device: the drive's error as written ("12", "E-IBS"); empty:
                              // a generic external fault
  bool level = false;         // input: true = high
  std::size_t source_line = 0;  // where it was read from (0 = built in)
  std::uint32_t source_client = 0;  // a control entry: the socket's client it came from (0: a file or standard input)
};

// Faults drawn at random over the run (all rates per simulated second; 0 = off).
struct RandomFaults {
  std::uint64_t seed = 1;
  double corrupt_per_s = 0.0;
  double power_cycle_per_s = 0.0;
  double device_fault_per_s = 0.0;
  double lost_per_s = 0.0;
  double master_restart_per_s = 0.0;

  friend bool operator==(const RandomFaults&, const RandomFaults&) = default;
};

struct Scenario {
  std::string name = "default";
  Duration duration = 6s;      // simulated time to run
  BusSettings bus;
  std::vector<DeviceConfig> devices;  // ring order
  std::vector<TimelineEntry> timeline;  // in time order
  RandomFaults random;
  // The test bench's lines (`ibs run --realtime` only): the devices with `lustbus = ADDR` answer
  // on `lustbus` ([lustbus]); the controllers answer on `controller_line` ([dfs1]).
  std::optional<ServedLine> lustbus;
  std::optional<ServedLine> controller_line;
  std::vector<LineController> controllers;

  // True when the scenario serves a line (and so needs a real-time run).
  [[nodiscard]] bool serves_lines() const { return lustbus.has_value() || controller_line.has_value(); }
};

// The built-in scenario of `ibs run` without arguments: an MC6000 (SUPI 11 / IBCNF 2) and a
// VF1000; both to ENABLED, the MC6000 to 2500.25 rpm, the VF1000 to 50 Hz, parameter reads and
// writes on both channels, then both stopped.
Scenario default_scenario();

// Bad scenario input: what() is `FILE:LINE: what is wrong` (LINE 0 when the file cannot be read).
class ScenarioError : public std::runtime_error {
 public:
  ScenarioError(const std::string& file, std::size_t line, const std::string& what);
  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] std::size_t line() const { return line_; }

 private:
  std::string file_;
  std::size_t line_;
};

// Checks a scenario built in code with the same rules the parsers apply (lines: the entries'
// source_line, 0 elsewhere); throws ScenarioError naming `file`.
void validate_scenario(const Scenario& s, const std::string& file = "scenario");

// Times in scenario files (base/time_text.hpp): "6 s", "250 ms", "8.2 ms"; a whole number of
// nanoseconds, 0 .. 24 h. parse_time throws std::invalid_argument saying what is wrong.
using ibs::format_time;
using ibs::parse_time;

// Names for reports: bus sides as the files spell them ("remote"), actions as their enumerators
// ("fault_corrupt"; the files write fault = "corrupt").
std::string_view bus_text(interbus::BusKind b);
std::string_view to_string(Action a);

// Reads a scenario from a .toml or .json file (by extension), checks it whole (unknown keys,
// types, ranges, device names, SUPI/IBCNF pairs, times inside the duration) and returns it, or
// throws ScenarioError for the first problem, naming file and line. A file without `name` is
// named after its file name's stem.
Scenario load_scenario(const std::string& path);
Scenario parse_scenario_toml(const std::string& text, const std::string& file);
Scenario parse_scenario_json(const std::string& text, const std::string& file);
// One line of a live control channel (`ibs run --control`, docs/scenarios.md "Control channel"):
// a JSON object that is a timeline entry without `at`, read and checked as the files' entries
// are, against the devices of `running`. Throws ScenarioError whose what() is
// `SOURCE:LINE: what is wrong` (`control:LINE`, or `control:CLIENT:LINE` for a socket's client:
// control::Origin::name). The entry's `at` is 0 (it applies when it arrives) and its
// source_line is `line`.
TimelineEntry parse_control_line(const std::string& text, std::size_t line, const Scenario& running,
                                 const std::string& source = "control");
// An entry as a control line (JSON, without `at`): parse_control_line reads it back equal.
std::string write_control_line(const TimelineEntry& e);
// Writes a valid scenario so that the parsers read it back equal (operator== below).
std::string write_scenario_toml(const Scenario& s);
std::string write_scenario_json(const Scenario& s);

// Equality of meaning: fields that do not apply are not compared (a drive's own setting compares
// as the drive reads it, its default when not given, and one its kind does not declare not at
// all; of an entry only the fields its action uses, never
// source_line), so every valid scenario survives
// a write/parse round trip equal.
bool operator==(const DeviceConfig& a, const DeviceConfig& b);
bool operator==(const TimelineEntry& a, const TimelineEntry& b);
bool operator==(const Scenario& a, const Scenario& b);

}  // namespace ibs::sim
