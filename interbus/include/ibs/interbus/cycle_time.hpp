// INTERBUS cycle time, reaction time and error recovery (public-facts.md, "Cycle time": Beckhoff
// BC4000 documentation, same form in Lenze EMF2111IB):
//
//   T_cycle = SW + (13 * (6 + N) + 1.5 * M) * T_bit  [+ cable length * 0.24 ms/km, Lenze]
//
// N = process-data bytes in the ring (PCP words included: they are register words like any
// other), M = remote-bus devices (bus couplers), T_bit = 2 us at 500 kbit/s.
#pragma once

#include <cstddef>

#include "ibs/base/time.hpp"

namespace ibs::interbus {

struct BusConfig;

enum class BaudRate { kbit500, mbit2 };

inline constexpr Duration kBitTime500k = 2us;  // 500 kbit/s, every INTERBUS device
inline constexpr Duration kBitTime2M = 500ns;  // 2 Mbit/s, later devices only
constexpr Duration bit_time(BaudRate b) {
  return b == BaudRate::mbit2 ? kBitTime2M : kBitTime500k;
}

// Every term of the formula, defaults as in the sources.
struct CycleTimeParams {
  Duration software_time = 200us;       // SW: the master's software time per cycle (Beckhoff)
  Duration bit_time = kBitTime500k;     // T_bit
  double line_bits_per_byte = 13.0;     // the 13: line bits per data byte
  double overhead_bytes = 6.0;          // the 6: protocol bytes of every cycle
  double bits_per_remote_device = 1.5;  // the 1.5: per remote-bus device / coupler
  double cable_km = 0.0;                // total cable length; 0 = Beckhoff's form
  Duration cable_time_per_km = 240us;   // Lenze's cable term, about 0.24 ms per km
};

constexpr CycleTimeParams params_for(BaudRate b) {
  CycleTimeParams p;
  p.bit_time = bit_time(b);
  return p;
}

// What the formula needs from a ring.
struct RingLoad {
  std::size_t data_bytes = 0;      // N
  std::size_t remote_devices = 0;  // M
};
RingLoad ring_load(const BusConfig& c);

// Rounded to the nearest nanosecond (exact for the defaults at 500 kbit/s and 2 Mbit/s).
Duration cycle_time(RingLoad load, const CycleTimeParams& p = {});
Duration cycle_time(const BusConfig& c, const CycleTimeParams& p = {});

// Data written just after a cycle started reaches the device at the end of the next one.
inline constexpr int kReactionCycles = 2;
// Cycles after a transmission error before valid data flows again (about 5).
inline constexpr int kRecoveryCycles = 5;

constexpr Duration worst_case_reaction_time(Duration cycle, int cycles = kReactionCycles) {
  return cycle * cycles;
}
constexpr Duration recovery_time(Duration cycle, int cycles = kRecoveryCycles) {
  return cycle * cycles;
}

}  // namespace ibs::interbus
