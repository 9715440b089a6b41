// `ibs run` with a CANLust bus (CANLust manual; docs/scenarios.md, "A CANLust bus"): CDA3000 drives on
// the in-process virtual CAN bus (bit timing, arbitration, bus load) under the wing's master
// driver, in simulated time. A scenario file says `protocol = "canlust"` in its [bus] table; the
// same document reader as the INTERBUS scenarios reads it (TOML or JSON, every key and value with
// its line), so errors name file:line the same way.
//
//   name = "two conveyors"
//   duration = "3 s"
//   [bus]
//   protocol = "canlust"
//   bitrate = 500000            # 489-CLBDR, 25000..500000
//   id_step = 2                 # CAN-E1 / D1
//   control_period = "50 ms"    # the driver's least control telegram rate (D30)
//   [[device]]
//   name = "left"
//   type = "cda3000"
//   address = 1                 # 571-CLADR
//   cacnf = 2                   # 492-CACNF, 1..3
//   watchdog_ms = 100           # 574-CAWDG, 0 = off
//   status_ms = 80              # 575-CASCY
//   power_on = "0 s"
//   [[timeline]]
//   at = "0.2 s"
//   system = "start"            # or "stop"
//   [[timeline]] at / device / state = "enabled"      (a DRIVECOM target)
//   [[timeline]] at / device / easydrive = 1          (EasyDrive bits, cacnf = 4)
//   [[timeline]] at / device / reference_hz = 20.5
//   [[timeline]] at / device / read = 575   |  write = 575 + value = "10"
//   [[timeline]] at / device / fault = "mains_reset" | "mains_off" | "mains_on"
//   [[timeline]] at / fault = "master_silent" + duration = "300 ms"   (no master frame: the
//                                                watchdogs of 574-CAWDG trip)
//   [[timeline]] at / device / fault = "device" + cause = "E-OTI"   (the drive's error, by name or number)
//   [[timeline]] at / device / mains = "off" | "on"
//   [[timeline]] at / device / load = 80           (load torque, % of the rated torque)
//   [[timeline]] at / device / input = "ENPO" + level = "low" | "high"
//
// With `bus = "udp:LOCALPORT:HOST:PORT"` or `"socketcan:IFACE"` in [bus], the drives are served
// on that transport in real time (`run_realtime`) for the user's own master: the timeline then
// holds drive events only (faults, mains, load, inputs).
//
// The run allocates as it records (a simulation, not the cycle path); the driver's cycle and the
// drives stay allocation-free as they are.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ibs/devices/canlust_face.hpp"
#include "ibs/drivecom/sequencer.hpp"
#include "ibs/base/time.hpp"

