// The DFS-1's object dictionary (issue 38): the parameters the public pages name
// (../shared/notes/public-facts.md, "PowerTec DFS-1"; DFS-1 manual), one od::Entry each, as the
// controller serves them with commands 85 and 86 (the DFS-1 codec, dfs1/od_codec.hpp, and
// dfs1::ParameterHandler encode them). Every number, range, default or unit the sources do not give
// is a modelling choice marked `invented` with what was invented in `source` (docs/dfs1.md,
// "Parameters").
//
// How the DFS-1's parameters become entries:
// - every value is a 32-bit number on the line (the notes: "Values are always 4 bytes, most
//   significant byte first"): od::Type::usign32, whatever its range;
// - a parameter is the controller's setup, kept over a power cycle (D20): Storage::eeprom;
// - the name is the one the pages give ("unit ID"); the DFS-1 has no short names and no texts;
// - the controller keeps no 85-SIOF: a refused access is answered with its NAK (82, 83) alone.
//
// The named numbers below are the wing's: the controller, the master and the tests use them.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "ibs/od/dictionary.hpp"

namespace ibs::devices::dfs1 {

// Numbers used by the emulator.
inline constexpr std::uint8_t kUnitId = 1;
inline constexpr std::uint8_t kBaudCode = 2;
inline constexpr std::uint8_t kRemoteFunctions = 3;
inline constexpr std::uint8_t kProtocol = 4;
inline constexpr std::uint8_t kMaxSpeed = 6;
inline constexpr std::uint8_t kJumpOrMop = 48;
inline constexpr std::uint8_t kTurnaroundDelay = 56;
inline constexpr std::uint8_t kContactorDelay = 62;

// Parameter 3: which functions the serial line may command (bit meanings invented, D6).
inline constexpr std::uint32_t kRemoteSpeedReference = 0x01;  // 82, 84
inline constexpr std::uint32_t kRemoteStartStop = 0x02;       // 83, 84
inline constexpr std::uint32_t kRemoteAnalogOutputs = 0x04;   // 89
inline constexpr std::uint32_t kRemoteDigitalOutputs = 0x08;  // 8C
inline constexpr std::uint32_t kRemoteAll = 0x0F;

namespace detail {
constexpr od::Entry parameter(std::uint8_t number, std::string_view name, std::string_view unit,
                              std::int64_t min, std::int64_t max, std::int64_t default_value,
                              bool invented, std::string_view source) {
  return {.number = number,
          .name = name,
          .type = od::Type::usign32,
          .min = min,
          .max = max,
          .default_value = default_value,
          .unit = unit,
          .storage = od::Storage::eeprom,
          .invented = invented,
          .source = source};
}
}  // namespace detail

inline constexpr std::array kEntries{
    detail::parameter(kUnitId, "unit ID", "", 1, 255, 1, false, "notes: UID 1..255, default 1"),
    detail::parameter(kBaudCode, "baud rate code", "code", 0, 7, 2, true,
                      "notes: 0..7, default 2; the code table is invented (baud_for_code)"),
    detail::parameter(kRemoteFunctions, "remote functions", "bit mask", 0, 15, 0, true,
                      "DFS-1 manual contents: 'SET Parameter #3 to Select Which Functions are "
                      "Remote'; bits, range and default invented (D6)"),
    detail::parameter(kProtocol, "protocol", "code", 0, 1, 0, true,
                      "notes: 0 = Powertec binary; 1 (another protocol, not modelled) invented"),
    detail::parameter(kMaxSpeed, "maximum motor speed", "rpm", 1, 99999, 1750, true,
                      "DFS-1 manual contents: 'USE Parameter #6 to SET the Absolute Maximum Motor "
                      "Speed', 'To 99,999'; default 1750 (06D6h, a default the contents show) "
                      "invented"),
    detail::parameter(kJumpOrMop, "jump or MOP", "code", 0, 1, 0, false,
                      "DFS-1 manual, note 3: 0 jump, 1 MOP"),
    detail::parameter(kTurnaroundDelay, "communications turnaround delay", "ms", 0, 255, 2, true,
                      "notes: units not public; 1 ms per count, range and default invented (D2)"),
    detail::parameter(kContactorDelay, "contactor delay", "25 ms", 0, 40, 4, true,
                      "notes: 25 ms steps; range and default invented"),
};

// The index, made at compile time: a dictionary od's checks refuse does not compile.
inline constexpr od::Dictionary kDictionary{kEntries};

// A controller's own UID as the default of parameter 1 (ControllerConfig::uid): the overlay its
// store is made with.
constexpr od::DefaultOverride unit_id_default(std::uint8_t uid) {
  return {kUnitId, uid};
}

}  // namespace ibs::devices::dfs1
