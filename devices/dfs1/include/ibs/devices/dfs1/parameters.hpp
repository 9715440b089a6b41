// The DFS-1 parameters that the public pages name (../shared/notes/public-facts.md, "PowerTec
// DFS-1"; DFS-1 manual). Every number, range, default or unit the sources do not give is a modelling
// choice marked `invented` with what was invented in `note` (docs/dfs1.md, "Parameters").
// A read or write of a number outside this table is NAK 82, a value outside the range NAK 83.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "ibs/devices/dfs1/dictionary.hpp"

namespace ibs::devices::dfs1 {

struct ParameterInfo {
  std::uint8_t number;
  std::string_view name;
  std::string_view unit;
  std::uint32_t min;
  std::uint32_t max;
  std::uint32_t default_value;
  bool invented;          // some of range / default / unit / meaning is a modelling choice
  std::string_view note;  // the source, and what is invented
};

// The named numbers and parameter 3's bits are the dictionary's (dictionary.hpp).

inline constexpr std::array<ParameterInfo, 8> kParameters = {{
    {kUnitId, "unit ID", "", 1, 255, 1, false, "notes: UID 1..255, default 1"},
    {kBaudCode, "baud rate code", "code", 0, 7, 2, true,
     "notes: 0..7, default 2; the code table is invented (baud_for_code)"},
    {kRemoteFunctions, "remote functions", "bit mask", 0, 15, 0, true,
     "DFS-1 manual contents: 'SET Parameter #3 to Select Which Functions are Remote'; bits, range and "
     "default invented (D6)"},
    {kProtocol, "protocol", "code", 0, 1, 0, true,
     "notes: 0 = Powertec binary; 1 (another protocol, not modelled) invented"},
    {kMaxSpeed, "maximum motor speed", "rpm", 1, 99999, 1750, true,
     "DFS-1 manual contents: 'USE Parameter #6 to SET the Absolute Maximum Motor Speed', 'To 99,999'; "
     "default 1750 (06D6h, a default the contents show) invented"},
    {kJumpOrMop, "jump or MOP", "code", 0, 1, 0, false, "DFS-1 manual, note 3: 0 jump, 1 MOP"},
    {kTurnaroundDelay, "communications turnaround delay", "ms", 0, 255, 2, true,
     "notes: units not public; 1 ms per count, range and default invented (D2)"},
    {kContactorDelay, "contactor delay", "25 ms", 0, 40, 4, true,
     "notes: 25 ms steps; range and default invented"},
}};

// The row of a parameter number; nullptr when the table has none (NAK 82).
const ParameterInfo* find_parameter(std::uint8_t number);

// Parameter 2's codes (invented: the manual names 19.2k and 38.4k only): 0 1200, 1 2400,
// 2 4800, 3 9600, 4 19200, 5 38400, 6 57600, 7 115200.
std::optional<std::uint32_t> baud_for_code(std::uint32_t code);
std::optional<std::uint32_t> code_for_baud(std::uint32_t baud);

}  // namespace ibs::devices::dfs1
