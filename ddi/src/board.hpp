// The virtual board (docs/ddi.md): a scenario's ring in the cycle simulator with the board's
// firmware as its master, run by a thread of its own at the bus cycle time in real time, or one
// bus cycle per call of the application's (stepped). Everything the DDI does with it happens
// under its lock, which the real-time thread takes for each cycle.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "firmware.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/simulator.hpp"

namespace ibs::ddi {

enum class Mode : std::uint8_t { realtime, stepped };

// What the board does with the timeline entries of a scenario that command a master (`state`,
// `speed`, `read`, `wait_state`, ...): behind the DDI the application is the master.
enum class MasterCommands : std::uint8_t {
  ignore,      // leaves them out, with one note on stderr; master_restart is the board's SysFail
  ibs_master,  // leaves them to `ibs master --board` running the same file, master_restart too
};

struct BoardOptions {
  Mode mode = Mode::realtime;
  std::string scenario;  // a scenario file; empty: the default bus
  int rt_priority = 0;   // the real-time thread's SCHED_FIFO priority (0: none)
  MasterCommands master_commands = MasterCommands::ignore;
};

// The options from the environment: IBS_DDI_MODE (realtime | stepped), IBS_DDI_SCENARIO,
// IBS_DDI_RT_PRIORITY, IBS_DDI_MASTER_COMMANDS (ignore | ibs-master). Throws
// std::invalid_argument naming the variable for a value it cannot use.
BoardOptions options_from_environment();

// The scenario for a board: the file's (or the default bus's) ring and faults; the entries that
// command a master are left out, as `commands` says (`note` gets the one note of
// MasterCommands::ignore, when there were any).
sim::Scenario board_scenario(const std::string& path, MasterCommands commands = MasterCommands::ignore,
                             std::string* note = nullptr);

class Board {
 public:
  // Throws sim::ScenarioError or std::invalid_argument for a scenario or ring it cannot run.
  explicit Board(const BoardOptions& options);
  ~Board();
  Board(const Board&) = delete;
  Board& operator=(const Board&) = delete;

  // Held by every DDI call and by the real-time thread for each cycle.
  std::mutex& mutex() { return mutex_; }
  // Stepped mode: one bus cycle (with the lock held).
  void step();
  // Stepped mode: a DTI read ran a bus cycle; the next mailbox receive that finds nothing then
  // runs none (take_read_cycle), so that a loop that reads the data and then empties the mailbox
  // runs one bus cycle a pass.
  void note_read_cycle() { read_cycle_ = true; }
  bool take_read_cycle() { return std::exchange(read_cycle_, false); }

  Firmware& firmware() { return *firmware_; }
  [[nodiscard]] const interbus::BusConfig& config() const { return sim_->bus(); }
  [[nodiscard]] Duration cycle_time() const { return sim_->cycle_time(); }
  [[nodiscard]] Mode mode() const { return options_.mode; }
  [[nodiscard]] Time now() const { return sim_->now(); }

 private:
  void run_realtime();

  BoardOptions options_;
  sim::Scenario scenario_;
  std::unique_ptr<sim::Simulator> sim_;
  std::unique_ptr<Firmware> firmware_;
  std::mutex mutex_;
  std::uint64_t cycle_ = 0;  // the bus cycles run
  bool read_cycle_ = false;  // a DTI read ran the last cycle (stepped mode)
  std::atomic<bool> stop_{false};
  std::thread thread_;  // last: it stops before the rest goes
};

}  // namespace ibs::ddi
