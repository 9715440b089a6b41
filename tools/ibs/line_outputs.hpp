// The outputs of `ibs lustbus` and `ibs dfs1` besides their report: the byte log of `--log FILE`
// (serial/byte_log.hpp, written as it comes) and the capture of `--pcap FILE` (serial/capture.hpp,
// docs/pcap.md "Serial lines"), and where a command's own report goes when one of them is `-`
// (standard output): to standard error. The capture follows the output rules of
// docs/robustness.md ("Output files", output_files.hpp): written under a temporary name and
// renamed into place at the command's end, never replacing what is not a regular file, a FIFO or
// `-` written through as it comes (a live capture: each telegram flushed).
#pragma once

#include <functional>
#include <iosfwd>
#include <memory>
#include <string>

#include "ibs/serial/byte_log.hpp"
#include "ibs/serial/capture.hpp"

namespace CLI {
class App;
}

namespace ibs::cli {

// --log FILE and --pcap FILE on a command of a serial line.
void add_line_output_options(CLI::App* cmd, std::string& log, std::string& pcap);

// The byte log of --log: none (empty `log`), the file, or for `-` `stdout_stream` (which must not
// be null then). Throws std::runtime_error naming the file when it cannot be opened.
std::unique_ptr<serial::ByteLog> open_byte_log(const std::string& log, std::ostream* stdout_stream);

struct LineOutputs {
  std::string log;   // --log: empty none, "-" standard output
  std::string pcap;  // --pcap: empty none, "-" standard output
  serial::LineProtocol protocol = serial::LineProtocol::lustbus;
  bool serves = false;  // an emulator: the host's bytes are the ones its port reads
  std::string who;      // "ibs lustbus read", for messages
  int bad_input = 2;    // the command's exit code for bad input
};

// Runs `command(tap, say)` with the capture of `o.pcap`: `tap` is what the command sets on its
// port (nullptr without --pcap), `say` where it prints its own report (standard error when --log
// or --pcap is `-`, else `out`); it returns its exit code, which is returned. The capture is
// kept when the command ends with anything but bad input -- a device that did not answer is what
// a capture is for -- and is not written (no file at all) after bad input, after an exception
// and when SIGINT or SIGTERM came while the command ran and it did not take the signal itself as
// its end (emulate and --repeat do): then the command says so and exits 130. A FILE that cannot
// be created is bad input before anything runs.
int run_with_line_outputs(const LineOutputs& o, std::ostream& out, std::ostream& err,
                          const std::function<int(serial::ByteTap* tap, std::ostream& say)>& command);

}  // namespace ibs::cli
