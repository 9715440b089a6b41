// `ibs canlust ...`: CDA3000 drives on a CANLust bus (docs/canlust.md, "Command line").
//
//   ibs canlust emulate  -p BUS [--cacnf N] [--watchdog-reaction R] [--factory] [--control SPEC] cda3000@ADDR...
//   ibs canlust start    -p BUS [--listen-ms MS]
//   ibs canlust stop     -p BUS [--listen-ms MS]
//   ibs canlust read     -p BUS -a ADDR PARAM [--repeat N] [--interval MS]
//   ibs canlust write    -p BUS -a ADDR PARAM VALUE
//   ibs canlust describe -p BUS -a ADDR PARAM
//   ibs canlust download -p BUS -a ADDR FILE
//   ibs canlust monitor  -p BUS [-f FILTER]... [-n COUNT] [-t a|d|z] [-T MS] [--duration-ms MS]
//   ibs canlust send     -p BUS ID#DATA
//   ibs canlust play     -p BUS FILE|-
//
// BUS (-p, --bus) is udp:LOCALPORT:HOST:PORT (CAN over UDP in cannelloni's format; LOCALPORT 0:
// any, PORT 0: whoever sends first) or socketcan:IFACE. Every command takes [--id-step N]
// [--cacnf N] [-j, --json] [--log FILE] (candump -l format) [--pcap FILE]
// (LINKTYPE_CAN_SOCKETCAN). monitor, send and play are can-utils' candump, cansend and canplayer
// with CANLust's words beside the frames (their text forms: can/can_text.hpp, can/candump.hpp).
// Exit codes: 0 ok, 1 the drive refused or did not answer (the decoded reason is printed), a frame
// was not sent; 2 bad input; 130 play interrupted.
// Floor 4: real time from the steady clock and real sockets around the sans-I/O machines of
// canlust/: the emulated drives are the registry's CANLust faces (devices/drives.hpp), found by
// the NAME of NAME@ADDR; the client commands read, write and explain in the CDA3000's table.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <iostream>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/can/transport.hpp"
#include "ibs/canlust/frame.hpp"
#include "ibs/devices/canlust_face.hpp"
#include "repeat.hpp"

namespace CLI {
class App;
}

