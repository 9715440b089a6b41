// The fault campaign (issue 9, docs/robustness.md "Fault campaign"): the simulator runs a ring of
// every drive kind the registry knows, each kind's devices as its campaign profile lays them out
// (devices/campaign_profile.hpp), with random faults from a seed -- corrupted cycles, power cycles,
// lost devices, device faults, master restarts, sample jitter, long outages for the watchdogs --
// during continuous parameter traffic and state commands on every device, and an oracle
// independent of the code under test checks every step:
//
// - a write reported successful is held by the device, and no device holds a value nobody wrote
//   (the store, RAM and EEPROM, against a model of the values master writes may have left there);
// - a read returns a value the model allows; out-of-range writes are never `written`;
// - every request ends within the documented timeout of its channel plus a margin, with an
//   outcome its operation can have;
// - no drive is ENABLED unless the master requested ENABLED after its last fault, power cycle or
//   master restart (and not during an open SLOAD download, LUSTBUS manual 11.4);
// - EMERGENCY STOP / BLOCK POWER (and every other withdrawal) has the drive out of ENABLED by
//   the device's first sample after the bus delivered the word;
// - the bus watchdogs trip neither before their time nor later than their time plus one sample
//   period after the last valid cycle.
//
// The oracle (`CampaignChecker`) takes plain observations, so tests can feed it wrong ones and see
// it report them; `run_campaign` feeds it from a `Simulator`.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ibs/devices/campaign_profile.hpp"
#include "ibs/devices/driver.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/base/time.hpp"
#include "ibs/sim/scenario.hpp"

namespace ibs::sim {

struct Violation {
  Time at{0};
  std::string device;
  std::string check;  // "store", "read", "outcome", "overdue", "enabled", "stop", "watchdog-early",
                      // "watchdog-late", "download-lock"
  std::string what;
};

// What a parameter is to the oracle, and its model (devices/campaign_profile.hpp: the drive's
// profile gives them from the manuals).
using ParamRole = devices::CampaignRole;
using ParamModelSpec = devices::CampaignParam;

struct CheckerDeviceSpec {
  std::string name;
  Duration period{0};  // sample period
  Duration jitter{0};
  bool has_pd = true;  // DRIVECOM through process data
  std::vector<ParamModelSpec> params;
  // The bus watchdog: a parameter whose raw value `watchdog_ms` turns into the monitoring time in
  // ms (0 or less: off; empty: the value is ms), or a fixed time for a device whose watchdog
  // cannot be changed. Neither: none.
  std::uint16_t watchdog_parameter = 0;
  std::function<std::int64_t(std::int64_t)> watchdog_ms;
  std::int64_t watchdog_fixed_ms = 0;
  // ParamRole::download: after its end the drive checks the dataset this long, and may stay
  // disabled meanwhile; how a violation names the download and the promise.
  Duration download_check{0};
  std::string download_label = "SLOAD";
  std::string download_source = "LUSTBUS manual 11.4: secured until it ends";
};

using StoreEntry = devices::CampaignStoreEntry;

enum class StateCommand : std::uint8_t { enable, other_target, emergency_stop, block_power };

struct CheckCounts {
  std::uint64_t store_checks = 0;   // parameter values compared with the model
  std::uint64_t read_checks = 0;
  std::uint64_t outcome_checks = 0;
  std::uint64_t deadline_checks = 0;
  std::uint64_t state_checks = 0;
  std::uint64_t stop_checks = 0;     // withdrawals whose deadline was checked
  std::uint64_t watchdog_trips = 0;  // trips checked against their time
  std::uint64_t watchdog_late_checks = 0;
};

// The oracle. Devices are added first; then every observation in time order.
class CampaignChecker {
 public:
  std::size_t add_device(CheckerDeviceSpec spec);
  [[nodiscard]] std::size_t device_count() const { return devices_.size(); }

  // Parameter traffic: one outstanding request per device. `limit`: the time it must end in.
  void submitted(std::size_t dev, devices::ParamOp op, std::uint16_t number, std::int64_t value, Time now,
                 Duration limit);
  void ended(std::size_t dev, devices::ParamKind kind, std::int64_t value, Time now);
  [[nodiscard]] bool outstanding(std::size_t dev) const { return devices_[dev].out.has_value(); }
  // Requests past their limit (reported once each).
  void check_overdue(Time now);
  // The device's parameter store now.
  void check_store(std::size_t dev, Time now, const std::vector<StoreEntry>& store);
  // Somebody set a value directly on the device (the technician restoring a layout parameter).
  void set_value(std::size_t dev, std::uint16_t number, std::int64_t value);

  // Faults and commands.
  // state_then: the drive's state before (a power cycle during NOT READY joins the initialisation
  // the master already sees; nullopt: unknown, counts as a new power cycle).
  void power_cycle(std::size_t dev, Time now, std::optional<drivecom::State> state_then = std::nullopt);
  void device_fault(std::size_t dev, Time now, std::optional<drivecom::State> state_then);
  // A boot the master asked for (a reset from FAULT, CampaignProfile::software_resets): its
  // parameters and its watchdog as after a power cycle.
  void software_reset(std::size_t dev, Time now);
  void master_restart(Time now);
  void state_command(std::size_t dev, StateCommand c, Time now);
  // The master's cycle at `t` ran (its words go out at the next exchange).
  void master_cycle(Time t);
  // The exchange at `t`: did the master's words reach the device, and did the bus feed its
  // watchdog (a valid cycle without module error)?
  void exchange(std::size_t dev, Time t, bool words_delivered, bool watchdog_fed);
  // The device as it is after the samples up to `t`: its state, whether its bus watchdog has
  // tripped (DeviceEmulator::watchdog_tripped) and whether that made a device fault (its
  // error_number()).
  void observe(std::size_t dev, Time t, drivecom::State state, bool watchdog_tripped, bool watchdog_fault);

