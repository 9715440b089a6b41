// The `ibs` subcommands. Each returns the process exit code.
#pragma once

#include "progress.hpp"

#include <cstdint>
#include <string>

namespace ibs::cli {

// Exit codes shared by all subcommands.
inline constexpr int kExitOk = 0;
inline constexpr int kExitMismatch = 1;  // replay: a row did not match
inline constexpr int kExitBadInput = 2;  // malformed file, bad option, refused configuration
inline constexpr int kExitInterrupted = 130;  // run: SIGINT / SIGTERM; nothing written (128 + SIGINT)

struct RunOptions {
  std::string scenario;   // empty: the built-in default scenario; "-": standard input
  std::string format;     // --format toml|json: the scenario's format (required for "-")
  bool json = false;
  std::string trace_dir;  // empty: no traces
  std::string vcd_file;   // empty: no VCD (else also FILE.states.txt and FILE.gtkw)
  std::string pcap_file;  // empty: no capture for Wireshark (docs/pcap.md)
  std::string lustbus_pcap;  // the test bench's [lustbus] line as a capture (docs/pcap.md, "Serial lines")
  std::string dfs1_pcap;     // the test bench's [dfs1] line as a capture
  std::string plot_file;  // empty: no plot; FILE.svg or FILE.png through gnuplot
  unsigned threads = 1;   // device-stepping threads (sim::SimOptions::threads): 0 = automatic
  bool realtime = false;  // the master paced at the bus cycle in real time (sim/realtime.hpp)
  int rt_priority = 0;    // with realtime: SCHED_FIFO priority 1..99 and mlockall
  std::string control;    // with realtime: the live control channel ("-", "unix:PATH"); empty: none
  std::string stats_every;  // with realtime: a time ("60 s"): one `ibs-stats:` line on stderr each; empty: none
  ProgressOptions progress;  // -q, --progress (progress.hpp)
};

// `ibs master --board NODE [SCENARIO] [--json] [--duration S]` (docs/board.md).
struct MasterOptions {
  std::string board;        // the board without the node suffix: IBB1N1, IBETH01N1
  std::string scenario;     // empty: the built-in default scenario
  bool json = false;
  double duration_s = 0.0;  // > 0: run this long instead of the scenario's duration
};

struct CampaignOptions {
  std::uint64_t seed = 1;
  std::uint64_t transactions = 100000;
  bool json = false;
  bool enable_during_download = false;
  ProgressOptions progress;  // -q, --progress (progress.hpp)
};

// `pcap_file` (may be empty): the replay as a capture for Wireshark, a ring of one (docs/pcap.md).
// `json`: the result as one JSON object on one line (docs/replay.md) instead of the text.
int replay(const std::string& emulate, const std::string& file, const std::string& pcap_file = "", bool json = false);
// `json`: one JSON object per file on one line (trace_input.hpp) instead of the decoded trace.
int decode(const std::string& file, bool json = false);
int run(const RunOptions& options);
// A scenario's master side against a controller board: 0 ok, 2 bad input or a DDI error, 130 interrupted.
int master(const MasterOptions& options);
// The fault campaign (sim/campaign.hpp): exit 1 when a check failed.
int campaign(const CampaignOptions& options);

}  // namespace ibs::cli
