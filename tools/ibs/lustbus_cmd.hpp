// `ibs lustbus ...`: LUSTBUS (LUSTBUS manual) over a serial port (docs/lustbus.md, "Command line").
//
//   ibs lustbus emulate (--port PATH | --pty) [--baud N] [--SETTING...] [--control SPEC] DEVICE...
//                                                  DEVICE: vf1000@ADDR, mc6000@ADDR
//   ibs lustbus read     --port PATH --addr N --device vf1000|mc6000 PARAM
//   ibs lustbus write    --port PATH --addr N --device vf1000|mc6000 PARAM VALUE
//   ibs lustbus describe --port PATH --addr N --device vf1000|mc6000 PARAM
//   ibs lustbus scan     --port PATH
//   ibs lustbus download --port PATH --addr N FILE                      (MC6000, 11.4)
//
// with [--baud N] [--timeout-ms N] [--json] [--log FILE] [--pcap FILE]. 7E1 (2.1); RS-485 direction control
// (TIOCSRS485) is asked for and used where the port has it. PARAM is a number or a name; VALUE is
// in the parameter's engineering unit, or raw with a 0x prefix. Exit codes: 0 ok, 1 the device
// answered NAK (the 85-SIOF/SERR cause is printed) or not at all, 2 bad input. Floor 4: the
// steady clock and real ports around the sans-I/O Host, Receiver and the wings' Responders.
#pragma once

#include "repeat.hpp"

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "ibs/devices/lustbus_face.hpp"
#include "ibs/devices/settings.hpp"

#include "ibs/lustbus/host.hpp"
#include "ibs/serial/serial_port.hpp"

namespace CLI {
class App;
}

namespace ibs::cli {

inline constexpr int kExitLustbusOk = 0;
inline constexpr int kExitLustbusDevice = 1;    // NAK, no answer, a broken answer
inline constexpr int kExitLustbusBadInput = 2;  // bad options or values, a port that does not open

struct LustbusPortOptions {
  std::string port;
  std::uint32_t baud = 9600;
  std::string log;  // empty: no byte log; "-": standard output
  // For `--log -`: the stream the log goes to (the command's standard output, set by
  // run_lustbus_commands, which then prints the command's own output on standard error).
  std::ostream* log_stream = nullptr;
  // Where the byte log is kept when the readings of --repeat share one (one file, one header,
  // one time base): opened there by the first reading, after its checks, and used by the rest
  // (set by run_lustbus_commands). Null: each command opens its own.
  std::unique_ptr<serial::ByteLog>* shared_log = nullptr;
  std::string pcap;  // --pcap: empty none, "-" standard output (line_outputs.hpp)
  serial::ByteTap* tap = nullptr;  // the capture's, set on the port (run_lustbus_commands sets it)
};

struct LustbusEmulateOptions {
  LustbusPortOptions port;
  bool pty = false;
  std::string pty_link;  // --pty-link PATH: a stable link to the pty (implies --pty), removed at exit
  std::vector<std::string> devices;  // vf1000@ADDR, mc6000@ADDR
  // The drives' own settings given as options (--keypad, ...): one option per setting the
  // LUSTBUS faces declare (LustbusFace::settings); each drive takes those its face declares.
  devices::SettingValues settings;
  // 10: reaction times drawn from the drive's table (which a setting such as a KEYPAD may widen),
  // seeded (seed + address per drive); reaction_ms >= 0 fixes them instead.
  std::uint64_t seed = 1;
  int reaction_ms = -1;
  // A live control channel ("-", "unix:PATH"; empty: none): JSON lines of plant and fault events
  // for the drives (docs/lustbus.md, "Events on demand").
  std::string control;
  // --json: one JSON object a line per event (telegram in, answer out, corrupt telegram, fault)
  // instead of the text (emulate_events.hpp; docs/lustbus.md, "Events as JSON").
  bool json = false;
};

struct LustbusClientOptions {
  LustbusPortOptions port;
  int addr = -1;
  std::string device;  // vf1000 | mc6000
  std::string parameter;  // PARAM; download: FILE
  std::optional<std::string> value;
  int timeout_ms = 250;
  bool json = false;
  RepeatOptions repeat;  // read: --repeat N, --interval MS
};

struct LustbusCommandState {
  CLI::App* lustbus = nullptr;
  CLI::App* emulate = nullptr;
  CLI::App* read = nullptr;
  CLI::App* write = nullptr;
  CLI::App* describe = nullptr;
  CLI::App* scan = nullptr;
  CLI::App* download = nullptr;
  LustbusEmulateOptions emulate_options;
  LustbusClientOptions client_options;
};

void add_lustbus_commands(CLI::App& app, LustbusCommandState& state);
// After app.parse(): runs the chosen one; nullopt when `lustbus` was not chosen. `emulate` serves
// until SIGINT or SIGTERM and then returns 0.
std::optional<int> run_lustbus_commands(const LustbusCommandState& state);
std::optional<int> run_lustbus_commands(const LustbusCommandState& state, std::ostream& out,
                                        std::ostream& err);

// One drive `emulate` serves: its DEVICE text ("vf1000@1") and its LUSTBUS face.
struct ServedLustbusDrive {
  std::string spec;
  const devices::LustbusFace* face = nullptr;
};
// The drives' own settings given to `emulate`, drive by drive (in `served`'s order): each takes
// the ones its face declares (LustbusFace::settings). Throws std::invalid_argument for a setting
// none of the served faces declares ("--NAME applies to none of the drives served (...)"), one
// declared as another type, or a value outside a declaration's range (naming the drive).
std::vector<devices::SettingValues> lustbus_drive_settings(const devices::SettingValues& given,
                                                           std::span<const ServedLustbusDrive> served);

// The emulator serves its drives with serial::serve (transports/serial/serve.hpp) through
// lustbus::ServedReceiver; the host commands run their requests with serial::transact
// (transports/serial/lustbus_host.hpp). `ibs decode` of their byte logs and captures is
// serial_decode.hpp's.

}  // namespace ibs::cli
