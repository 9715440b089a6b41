// `ibs master --board` as a library (docs/board.md): the master side of a scenario -- its ring,
// its timeline of master commands and parameter requests -- run against an INTERBUS controller
// board through the DDI (ibs::master_ddi) instead of the simulator, with the summary of
// `ibs run` recorded by the same code (sim::MasterTimeline) and printed by the same formatter
// (sim/report.hpp), so that the two can be compared.
//
// The run: the drivers of the scenario's devices, the board brought up (DdiBoard::open: plug &
// play off, the configuration compared, data transfer started), the PCP drivers on the board's
// mailbox; then one master cycle per period -- in real time on CLOCK_MONOTONIC deadlines, or
// stepped for a board that runs one bus cycle per exchange (ibs's virtual board with
// IBS_DDI_MODE=stepped) -- applying the timeline's master commands at their times (the faults
// are the board's: with IBS_DDI_SCENARIO naming the same file the virtual board runs them), and
// what the board reports (BUS, peripheral faults, BSA, SysFail) recorded as the summary's
// faults. At the end, at a stop request (SIGINT, SIGTERM) or when the board fails, the drives
// are brought to a safe state (master::stop_drives), data transfer stops and the nodes close.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ibs/base/error.hpp"
#include "ibs/master/ddi_board.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/simulator.hpp"

namespace ibs::board {

enum class Clock : std::uint8_t {
  realtime,  // cycle k at start + k periods on CLOCK_MONOTONIC; its time is the clock's
  stepped,   // no waiting; cycle k's time is k periods (a board stepped by each exchange)
};

struct RunOptions {
  std::string board = "IBB1N1";     // the board without the node suffix (DdiBoardOptions::board)
  std::optional<Duration> duration;  // how long to run; default: the scenario's duration
  // The master loop's period; zero: the board's cycle time (Read_Value 2231H), else the bus
  // cycle time the scenario gives (its cycle_time, or the formula's).
  Duration period{0};
  Clock clock = Clock::realtime;
  // Asked after every cycle; true ends the run there (SIGINT / SIGTERM): the drives are stopped
  // and the board shut down as at the end.
  std::function<bool()> stop;
  Duration service_deadline = 5s;  // each firmware service of bring-up and shutdown
  master::StopOptions stop_drives;
};

// The shutdown as it went.
struct Shutdown {
  bool drives_safe = false;  // every drive reached its safe state in time
  std::vector<std::string> states;  // per device: the state its master saw at the end
  Error error;                      // Stop_Data_Transfer or closing a node failed
};

struct RunResult {
  sim::Summary summary;  // the scenario's part, as `ibs run` reports it
  std::string board;
  Duration board_cycle_time{0};  // Read_Value 2231H (0: not given)
  Duration period{0};            // the loop's
  Clock clock = Clock::realtime;
  bool started = false;      // the board came up: the summary holds a run
  bool interrupted = false;  // `stop` ended the run
  Error error;               // what ended the run or the bring-up: a DDI call or service and its code
  Shutdown shutdown;
};

// The scenario's ring as its master sees it: one driver per device (from its drive kind's
// descriptor), the bus configuration, and the bus cycle time the scenario gives (its cycle_time,
// or the formula's). Throws std::invalid_argument, as the simulator, for a ring it cannot build.
struct MasterRing {
  interbus::BusConfig config;
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers;
  std::vector<std::string> kinds;
  Duration cycle_time{0};
};
MasterRing make_master_ring(const sim::Scenario& scenario);

// Throws std::invalid_argument for a scenario whose ring cannot be configured (as the
// simulator); every problem with the board is RunResult::error.
RunResult run(const sim::Scenario& scenario, const RunOptions& options);

// The board's part of the report, after the summary: text, and an object for the summary's JSON
// (`board`).
std::string format_board_text(const RunResult& r);
std::string format_board_json(const RunResult& r);

}  // namespace ibs::board
