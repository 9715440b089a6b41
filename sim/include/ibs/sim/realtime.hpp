// `ibs run --realtime`: the scenario with the master cycle paced at the bus cycle time in real
// time. Each cycle has an absolute deadline on CLOCK_MONOTONIC (start + k cycle times); the runner
// sleeps until it with clock_nanosleep(TIMER_ABSTIME), then lets the ring and the master run up to
// that cycle (Simulator::run_until), so the simulated devices follow wall-clock time. Per cycle it
// measures the wake-up latency against the deadline and whether the cycle's work ended before the
// next deadline (an overrun when not); the master's processing time is the simulator's own
// measurement. Optionally SCHED_FIFO at a priority and mlockall; when the system refuses either,
// a note says so once and the run goes on. The results go into `Summary::realtime`.
#pragma once

#include <functional>

#include <cstdint>
#include <string>

#include "ibs/sim/simulator.hpp"

namespace ibs::sim {

// The pacing every real-time runner uses (this one, the DDI board's thread): CLOCK_MONOTONIC in
// nanoseconds, a sleep to an absolute deadline on it (clock_nanosleep, TIMER_ABSTIME, resumed
// after a signal), and SCHED_FIFO at `priority` for the calling thread: empty when granted, else
// what to tell ("SCHED_FIFO priority 50 refused (...): running at the normal priority").
std::int64_t monotonic_ns();
void sleep_until_ns(std::int64_t deadline);
std::string set_fifo_priority(int priority);

// The figures of the cycles since the last report (RealtimeOptions::each_interval): the wake-up
// latency's percentiles from a fixed histogram (each value the upper end of its bucket, within
// 1/16 of it; the maximum exact) and the overruns.
struct RealtimeInterval {
  Time now{0};                // the simulated time reached
  std::uint64_t cycles = 0;   // in the interval
  std::uint64_t overruns = 0;
  std::int64_t wake_p50_ns = 0;
  std::int64_t wake_p99_ns = 0;
  std::int64_t wake_p999_ns = 0;
  std::int64_t wake_max_ns = 0;
  bool last = false;  // the report at the end, of the cycles after the last whole interval
};

struct RealtimeOptions {
  int rt_priority = 0;  // 1..99: SCHED_FIFO at this priority and memory locked (mlockall); 0: neither
  // Asked every 64 cycles between two deadlines; true ends the run there (`ibs run` on SIGINT or
  // SIGTERM). The simulator is then left part-way: its summary is not final.
  std::function<bool()> stop;
  // Called after every cycle's work with the simulated time reached, before the runner sleeps to
  // the next deadline (the test bench serves its ports and reads its control channel here, on the
  // simulator's own thread: nothing is shared, nothing locks). Its time counts into the cycle's:
  // an overrun it causes is counted like any other.
  std::function<void(Time now)> each_cycle{};
  // Every `interval` of the run (0: never), after a cycle's work, and once more at its end for the
  // cycles after the last whole interval: the figures of the cycles since the last call (a soak's
  // minute, docs/robustness.md). The runner keeps them without allocating; the call's own time
  // counts into its cycle, as each_cycle's does.
  Duration interval{0};
  std::function<void(const RealtimeInterval&)> each_interval{};
};

// Runs `sim` from its start to the end of its scenario in real time. Allocates only before the
// first deadline (the per-cycle records are reserved); throws nothing of its own.
void run_realtime(Simulator& sim, const RealtimeOptions& realtime, const SimOptions& options = {});

}  // namespace ibs::sim
