// Recorded simulator runs are `ibs-trace 1` files that replay unchanged against the device models
// (../shared/specs/trace-format.md).
#include <gtest/gtest.h>

#include "ibs/devices/trace_adapters.hpp"
#include "ibs/sim/simulator.hpp"

namespace ibs::sim {
namespace {

TimelineEntry entry(Time t, const std::string& dev, Action a, const std::string& value = "", double number = 0,
                    std::uint16_t parameter = 0) {
  TimelineEntry e;
  e.at = t;
  e.device = dev;
  e.action = a;
  e.value = value;
  e.number = number;
  e.parameter = parameter;
  return e;
}

Scenario busy_run() {
  Scenario s;
  s.duration = 3s;
  DeviceConfig mc;
  mc.name = "servo";
  mc.kind = DeviceKind::mc6000;
  mc.phase = 300us;
  mc.jitter = 50us;
  DeviceConfig vf;
  vf.name = "inverter";
  vf.kind = DeviceKind::vf1000;
  vf.phase = 5ms;
  vf.jitter = 1ms;
  s.devices = {mc, vf};
  s.timeline = {entry(0s, "servo", Action::state, "enabled"),
                entry(0s, "inverter", Action::state, "enabled"),
                entry(10ms, "inverter", Action::read, "", 0, 85),
                entry(100ms, "servo", Action::speed, "", 2500.25),
                entry(100ms, "inverter", Action::frequency, "", -20.0),
                entry(400ms, "inverter", Action::write, "", 500, 22),
                entry(800ms, "inverter", Action::describe, "", 0, 45),
                entry(1500ms, "servo", Action::emergency_stop),
                entry(2000ms, "inverter", Action::state, "ready"),
                entry(2200ms, "servo", Action::state, "enabled"),
                entry(2200ms, "", Action::fault_corrupt, "", 0, 0)};
  return s;
}

TEST(Recording, EveryDeviceTraceReplaysUnchanged) {
  Simulator sim(busy_run());
  SimOptions o;
  o.record_traces = true;
  sim.run(o);
  const auto traces = sim.traces();
  ASSERT_EQ(traces.size(), 2U);
  for (const auto& r : traces) {
    // Through the text format, as a file on disk would be.
    const trace::Trace t = trace::parse(trace::write(r.trace), r.file_name);
    EXPECT_GT(t.rows.size(), 300U) << r.file_name;
    const auto device = devices::make_device_side(t);
    const auto explain = devices::make_explainer(t);
    const auto result = trace::replay_device(t, *device, *explain);
    EXPECT_TRUE(result.matched) << r.file_name << "\n" << result.message;
    EXPECT_EQ(result.steps_matched, t.rows.size());
  }
  EXPECT_EQ(traces[0].file_name, "servo.trace");
  EXPECT_EQ(traces[1].file_name, "inverter.trace");
}

TEST(Recording, ATamperedRecordingFailsAtTheTamperedRow) {
  Simulator sim(busy_run());
  SimOptions o;
  o.record_traces = true;
  sim.run(o);
  trace::Trace t = sim.traces()[1].trace;
  t.rows[200].s2m[0].value ^= 0x0400;  // flip "reference reached"
  const auto device = devices::make_device_side(t);
  const auto result = trace::replay_device(t, *device, *devices::make_explainer(t));
  EXPECT_FALSE(result.matched);
  EXPECT_EQ(result.steps_matched, 200U);
}

TEST(Recording, APowerCycleStartsANewRecordingOnceTheDeviceLooksFreshlyStarted) {
  // The trace format has no power cycle: the recording ends there, and a new one starts when the
  // device shows what a device started with `init: power-on` shows (the master sends BLOCK POWER).
  Scenario s = busy_run();
  std::erase_if(s.timeline, [](const TimelineEntry& e) { return e.device == "inverter" && e.at >= 900ms; });
  s.timeline.push_back(entry(900ms, "inverter", Action::state, "start-up-inhibit"));
  s.timeline.push_back(entry(1000ms, "inverter", Action::fault_power_cycle));
  s.timeline.push_back(entry(6000ms, "inverter", Action::state, "enabled"));
  s.timeline.push_back(entry(6000ms, "inverter", Action::frequency, "", 10.0));
  s.duration = 8s;
  std::stable_sort(s.timeline.begin(), s.timeline.end(),
                   [](const TimelineEntry& a, const TimelineEntry& b) { return a.at < b.at; });
  Simulator sim(s);
  SimOptions o;
  o.record_traces = true;
  sim.run(o);
  const auto traces = sim.traces();
  ASSERT_EQ(traces.size(), 3U);
  EXPECT_EQ(traces[2].file_name, "inverter.2.trace");
  EXPECT_EQ(traces[2].trace.header.init, trace::InitState::power_on);
  EXPECT_NE(traces[1].trace.trailing_comments.at(0).find("recording ends: power cycle"), std::string::npos);
  for (const auto& r : traces) {
    const trace::Trace t = trace::parse(trace::write(r.trace), r.file_name);
    const auto result = trace::replay_device(t, *devices::make_device_side(t), *devices::make_explainer(t));
    EXPECT_TRUE(result.matched) << r.file_name << "\n" << result.message;
  }
}

}  // namespace
}  // namespace ibs::sim

