#include "ibs/sim/realtime.hpp"

#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

namespace ibs::sim {

namespace {

// Wake-up latencies in buckets of 1/16 of their power of two (16 exact ones below 16 ns): fixed
// memory, O(1) a cycle, percentiles within 1/16.
class LatencyHistogram {
 public:
  void add(std::uint32_t ns) {
    ++counts_[index(ns)];
    ++total_;
    max_ = std::max(max_, ns);
  }
  void clear() {
    counts_.fill(0);
    total_ = 0;
    max_ = 0;
  }
  [[nodiscard]] std::uint64_t total() const { return total_; }
  [[nodiscard]] std::uint32_t max() const { return max_; }
  // The upper end of the bucket that holds the value of rank ceil(q * total) (1-based).
  [[nodiscard]] std::int64_t quantile(double q) const {
    if (total_ == 0) return 0;
    const auto rank = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(q * static_cast<double>(total_) + 0.999999));
    std::uint64_t seen = 0;
    for (std::size_t i = 0; i < counts_.size(); ++i) {
      seen += counts_[i];
      if (seen >= rank) return std::min<std::int64_t>(upper(i), max_);
    }
    return max_;
  }

 private:
  static constexpr std::size_t kSub = 16;
  static std::size_t index(std::uint32_t v) {
    if (v < kSub) return v;
    const int e = 31 - __builtin_clz(v);  // v >= 16: e >= 4
    const auto shift = static_cast<unsigned>(e - 4);
    return kSub + static_cast<std::size_t>(e - 4) * kSub + ((v >> shift) & (kSub - 1));
  }
  static std::int64_t upper(std::size_t i) {
    if (i < kSub) return static_cast<std::int64_t>(i);
    const std::size_t octave = (i - kSub) / kSub;
    const std::size_t sub = (i - kSub) % kSub;
    const std::int64_t step = std::int64_t{1} << octave;
    return static_cast<std::int64_t>(kSub + sub) * step + step - 1;
  }
  std::array<std::uint64_t, kSub + 28 * kSub> counts_{};
  std::uint64_t total_ = 0;
  std::uint32_t max_ = 0;
};

}  // namespace

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
  // Written before the first deadline, so that no cycle takes a page fault for its record.
  std::vector<std::uint32_t> wake(cycles + 1, 0);
  std::size_t recorded = 0;
  std::uint64_t index = 0;
  // The interval reports (each_interval): a fixed histogram, cleared after each.
  LatencyHistogram interval_wake;
  std::uint64_t interval_overruns = 0;
  const bool reports = realtime.interval > Duration{0} && realtime.each_interval;
  Time next_report = reports ? Time{0} + realtime.interval : Time::max();
  const auto report = [&](bool last) {
    const RealtimeInterval iv{sim.now(),
                              interval_wake.total(),
                              interval_overruns,
                              interval_wake.quantile(0.5),
                              interval_wake.quantile(0.99),
                              interval_wake.quantile(0.999),
                              static_cast<std::int64_t>(interval_wake.max()),
                              last};
    realtime.each_interval(iv);
    interval_wake.clear();
    interval_overruns = 0;
  };
  // The first deadline one cycle from now: the cycles of the run are k = 1 .. n.
  const std::int64_t start = monotonic_ns();
  bool stopped = false;
  for (Time t = Time{0} + cycle; t <= Time{0} + end; t += cycle, ++index) {
    const std::int64_t deadline = start + (t - Time{0}).count();
    sleep_until_ns(deadline);
    const std::int64_t woke = monotonic_ns();
    const auto latency = static_cast<std::uint32_t>(std::clamp<std::int64_t>(woke - deadline, 0, 0xFFFFFFFF));
    if (recorded < wake.size()) wake[recorded++] = latency;
    interval_wake.add(latency);
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
      ++interval_overruns;
      if (!r.first_overrun) r.first_overrun = t;
      if (Duration{late} > r.worst_overrun_by) {
        r.worst_overrun_by = Duration{late};
        r.worst_overrun = t;
      }
    }
    if (t >= next_report) {
      report(false);
      next_report += realtime.interval;
    }
  }
  // The cycles after the last whole interval: a last, shorter one.
  if (reports && interval_wake.total() > 0) report(true);
  wake.resize(recorded);
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
