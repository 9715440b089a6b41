// `ibs dfs1 ...`: the PowerTec DFS-1 over a serial port (docs/dfs1.md, "Command line").
//
//   ibs dfs1 emulate (--port PATH | --pty) [--baud N] [--control SPEC] dfs1@UID...
//   ibs dfs1 status --port PATH --uid N
//   ibs dfs1 read   --port PATH --uid N PARAM
//   ibs dfs1 write  --port PATH --uid N PARAM VALUE
//   ibs dfs1 speed  --port PATH --uid N [RPM] [--set | --execute]
//
// with [--baud N] [--framing 8N1] [--timeout-ms N] [--rs485] [--json] [--log FILE] [--pcap FILE]. Exit codes:
// 0 ok, 1 the device answered NAK or not at all (the decoded error is printed), 2 bad input.
// This is floor 4: real time from the steady clock, real ports; the protocol machines inside are
// the sans-I/O ones of dfs1/ and devices/dfs1/.
#pragma once

#include "repeat.hpp"

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/devices/dfs1/events.hpp"
#include "ibs/dfs1/host.hpp"
#include "ibs/serial/serial_port.hpp"

namespace CLI {
class App;
}

namespace ibs::cli {

inline constexpr int kExitDfs1Ok = 0;
inline constexpr int kExitDfs1Device = 1;    // NAK, timeout, bad response
inline constexpr int kExitDfs1BadInput = 2;  // bad options, a port that does not open

struct Dfs1PortOptions {
  std::string port;
  std::uint32_t baud = 9600;
  std::string framing = "8N1";  // decision D9: binary data needs 8 bits
  bool rs485 = false;
  std::string log;  // empty: no byte log; "-": standard output
  // For `--log -`: the stream the log goes to (the command's standard output, set by
  // run_dfs1_commands, which then prints the command's own output on standard error).
  std::ostream* log_stream = nullptr;
  // Where the byte log is kept when the readings of --repeat share one (one file, one header,
  // one time base): opened there by the first reading, after its checks, and used by the rest
  // (set by run_dfs1_commands). Null: each command opens its own.
  std::unique_ptr<serial::ByteLog>* shared_log = nullptr;
  std::string pcap;  // --pcap: empty none, "-" standard output (line_outputs.hpp)
  serial::ByteTap* tap = nullptr;  // the capture's, set on the port (run_dfs1_commands sets it)
};

struct Dfs1EmulateOptions {
  Dfs1PortOptions port;
  bool pty = false;
  std::string pty_link;  // --pty-link PATH: a stable link to the pty (implies --pty), removed at exit
  std::vector<std::string> devices;  // dfs1@UID
  std::string control;               // --control: "-" or "unix:PATH"; empty: none
  // --json: one JSON object a line per event (request in, reply out, corrupt frame, fault) instead
  // of the text (emulate_events.hpp; docs/dfs1.md, "Events as JSON").
  bool json = false;
};

struct Dfs1ClientOptions {
  Dfs1PortOptions port;
  int uid = -1;
  int timeout_ms = 200;  // response timeout; the inter-byte timeout is 20 ms
  bool json = false;
  std::optional<long long> parameter;  // read, write
  std::optional<long long> value;      // write; speed: RPM
  bool set_only = false;               // speed --set: 82
  bool execute_only = false;           // speed --execute: 83 (UID 0 allowed)
  RepeatOptions repeat;                // status, read: --repeat N, --interval MS
};

struct Dfs1CommandState {
  CLI::App* dfs1 = nullptr;
  CLI::App* emulate = nullptr;
  CLI::App* status = nullptr;
  CLI::App* read = nullptr;
  CLI::App* write = nullptr;
  CLI::App* speed = nullptr;
  Dfs1EmulateOptions emulate_options;
  Dfs1ClientOptions client_options;
};

// Adds `dfs1` and its subcommands to the app; `state` must outlive app.parse().
void add_dfs1_commands(CLI::App& app, Dfs1CommandState& state);
// After app.parse(): runs the chosen one and returns its exit code; nullopt when `dfs1` was not
// chosen. `emulate` serves until SIGINT or SIGTERM and then returns 0.
std::optional<int> run_dfs1_commands(const Dfs1CommandState& state);
std::optional<int> run_dfs1_commands(const Dfs1CommandState& state, std::ostream& out,
                                     std::ostream& err);

// One line of a DFS-1 control channel (docs/dfs1.md, "Faults on demand"): a JSON object whose
// keys devices::dfs1::parse_event() reads; `error` says what is wrong (not JSON, not an object, or
// the key and value). For `ibs dfs1 emulate --control` and any run that drives DFS-1 controllers.
devices::dfs1::ParsedControl parse_dfs1_control_line(std::string_view text);

// The emulator serves with serial::serve through devices::dfs1::ServedController; the client
// commands run their transaction with serial::transact (transports/serial/dfs1_host.hpp).

}  // namespace ibs::cli