namespace ibs::sim {
namespace {

TEST(Recording, ADeviceWithoutProcessDataIsNotRecorded) {
  Scenario s;
  s.duration = 500ms;
  DeviceConfig pcp_only;
  pcp_only.name = "parameters";
  pcp_only.kind = DeviceKind::mc6000;
  pcp_only.supi = 3;  // 4 PCP words, no process data
  pcp_only.ibcnf = 0;
  DeviceConfig vf;
  vf.name = "inverter";
  vf.kind = DeviceKind::vf1000;
  s.devices = {pcp_only, vf};
  s.timeline = {entry(0s, "parameters", Action::read, "", 0, 85)};
  Simulator sim(s);
  SimOptions o;
  o.record_traces = true;
  sim.run(o);
  const auto traces = sim.traces();
  ASSERT_EQ(traces.size(), 1U);
  EXPECT_EQ(traces[0].file_name, "inverter.trace");
  ASSERT_EQ(sim.summary().transactions.size(), 1U);
  EXPECT_EQ(sim.summary().transactions[0].kind, devices::ParamKind::value) << sim.summary().transactions[0].result;
}

}  // namespace
}  // namespace ibs::sim

namespace ibs::sim {
namespace {

struct NullObserver final : Observer {
  void on_cycle(Time, bool, const interbus::ProcessImage&) override { ++cycles; }
  void on_sample(Time, std::size_t, std::span<const Word>, std::span<const Word>) override { ++samples; }
  std::uint64_t cycles = 0;
  std::uint64_t samples = 0;
};

std::string fingerprint(Simulator& sim) {
  std::string f;
  for (const auto& d : sim.summary().devices) {
    for (const auto& s : d.states) f += std::to_string(s.at.count()) + d.name + s.what + "\n";
  }
  for (const auto& t : sim.summary().transactions) {
    f += std::to_string(t.finished ? t.finished->count() : -1) + t.result + "\n";
  }
  for (const auto& x : sim.summary().faults) f += std::to_string(x.at.count()) + x.kind + "\n";
  for (const auto& r : sim.traces()) f += trace::write(r.trace);
  return f;
}

TEST(Recording, AnObserverDoesNotChangeTheRun) {
  // Without an observer the simulator steps device by device between cycle ends; with one (a VCD
  // file) strictly in time order. Both must give the same run, jitter and random faults included.
  Scenario s = busy_run();
  s.random.seed = 7;
  s.random.corrupt_per_s = 3;
  s.random.device_fault_per_s = 0.5;
  SimOptions o;
  o.record_traces = true;
  o.measure_master_time = false;
  Simulator plain(s);
  plain.run(o);
  Simulator observed(s);
  NullObserver null;
  observed.add_observer(&null);
  observed.run(o);
  EXPECT_GT(null.samples, 3000U);
  EXPECT_EQ(null.cycles, observed.summary().cycles);
  const std::string a = fingerprint(plain);
  EXPECT_GT(a.size(), 10000U);
  EXPECT_EQ(a, fingerprint(observed));
}

}  // namespace
}  // namespace ibs::sim
