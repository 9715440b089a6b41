// One DRIVECOM step on each side for each drive type, and a closed loop START-UP INHIBIT ->
// ENABLED. Targets (issue 2): each step well under 5 ns.
#include <benchmark/benchmark.h>

#include <array>

#include "ibs/devices/mc6000/pd_device.hpp"
#include "ibs/devices/mc6000/pd_master.hpp"
#include "ibs/devices/vf1000/pd_device.hpp"
#include "ibs/devices/vf1000/pd_master.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/drivecom/sequencer.hpp"

namespace {

using namespace ibs;
using namespace ibs::drivecom;

// A device sample in a steady state (ENABLED, ENABLE held): the cycle's common case.
void device_step(benchmark::State& st, EmergencyStopExit exit) {
  DeviceStateMachine m(exit, State::enabled);
  DeviceInputs in{.control = 0x000F};
  for (auto _ : st) {
    benchmark::DoNotOptimize(in);
    const SampleResult r = m.sample(in);
    benchmark::DoNotOptimize(r);
  }
}
void BM_DeviceStep_Mc6000(benchmark::State& st) { device_step(st, EmergencyStopExit::on_block_power_only); }
void BM_DeviceStep_Vf1000(benchmark::State& st) { device_step(st, EmergencyStopExit::automatic_when_stopped); }

// A master step holding ENABLED (application bits as each driver sets them).
void master_step(benchmark::State& st, Word app_bits) {
  Sequencer seq;
  seq.set_application_bits(app_bits);
  seq.request(Target::enabled, 0ns);
  Word status = 0x0637;
  Time now{0};
  for (auto _ : st) {
    benchmark::DoNotOptimize(status);
    const Word w = seq.step(status, now);
    benchmark::DoNotOptimize(w);
    now += 1ms;
  }
}
void BM_MasterStep_Mc6000(benchmark::State& st) { master_step(st, 0x0000); }
void BM_MasterStep_Vf1000(benchmark::State& st) { master_step(st, 0x8070); }

// The full process-data step of each drive model and master driver, words in and out.
void BM_Mc6000PdDeviceSample(benchmark::State& st) {
  devices::Mc6000PdDevice dev;
  std::array<Word, 3> out{0x000F, 0x09C4, 0x4000}, in{};
  for (auto _ : st) {
    dev.sample(out, in, 1ms);
    benchmark::DoNotOptimize(in);
  }
}
void BM_Vf1000PdDeviceSample(benchmark::State& st) {
  devices::Vf1000PdDevice dev;
  std::array<Word, 3> out{0x807F, 0x03E8, 0x0000}, in{};
  for (auto _ : st) {
    dev.sample(out, in, ibs::devices::vf1000::kSamplePeriod);
    benchmark::DoNotOptimize(in);
  }
}
void BM_Mc6000PdMasterCycle(benchmark::State& st) {
  devices::Mc6000PdMaster m(devices::mc6000::make_layout(11, 2));
  m.set_reference_rpm(2500.25);
  m.sequencer().request(Target::enabled, 0ns);
  std::array<Word, 3> s2m{0x0637, 0x09C4, 0x4000}, m2s{};
  Time now{0};
  for (auto _ : st) {
    m.cycle(s2m, m2s, now);
    benchmark::DoNotOptimize(m2s);
    now += 1ms;
  }
}

// Closed loop: master and MC6000-style device from START-UP INHIBIT to ENABLED (2 cycles), both
// built anew each time. Out of line so that callgrind counts one start-up per call
// (bench/callgrind_per_call.sh ... closed_loop_once).
[[gnu::noinline]] Word closed_loop_once(EmergencyStopExit exit, std::int64_t& cycles) {
  DeviceStateMachine dev(exit, State::start_up_inhibit);
  Sequencer seq;
  seq.request(Target::enabled, 0ns);
  Word status = 0x0240;
  Time now{0};
  while (dev.state() != State::enabled) {
    DeviceInputs in{.control = seq.step(status, now)};
    dev.sample(in);
    status = status_word(dev.state(), dev.last_control(), {});
    now += 1ms;
    ++cycles;
  }
  return status;
}
void closed_loop(benchmark::State& st, EmergencyStopExit exit) {
  std::int64_t cycles = 0;
  for (auto _ : st) {
    const Word status = closed_loop_once(exit, cycles);
    // The loop's value checked: ENABLED as the device shows it (5.1.3), not only reached.
    if (decode_state(status) != State::enabled) st.SkipWithError("the closed loop did not end in ENABLED");
    benchmark::DoNotOptimize(status);
  }
  st.counters["cycles"] = benchmark::Counter(static_cast<double>(cycles) / static_cast<double>(st.iterations()));
}
void BM_ClosedLoopStartUpToEnabled_Mc6000(benchmark::State& st) { closed_loop(st, EmergencyStopExit::on_block_power_only); }
void BM_ClosedLoopStartUpToEnabled_Vf1000(benchmark::State& st) { closed_loop(st, EmergencyStopExit::automatic_when_stopped); }

BENCHMARK(BM_DeviceStep_Mc6000);
BENCHMARK(BM_DeviceStep_Vf1000);
BENCHMARK(BM_MasterStep_Mc6000);
BENCHMARK(BM_MasterStep_Vf1000);
BENCHMARK(BM_Mc6000PdDeviceSample);
BENCHMARK(BM_Vf1000PdDeviceSample);
BENCHMARK(BM_Mc6000PdMasterCycle);
BENCHMARK(BM_ClosedLoopStartUpToEnabled_Mc6000);
BENCHMARK(BM_ClosedLoopStartUpToEnabled_Vf1000);

}  // namespace
