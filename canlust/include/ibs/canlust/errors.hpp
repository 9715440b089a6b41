// Error numbers and reactions as far as the CANLust manual shows them (6.1 programmable error responses,
// 6.2 table 5.9 error messages). The table is the CM-CAN1 manual's and lists errors of the bus
// module itself (E-OP2) next to drive errors; a drive wing may report any number, these are the
// ones the protocol core names. The seed's table is fragmentary: only what it prints is here.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace ibs::canlust {

struct ErrorInfo {
  std::uint8_t number;      // "Bus" column of table 5.9, byte 0 of the error telegram
  std::string_view name;    // DM/KP display name
  std::string_view cause;
};

inline constexpr std::uint8_t kErrorOti = 8;    // E-OTI drive unit overheating
inline constexpr std::uint8_t kErrorPls = 9;    // E-PLS plausibility error
inline constexpr std::uint8_t kErrorPar = 10;   // E-PAR faulty parameter setting
inline constexpr std::uint8_t kErrorFlt = 11;   // E-FLT floating point error
inline constexpr std::uint8_t kErrorPwr = 12;   // E-PWR power pack not recognised
inline constexpr std::uint8_t kErrorOp2 = 16;   // E-OP2 error in the module at option slot 2

// E-OP2 locations: 170 "error in module at option slot 2" (remedy: check module and identifier),
// 171 (text cut off in the seed), 172 (the ERR_STRUC example of 4.1.1).
inline constexpr std::uint8_t kLocationOp2Module = 170;
inline constexpr std::uint8_t kLocationOp2_171 = 171;
inline constexpr std::uint8_t kLocationOp2_172 = 172;

inline constexpr std::array<ErrorInfo, 6> kErrorTable = {{
    {kErrorOti, "E-OTI", "drive unit overheating"},
    {kErrorPls, "E-PLS", "plausibility error in parameter or program sequence"},
    {kErrorPar, "E-PAR", "faulty parameter setting"},
    {kErrorFlt, "E-FLT", "floating point error"},
    {kErrorPwr, "E-PWR", "power pack not recognized"},
    {kErrorOp2, "E-OP2", "error in module at option slot 2"},
}};
std::optional<ErrorInfo> find_error(std::uint8_t number);

// 6.1: "The error response is programmable for each error in four stages"; the seed names
// a warning message (WRN) and STOP. The codes and the two middle names are decision D6 / D7.
enum class ErrorReaction : std::uint8_t {
  warning = 0,        // WRN: a warning, the drive keeps running
  stop = 1,           // STOP: controlled stop, then the power stage is disabled
  quick_stop = 2,     // a faster stop (name not public)
  disable_power = 3,  // the power stage is disabled at once, the motor coasts (6.1 default)
};
std::string_view to_string(ErrorReaction r);

}  // namespace ibs::canlust
