#include "line_outputs.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "ibs/dfs1/capture_framer.hpp"
#include "ibs/lustbus/capture_framer.hpp"
#include "output_files.hpp"
#include "stop_signals.hpp"

namespace ibs::cli {

void add_line_output_options(CLI::App* cmd, std::string& log, std::string& pcap) {
  cmd->add_option("--log", log,
                  "write every byte with time and direction to FILE; - writes them to standard output (and what "
                  "the command prints to standard error)");
  cmd->add_option("--pcap", pcap,
                  "write every telegram with its direction and time to FILE as a pcap capture for Wireshark "
                  "(tools/wireshark, docs/pcap.md); - writes it to standard output as it comes");
}

std::unique_ptr<serial::ByteLog> open_byte_log(const std::string& log, std::ostream* stdout_stream) {
  if (log.empty()) return nullptr;
  if (log == "-" && stdout_stream != nullptr) return std::make_unique<serial::ByteLog>(*stdout_stream);
  return std::make_unique<serial::ByteLog>(log);
}

namespace {

std::unique_ptr<base::TelegramFramer> make_framer(serial::LineProtocol p) {
  if (p == serial::LineProtocol::lustbus) return std::make_unique<lustbus::CaptureFramer>();
  return std::make_unique<dfs1::CaptureFramer>();
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  return std::filesystem::weakly_canonical(a, ec) == std::filesystem::weakly_canonical(b, ec);
}

}  // namespace

int run_with_line_outputs(const LineOutputs& o, std::ostream& out, std::ostream& err,
                          const std::function<int(serial::ByteTap* tap, std::ostream& say)>& command) {
  if (o.log == "-" && o.pcap == "-") {
    err << o.who << ": --log - and --pcap - both ask for standard output; give one of them a file\n";
    return o.bad_input;
  }
  if (!o.log.empty() && !o.pcap.empty() && o.log != "-" && o.pcap != "-" && same_file(o.log, o.pcap)) {
    err << o.who << ": --log " << o.log << " and --pcap " << o.pcap << " are the same file; nothing was written\n";
    return o.bad_input;
  }
  std::ostream& say = o.log == "-" || o.pcap == "-" ? err : out;
  if (o.pcap.empty()) return command(nullptr, say);
  if (o.pcap == "-" && &out == &std::cout && ::isatty(STDOUT_FILENO) != 0) {
    err << o.who << ": --pcap -: standard output is a terminal; pipe the capture on (| tshark -r -) or give a file\n";
    return o.bad_input;
  }
  // Blocked while the command runs: an interrupt ends it at its next look (a host command's
  // request runs to its end, bounded by its timeouts) and leaves no capture.
  StopSignals signals;
  OutputFiles files;
  std::string error;
  std::ostream* stream = o.pcap == "-" ? &out : files.open(o.pcap, error);
  if (stream == nullptr) {
    err << o.who << ": --pcap " << error << "\n";
    return o.bad_input;
  }
  std::error_code ec;
  const bool live = o.pcap == "-" || std::filesystem::is_fifo(o.pcap, ec);
  const auto framer = make_framer(o.protocol);
  std::optional<serial::LineCapture> capture;
  try {
    capture.emplace(*stream, o.protocol, *framer, o.serves ? serial::Direction::rx : serial::Direction::tx,
                    pcap::wall_clock_epoch(), std::function<Time()>{}, live);
  } catch (const pcap::PcapError& e) {
    err << o.who << ": --pcap " << o.pcap << ": " << e.what() << "\n";
    return o.bad_input;
  }
  const int rc = command(&*capture, say);
  if (rc == o.bad_input) return rc;
  if (signals.raised()) {
    err << o.who << ": interrupted by a signal; no capture was written\n";
    return kExitInterrupted;
  }
  try {
    capture->finish();
  } catch (const pcap::PcapError& e) {
    err << o.who << ": --pcap " << o.pcap << ": " << e.what() << "; nothing was written\n";
    return o.bad_input;
  }
  if (!files.commit(error)) {
    err << o.who << ": --pcap " << error << "\n";
    return o.bad_input;
  }
  return rc;
}

}  // namespace ibs::cli
