// The plot recorder (docs/simulator.md, "Plots"): what it keeps of a run, that it keeps a bounded
// number of points however long the run, and the gnuplot script it writes. The picture itself,
// drawn by gnuplot, is checked by `Pictures.*` in tests/tools/outputs_test.cpp.
#include "ibs/sim/plot_recorder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

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
       {"set terminal svg size 1200,990 ", "$reference0 << EOD\n", "$actual1 << EOD\n", "$state1 << EOD\n",
        "$device_actual1 << EOD\n", "$seen_state0 << EOD\n", "title \"reference (rpm)\"",
        "title \"actual, master's view (Hz)\"", "title \"actual, device (Hz)\"", "title \"state, master's view\"",
        "title \"state, device\"",
        "title \"done transactions\"", "set xlabel \"time (s)\"", "set ylabel \"reference, actual (Hz)\"",
        "set title \"vf1000 (ID code 33BH)\"", "\"EMERGENCY STOP ACTIVE\" 7",
        "set label \"2 events: device-fault, fault-cleared\" at 6",
        "set label \"corrupt\" at 3", "title \"fault events\"", "\"read 85\"", "\"write 409\"",
        "\"describe 406\"", "unset multiplot\n"}) {
    EXPECT_TRUE(contains(svg, what)) << what;
  }
  // The device fault is the VF1000's: marked in its panels only; the corrupted cycles in all.
  const auto mc_part = svg.substr(svg.find("\n# mc6000\n"), svg.find("\n# vf1000\n") - svg.find("\n# mc6000\n"));
  EXPECT_FALSE(contains(mc_part, "device-fault"));
  EXPECT_TRUE(contains(mc_part, "\"corrupt\""));
  EXPECT_TRUE(contains(plot.script(sim.summary(), PlotFormat::png), "set terminal pngcairo size 1200,990 "));
}

// The lines of a datablock `$name << EOD ... EOD`.
std::vector<std::string> datablock_lines(const std::string& script, const std::string& name) {
  std::vector<std::string> out;
  const auto start = script.find(name + " << EOD\n");
  if (start == std::string::npos) return out;
  std::istringstream in(script.substr(start + name.size() + 8));
  for (std::string l; std::getline(in, l) && l != "EOD";) out.push_back(l);
  return out;
}