namespace ibs::sim::canlust {

struct DriveSpec {
  std::string name;
  std::string kind;  // the scenario's `type`: the drive's name in the registry
  std::uint8_t address = 1;
  std::uint8_t cacnf = 2;  // 1..3 DRIVECOM, 4 EasyDrive
  std::uint16_t watchdog_ms = 0;
  std::uint16_t status_ms = 80;
  Time power_on{};
  std::size_t line = 0;
};

enum class Action : std::uint8_t {
  start, stop, state, easydrive, reference, read, write, mains_reset, mains_off, mains_on, master_silent,
  device_fault, load, input,
};
std::string_view to_string(Action a);
// true for what only the scenario's own master does (System Start / Stop, states, references,
// parameters, master_silent): refused with a served bus, where the user's master drives.
bool is_master_command(Action a);

struct Entry {
  Time at{};
  Action action = Action::start;
  std::string device;  // empty for start, stop, master_silent
  drivecom::Target target = drivecom::Target::enabled;
  std::uint16_t bits = 0;  // easydrive: the direct-control bits (492-CACNF = 4)
  double hz = 0.0;
  std::uint16_t parameter = 0;
  std::string value;    // write: as `ibs canlust write` takes it ("10", "OPTN2", "20.5")
  Duration duration{};  // master_silent
  std::string cause;    // device_fault: the drive's error as given ("E-OTI", "8")
  double load = 0.0;    // load: % of the rated torque
  std::string input;    // input: the terminal ("ENPO")
  bool level = false;   // input: high
  std::size_t line = 0;
};
// The drive's event an entry stands for (device_fault, mains_*, load, input).
devices::CanlustEvent event_of(const Entry& e);

struct Scenario {
  std::string name;
  Duration duration = std::chrono::seconds(2);
  std::uint32_t bitrate = 500'000;
  std::uint16_t id_step = 2;
  Duration control_period = std::chrono::milliseconds(50);
  std::vector<DriveSpec> drives;
  std::vector<Entry> timeline;
  // [bus] bus: "" the virtual bus with the scenario's master; "udp:LOCALPORT:HOST:PORT" or
  // "socketcan:IFACE": the drives served there in real time for the user's own master.
  std::string bus;
  std::size_t bus_line = 0;
};

// Reads and checks a CANLust scenario; throws sim::ScenarioError naming file:line. `ibs run` reads
// a file of either bus through sim::load_any_scenario (scenario_file.hpp).
Scenario load_scenario(const std::string& path);
Scenario parse_scenario(const std::string& text, const std::string& file, bool json);
// One line of a live control channel (`ibs run --control`): a JSON object, a timeline entry
// without `at`, checked as the file's entries are; throws sim::ScenarioError(source, number, ...)
// (source: `control`, or `control:CLIENT` for a socket's client, control::Origin::name).
Entry parse_control_entry(const Scenario& s, const std::string& line, std::size_t number,
                          const std::string& source = "control");

// What a run shows.
struct StateChange {
  Time at{};
  std::string state;  // DRIVECOM state name
};
struct DriveResult {
  std::string name;
  std::string kind;
  std::uint8_t address = 0;
  std::optional<Time> logon;         // the first logon frame
  std::optional<Time> started;       // when the drive executed System Start
  std::string system_state;          // at the end
  std::string state;                 // DRIVECOM, at the end (inside the drive, EasyDrive too)
  std::string status;                // the last status word the master received, explained
  double actual_hz = 0.0;
  double reference_hz = 0.0;
  std::uint32_t watchdog_trips = 0;
  std::uint32_t errors = 0;          // error telegrams the master received from it
  std::vector<StateChange> states;   // every DRIVECOM state change
  // A served bus (the user's master): frames for this drive received from the bus (its own
  // identifiers and the System broadcast) and frames it sent.
  std::uint64_t frames_received = 0;
  std::uint64_t frames_sent = 0;
};
struct EntryResult {
  Time at{};
  std::string device;   // empty for the whole bus
  std::string type;     // "command", "parameter" or "fault", as the run summary's events
  std::string what;     // "left: read 575-CASCY"
  std::string outcome;  // "80 ms", "refused: ...", "ok"
  bool ok = true;
};
struct Report {
  std::string name;
  Duration duration{};
  std::uint32_t bitrate = 0;
  std::uint64_t frames = 0;
  std::uint64_t bits = 0;
  std::uint64_t stuff_bits = 0;
  std::uint64_t arbitration_losses = 0;
  std::uint64_t overflows = 0;
  double load = 0.0;       // over the whole run
  double peak_load = 0.0;  // the busiest 100 ms window
  std::optional<Duration> start_spread;  // last minus first drive executing System Start
  std::vector<DriveResult> drives;
  std::vector<EntryResult> entries;
  double wall_seconds = 0.0;  // the host's time for the run
  // run_realtime only.
  struct Realtime {
    std::string served;     // "canlust udp: 29800" / "canlust socketcan: can0"; empty: the virtual bus
    Duration step{};        // the pacing step
    std::uint64_t cycles = 0;
    std::uint64_t overruns = 0;        // steps whose work ended after the next deadline
    Duration worst_overrun{};
    std::optional<Time> first_overrun;
    std::uint64_t bus_errors = 0;      // sends or receives the transport refused
  };
  std::optional<Realtime> realtime;
};

// Runs the scenario; with `pcap_path`, every frame on the bus goes to that capture
// (LINKTYPE_CAN_SOCKETCAN, docs/canlust.md), written there directly and closed at the end -- the
// caller makes it all or nothing (`ibs run` writes a temporary and renames it into place) --
// throws std::runtime_error when it cannot be written.
Report run(const Scenario& s, const std::string& pcap_path = "");

// `ibs run --realtime`: the same run paced in real time, step by step at absolute deadlines
// (CLOCK_MONOTONIC), so that entries from a live control channel can come in between; with
// `s.bus` the drives are served on that transport for the user's master instead (no virtual bus,
// no master of the scenario's). Control entries are applied at the time they are handed over and
// listed with the timeline's. Throws std::runtime_error when the bus does not open.
struct RealtimeOptions {
  Duration step = std::chrono::milliseconds(1);  // D37: the drives' time base (574, 575 in ms)
  // Called once the bus is open, before the first deadline: "canlust udp: 29800" (the port bound).
  std::function<void(const std::string& line)> ready;
  // Called after each step's work with the time reached: entries to apply at once go into `out`.
  std::function<void(Time now, std::vector<Entry>& out)> each_step;
  // Asked every step; true ends the run there.
  std::function<bool()> stop;
};
Report run_realtime(const Scenario& s, const RealtimeOptions& o, const std::string& pcap_path = "");
std::string format_text(const Report& r);
// The run summary of docs/scenarios.md, "Run summary (JSON)": the same schema as an INTERBUS run.
std::string format_json(const Report& r);

}  // namespace ibs::sim::canlust
