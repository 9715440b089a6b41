// A full bus: 64 MC6000 with four process-data words each (SUPI 12, 256 words each way).
// Targets (issue 4): one master cycle under 1 us; the simulation at least 1000 times faster than
// real time.
#include <benchmark/benchmark.h>

#include "ibs/devices/mc6000/driver.hpp"
#include "ibs/master/master_loop.hpp"
#include "ibs/sim/simulator.hpp"

namespace {

using namespace ibs;
using namespace ibs::sim;
using master::MasterLoop;

void BM_MasterCycleFullBus(benchmark::State& st) {
  std::vector<interbus::DeviceSpec> specs;
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers;
  const auto layout = devices::mc6000::make_layout(12, 2);
  for (int i = 0; i < 64; ++i) {
    specs.push_back({"mc" + std::to_string(i), interbus::IdCode{layout.id_code}, std::nullopt});
    drivers.push_back(std::make_unique<devices::Mc6000Driver>(layout));
  }
  MasterLoop loop(interbus::make_bus_config(specs), std::move(drivers));
  interbus::ProcessImage image;
  loop.initial(image);
  std::vector<master::LinkState> links(64);
  for (std::size_t i = 0; i < 64; ++i) {
    loop.driver(i).sequencer().request(drivecom::Target::enabled, 0ns);
    loop.driver(i).set_reference(1000.0 + static_cast<double>(i));
    image.in[4 * i] = 0x0637;  // ENABLED, reference reached
  }
  Time now{0};
  for (auto _ : st) {
    loop.cycle(image, now, master::Exchange{true, links});
    benchmark::DoNotOptimize(image.out.data());
    now += 1ms;
  }
}
BENCHMARK(BM_MasterCycleFullBus);

Scenario full_bus(Duration duration) {
  Scenario s;
  s.duration = duration;
  for (int i = 0; i < 64; ++i) {
    DeviceConfig d;
    d.name = "mc" + std::to_string(i);
    d.kind = "mc6000";
    d.supi = 12;
    d.ibcnf = 2;
    d.phase = std::chrono::microseconds(i * 15);
    s.devices.push_back(d);
    TimelineEntry e;
    e.device = d.name;
    e.action = Action::state;
    e.value = "enabled";
    s.timeline.push_back(e);
    e.action = Action::speed;
    e.number = 1000.0 + 10.0 * i;
    s.timeline.push_back(e);
  }
  return s;
}

// One simulated second of the full bus: cycles at the formula's cycle time (13.7 ms for 512 bytes)
// and 64 servos sampling every 1 ms with their plants, all enabled and accelerating to their
// speeds at t = 0. Argument: the threads stepping the devices. Wall-clock time, against real time.
void BM_SimulateFullBusOneSecond(benchmark::State& st) {
  const Scenario s = full_bus(1s);
  double simulated = 0;
  for (auto _ : st) {
    Simulator sim(s);
    SimOptions o;
    o.measure_master_time = false;
    o.threads = static_cast<unsigned>(st.range(0));
    sim.run(o);
    simulated += 1.0;
    benchmark::DoNotOptimize(sim.summary().cycles);
  }
  st.counters["x_real_time"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulateFullBusOneSecond)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// One simulated bus cycle (13.7 ms) of the same bus, all device models, in a long run (the
// drives at their speeds after the first second). Argument: threads.
void BM_SimulatedCycleFullBus(benchmark::State& st) {
  const Scenario s = full_bus(3600s);
  Simulator sim(s);
  SimOptions o;
  o.measure_master_time = false;
  o.threads = static_cast<unsigned>(st.range(0));
  Time until = 1s;
  sim.run_until(until, o);
  for (auto _ : st) {
    until += sim.cycle_time();
    sim.run_until(until, o);
  }
  const double per_cycle_s = static_cast<double>(sim.cycle_time().count()) * 1e-9;
  st.counters["x_real_time"] =
      benchmark::Counter(static_cast<double>(st.iterations()) * per_cycle_s, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulatedCycleFullBus)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

// The default scenario of `ibs run` (an MC6000 and a VF1000, 8 s with parameter traffic).
void BM_SimulateDefaultScenario(benchmark::State& st) {
  const Scenario s = default_scenario();
  double simulated = 0;
  for (auto _ : st) {
    Simulator sim(s);
    SimOptions o;
    o.measure_master_time = false;
    sim.run(o);
    simulated += static_cast<double>(s.duration.count()) / 1e9;
    benchmark::DoNotOptimize(sim.summary().cycles);
  }
  st.counters["x_real_time"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulateDefaultScenario)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
