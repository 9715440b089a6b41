#include "ibs/sim/realtime.hpp"

#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

namespace ibs::sim {

std::int64_t monotonic_ns() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  const std::int64_t sec = ts.tv_sec;
  return sec * 1'000'000'000 + ts.tv_nsec;
}

void sleep_until_ns(std::int64_t deadline) {
  timespec ts{};
  ts.tv_sec = deadline / 1'000'000'000;
  ts.tv_nsec = deadline % 1'000'000'000;
  while (::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

std::string set_fifo_priority(int priority) {
  sched_param p{};
  p.sched_priority = priority;
  // On Linux, pid 0 is the calling thread.
  if (::sched_setscheduler(0, SCHED_FIFO, &p) == 0) return {};
  return "SCHED_FIFO priority " + std::to_string(priority) + " refused (" + std::strerror(errno) +
         "): running at the normal priority";
}

void run_realtime(Simulator& sim, const RealtimeOptions& realtime, const SimOptions& options) {
  RealtimeStats r;
  r.cycle_time = sim.cycle_time();
  if (realtime.rt_priority > 0) {
    if (std::string refused = set_fifo_priority(realtime.rt_priority); refused.empty()) {
      r.rt_priority = realtime.rt_priority;
    } else {
      r.notes.push_back(std::move(refused));
    }
    if (::mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      r.memory_locked = true;
    } else {
      r.notes.push_back(std::string("mlockall refused (") + std::strerror(errno) + "): memory not locked");
    }
  }
  const Duration cycle = sim.cycle_time();
  const Duration end = sim.scenario_duration();
  const auto cycles = static_cast<std::size_t>(end / cycle);
  std::vector<std::uint32_t> wake;
  wake.reserve(cycles + 1);
  std::uint64_t index = 0;
  // The first deadline one cycle from now: the cycles of the run are k = 1 .. n.
  const std::int64_t start = monotonic_ns();
  bool stopped = false;
  for (Time t = Time{0} + cycle; t <= Time{0} + end; t += cycle, ++index) {
    const std::int64_t deadline = start + (t - Time{0}).count();
    sleep_until_ns(deadline);
    const std::int64_t woke = monotonic_ns();
    wake.push_back(static_cast<std::uint32_t>(std::clamp<std::int64_t>(woke - deadline, 0, 0xFFFFFFFF)));
    sim.run_until(t, options);
    if (realtime.each_cycle) realtime.each_cycle(sim.now());
    if (realtime.stop && (index & 63U) == 0 && realtime.stop()) {
      stopped = true;
      break;
    }
    const std::int64_t done = monotonic_ns();
    const std::int64_t late = done - (deadline + cycle.count());
    if (late > 0) {
      ++r.overruns;
      if (!r.first_overrun) r.first_overrun = t;
      if (Duration{late} > r.worst_overrun_by) {
        r.worst_overrun_by = Duration{late};
        r.worst_overrun = t;
      }
    }
  }
  if (!stopped) sim.run(options);  // the rest of the scenario after the last whole cycle
  r.wake = timing_stats(wake, cycle, processing_budgets());
  r.processing = sim.summary().master;
  if (r.rt_priority > 0) {
    sched_param p{};
    p.sched_priority = 0;
    ::sched_setscheduler(0, SCHED_OTHER, &p);
  }
  if (r.memory_locked) ::munlockall();
  sim.set_realtime(std::move(r));
}

}  // namespace ibs::sim
