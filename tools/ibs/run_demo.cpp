// `ibs run`: the built-in default bus (an MC6000 with SUPI 11 / IBCNF 2 and a VF1000) driven by
// the master: both drives to ENABLED, the MC6000 to 2500.25 rpm, the VF1000 to 50 Hz, then both
// stopped. The master cycles every 1 ms; each drive samples its words at its own period.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "ibs/devices/drive_pd.hpp"

namespace ibs::cli {

namespace {

using drivecom::State;

struct Event {
  Time at;
  std::string what;
};

struct DriveLog {
  const char* name;
  std::optional<State> last;
  std::vector<Event> events;
  void observe(Time now, State s) {
    if (last == s) return;
    last = s;
    events.push_back({now, std::string(drivecom::to_string(s))});
  }
};

double ms(Time t) { return to_ms(t); }

}  // namespace

int run_demo() {
  constexpr Duration kCycle = 1ms;
  constexpr Time kEnd = 12s;

  devices::Mc6000PdDevice mc;
  devices::Vf1000PdDevice vf;
  mc.power_on();
  vf.power_on();
  devices::Mc6000PdMaster mc_master(mc.layout());
  devices::Vf1000PdMaster vf_master;

  const auto mc_words = static_cast<std::size_t>(mc.layout().pd_words);
  std::array<Word, 4> mc_out{};  // master -> MC6000
  std::array<Word, 4> mc_in{};   // MC6000 -> master
  std::array<Word, 3> vf_out{};
  std::array<Word, 3> vf_in{};
  const std::span<Word> mc_out_s(mc_out.data(), mc_words);
  const std::span<Word> mc_in_s(mc_in.data(), mc_words);
  mc_master.initial(mc_out_s);
  vf_master.initial(vf_out);
  mc.output(mc_in_s);
  vf.output(vf_in);

  DriveLog mc_log{"MC6000", {}, {}};
  DriveLog vf_log{"VF1000", {}, {}};
  std::vector<double> cycle_ns;
  cycle_ns.reserve(static_cast<std::size_t>(kEnd / kCycle));

  enum class Phase { start, run, stop, done } phase = Phase::start;
  Time vf_next_sample{0};
  Time mc_reached{-1}, vf_reached{-1}, stop_at{-1}, mc_stopped{-1}, vf_stopped{-1};

  mc_master.sequencer().request(drivecom::Target::enabled, 0ns);
  vf_master.sequencer().request(drivecom::Target::enabled, 0ns);

  for (Time now{0}; now <= kEnd; now += kCycle) {
    // Devices sample what the master wrote in the previous cycle.
    mc.sample(mc_out_s, mc_in_s, kCycle);
    if (now >= vf_next_sample) {
      vf.sample(vf_out, vf_in, kVf1000SamplePeriod);
      vf_next_sample += kVf1000SamplePeriod;
    }
    // The master's cycle: read inputs, step both drivers, write outputs.
    const auto t0 = std::chrono::steady_clock::now();
    mc_master.cycle(mc_in_s, mc_out_s, now);
    vf_master.cycle(vf_in, vf_out, now, 0);
    const auto t1 = std::chrono::steady_clock::now();
    cycle_ns.push_back(static_cast<double>(std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count()));

    if (const auto s = mc_master.sequencer().report().state_seen) mc_log.observe(now, *s);
    if (const auto s = vf_master.sequencer().report().state_seen) vf_log.observe(now, *s);

    switch (phase) {
      case Phase::start:
        if (mc.state() == State::enabled) mc_master.set_reference_rpm(2500.25);
        if (vf.state() == State::enabled) vf_master.set_frequency_hz(50.0);
        if (mc_reached < 0ns && (mc_in[0] & 0x0400U) != 0 && mc_master.actual_rpm() == 2500.25) {
          mc_reached = now;
          mc_log.events.push_back({now, "reference 2500.25 rpm reached"});
        }
        if (vf_reached < 0ns && (vf_in[0] & 0x0400U) != 0 && vf_master.actual_hz() == 50.0) {
          vf_reached = now;
          vf_log.events.push_back({now, "reference 50.00 Hz reached"});
        }
        if (mc_reached >= 0ns && vf_reached >= 0ns && now >= std::max(mc_reached, vf_reached) + 1s) {
          phase = Phase::stop;
          stop_at = now;
          mc_master.set_reference_rpm(0.0);
          vf_master.set_frequency_hz(0.0);
          mc_log.events.push_back({now, "stop: reference 0 rpm"});
          vf_log.events.push_back({now, "stop: reference 0 Hz"});
        }
        break;
      case Phase::stop:
        if (mc_stopped < 0ns && mc_master.actual_rpm() == 0.0) {
          mc_stopped = now;
          mc_master.sequencer().request(drivecom::Target::ready, now);
        }
        if (vf_stopped < 0ns && vf_master.actual_hz() == 0.0) {
          vf_stopped = now;
          vf_master.sequencer().request(drivecom::Target::ready, now);
        }
        if (mc_stopped >= 0ns && vf_stopped >= 0ns &&
            mc_master.sequencer().report().phase == drivecom::Phase::reached &&
            vf_master.sequencer().report().phase == drivecom::Phase::reached) {
          phase = Phase::done;
        }
        break;
      case Phase::run:
      case Phase::done: break;
    }
    if (phase == Phase::done) break;
  }

  std::printf("ibs run: DRIVECOM demonstration on the default bus (MC6000 SUPI 11 / IBCNF 2, VF1000)\n");
  std::printf("master cycle 1.000 ms; MC6000 samples every 1 ms, VF1000 every 8.2 ms\n\n");
  for (const DriveLog* log : {&mc_log, &vf_log}) {
    std::printf("%s\n", log->name);
    for (const auto& e : log->events) std::printf("  %9.1f ms  %s\n", ms(e.at), e.what.c_str());
    std::printf("\n");
  }
  std::sort(cycle_ns.begin(), cycle_ns.end());
  const double median = cycle_ns.empty() ? 0.0 : cycle_ns[cycle_ns.size() / 2];
  const double worst = cycle_ns.empty() ? 0.0 : cycle_ns.back();
  std::printf("master processing per cycle (both drivers): median %.0f ns, max %.0f ns over %zu cycles\n",
              median, worst, cycle_ns.size());
  std::printf("  budget 1 ms (MC6000): %.4f %% used at the median; budget 8.2 ms (VF1000): %.5f %%\n",
              median / 1e4, median / 8.2e4);
  const bool ok = phase == Phase::done;
  std::printf("\nresult: %s\n", ok ? "both drives started, ran to their references and stopped"
                                   : "the sequence did not complete");
  return ok ? kExitOk : kExitMismatch;
}

}  // namespace ibs::cli
