// ibs: the command line of the INTERBUS-S stack and simulator.
#include <CLI/CLI.hpp>
#include <iostream>

#include "bus_commands.hpp"
#include "dfs1_cmd.hpp"
#include "commands.hpp"

namespace {

int run_ibs(int argc, char** argv) {
  CLI::App app{"ibs: INTERBUS-S stack and cycle simulator for LUST VF1000 and MC6000 drives"};
  app.require_subcommand(1);

  ibs::cli::RunOptions run_options;
  auto* run = app.add_subcommand(
      "run", "simulate a bus: the built-in default (an MC6000 and a VF1000 brought up, run and stopped) or a scenario file");
  run->add_option("SCENARIO", run_options.scenario, "a scenario file (.toml or .json, docs/scenarios.md)");
  run->add_flag("--json", run_options.json, "print the summary as JSON");
  run->add_option("--trace", run_options.trace_dir, "write one ibs-trace 1 file per device into this directory");
  run->add_option("--vcd", run_options.vcd_file, "write the run as a VCD file for gtkwave");
  run->add_option("--threads", run_options.threads,
                  "threads that step the devices (the run is the same for any number; 0: one per core "
                  "as far as the ring has work for them)")
      ->check(CLI::Range(0U, 256U))
      ->default_val(1U);

  std::string emulate;
  std::string replay_file;
  auto* replay = app.add_subcommand(
      "replay", "replay an ibs-trace 1 file against the emulated device or master side");
  replay->add_option("--emulate", emulate, "which side the project emulates")
      ->required()
      ->check(CLI::IsMember({"device", "master"}));
  replay->add_option("FILE", replay_file, "the trace file")->required();

  std::string decode_file;
  auto* decode = app.add_subcommand("decode", "print a trace with every word explained in the remark");
  decode->add_option("FILE", decode_file, "the trace file")->required();

  ibs::cli::CampaignOptions campaign_options;
  auto* campaign = app.add_subcommand(
      "campaign", "the fault campaign: random faults during parameter traffic and state commands, every step checked");
  campaign->add_option("--seed", campaign_options.seed, "the random seed (default 1)");
  campaign->add_option("--transactions", campaign_options.transactions,
                       "parameter transactions to run (default 100000, at most 100 million)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{100000000}));
  campaign->add_flag("--json", campaign_options.json, "print the result as JSON");
  campaign->add_flag("--enable-during-download", campaign_options.enable_during_download,
                     "also request ENABLED while an 80-SLOAD download is open (the servo must refuse)");

  ibs::cli::BusCommandState bus_state;
  ibs::cli::add_bus_commands(app, bus_state);
  ibs::cli::Dfs1CommandState dfs1_state;
  ibs::cli::add_dfs1_commands(app, dfs1_state);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return ibs::cli::kExitBadInput;
  }
  if (const auto rc = ibs::cli::run_bus_commands(bus_state)) return *rc;
  if (const auto rc = ibs::cli::run_dfs1_commands(dfs1_state)) return *rc;
  if (run->parsed()) return ibs::cli::run(run_options);
  if (replay->parsed()) return ibs::cli::replay(emulate, replay_file);
  if (decode->parsed()) return ibs::cli::decode(decode_file);
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