// The fault labels (text, time) in a part of the script.
std::vector<std::pair<std::string, double>> fault_labels(const std::string& part) {
  std::vector<std::pair<std::string, double>> out;
  const std::regex label(R"re(set label "([^"]*)" at ([-0-9.e+]+), graph)re");
  for (auto it = std::sregex_iterator(part.begin(), part.end(), label); it != std::sregex_iterator(); ++it) {
    out.emplace_back((*it)[1], std::stod((*it)[2]));
  }
  return out;
}

FaultRecord fault(int at_ms, const std::string& device, const std::string& kind) {
  FaultRecord f;
  f.at = std::chrono::milliseconds(at_ms);
  f.device = device;
  f.kind = kind;
  return f;
}

TransactionRecord transaction(int at_ms, devices::ParamOp op, std::uint16_t number, devices::ParamKind kind) {
  TransactionRecord tr;
  tr.device = "mc6000";
  tr.op = op;
  tr.number = number;
  tr.kind = kind;
  tr.submitted = std::chrono::milliseconds(at_ms);
  tr.answered = tr.finished = tr.submitted + 20ms;
  return tr;
}

// Issue 27.14: events that cluster get labels that can be read apart. Fault events closer than
// a label's width share one label that counts them; transaction labels take one of three rows,
// and one that finds no row free is counted into the label before it.
TEST(PlotRecorder, LabelsOfClusteredEventsDoNotOverlap) {
  const Scenario s = default_scenario();  // 8 s, mc6000 and vf1000
  Simulator sim(s);
  PlotRecorder plot(sim, s.duration);
  sim.add_observer(&plot);
  sim.run();
  plot.finish(s.duration);
  Summary summary = sim.summary();
  summary.faults = {fault(1000, "", "corrupt"),          fault(1001, "", "corrupt"),
                    fault(1002, "", "corrupt"),          fault(1003, "vf1000", "lost"),
                    fault(3000, "mc6000", "device-fault"), fault(3500, "mc6000", "fault-cleared")};
  summary.transactions.clear();
  for (int k = 0; k < 5; ++k) {
    summary.transactions.push_back(transaction(2000 + k, devices::ParamOp::read,
                                               static_cast<std::uint16_t>(85 + k), devices::ParamKind::value));
  }
  summary.transactions.push_back(transaction(5000, devices::ParamOp::write, 409, devices::ParamKind::written));
  summary.transactions.push_back(transaction(7950, devices::ParamOp::describe, 406, devices::ParamKind::timeout));
  const std::string script = plot.script(summary, PlotFormat::svg);
  const auto mc_at = script.find("\n# mc6000\n");
  const auto vf_at = script.find("\n# vf1000\n");
  ASSERT_NE(mc_at, std::string::npos);
  ASSERT_NE(vf_at, std::string::npos);

  // Faults: every event keeps its line (in both panels), the three corrupted cycles 1 ms apart
  // share one label, events half a second apart have their own.
  const std::string mc_part = script.substr(mc_at, vf_at - mc_at);
  const std::string vf_part = script.substr(vf_at);
  const auto count = [](const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count(mc_part, "set arrow from "), 2U * 5U);
  EXPECT_EQ(count(vf_part, "set arrow from "), 2U * 4U);
  const auto mc_labels = fault_labels(mc_part);
  const std::vector<std::pair<std::string, double>> mc_want{
      {"3 events: corrupt x3", 1.0}, {"device-fault", 3.0}, {"fault-cleared", 3.5}};
  EXPECT_EQ(mc_labels, mc_want);
  const auto vf_labels = fault_labels(vf_part);
  const std::vector<std::pair<std::string, double>> vf_want{{"4 events: corrupt x3, lost", 1.0}};
  EXPECT_EQ(vf_labels, vf_want);

  // Transactions: five within 4 ms take the three rows, the last two counted into the third;
  // each label has a place of its own.
  const auto left = datablock_lines(script, "$labels0");
  const std::vector<std::string> want_left{"2 9 \"read 85\"", "2.001 9.9 \"read 86\"", "2.002 10.8 \"read 87 +2\"",
                                           "5 9 \"write 409\""};
  EXPECT_EQ(left, want_left);
  // Near the right edge the label ends at its transaction, inside the plot.
  const auto right = datablock_lines(script, "$labels_right0");
  const std::vector<std::string> want_right{"7.95 9 \"describe 406\""};
  EXPECT_EQ(right, want_right);
  std::set<std::string> places;
  for (const auto& l : left) places.insert(l.substr(0, l.find(" \"")));
  EXPECT_EQ(places.size(), left.size());
  EXPECT_TRUE(contains(mc_part, "$labels_right0 using 1:2:3 with labels right"));
  EXPECT_TRUE(datablock_lines(script, "$labels1").empty()) << "the VF1000 had no transactions";

  // The key: both viewpoints of value and state, done and failed transactions, fault events;
  // and the grid.
  for (const char* what :
       {"title \"actual, master's view (rpm)\"", "title \"actual, device (rpm)\"", "title \"state, master's view\"",
        "title \"state, device\"", "title \"done transactions\"", "title \"failed transactions\"",
        "title \"fault events\""}) {
    EXPECT_TRUE(contains(mc_part, what)) << what;
  }
  EXPECT_TRUE(contains(script, "\nset grid xtics ytics mxtics "));
  // The VF1000 had no transactions: no transaction entries in its key.
  EXPECT_FALSE(contains(vf_part, "done transactions"));
}

// The two viewpoints of the state are kept apart: the master learns a state from a status word
// that the VF1000 (sampling every 8.2 ms, INTERBUS manual) sends some cycles after it entered it, here
// START-UP INHIBIT at the end of the initialisation after a power cycle. At the end both agree.
TEST(PlotRecorder, TheMastersViewOfTheStateIsKeptApartFromTheDevices) {
  Scenario s = default_scenario();
  TimelineEntry off;
  off.at = 3s;
  off.device = "vf1000";
  off.action = Action::fault_power_cycle;
  s.timeline.push_back(off);
  std::stable_sort(s.timeline.begin(), s.timeline.end(),
                   [](const TimelineEntry& a, const TimelineEntry& b) { return a.at < b.at; });
  Simulator sim(s);
  PlotRecorder plot(sim, s.duration);
  sim.add_observer(&plot);
  sim.run();
  plot.finish(s.duration);
  const auto& vf = plot.drives()[1];
  ASSERT_EQ(vf.name, "vf1000");
  const auto at = [](const std::vector<PlotRecorder::Point>& p, double t) {
    double v = -1.0;
    for (const auto& x : p) {
      if (x.t > t) break;
      v = x.v;
    }
    return v;
  };
  const auto inhibit = static_cast<double>(drivecom::State::start_up_inhibit);
  const auto first_after = [&](const std::vector<PlotRecorder::Point>& p, double t) {
    const auto it = std::find_if(p.begin(), p.end(), [&](auto& x) { return x.t > t && x.v == inhibit; });
    return it == p.end() ? -1.0 : it->t;
  };
  EXPECT_EQ(at(vf.state, 3.05), static_cast<double>(drivecom::State::not_ready));
  const double device = first_after(vf.state, 3.5);
  const double master = first_after(vf.seen_state, 3.5);
  ASSERT_GT(device, 3.5);
  EXPECT_GT(master, device);
  EXPECT_LT(master - device, 0.05);
  EXPECT_EQ(at(vf.seen_state, device), static_cast<double>(drivecom::State::not_ready));
  EXPECT_EQ(vf.state.back().v, vf.seen_state.back().v);
  EXPECT_FALSE(vf.device_actual.empty());
}

}  // namespace
}  // namespace ibs::sim