  // A check made outside the oracle (e.g. the layout after a power-on with changed layout
  // parameters).
  void report(std::size_t dev, Time at, std::string check, std::string what);
  // The values the model allows for a parameter now (RAM, or the EEPROM copy).
  [[nodiscard]] std::vector<std::int64_t> possible(std::size_t dev, std::uint16_t number, bool eeprom) const;

  [[nodiscard]] const std::vector<Violation>& violations() const { return violations_; }
  [[nodiscard]] std::uint64_t violation_count() const { return violation_count_; }
  [[nodiscard]] const CheckCounts& counts() const { return counts_; }
  // A download (SLOAD = -1 .. 0) is open on the device, as far as the master knows.
  [[nodiscard]] bool download_open(std::size_t dev) const { return devices_[dev].download_open; }
  std::size_t max_violations_kept = 1000;

 private:
  struct Cell {
    ParamModelSpec spec;
    std::vector<std::int64_t> ram;     // values the RAM may hold
    std::vector<std::int64_t> eeprom;  // values the EEPROM copy may hold
    std::optional<Time> settle_at;     // then RAM/EEPROM become `settle`
    std::int64_t settle = 0;
    bool settle_ram = false;
    std::optional<std::int64_t> reported_ram, reported_eeprom;  // a wrong value already reported
  };
  struct Outstanding {
    devices::ParamOp op = devices::ParamOp::read;
    std::uint16_t number = 0;
    std::int64_t value = 0;
    Time submitted{0};
    Time deadline{0};
    bool overdue_reported = false;
    bool disturbed = false;              // a power cycle or factory reset happened meanwhile
    std::vector<std::int64_t> allowed;   // read: values the RAM held during the request
  };
  struct Dev {
    CheckerDeviceSpec spec;
    std::vector<Cell> cells;
    std::optional<Outstanding> out;
    // State.
    bool permitted = false;  // the last state command asked for ENABLED, no fault since
    std::optional<Time> written_after;  // a withdrawal goes out with the master cycle after this
    std::optional<Time> word_out;       // ... the master wrote it then; delivered at the next exchange
    std::optional<Time> leave_by;       // the drive must be out of ENABLED from here on
    std::string leave_why;
    bool enabled_reported = false;
    bool download_open = false;
    // SLOAD = -2 confirmed: the servo may free the drive from this time on (its dataset check
    // ends download_check after it executed the write, which happened after the submission).
    std::optional<Time> lock_may_end;
    // Watchdog.
    bool armed = false;
    std::optional<Time> last_fed;
    std::optional<Time> fed_before_slice;
    bool tripped = false;
    bool watchdog_fault = false;
    bool late_reported = false;
    bool lock_reported = false;
    std::optional<drivecom::State> last_state;  // at the previous observation
    // Switched off and on in a fault state: the first state after the self-test decides (power_cycle()).
    std::optional<Time> boot_from_fault;
  };

  Cell* cell(Dev& d, std::uint16_t number);
  [[nodiscard]] std::vector<std::int64_t> allowed_now(const Dev& d, const Cell& c, bool eeprom) const;
  void violation(const Dev& d, Time at, std::string check, std::string what);
  void withdraw(Dev& d, Time t, const std::string& why, bool via_master);
  void factory_reset(Dev& d, bool certain);
  void settle(Dev& d, Time now);
  void reboot_store(Dev& d, Time now);  // a boot: RAM from EEPROM or factory values
  [[nodiscard]] std::pair<std::int64_t, std::int64_t> watchdog_window(const Dev& d) const;  // ms: min, max; -1 off

  std::vector<Dev> devices_;
  std::vector<Violation> violations_;
  std::uint64_t violation_count_ = 0;
  CheckCounts counts_;
};

struct CampaignOptions {
  std::uint64_t seed = 1;
  std::uint64_t transactions = 100000;  // parameter transactions to complete
  // Whether the master may request ENABLED while an SLOAD download it started is open. A
  // master following LUSTBUS manual 11.4 does not (the default); true probes the servo's promise to stay
  // "secured against being engaged until the download has ended".
  bool enable_during_download = false;
  // Called about every simulated 10 s with the transactions done so far.
  std::function<void(std::uint64_t transactions, Time simulated)> progress;
};

struct CampaignResult {
  std::uint64_t seed = 0;
  Duration simulated{0};
  double wall_seconds = 0.0;
  Duration cycle_time{0};
  std::vector<std::string> devices;  // "name: " and the profile's description, phase, jitter
  std::uint64_t transactions = 0;
  std::map<std::string, std::uint64_t> transactions_by;  // "read value", "write nak", ...
  std::map<std::string, std::uint64_t> special;          // scripted sequences: "80-SLOAD downloads", ...
  std::uint64_t state_commands = 0;
  std::map<std::string, std::uint64_t> state_commands_by;
  std::map<std::string, std::uint64_t> faults;  // per kind, as the simulator records them
  CheckCounts checks;
  std::uint64_t violation_count = 0;
  std::vector<Violation> violations;  // the first ones (at most 1000)
};

// Runs a campaign; deterministic for a seed.
CampaignResult run_campaign(const CampaignOptions& options);

}  // namespace ibs::sim
