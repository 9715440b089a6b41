// Recorded simulator runs are `ibs-trace 1` files that replay unchanged against the device models
// (../shared/specs/trace-format.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>

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
  mc.kind = "mc6000";
  mc.phase = 300us;
  mc.jitter = 50us;
  DeviceConfig vf;
  vf.name = "inverter";
  vf.kind = "vf1000";
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

// Device faults are recorded as `! fault` / `! fault-cleared` event lines
// (trace-format.md, "Events"), so a recording with injected faults replays unchanged.
TEST(Recording, InjectedDeviceFaultsAreRecordedAsEventsAndReplay) {
  Scenario s = busy_run();
  for (const char* dev : {"servo", "inverter"}) {
    TimelineEntry f = entry(600ms, dev, Action::fault_device);
    f.duration = 40ms;
    s.timeline.push_back(f);
    s.timeline.push_back(entry(1200ms, dev, Action::state, "enabled"));
  }
  std::stable_sort(s.timeline.begin(), s.timeline.end(), [](const auto& a, const auto& b) { return a.at < b.at; });
  Simulator sim(s);
  SimOptions o;
  o.record_traces = true;
  sim.run(o);
  const auto traces = sim.traces();
  ASSERT_EQ(traces.size(), 2U);
  for (const auto& r : traces) {
    const std::string text = trace::write(r.trace);
    EXPECT_NE(text.find("\n! fault injected at 60"), std::string::npos) << r.file_name;
    EXPECT_NE(text.find("\n! fault-cleared at "), std::string::npos) << r.file_name;
    const trace::Trace t = trace::parse(text, r.file_name);
    const auto result = trace::replay_device(t, *devices::make_device_side(t), *devices::make_explainer(t));
    EXPECT_TRUE(result.matched) << r.file_name << "\n" << result.message;
    EXPECT_EQ(result.steps_matched, t.rows.size());
    // Without its events the same recording does not replay: the fault is not in the words.
    trace::Trace stripped = t;
    for (auto& row : stripped.rows) row.events_before.clear();
    const auto without = trace::replay_device(stripped, *devices::make_device_side(stripped),
                                              *devices::make_explainer(stripped));
    EXPECT_FALSE(without.matched) << r.file_name;
  }
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
  EXPECT_EQ(traces[2].trace.header.init, DeviceStart::initialised);
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
  pcp_only.kind = "mc6000";
  pcp_only.settings.set_integer("supi", 3);  // 4 PCP words, no process data
  pcp_only.settings.set_integer("ibcnf", 0);
  DeviceConfig vf;
  vf.name = "inverter";
  vf.kind = "vf1000";
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

// A ring with work for several threads: servos without PCP (stepped a cycle's samples at a time),
// some with jitter, servos with PCP, inverters; watchdogs, e-stops, parameter traffic and random
// faults of every kind.
Scenario big_ring() {
  Scenario s;
  s.duration = 2s;
  s.random.seed = 11;
  s.random.corrupt_per_s = 2;
  s.random.power_cycle_per_s = 1;
  s.random.device_fault_per_s = 2;
  s.random.lost_per_s = 1;
  s.bus.cycle_time = 4ms;
  for (int i = 0; i < 20; ++i) {
    DeviceConfig d;
    d.name = "d" + std::to_string(i);
    d.kind = i % 10 == 9 ? "vf1000" : "mc6000";
    d.settings.set_integer("supi", i % 10 == 8 ? 11 : 12);
    d.settings.set_integer("ibcnf", 2);
    // Every third servo samples exactly at the cycle ends (4 ms, a whole number of periods):
    // those samples come after the exchange.
    d.phase = i % 3 == 0 ? Duration{0} : std::chrono::microseconds(37 * i);
    if (i % 4 == 1) d.jitter = 80us;
    if (i % 5 == 2) d.watchdog_ms = 15;
    s.devices.push_back(d);
    s.timeline.push_back(entry(0s, d.name, Action::state, "enabled"));
    s.timeline.push_back(entry(50ms, d.name, d.kind == "vf1000" ? Action::frequency : Action::speed, "",
                               d.kind == "vf1000" ? 30.0 : 400.0 + 150.0 * i));
    if (i % 6 == 3) s.timeline.push_back(entry(900ms, d.name, Action::emergency_stop));
  }
  s.timeline.push_back(entry(300ms, "d8", Action::read, "", 0, 77));
  s.timeline.push_back(entry(400ms, "d9", Action::read, "", 0, 85));
  TimelineEntry corrupt = entry(1200ms, "", Action::fault_corrupt);
  corrupt.count = 30;  // ~30 cycles without data: the watchdogs of 15 ms run out
  s.timeline.push_back(corrupt);
  std::sort(s.timeline.begin(), s.timeline.end(), [](const TimelineEntry& a, const TimelineEntry& b) { return a.at < b.at; });
  return s;
}

std::string final_values(Simulator& sim) {
  std::string f;
  for (const auto& d : sim.summary().devices) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%a %a %llu ", d.final_actual, d.final_reference,
                  static_cast<unsigned long long>(d.samples));
    f += d.name + " " + d.final_state + " " + buf + "\n";
  }
  return f;
}

TEST(Recording, ThreadsAndCycleAtATimeSteppingDoNotChangeTheRun) {
  // The run on one thread, on three (more than this machine may have: the parts still split),
  // and strictly in time order with an observer must be the same, bit for bit.
  const Scenario s = big_ring();
  const auto run = [&](unsigned threads, bool observe, bool record) {
    auto sim = std::make_unique<Simulator>(s);
    NullObserver null;
    if (observe) sim->add_observer(&null);
    SimOptions o;
    o.measure_master_time = false;
    o.threads = threads;
    o.record_traces = record;
    sim->run(o);
    EXPECT_EQ(sim->threads(), observe ? 1U : threads);
    return fingerprint(*sim) + final_values(*sim);
  };
  const std::string one = run(1, false, false);
  EXPECT_GT(one.size(), 2000U);
  EXPECT_NE(one.find("reached"), std::string::npos);
  EXPECT_NE(one.find("watchdog"), std::string::npos);
  EXPECT_NE(one.find("power-cycle"), std::string::npos);
  EXPECT_EQ(one, run(3, false, false));
  EXPECT_EQ(one, run(1, true, false));
  // Recorded, every device goes sample by sample; the traces agree too.
  const std::string recorded = run(2, false, true);
  EXPECT_EQ(recorded, run(1, true, true));
}

}  // namespace
}  // namespace ibs::sim
