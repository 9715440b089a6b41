// `ibs master --board NODE [SCENARIO] [--json] [--duration S]`: the master side of a scenario
// against an INTERBUS controller board (board/, docs/board.md). Parsing and printing only; the
// run is ibs::board::run.
#include <iostream>
#include <variant>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "stop_signals.hpp"
#include "ibs/board/run.hpp"
#include "ibs/sim/canlust_scenario.hpp"
#include "ibs/sim/report.hpp"
#include "ibs/sim/scenario_file.hpp"

namespace ibs::cli {

int master(const MasterOptions& o) {
  // The board's name, not a node's: the adapter opens NAME_D and NAME_M itself.
  if (o.board.size() > 2 && (o.board.ends_with("_D") || o.board.ends_with("_M"))) {
    std::cerr << "--board " << o.board << ": give the board without the node suffix ("
              << o.board.substr(0, o.board.size() - 2) << "): the master opens its data and its mailbox node\n";
    return kExitBadInput;
  }
  sim::Scenario scenario;
  try {
    if (o.scenario.empty()) {
      scenario = sim::default_scenario();
    } else {
      sim::AnyScenario any = sim::load_any_scenario(o.scenario);
      if (std::holds_alternative<sim::canlust::Scenario>(any)) {
        std::cerr << o.scenario << ": a CANLust scenario; ibs master runs an INTERBUS ring's master on a board\n";
        return kExitBadInput;
      }
      scenario = std::move(std::get<sim::Scenario>(any));
    }
  } catch (const sim::ScenarioError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
  board::RunOptions options;
  options.board = o.board;
  if (o.duration_s > 0.0) {
    options.duration = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(o.duration_s));
  }
  // SIGINT and SIGTERM end the run between two cycles; the drives are stopped and the board shut
  // down before the summary is printed.
  StopSignals signals;
  options.stop = [&signals] { return signals.raised(); };
  board::RunResult r;
  try {
    r = board::run(scenario, options);
  } catch (const std::invalid_argument& e) {
    std::cerr << (o.scenario.empty() ? std::string("default scenario") : o.scenario) << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  if (r.started) {
    if (o.json) {
      nlohmann::ordered_json j = nlohmann::ordered_json::parse(sim::format_json(r.summary));
      j["board"] = nlohmann::ordered_json::parse(board::format_board_json(r));
      std::cout << j.dump(2) << "\n";
    } else {
      std::cout << sim::format_text(r.summary) << board::format_board_text(r);
    }
  }
  if (r.error) {
    std::cerr << "ibs master: " << r.error.message << "\n";
    return kExitBadInput;
  }
  if (r.shutdown.error) {
    std::cerr << "ibs master: " << r.shutdown.error.message << "\n";
    return kExitBadInput;
  }
  return r.interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace ibs::cli
