// The plot recorder (docs/simulator.md, "Plots"): what it keeps of a run, that it keeps a bounded
// number of points however long the run, and the gnuplot script it writes. The picture itself,
// drawn by gnuplot, is checked by `Pictures.*` in tests/tools/outputs_test.cpp.
#include "ibs/sim/plot_recorder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "ibs/drivecom/status_word.hpp"

namespace ibs::sim {
namespace {

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

Scenario with_faults() {
  Scenario s = default_scenario();
  TimelineEntry f;
  f.at = 6s;
  f.device = "vf1000";
  f.action = Action::fault_device;
  f.duration = 100ms;
  s.timeline.push_back(f);
  TimelineEntry c;
  c.at = 3s;
  c.action = Action::fault_corrupt;
  s.timeline.push_back(c);
  std::stable_sort(s.timeline.begin(), s.timeline.end(),
                   [](const TimelineEntry& a, const TimelineEntry& b) { return a.at < b.at; });
  return s;
}

TEST(PlotRecorder, KeepsEachDrivesValuesAndStates) {
  const Scenario s = default_scenario();
  Simulator sim(s);
  PlotRecorder plot(sim, s.duration, 400);
  sim.add_observer(&plot);
  sim.run();
  plot.finish(s.duration);
  ASSERT_EQ(plot.drives().size(), 2U);
  const auto& mc = plot.drives()[0];
  const auto& vf = plot.drives()[1];
  EXPECT_EQ(mc.name, "mc6000");
  EXPECT_EQ(mc.unit, "rpm");
  EXPECT_EQ(vf.unit, "Hz");
  const auto peak = [](const std::vector<PlotRecorder::Point>& p) {
    return std::max_element(p.begin(), p.end(), [](auto& a, auto& b) { return a.v < b.v; })->v;
  };
  EXPECT_DOUBLE_EQ(peak(mc.reference), 2500.25);
  // The speed loop overshoots by about 2 rpm; each bin keeps its highest point, so the peak shows.
  EXPECT_GT(peak(mc.actual), 2501.0);
  EXPECT_LT(peak(mc.actual), 2510.0);
  EXPECT_DOUBLE_EQ(peak(vf.reference), 50.0);
  // 8 s of 0.726 ms cycles in 400 bins: at most four points a bin.
  EXPECT_LE(mc.actual.size(), 4U * 400U);
  EXPECT_GT(mc.actual.size(), 50U);
  EXPECT_TRUE(std::is_sorted(mc.actual.begin(), mc.actual.end(), [](auto& a, auto& b) { return a.t < b.t; }));
  // States: one point per change, the last one at the end of the run.
  const auto enabled = static_cast<double>(drivecom::State::enabled);
  EXPECT_NE(std::find_if(vf.state.begin(), vf.state.end(), [&](auto& p) { return p.v == enabled; }), vf.state.end());
  EXPECT_DOUBLE_EQ(vf.state.back().t, 8.0);
  EXPECT_EQ(vf.state.back().v, static_cast<double>(drivecom::State::ready));
}

TEST(PlotRecorder, TheScriptDrawsEverySeriesFaultAndTransaction) {
  const Scenario s = with_faults();
  Simulator sim(s);
  PlotRecorder plot(sim, s.duration);
  sim.add_observer(&plot);
  sim.run();
  plot.finish(s.duration);
  const std::string svg = plot.script(sim.summary(), PlotFormat::svg);
  for (const char* what :
       {"set terminal svg size 1200,910 ", "$reference0 << EOD\n", "$actual1 << EOD\n", "$state1 << EOD\n",
        "title \"reference (rpm)\"", "title \"actual (Hz)\"", "title \"DRIVECOM state\"",
        "title \"parameter transactions\"", "set xlabel \"time (s)\"", "set ylabel \"reference, actual (Hz)\"",
        "set title \"vf1000 (ID code 33BH)\"", "\"EMERGENCY STOP ACTIVE\" 7", "set label \"device-fault\" at 6",
        "set label \"corrupt\" at 3", "title \"fault events\"", "\"read 85\"", "\"write 409\"",
        "\"describe 406\"", "unset multiplot\n"}) {
    EXPECT_TRUE(contains(svg, what)) << what;
  }
  // The device fault is the VF1000's: marked in its panels only; the corrupted cycles in all.
  const auto mc_part = svg.substr(svg.find("\n# mc6000\n"), svg.find("\n# vf1000\n") - svg.find("\n# mc6000\n"));
  EXPECT_FALSE(contains(mc_part, "device-fault"));
  EXPECT_TRUE(contains(mc_part, "\"corrupt\""));
  EXPECT_TRUE(contains(plot.script(sim.summary(), PlotFormat::png), "set terminal pngcairo size 1200,910 "));
}

}  // namespace
}  // namespace ibs::sim
