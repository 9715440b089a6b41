// ibs: the command line of the INTERBUS-S stack and simulator.
#include <CLI/CLI.hpp>
#include <iostream>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ibs: INTERBUS-S stack and cycle simulator for LUST VF1000 and MC6000 drives"};
  app.require_subcommand(1);

  auto* run = app.add_subcommand("run", "run the main job: bring both drives up, run them, stop them");

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
  if (run->parsed()) return ibs::cli::run_demo();
  if (replay->parsed()) return ibs::cli::replay(emulate, replay_file);
  if (decode->parsed()) return ibs::cli::decode(decode_file);
  return ibs::cli::kExitBadInput;
}
