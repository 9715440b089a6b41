// The cycle simulator's private parts, shared by the files that implement it, each with one job:
//   simulator.cpp            the ring built from a scenario, the run from start to finish
//   simulator_stepping.cpp   the devices' samples between cycle ends: device by device (one or
//                            several threads, held stretches) or time-ordered (with observers)
//   simulator_cycle.cpp      the cycle end: the bus exchange (the far side of the master's bus
//                            seam, master/bus.hpp) and the master's half, what the summary takes
//   simulator_faults.cpp     the scenario's timeline, injected and random faults
//   simulator_recording.cpp  traces of the devices' words
#pragma once

#include <sched.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "ibs/interbus/cycle_time.hpp"
#include "ibs/interbus/id_code.hpp"
#include "ibs/sim/master_timeline.hpp"
#include "ibs/sim/simulator.hpp"

namespace ibs::sim {

using State = drivecom::State;

namespace detail {


inline std::string fmt_value(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

inline double wall_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}


// The processor cores this process may run on (its affinity mask: `taskset` and container CPU
// sets count, not only the machine's cores).
inline unsigned usable_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return static_cast<unsigned>(std::max(1, CPU_COUNT(&set)));
  return std::max(1U, std::thread::hardware_concurrency());
}

// Copies a device's words (at most four) without a library call: every cycle does it for every
// device.
inline void copy_words(std::span<const Word> from, Word* to) {
  switch (from.size()) {
    case 4: to[3] = from[3]; [[fallthrough]];
    case 3: to[2] = from[2]; [[fallthrough]];
    case 2: to[1] = from[1]; [[fallthrough]];
    case 1: to[0] = from[0]; [[fallthrough]];
    case 0: break;
    default: std::copy(from.begin(), from.end(), to);
  }
}

// Exponentially distributed time to the next random fault of a given rate (per second).
inline Time next_random(std::mt19937_64& rng, Time from, double rate_per_s) {
  if (rate_per_s <= 0.0) return Time::max();
  std::exponential_distribution<double> d(rate_per_s);
  const double s = d(rng);
  return from + std::chrono::duration_cast<Duration>(std::chrono::duration<double>(s));
}

}  // namespace detail

struct Simulator::Recording {
  trace::Trace trace;
  std::uint64_t step = 0;
  std::string remark;  // events to note on the next row
  // Device faults as trace events: injected before the device's next sample, they show after
  // that sample's row (before the step whose s2m is the first answer the fault can change).
  std::vector<trace::Event> events_pending;
  // What goes between the last row and the next one, in order: those events and the samples
  // without data (`! no-data N`, trace-format.md "Events").
  std::vector<trace::Event> between;
  std::string file_name;
};

struct Simulator::Device {
  DeviceConfig cfg;
  std::size_t index = 0;
  const devices::DriveKind* kind = nullptr;
  devices::Configuration configuration;
  std::unique_ptr<devices::DeviceEmulator> emu;
  Duration period{0};
  std::size_t pd_words = 0;
  std::size_t pcp_words = 0;
  // The device's slices of the master's process image (set once the ring is built): its whole
  // input slot, and the words it exchanges each way.
  std::span<Word> in_slot, in, out, pcp_in, pcp_out;
  std::array<Word, 4> m2s{};  // the master's process-data words as the bus last delivered them
  // A valid cycle delivered the master's words since the device's last sample; one ever did.
  // Recorded: a sample no valid cycle reached is a trace step without data.
  bool delivered = false;
  bool ever_delivered = false;
  std::array<Word, 4> pcp_m2s{};
  // What the device's sampling writes, in cache lines of its own: with several threads the
  // device is stepped on one while the cycle end runs on another.
  alignas(64) std::array<Word, 4> s2m{};  // the device's words, picked up by the next valid cycle
  std::array<Word, 4> pcp_s2m{};
  std::uint64_t k = 0;  // samples taken
  Time next_sample{0};
  Time last_sample{0};
  std::uint64_t jitter_state = 0;
  alignas(64) Time lost_until{-1};
  Time fault_until{-1};
  std::optional<int> reported_error;
  std::vector<Recording> recordings;
  bool recording = false;
  bool power_cycled = false;
  bool switched_off = false;  // bypassed by the master (Simulator::set_switched_off)
  std::uint32_t notices = 0;  // the emulator's notices already in the records
  // Summary records the device's sampling made (15-PLRDY), moved into the summary at the next
  // cycle end: the sampling may run on another thread than the summary's.
  std::vector<StateRecord> records;
  std::optional<int> error_at_cycle;  // error_number() at the last cycle end
  // splitmix64: a small, fast generator of its own for the device's sample jitter.
  std::uint64_t jitter_rng() {
    std::uint64_t z = (jitter_state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27U)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31U);
  }
  // What a device started for a trace shows before its first sample (`init: power-on` and
  // `init: operational`).
  std::array<Word, 4> fresh_initialised{};
  std::array<Word, 4> fresh_operational{};

  [[nodiscard]] bool lost(Time t) const { return t < lost_until; }
  [[nodiscard]] bool module_error(Time t) const {
    return lost(t) || emu->module_error(t);
  }
  [[nodiscard]] State state() const { return emu->state(); }
  [[nodiscard]] std::span<Word> pd_m2s() { return {m2s.data(), pd_words}; }
  [[nodiscard]] std::span<Word> pd_s2m() { return {s2m.data(), pd_words}; }
};

}  // namespace ibs::sim
