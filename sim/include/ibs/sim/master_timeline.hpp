// The master's side of a scenario, whatever carries its bus: the timeline's commands and
// parameter requests applied to a master loop's drivers, and what the run summary
// (simulator.hpp, report.hpp) records of those drivers -- the states each saw, the references
// reached, the waits, the sequencers' failures, every parameter transaction with its outcome.
// The cycle simulator runs it at each cycle end (the bus is its own); `ibs master --board` runs
// it against a controller board (board/, docs/board.md). One code, one summary, so that the two
// can be compared line by line.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "ibs/interbus/process_image.hpp"
#include "ibs/master/master_loop.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/simulator.hpp"

namespace ibs::sim {

class MasterTimeline {
 public:
  // Over `loop`'s drivers, the devices' inputs in `image`, records into `summary` (its
  // `devices` as many as the loop's; `transactions` appended to). All three outlive this.
  MasterTimeline(master::MasterLoop& loop, const interbus::ProcessImage& image, Summary& summary);

  // The actions that command the master (state, emergency_stop, block_power, speed, frequency,
  // read, write, describe, wait_state); the others are the bus's and the drives' (faults, plant
  // events) or, for master_restart, the loop's own restart.
  static bool is_master_command(Action a);
  // Device i waits for a state (wait_state): its entries wait too.
  [[nodiscard]] bool waiting(std::size_t i) const { return devices_[i].waiting_for.has_value(); }
  // Applies a master command for device i at t (is_master_command(e.action)).
  void apply(const TimelineEntry& e, std::size_t i, Time t);
  // After the master's cycle at t: what device i's driver saw, into the summary.
  void observe_device(std::size_t i, Time t);
  // After the master's cycle at t: the parameter transactions answered or finished.
  void observe_transactions(Time t);
  // At the end of the run: what is still pending says so.
  void finish();

 private:
  struct Device {
    std::span<const Word> in;  // the device's input words in the image
    std::optional<drivecom::State> last_seen;
    double reached_for = 0.0;  // the reference whose "reached" was last reported
    bool reached_reported = true;
    std::optional<drivecom::State> waiting_for;
    Time wait_deadline{0};
    bool failure_reported = false;  // the sequencer's current failure is in the summary
  };
  master::MasterLoop& loop_;
  Summary& summary_;
  std::vector<Device> devices_;
  std::vector<std::size_t> transaction_device_;  // per summary transaction (all this one's): its device
};

}  // namespace ibs::sim
