// `ibs layout` and `ibs timing`: what a device puts on the bus and what the ring costs per cycle.
// Each command returns the process exit code (commands.hpp) and writes its report to `out`, its
// complaint to `err`; the one-argument forms use std::cout and std::cerr.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "ibs/base/time.hpp"
#include "ibs/devices/settings.hpp"

namespace CLI {
class App;
}

namespace ibs::cli {

// `ibs layout DEVICE [--SETTING VALUE...] [--bus local|remote] [--json]`, DEVICE a drive kind's
// name; the options are the settings the kinds declare as placing the device on the ring
// (devices/settings.hpp), and which of them a kind needs is its descriptor's.
struct LayoutOptions {
  std::string device;              // the drive kind's name
  devices::SettingValues settings;  // the --SETTING options given
  std::optional<std::string> bus;  // "local" or "remote" (default)
  bool json = false;
};

// `ibs timing [DEVICE...] [--baud 500k|2M] [--sw-us N] [--json]`, DEVICE = NAME[:FIELD...] as the
// drive kind takes it (`mc6000:SUPI[:local|remote]`, `vf1000`), in ring order; none = the default
// bus of `ibs run`.
struct TimingOptions {
  std::vector<std::string> devices;
  std::string baud = "500k";
  std::optional<double> software_time_us;  // SW; the formula's default 200 us when not given
  bool json = false;
};

// The ring `ibs timing` measures when no device is named: the default bus of `ibs run`.
std::vector<std::string> default_timing_ring();

int layout_command(const LayoutOptions& options, std::ostream& out, std::ostream& err);
int layout_command(const LayoutOptions& options);
int timing_command(const TimingOptions& options, std::ostream& out, std::ostream& err);
int timing_command(const TimingOptions& options);

// Exact decimal text of a duration, trailing zeros dropped: format_us(52750ns) = "52.75",
// format_ms(726000ns) = "0.726", format_ms(2ms) = "2".
std::string format_us(Duration d);
std::string format_ms(Duration d);
// The shortest text that reads back as the same double: "1.5", "263", "105.5".
std::string format_number(double v);

// The parsed command line of both subcommands; add_bus_commands() fills it in through CLI11.
struct BusCommandState {
  CLI::App* layout = nullptr;
  CLI::App* timing = nullptr;
  LayoutOptions layout_options;
  TimingOptions timing_options;
};

// Adds `layout` and `timing` to the app; `state` must outlive app.parse().
void add_bus_commands(CLI::App& app, BusCommandState& state);
// After app.parse(): runs the chosen one and returns its exit code, nullopt when neither was
// chosen.
std::optional<int> run_bus_commands(const BusCommandState& state);
std::optional<int> run_bus_commands(const BusCommandState& state, std::ostream& out,
                                    std::ostream& err);

}  // namespace ibs::cli
