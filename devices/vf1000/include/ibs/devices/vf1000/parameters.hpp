// The VF1000's parameters (INTERBUS manual 3.1.1, 4.1.1, 4.1.3; LUSTBUS manual for the family's numbers): the
// table with the manuals' numbers, names, units, categories, types, ranges and defaults, the
// numbers the drive acts on, and the process-data watchdog's settings 906/907. The table belongs
// to the drive: the communication-word server serves it (vf1000_channel/server.hpp) through the
// drive-neutral table and store of drive/parameters.hpp.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>

#include "ibs/devices/vf1000/dictionary.hpp"
#include "ibs/drive/parameters.hpp"
#include "ibs/base/words.hpp"

namespace ibs::devices::vf1000 {

// The parameter numbers (pnr::) are the dictionary's (dictionary.hpp), written once there.

// The VF1000 parameter table with the INTERBUS factory defaults (sorted by number; static data).
std::span<const drive::ParameterInfo> parameters();
// The same table with the standard factory defaults of an inverter without the INTERBUS software
// package (INTERBUS manual 3.1.1; LUSTBUS manual 4.1: a drive on LUSTBUS alone; decision VF-E20).
std::span<const drive::ParameterInfo> standalone_parameters();
// 61-SOUTA = 7 switches the data direction of an RS-485 interface (LUSTBUS manual 4).
inline constexpr Word kSoutaRs485 = 7;

// 907-IBCOD: the reaction to the process-data watchdog (INTERBUS manual 4.1.1).
enum class IbCod : std::uint8_t {
  no_action = 0,
  shutdown_e_ibs = 1,  // shutdown with error E-IBS (no. 12)
  block_power = 2,     // device control command "Block power"
  emergency_stop = 3,  // device control command "Emergency Stop"
};
inline constexpr std::uint8_t kErrorEIbs = 12;
// 906-IB-WD: the monitoring time the inverter actually uses. It counts in 50 ms steps, rounding
// up (IB-WD = 65 -> 100 ms); the maximum value 65535 switches the monitoring off (nullopt).
constexpr std::optional<std::chrono::milliseconds> ib_wd_monitoring_time(Word ib_wd) {
  if (ib_wd == 0xFFFF) return std::nullopt;
  const unsigned steps = (static_cast<unsigned>(ib_wd) + 49U) / 50U;
  return std::chrono::milliseconds(50U * steps);
}

}  // namespace ibs::devices::vf1000