namespace ibs::cli {

inline constexpr int kExitCanOk = 0;
inline constexpr int kExitCanDevice = 1;    // refused, timeout, bad reply
inline constexpr int kExitCanBadInput = 2;  // bad options, a bus that does not open
inline constexpr int kExitCanInterrupted = 130;  // play: SIGINT / SIGTERM before its last frame

class FrameRecorder;

struct CanBusOptions {
  std::string bus;
  unsigned id_step = 2;  // decision D1
  unsigned cacnf = 2;    // the drives' 492-CACNF: how control and status telegrams are laid out
  bool json = false;
  // Where `--log -` writes (standard output; run_canlust_commands sets the stream it was given).
  std::ostream* log_stdout = &std::cout;
  std::string log;   // candump -l log of every frame sent and received
  std::string pcap;  // the same frames as a pcap file
  // Where the recorder is kept when the readings of --repeat share one (one log, one capture):
  // made there by the first reading's bus, after its checks, and used by the rest (set by
  // run_canlust_commands). Null: each command records on its own.
  std::unique_ptr<FrameRecorder>* shared_recorder = nullptr;
};

struct CanlustEmulateOptions {
  CanBusOptions bus;
  std::vector<std::string> devices;  // cda3000@ADDR
  std::string watchdog_reaction = "disable-power";
  bool factory = false;  // factory settings (CLADR 0, CLSEL TERM): ADDR is the connector's, 0..7
  std::string control;   // live control channel: "-" or "unix:PATH" (ibs/control/channel.hpp); empty: none
};

struct CanlustClientOptions {
  CanBusOptions bus;
  int address = -1;
  std::string parameter;
  std::string value;
  int timeout_ms = 0;     // 0: 250 ms, strings 2 s, 150-SAVE / 04-PROG 2 s
  int listen_ms = 300;    // start / stop: how long to listen for the drives' answers
  int duration_ms = 0;    // monitor: 0 = until SIGINT / SIGTERM
  RepeatOptions repeat;   // read: --repeat N --interval MS
  std::vector<std::string> filters;  // monitor: candump's ID:MASK, ID~MASK, j; comma-separated or repeated
  unsigned count = 0;                // monitor: stop after COUNT frames shown (0: no limit)
  std::string timestamp = "z";       // monitor: a absolute, d delta, z since the first frame (candump -t)
  int idle_ms = 0;                   // monitor: stop after MS without a frame (candump -T; 0: never)
  std::string frame;                 // send: cansend's ID#DATA
  std::string file;                  // play: a candump log, "-" standard input
};

struct CanlustCommandState {
  CLI::App* canlust = nullptr;
  CLI::App* emulate = nullptr;
  CLI::App* start = nullptr;
  CLI::App* stop = nullptr;
  CLI::App* read = nullptr;
  CLI::App* write = nullptr;
  CLI::App* describe = nullptr;
  CLI::App* download = nullptr;
  CLI::App* monitor = nullptr;
  CLI::App* send = nullptr;
  CLI::App* play = nullptr;
  CanlustEmulateOptions emulate_options;
  CanlustClientOptions client_options;
};

void add_canlust_commands(CLI::App& app, CanlustCommandState& state);
// After app.parse(): runs the chosen one; nullopt when `canlust` was not chosen.
std::optional<int> run_canlust_commands(const CanlustCommandState& state);
std::optional<int> run_canlust_commands(const CanlustCommandState& state, std::ostream& out,
                                        std::ostream& err);

// ---- pieces, also for tests -----------------------------------------------------------------

// Opens BUS; throws std::invalid_argument saying what is wrong with it (or why it did not open).
std::unique_ptr<can::CanTransport> open_bus(const std::string& spec);

// Every frame sent or received, with the wall-clock time: a candump -l log (can/candump.hpp)
// and/or a pcap file.
class FrameRecorder {
 public:
  // Throws std::invalid_argument when a file does not open (or pcap is not built in).
  // `log` "-": the log goes to `log_stdout`.
  FrameRecorder(const std::string& log, const std::string& pcap, std::string interface_name,
                std::ostream* log_stdout = &std::cout);
  ~FrameRecorder();
  FrameRecorder(const FrameRecorder&) = delete;
  FrameRecorder& operator=(const FrameRecorder&) = delete;
  void record(const canlust::CanFrame& f, std::chrono::system_clock::time_point at);
  void record(const canlust::CanFrame& f) { record(f, std::chrono::system_clock::now()); }

 private:
  struct Files;
  std::unique_ptr<Files> files_;
};

// `ibs decode FILE` for a candump log: every frame explained; nullopt when FILE is not a candump
// log (the caller then reads it as a trace).
std::optional<int> decode_candump_log(const std::string& file, unsigned id_step, unsigned cacnf,
                                      std::ostream& out, std::ostream& err);

// The emulator's loop: `drives` (the registry's CANLust faces made them) on `bus`, each frame one
// drive sends delivered to the others as well (they share the bus); returns when stop() is true
// (asked at least every 20 ms).
// `each_turn(now)`, when given, runs once per turn of the loop (at least every 20 ms), on the
// loop's own thread: the control channel of `emulate --control` is read there.
// `watch`, when given, is told what the loop did as it happens (`emulate --json`).
struct ServeWatch {
  // A frame from the bus, once every drive has taken it.
  std::function<void(const canlust::CanFrame& f, Time now)> received;
  // Drive `i` has stepped to `now` (its state may have changed); then each frame it sent.
  std::function<void(std::size_t i, Time now)> stepped;
  std::function<void(std::size_t i, const canlust::CanFrame& f, Time now)> sent;
};
void serve_canlust(can::CanTransport& bus, std::span<devices::CanlustDrive* const> drives,
                   FrameRecorder* recorder, const std::function<bool()>& stop,
                   const std::function<void(Time now)>& each_turn = {}, const ServeWatch* watch = nullptr);

}  // namespace ibs::cli
