// `ibs run --realtime` (sim/realtime.hpp): the same run as the simulator's, paced in real time,
// with the per-cycle statistics filled in; and the statistics themselves on known numbers. No
// assertion on how long anything took: the figures are the machine's.
#include <gtest/gtest.h>

#include "ibs/sim/realtime.hpp"
#include "ibs/sim/report.hpp"
#include "ibs/sim/scenario.hpp"

namespace ibs::sim {
namespace {

using namespace std::chrono_literals;

TEST(TimingStats, PercentilesWorstCycleAndBudgets) {
  std::vector<std::uint32_t> ns(1000, 100);
  ns[10] = 2'000'000;  // 2 ms: over the 1 ms budget, not over 8.2 ms
  ns[500] = 9'000'000;  // over both
  ns[900] = 1'500'000;
  const Duration budgets[] = {1ms, 8200us};
  const TimingStats t = timing_stats(ns, 1ms, budgets);
  EXPECT_EQ(t.cycles, 1000U);
  EXPECT_EQ(t.median_ns, 100.0);
  EXPECT_EQ(t.p99_ns, 100.0);
  EXPECT_EQ(t.p999_ns, 2'000'000.0);  // the third-largest of 1000
  EXPECT_EQ(t.max_ns, 9'000'000.0);
  EXPECT_EQ(t.worst_cycle, 500U);
  EXPECT_EQ(t.worst_at, Time{501ms});  // cycle k ends at (k + 1) cycle times
  ASSERT_EQ(t.over.size(), 2U);
  EXPECT_EQ(t.over[0].cycles, 3U);
  EXPECT_EQ(t.over[0].first, Time{11ms});
  EXPECT_EQ(t.over[1].cycles, 1U);
  EXPECT_EQ(t.over[1].first, Time{501ms});
  EXPECT_EQ(timing_stats({}, 1ms, budgets).cycles, 0U);
}

TEST(Realtime, SameRunAsTheSimulatorWithItsStatistics) {
  Scenario s = default_scenario();
  s.duration = 300ms;
  Simulator fast(s);
  fast.run();
  Simulator paced(s);
  run_realtime(paced, RealtimeOptions{});
  const Summary& a = fast.summary();
  const Summary& b = paced.summary();
  // The devices follow the paced clock: the same run, event for event.
  ASSERT_EQ(a.devices.size(), b.devices.size());
  for (std::size_t i = 0; i < a.devices.size(); ++i) {
    EXPECT_EQ(a.devices[i].final_state, b.devices[i].final_state);
    EXPECT_EQ(a.devices[i].states.size(), b.devices[i].states.size());
    EXPECT_DOUBLE_EQ(a.devices[i].final_actual, b.devices[i].final_actual);
  }
  ASSERT_EQ(a.transactions.size(), b.transactions.size());
  for (std::size_t i = 0; i < a.transactions.size(); ++i) {
    EXPECT_EQ(a.transactions[i].result, b.transactions[i].result);
    EXPECT_EQ(a.transactions[i].finished, b.transactions[i].finished);
  }
  EXPECT_EQ(a.cycles, b.cycles);
  EXPECT_FALSE(a.realtime.has_value());
  ASSERT_TRUE(b.realtime.has_value());
  const RealtimeStats& r = *b.realtime;
  EXPECT_EQ(r.cycle_time, paced.cycle_time());
  EXPECT_EQ(r.wake.cycles, static_cast<std::uint64_t>(s.duration / paced.cycle_time()));
  EXPECT_LE(r.wake.median_ns, r.wake.p99_ns);
  EXPECT_LE(r.wake.p99_ns, r.wake.p999_ns);
  EXPECT_LE(r.wake.p999_ns, r.wake.max_ns);
  EXPECT_LT(r.wake.worst_at, Time{0} + s.duration + paced.cycle_time());
  EXPECT_LE(r.overruns, r.wake.cycles);
  EXPECT_EQ(r.overruns == 0, !r.first_overrun.has_value());
  EXPECT_EQ(r.rt_priority, 0);  // not asked for
  EXPECT_EQ(r.processing.cycles, b.master.cycles);
  // Both summaries say so.
  EXPECT_NE(format_text(b).find("real time (cycle"), std::string::npos);
  EXPECT_NE(format_text(b).find("wake-up latency: median"), std::string::npos);
  EXPECT_NE(format_json(b).find("\"wake_latency\""), std::string::npos);
  EXPECT_EQ(format_text(a).find("real time (cycle"), std::string::npos);
  EXPECT_NE(format_text(a).find("p99.9"), std::string::npos);
}

// Issue 41, the soak: every `interval` of a paced run the runner reports the cycles since the last
// report, their overruns and their wake-up latency's percentiles; the reports add up to the run.
TEST(Realtime, IntervalReportsAddUpToTheRun) {
  Scenario s = default_scenario();
  s.duration = 400ms;
  Simulator paced(s);
  RealtimeOptions rt;
  rt.interval = 100ms;
  std::vector<RealtimeInterval> reports;
  rt.each_interval = [&reports](const RealtimeInterval& iv) { reports.push_back(iv); };
  run_realtime(paced, rt);
  ASSERT_TRUE(paced.summary().realtime.has_value());
  const RealtimeStats& r = *paced.summary().realtime;
  ASSERT_GE(reports.size(), 4U);  // at 100, 200, 300 ms, and the last cycles up to 400 ms
  ASSERT_LE(reports.size(), 5U);
  std::uint64_t cycles = 0;
  std::uint64_t overruns = 0;
  for (std::size_t i = 0; i < reports.size(); ++i) {
    const RealtimeInterval& iv = reports[i];
    if (i + 1 < reports.size()) {
      EXPECT_GE(iv.now, Time{100ms * static_cast<int>(i + 1)});  // the last: the cycles after 300 ms
    }
    EXPECT_GT(iv.cycles, 0U);
    EXPECT_EQ(iv.last, i + 1 == reports.size());
    EXPECT_LE(iv.wake_p50_ns, iv.wake_p99_ns);
    EXPECT_LE(iv.wake_p99_ns, iv.wake_p999_ns);
    EXPECT_LE(iv.wake_p999_ns, iv.wake_max_ns);
    EXPECT_LE(static_cast<double>(iv.wake_max_ns), r.wake.max_ns);
    cycles += iv.cycles;
    overruns += iv.overruns;
  }
  EXPECT_EQ(cycles, r.wake.cycles) << "the reports cover every cycle of the run";
  EXPECT_EQ(overruns, r.overruns);
  // The maximum is exact: the whole run's is one report's.
  std::int64_t largest = 0;
  for (const RealtimeInterval& iv : reports) largest = std::max(largest, iv.wake_max_ns);
  EXPECT_EQ(static_cast<double>(largest), r.wake.max_ns);
}

}  // namespace
}  // namespace ibs::sim
