// The MC6000's parameters as the seeds name them (INTERBUS manual 3.2, 4.2; LUSTBUS manual for the family's
// numbers): the table with numbers, names, types, categories, ranges and defaults that the servo's
// PCP server serves (index = number + 5C00H, pcp/parameters.hpp), and the numbers and values the
// drive acts on. Categories are LUSTBUS manual's parameter kinds (11.2.1: RAM actual value '0', RAM
// control value '1', EEPROM value '2'). Where a seed gives a parameter's name but not its type,
// range or default, the table says so in its comment and docs/pcp.md lists the choice ("MC6000
// parameter model").
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "ibs/devices/mc6000/dictionary.hpp"
#include "ibs/devices/mc6000/drive_parameters.hpp"
#include "ibs/drive/parameters.hpp"
#include "ibs/drive/siof.hpp"
#include "ibs/pcp/parameters.hpp"

namespace ibs::devices::mc6000 {


// The parameter numbers and the named values (selector codes, reaction steps, 91-TYPE's code,
// the highest rate) are the dictionary's (dictionary.hpp), written once there.
inline constexpr std::uint16_t kParamSbaud = kSbaud;  // LUSTBUS manual 4, 11.5

// 85-SERR bits (LUSTBUS manual 9.2): the family's 85-SIOF bits (drive/siof.hpp).
inline constexpr std::uint8_t kSerrPowerOn = drive::siof_mask(drive::SiofBit::power_on);
inline constexpr std::uint8_t kSerrWatchdog = drive::siof_mask(drive::SiofBit::watchdog);
inline constexpr std::uint8_t kSerrEepromBusy = drive::siof_mask(drive::SiofBit::eeprom_busy);
inline constexpr std::uint8_t kSerrChecksum = drive::siof_mask(drive::SiofBit::checksum);
inline constexpr std::uint8_t kSerrNoParameter = drive::siof_mask(drive::SiofBit::no_parameter);
inline constexpr std::uint8_t kSerrNoChange = drive::siof_mask(drive::SiofBit::no_change);
inline constexpr std::uint8_t kSerrInvalidValue = drive::siof_mask(drive::SiofBit::invalid_value);

// 416-SCTL1 bits: 7.2.1, bit 0 starts the drive; 8.1.2, bit 7 resets an error.
inline constexpr std::uint32_t kSctl1Start = 0x0001;
inline constexpr std::uint32_t kSctl1Reset = 0x0080;

// 4-PROG commands (LUSTBUS manual 10 exception 1; 11.5).
inline constexpr std::int64_t kProgFactoryDefaults = drive::kLoadDefaults;
inline constexpr std::int64_t kProgActivateBaudrate = 111;
// 80-SLOAD handshake values (LUSTBUS manual 11.4).
inline constexpr std::int64_t kSloadBegin = drive::kDownloadBegin;
inline constexpr std::int64_t kSloadEnd = drive::kDownloadEnd;

// INTERBUS manual 3.2.1 "Modified Factory Default": the parameters the servo changes for INTERBUS
// operation the first time it detects the INTERBUS card at power-on (the table's defaults), and
// resets "to their factory defaults the next time the device is powered-up" after the card was
// withdrawn. The seeds give the values with the card only; without it every selector is code 0,
// the one that names no option: CLSEL TERM, RSSLx RCON (LUSTBUS manual 7.2: "0 (i.e., RCON)"), the
// function selectors OFF (docs/errata.md MC-D10).
struct OptionDefault {
  std::uint16_t number;
  std::int64_t with_card;     // 3.2.1's table
  std::int64_t without_card;  // the factory default (MC-D10)
};
inline constexpr std::array<OptionDefault, 11> kOptionDefaults{{
    {kClsel, kClselOpt1, 0},
    {kRssl1, kRsslRcon, kRsslRcon},
    {kRssl2, kRsslRcon, kRsslRcon},
    {kRssl3, kRsslOpt1, kRsslRcon},
    {kRssl4, kRsslRcon, kRsslRcon},
    {kFis00, kFunctionRopt1, kFunctionOff},
    {kFis01, kFunctionRopt1, kFunctionOff},
    {kFos00, kFunctionRopt1, kFunctionOff},
    {kFos01, kFunctionRopt1, kFunctionOff},
    {kFif0, kFunctionOff, kFunctionOff},
    {kFif1, kFunctionOff, kFunctionOff},
}};
inline constexpr std::int64_t kQ16Min = -2147483648LL;
inline constexpr std::int64_t kQ16Max = 2147483647LL;

// clang-format off
inline constexpr std::array<pcp::ParameterInfo, 34> kParameters{{
  // number name     type                 category               min     max      default          attributes
  {4,   "PROG",  pcp::DataType::usign8,    pcp::Category::ram_control,  0,      255,     0,               0},  // type, range chosen
  {15,  "PLRDY", pcp::DataType::usign8,    pcp::Category::ram_control,  0,      1,       1,               pcp::kAttrInitControl},  // INTERBUS manual 4.2; reads READY mode (1 after a start), type chosen (MC-D11)
  {77,  "SPEED", pcp::DataType::int32q16,  pcp::Category::ram_actual,   kQ16Min, kQ16Max, 0,              0},  // LUSTBUS manual 6.1.1.2: Q16 rpm
  {80,  "SLOAD", pcp::DataType::integer16, pcp::Category::ram_control,  -2,     999,     0,               0},  // LUSTBUS manual 11.4: -2, -1, 0, parameter number
  {kSbaud, "SBAUD", pcp::DataType::usign16,   pcp::Category::eeprom,       2400,   57600,   9600,            0},  // LUSTBUS manual 4: 2400..57600, factory 9600
  {kSaddr, "SADDR", pcp::DataType::usign8,    pcp::Category::eeprom,       1,      30,      1,               0},  // LUSTBUS manual 4.2: addresses 1..30; default chosen
  {83,  "SDMMY", pcp::DataType::usign16,   pcp::Category::ram_control,  0,      65535,   0,               0},  // LUSTBUS manual 5.2: free RAM word
  {84,  "SWDGT", pcp::DataType::usign16,   pcp::Category::eeprom,       0,      65535,   0,               0},  // LUSTBUS manual 1, 5.2: 0 = no watchdog (factory)
  {85,  "SERR",  pcp::DataType::usign8,    pcp::Category::ram_actual,   0,      255,     0,               pcp::kAttrShowHex},  // LUSTBUS manual 9.2 bits
  {91,  "TYPE",  pcp::DataType::usign16,   pcp::Category::ram_actual,   0,      65535,   kMc6000TypeCode, 0},  // value chosen
  {kUnit, "UNIT",  pcp::DataType::usign8,    pcp::Category::ram_control,  0,      255,     0,               pcp::kAttrShowText},  // LUSTBUS manual 11.2.1
  {108, "STEXT", pcp::DataType::usign8,    pcp::Category::ram_control,  0,      255,     0,               0},  // LUSTBUS manual 11.3
  {300, "CFCON", pcp::DataType::usign8,    pcp::Category::eeprom,       1,      6,       kCfconScon,      pcp::kAttrShowText | pcp::kAttrInitControl},  // codes follow the structure filter
  {402, "CLSEL", pcp::DataType::usign8,    pcp::Category::eeprom,       0,      5,       kClselOpt1,      pcp::kAttrShowText},  // INTERBUS manual 3.2.1: OPT1
  {405, "SUPI",  pcp::DataType::usign8,    pcp::Category::eeprom,       0,      12,      11,              0},  // INTERBUS manual 3.2.2; effective at power-on
  {406, "IBCNF", pcp::DataType::usign8,    pcp::Category::eeprom,       0,      4,       2,               0},  // INTERBUS manual 3.2.3, 5.3.3: Q16 is the default
  {407, "IBSTU", pcp::DataType::usign16,   pcp::Category::ram_control,  0,      65535,   0,               pcp::kAttrShowHex},  // INTERBUS manual 4.2.1 (the control word)
  {408, "IBSTA", pcp::DataType::usign16,   pcp::Category::ram_actual,   0,      65535,   0,               pcp::kAttrShowHex},  // INTERBUS manual 4.2.1
  {kButwd, "BUTWD", pcp::DataType::usign16,   pcp::Category::eeprom,       0,      65535,   0,               0},  // INTERBUS manual 3.2.4: ms, 0 = off; rest chosen
  {416, "SCTL1", pcp::DataType::usign16,   pcp::Category::ram_control,  0,      65535,   0,               pcp::kAttrShowHex},  // LUSTBUS manual 7.2, 8.1.2
  {417, "RSSL1", pcp::DataType::usign8,    pcp::Category::eeprom,       0,      7,       kRsslRcon,       pcp::kAttrShowText},  // INTERBUS manual 3.2.1
  {418, "RSSL2", pcp::DataType::usign8,    pcp::Category::eeprom,       0,      7,       kRsslRcon,       pcp::kAttrShowText},
  {419, "RSSL3", pcp::DataType::usign8,    pcp::Category::eeprom,       0,      7,       kRsslOpt1,       pcp::kAttrShowText},
  {420, "RSSL4", pcp::DataType::usign8,    pcp::Category::eeprom,       0,      7,       kRsslRcon,       pcp::kAttrShowText},
  {428, "RSIO",  pcp::DataType::int32q16,  pcp::Category::ram_control,  kQ16Min, kQ16Max, 0,              0},  // LUSTBUS manual 7.2.1
  {439, "FIS00", pcp::DataType::usign8,    pcp::Category::eeprom,       0,      255,     kFunctionRopt1,  pcp::kAttrShowText},  // INTERBUS manual 3.2.1, 5.3.2
  {440, "FIS01", pcp::DataType::usign8,    pcp::Category::eeprom,       0,      255,     kFunctionRopt1,  pcp::kAttrShowText},
  {kFif0, "FIF0",  pcp::DataType::usign8,    pcp::Category::eeprom,       0,      255,     kFunctionOff,    pcp::kAttrShowText},
  {kFif1, "FIF1",  pcp::DataType::usign8,    pcp::Category::eeprom,       0,      255,     kFunctionOff,    pcp::kAttrShowText},
  {445, "FOS00", pcp::DataType::usign8,    pcp::Category::eeprom,       0,      255,     kFunctionRopt1,  pcp::kAttrShowText},  // INTERBUS manual 3.2.1, 5.3.1
  {446, "FOS01", pcp::DataType::usign8,    pcp::Category::eeprom,       0,      255,     kFunctionRopt1,  pcp::kAttrShowText},
  {510, "REOP1", pcp::DataType::usign8,    pcp::Category::eeprom,       1,      5,       kReactionStop,   pcp::kAttrShowText},  // LUSTBUS manual 8; number, name, default chosen (MC-D7)
  {511, "RESIO", pcp::DataType::usign8,    pcp::Category::eeprom,       1,      5,       kReactionStop,   pcp::kAttrShowText},
  {512, "REDEV", pcp::DataType::usign8,    pcp::Category::eeprom,       1,      5,       kReactionStop,   pcp::kAttrShowText},
}};
// clang-format on
// The table has no FLOAT_IEEE, MC_ERROR or PASSWORD parameter because the seeds name none; the
// server takes any table, and the tests give it one with those types.

// The table as a span (what the server and the drivers take).
std::span<const pcp::ParameterInfo> parameters();

// A trace's `! write PNR VALUE` value (../shared/specs/trace-format.md: the raw value a channel
// carries, or a negative value of a signed type) as the raw value of type `t`; nullopt when it
// is none (wider than the type's bytes, or negative for an unsigned type).
std::optional<std::uint32_t> trace_raw(pcp::DataType t, std::int64_t value);

// The MC6000's parameter core (drive_parameters.hpp) as this table and the service structure
// (service.hpp: CardWriteable, LUSTBUS manual 11.4) define it.
DriveParametersConfig drive_parameters_config(const DriveTiming& timing = {});

}  // namespace ibs::devices::mc6000
