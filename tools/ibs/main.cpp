// ibs: the command line of the INTERBUS-S stack and simulator.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

#include "bus_commands.hpp"
#include "canlust_cmd.hpp"
#include "dfs1_cmd.hpp"
#include "help.hpp"
#include "lustbus_cmd.hpp"
#include "serial_decode.hpp"
#include "reference.hpp"
#include "commands.hpp"
#include "trace_input.hpp"

namespace {

// CLI11 turns "-1" given to an unsigned option into 2^64 - 1 and saturates a number too large
// for it: `--seed -1` and `--seed 18446744073709551616` both ran seed 18446744073709551615 and
// exited 0 (issue 23, defect 13). An unsigned option takes decimal digits whose value fits.
CLI::Validator unsigned_decimal(std::uint64_t max) {
  return CLI::Validator(
      [max](std::string& text) -> std::string {
        if (text.empty() || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
          return "expects a non-negative decimal integer, not '" + text + "'";
        }
        errno = 0;
        const unsigned long long v = std::strtoull(text.c_str(), nullptr, 10);
        if (errno == ERANGE || v > max) return "'" + text + "' is larger than the limit " + std::to_string(max);
        return {};
      },
      "UINT");
}

int run_ibs(int argc, char** argv) {
  // Named "ibs" whatever path started it: usage lines show the command a user types.
  CLI::App app{"ibs: LUST drives (VF1000, MC6000, CDA3000) and the PowerTec DFS-1 on INTERBUS-S, LUSTBUS, CANLust and the DFS-1 link: masters, emulated drives, the INTERBUS cycle simulator",
               "ibs"};
  // `ibs --version`: the project's version from CMake (project(ibs VERSION ...)).
  app.set_version_flag("-V,--version", std::string("ibs ") + IBS_VERSION);
  app.require_subcommand(1);

  ibs::cli::RunOptions run_options;
  auto* run = app.add_subcommand(
      "run", "simulate a bus: the built-in default (an MC6000 and a VF1000 brought up, run and stopped) or a scenario file");
  run->add_option("SCENARIO", run_options.scenario, "a scenario file (.toml or .json, docs/scenarios.md); - reads it from standard input (with --format)");
  run->add_option("--format", run_options.format, "the scenario's format, toml or json: required for -, else the file's extension gives it")
      ->check(CLI::IsMember({"toml", "json"}));
  run->add_flag("-j,--json", run_options.json, "print the summary as JSON");
  run->add_flag("-q,--quiet", run_options.progress.quiet, "no progress on standard error");
  run->add_flag("--progress", run_options.progress.always,
                "progress on standard error every second, as lines, even where it is not a terminal");
  run->add_option("--trace", run_options.trace_dir, "write one ibs-trace 1 file per device into this directory; - writes the one trace of a "
                  "one-device run to standard output");
  run->add_option("--vcd", run_options.vcd_file,
                  "write the run as a VCD file for gtkwave, with FILE.gtkw to open it ready to read");
  run->add_option("--pcap", run_options.pcap_file,
                  "write every bus cycle to a pcap file for Wireshark (tools/wireshark/interbus.lua)");
  run->add_option("--lustbus-pcap", run_options.lustbus_pcap,
                  "with --realtime and [lustbus]: write every telegram of the served line to a pcap file (tools/wireshark/lustbus.lua)");
  run->add_option("--dfs1-pcap", run_options.dfs1_pcap,
                  "with --realtime and [dfs1]: write every frame of the served line to a pcap file (tools/wireshark/dfs1.lua)");
  run->add_option("--plot", run_options.plot_file,
                  "draw each drive's reference, actual value and state over time, faults and parameter "
                  "transactions marked, as FILE.svg or FILE.png (needs gnuplot)");
  run->add_option("--threads", run_options.threads,
                  "threads that step the devices, 0..256 (the run is the same for any number; 0: one per "
                  "core as far as the ring has work for them)")
      ->check(CLI::Range(0U, 256U))
      ->default_val(1U);
  run->add_flag("--realtime", run_options.realtime,
                "pace the master cycle at the bus cycle time in real time (clock_nanosleep); report "
                "wake-up latency, processing time and overruns");
  run->add_option("--rt-priority", run_options.rt_priority,
                  "with --realtime: SCHED_FIFO at this priority (1..99) and memory locked (mlockall); "
                  "refusals are noted and the run goes on")
      ->check(CLI::Range(1, 99));
  run->add_option("--control", run_options.control,
                  "with --realtime: a live control channel, '-' (standard input) or unix:PATH, of JSON "
                  "lines, each a timeline entry without 'at' applied at once (docs/scenarios.md)");
  run->add_option("--stats-every", run_options.stats_every,
                  "with --realtime: every TIME (\"60 s\") one line 'ibs-stats: {JSON}' on standard error: "
                  "wake-up latency, overruns and every counter since the last (docs/robustness.md, \"Soak\")");

  ibs::cli::MasterOptions master_options;
  auto* master = app.add_subcommand(
      "master", "run a scenario's master side (its commands and parameter requests) in real time against an INTERBUS "
                "controller board through the DDI; prints the summary of ibs run (docs/board.md)");
  master->add_option("--board", master_options.board,
                     "the board, without the node suffix: IBB1N1 (ISA and PCI boards), IBETH01N1 (Ethernet controllers)")
      ->required();
  master->add_option("SCENARIO", master_options.scenario,
                     "a scenario file (.toml or .json, docs/scenarios.md); without one the default of ibs run");
  master->add_flag("-j,--json", master_options.json, "print the summary as JSON");
  master->add_option("--duration", master_options.duration_s, "run this many seconds instead of the scenario's duration")
      ->check(CLI::Range(0.001, 86400.0));

  std::string emulate;
  std::vector<std::string> replay_files;
  auto* replay = app.add_subcommand(
      "replay", "replay an ibs-trace 1 file against the emulated device or master side");
  replay->add_option("--emulate", emulate, "which side the project emulates: device or master")
      ->required()
      ->check(CLI::IsMember({"device", "master"}));
  replay->add_option("FILE", replay_files, "the trace files; - reads one from standard input")->required();
  std::string replay_pcap;
  replay->add_option("--pcap", replay_pcap, "write every replayed step to a pcap file for Wireshark");
  bool replay_json = false;
  replay->add_flag("-j,--json", replay_json,
                   "one JSON object per file, each on one line, with its mismatch (docs/replay.md)");

  std::vector<std::string> decode_files;
  bool decode_json = false;
  unsigned decode_id_step = 2;
  unsigned decode_cacnf = 2;
  auto* decode = app.add_subcommand(
      "decode", "print a trace with every word explained in the remark, a CANLust candump log with every frame explained, or a LUSTBUS byte log (--log) or LUSTBUS / DFS-1 capture (--pcap) telegram by telegram");
  decode->add_option("FILE", decode_files, "trace files, candump -l logs, byte logs of --log or captures of --pcap; - reads a trace from standard input")
      ->required();
  decode->add_flag("-j,--json", decode_json, "traces: one JSON object per file, each on one line (docs/replay.md)");
  decode->add_option("--id-step", decode_id_step, "candump log: CANLust identifier step (default 2)")
      ->check(unsigned_decimal(std::numeric_limits<unsigned>::max()));
  decode->add_option("--cacnf", decode_cacnf, "candump log: the drives' 492-CACNF (default 2)")
      ->check(unsigned_decimal(std::numeric_limits<unsigned>::max()));

  ibs::cli::CampaignOptions campaign_options;
  auto* campaign = app.add_subcommand(
      "campaign", "the fault campaign: random faults during parameter traffic and state commands, every step checked");
  campaign->add_option("--seed", campaign_options.seed, "the random seed (default 1)")
      ->check(unsigned_decimal(std::numeric_limits<std::uint64_t>::max()));
  campaign->add_option("--transactions", campaign_options.transactions,
                       "parameter transactions to run, 1..100000000 (default 100000)")
      ->check(unsigned_decimal(std::numeric_limits<std::uint64_t>::max()))
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{100000000}));
  campaign->add_flag("-j,--json", campaign_options.json, "print the result as JSON");
  campaign->add_flag("-q,--quiet", campaign_options.progress.quiet, "no progress on standard error");
  campaign->add_flag("--progress", campaign_options.progress.always,
                     "progress on standard error every second, as lines, even where it is not a terminal");
  campaign->add_flag("--enable-during-download", campaign_options.enable_during_download,
                     "also request ENABLED while an 80-SLOAD download is open (the servo must refuse)");

  ibs::cli::BusCommandState bus_state;
  ibs::cli::add_bus_commands(app, bus_state);
  ibs::cli::Dfs1CommandState dfs1_state;
  ibs::cli::add_dfs1_commands(app, dfs1_state);
  ibs::cli::LustbusCommandState lustbus_state;
  ibs::cli::add_lustbus_commands(app, lustbus_state);
  ibs::cli::CanlustCommandState canlust_state;
  ibs::cli::add_canlust_commands(app, canlust_state);

  std::string completion_shell;
  auto* completion = app.add_subcommand("completion", "print the shell completion script for ibs (bash)");
  completion->add_option("SHELL", completion_shell, "bash")->required()->check(CLI::IsMember({"bash"}));
  // Hidden (group ""): docs/cli.md and the man page's COMMANDS section, from this same tree.
  std::string reference_format;
  auto* reference = app.add_subcommand("reference", "print every command and option: docs/cli.md or a help2man include")
                        ->group("");
  reference->add_option("FORMAT", reference_format, "markdown (docs/cli.md) or man (help2man --include)")
      ->required()
      ->check(CLI::IsMember({"markdown", "man"}));
  ibs::cli::polish_help(app);  // after every command: metavariables, examples and exit codes

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return ibs::cli::kExitBadInput;
  }
  if (completion->parsed()) {
    std::cout << ibs::cli::bash_completion(app);
    return ibs::cli::kExitOk;
  }
  if (reference->parsed()) {
    std::cout << (reference_format == "man" ? ibs::cli::man_reference(app) : ibs::cli::markdown_reference(app));
    return ibs::cli::kExitOk;
  }
  if (const auto rc = ibs::cli::run_bus_commands(bus_state)) return *rc;
  if (const auto rc = ibs::cli::run_dfs1_commands(dfs1_state)) return *rc;
  if (const auto rc = ibs::cli::run_lustbus_commands(lustbus_state)) return *rc;
  if (const auto rc = ibs::cli::run_canlust_commands(canlust_state)) return *rc;
  if (run->parsed()) return ibs::cli::run(run_options);
  if (master->parsed()) return ibs::cli::master(master_options);
  if (replay->parsed() || decode->parsed()) {
    const auto& files = replay->parsed() ? replay_files : decode_files;
    if (const std::string problem = ibs::cli::check_inputs(files); !problem.empty()) {
      std::cerr << problem << "\n";
      return ibs::cli::kExitBadInput;
    }
    if (replay->parsed() && !replay_pcap.empty() && files.size() > 1) {
      std::cerr << "--pcap writes the capture of one replay: give one FILE\n";
      return ibs::cli::kExitBadInput;
    }
    // Several files: each result after a line `==> FILE <==` (not with --json, whose objects name
    // their file); the exit code is the worst: bad input (2) before a mismatch (1) before 0.
    int worst = ibs::cli::kExitOk;
    for (const std::string& file : files) {
      const bool json = replay->parsed() ? replay_json : decode_json;
      if (files.size() > 1 && !json) std::cout << "==> " << file << " <==\n" << std::flush;
      int rc = ibs::cli::kExitOk;
      if (replay->parsed()) {
        rc = ibs::cli::replay(emulate, file, replay_pcap, replay_json);
      } else if (std::ostringstream capture_text; const auto capture = file == "-" ? std::nullopt
                                                  : ibs::cli::decode_line_capture(file, capture_text, std::cerr)) {
        // A LUSTBUS or DFS-1 capture of --pcap (docs/pcap.md): explained as text, as a byte log is.
        rc = *capture;
        if (decode_json) {
          std::cerr << file << ": --json is for traces; a capture is explained as text (leave out --json)\n";
          rc = ibs::cli::kExitBadInput;
        } else {
          std::cout << capture_text.str() << std::flush;
        }
      } else if (std::ostringstream log_text; const auto log = file == "-" ? std::nullopt
                                                  : ibs::cli::decode_lustbus_log(file, log_text, std::cerr)) {
        // A log is explained as text; with --json the output is JSON or an error, never the text
        // first (the text is held until it is known which).
        rc = *log;
        if (decode_json) {
          std::cerr << file << ": --json is for traces; a byte log is explained as text (leave out --json)\n";
          rc = ibs::cli::kExitBadInput;
        } else {
          std::cout << log_text.str() << std::flush;
        }
      } else if (std::ostringstream candump_text; const auto candump = file == "-" ? std::nullopt
                                                  : ibs::cli::decode_candump_log(file, decode_id_step, decode_cacnf,
                                                                                 candump_text, std::cerr)) {
        rc = *candump;
        if (decode_json) {
          std::cerr << file << ": --json is for traces; a candump log is explained as text (leave out --json)\n";
          rc = ibs::cli::kExitBadInput;
        } else {
          std::cout << candump_text.str() << std::flush;
        }
      } else {
        rc = ibs::cli::decode(file, decode_json);
      }
      worst = std::max(worst, rc);
    }
    return worst;
  }
  if (campaign->parsed()) return ibs::cli::campaign(campaign_options);
  return ibs::cli::kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  // Every command reports bad input itself; what reaches here is unexpected (out of memory, a
  // failed write), and still gets a message and a non-zero exit rather than an abort.
  try {
    return run_ibs(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "ibs: " << e.what() << "\n";
  } catch (...) {
    std::cerr << "ibs: unknown error\n";
  }
  return ibs::cli::kExitBadInput;
}
