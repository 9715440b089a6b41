// A simulated RS-485 line in simulated time: one DFS-1 master and several emulated controllers
// share one half-duplex pair. A byte occupies the line for one character time, 10 bits at the
// baud rate (start, 8 data, stop: 8N1, decision D9), and reaches every other node when it ends;
// a sender never hears itself (echo off, as nanoMODBUS's multi-drop tests do). Two nodes that
// start at the same instant collide: the first in order (master, then controllers) wins and the
// collision is counted (the protocol should never cause one).
//
// The wing's own line for its tests and benchmarks (the LUSTBUS line of lustbus/ is the same idea
// for ISO 1745 telegrams, with its 7E1 characters).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "ibs/devices/dfs1/controller.hpp"
#include "ibs/devices/dfs1/master.hpp"
#include "ibs/base/time.hpp"

namespace ibs::devices::dfs1 {

// 10 bits per character at `baud` bits per second, rounded to the nanosecond.
Duration character_time(std::uint32_t baud);

class SimulatedLine {
 public:
  // `master` and every controller must outlive the line. Throws std::invalid_argument for baud 0.
  SimulatedLine(Master& master, std::vector<Controller*> controllers, std::uint32_t baud);

  Time now() const { return now_; }
  Duration character_time() const { return char_time_; }

  // Runs every event up to and including `t`; afterwards now() == t.
  void run_until(Time t);
  // Runs until the master is idle, no reply waits and the line is quiet, or `limit`; returns now().
  Time run_until_idle(Time limit);

  std::uint64_t bytes() const { return bytes_; }
  std::uint64_t collisions() const { return collisions_; }

  // Called for every byte when it has crossed the line: (end time, sender, byte); sender 0 is
  // the master, k the k-th controller (1-based).
  using Observer = std::function<void(Time, std::size_t, std::uint8_t)>;
  void set_observer(Observer o) { observer_ = std::move(o); }

 private:
  struct InFlight {
    std::uint8_t byte;
    std::size_t sender;
    Time ends;
  };
  bool quiet();
  void start_transmission();
  std::optional<Time> next_event() const;
  void advance_to(Time t);

  Master& master_;
  std::vector<Controller*> controllers_;
  Duration char_time_;
  Time now_{};
  std::optional<InFlight> in_flight_;
  std::uint64_t bytes_ = 0;
  std::uint64_t collisions_ = 0;
  Observer observer_;
};

}  // namespace ibs::devices::dfs1
