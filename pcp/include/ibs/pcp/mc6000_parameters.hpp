// The MC6000 parameters the seeds name, as the servo's PCP server exposes them.
// Index = parameter number + 5C00H (seed 001, 4.2). Categories are seed 000's parameter kinds
// (11.2.1: RAM actual value '0', RAM control value '1', EEPROM value '2').
// Where a seed gives a parameter's name but not its type, range or default, the table says so in
// its comment and docs/pcp.md lists the choice ("MC6000 parameter model").
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "ibs/pcp/data_types.hpp"

namespace ibs::pcp {

inline constexpr std::uint16_t kParameterIndexOffset = 0x5C00;  // seed 001, 4.2
inline constexpr std::uint16_t kMaxParameterNumber = 999;       // seed 000, 2.4.2: 3 digits

constexpr std::uint16_t index_of(std::uint16_t number) {
  return static_cast<std::uint16_t>(number + kParameterIndexOffset);
}
constexpr std::optional<std::uint16_t> number_of(std::uint16_t index) {
  if (index < kParameterIndexOffset || index > kParameterIndexOffset + kMaxParameterNumber) {
    return std::nullopt;
  }
  return static_cast<std::uint16_t>(index - kParameterIndexOffset);
}

// A parameter addressed by its number or directly by its object index.
struct ParameterRef {
  std::uint16_t index = 0;
  static constexpr ParameterRef number(std::uint16_t n) { return {index_of(n)}; }
  static constexpr ParameterRef object(std::uint16_t i) { return {i}; }
  friend bool operator==(const ParameterRef&, const ParameterRef&) = default;
};

// Seed 000, 11.2.1 ("The parameter kind"); the enumerator values are the ASCII codes given there.
enum class Category : std::uint8_t { ram_actual = '0', ram_control = '1', eeprom = '2' };
std::string_view to_string(Category c);

// Attribute bits of seed 000, 11.2.1 ("The attribute").
inline constexpr std::uint16_t kAttrShowParaText = 0x0004;
inline constexpr std::uint16_t kAttrShowText = 0x0020;
inline constexpr std::uint16_t kAttrInitControl = 0x0040;
inline constexpr std::uint16_t kAttrShowHex = 0x0100;
inline constexpr std::uint16_t kAttrPassword = 0x0200;

struct ParameterInfo {
  std::uint16_t number = 0;
  std::string_view name;  // at most 5 characters (seed 000, 11.2.1)
  DataType type = DataType::usign16;
  Category category = Category::ram_control;
  // Limits and default as signed_raw() numbers (FLOAT_IEEE: the float's bit pattern).
  std::int64_t min = 0;
  std::int64_t max = 0;
  std::int64_t default_value = 0;
  std::uint16_t attributes = 0;

  [[nodiscard]] constexpr std::uint16_t index() const { return index_of(number); }
  [[nodiscard]] constexpr bool writable() const { return category != Category::ram_actual; }
};

// Numbers with behaviour beyond storing a value (server.hpp says what they do).
inline constexpr std::uint16_t kProg = 4;     // seed 000, 10 and 11.5
inline constexpr std::uint16_t kPlrdy = 15;   // seed 001, 4.2
inline constexpr std::uint16_t kSpeed = 77;   // seed 000, 6.1.1.2
inline constexpr std::uint16_t kSload = 80;   // seed 000, 11.4
inline constexpr std::uint16_t kSerr = 85;    // seed 000, 9.2
inline constexpr std::uint16_t kType = 91;    // seed 000, 5.2
inline constexpr std::uint16_t kSupi = 405;   // seed 001, 3.2.2
inline constexpr std::uint16_t kIbcnf = 406;  // seed 001, 3.2.3
inline constexpr std::uint16_t kIbstu = 407;  // seed 001, 4.2.1
inline constexpr std::uint16_t kIbsta = 408;  // seed 001, 4.2.1

// 85-SERR bits (seed 000, 9.2).
inline constexpr std::uint8_t kSerrPowerOn = 0x01;
inline constexpr std::uint8_t kSerrWatchdog = 0x02;
inline constexpr std::uint8_t kSerrEepromBusy = 0x04;
inline constexpr std::uint8_t kSerrChecksum = 0x08;
inline constexpr std::uint8_t kSerrNoParameter = 0x20;
inline constexpr std::uint8_t kSerrNoChange = 0x40;
inline constexpr std::uint8_t kSerrInvalidValue = 0x80;

// 4-PROG commands (seed 000, 10 exception 1; 11.5).
inline constexpr std::int64_t kProgFactoryDefaults = 1;
inline constexpr std::int64_t kProgActivateBaudrate = 111;
// 80-SLOAD handshake values (seed 000, 11.4).
inline constexpr std::int64_t kSloadBegin = -1;
inline constexpr std::int64_t kSloadEnd = -2;

// Selector values the seeds name. RCON 0, RSIO 3, OPT1 6 (reference selectors: seed 000 7.2,
// seed 001 5.3.4), SIO 2, OPT1 4 (402-CLSEL: same places), SCON 2 (300-CFCON: seed 000 7.2.1).
// The function selectors' codes (OFF, ROPT1) are not in the seeds: chosen, docs/pcp.md.
inline constexpr std::int64_t kRsslRcon = 0;
inline constexpr std::int64_t kRsslRsio = 3;
inline constexpr std::int64_t kRsslOpt1 = 6;
inline constexpr std::int64_t kClselSio = 2;
inline constexpr std::int64_t kClselOpt1 = 4;
inline constexpr std::int64_t kCfconScon = 2;
inline constexpr std::int64_t kFunctionOff = 0;
inline constexpr std::int64_t kFunctionRopt1 = 6;
// 91-TYPE: the seeds name the parameter, not the MC6000's code: chosen.
inline constexpr std::int64_t kMc6000TypeCode = 6000;

inline constexpr std::int64_t kQ16Min = -2147483648LL;
inline constexpr std::int64_t kQ16Max = 2147483647LL;

// clang-format off
inline constexpr std::array<ParameterInfo, 31> kMc6000Parameters{{
  // number name     type                 category               min     max      default          attributes
  {4,   "PROG",  DataType::usign8,    Category::ram_control,  0,      255,     0,               0},  // type, range chosen
  {15,  "PLRDY", DataType::usign8,    Category::ram_control,  0,      1,       0,               kAttrInitControl},  // type chosen
  {77,  "SPEED", DataType::int32q16,  Category::ram_actual,   kQ16Min, kQ16Max, 0,              0},  // seed 000 6.1.1.2: Q16 rpm
  {80,  "SLOAD", DataType::integer16, Category::ram_control,  -2,     999,     0,               0},  // seed 000 11.4: -2, -1, 0, parameter number
  {81,  "SBAUD", DataType::usign16,   Category::eeprom,       2400,   57600,   9600,            0},  // seed 000 4: 2400..57600, factory 9600
  {82,  "SADDR", DataType::usign8,    Category::eeprom,       1,      30,      1,               0},  // seed 000 4.2: addresses 1..30; default chosen
  {83,  "SDMMY", DataType::usign16,   Category::ram_control,  0,      65535,   0,               0},  // seed 000 5.2: free RAM word
  {84,  "SWDGT", DataType::usign16,   Category::eeprom,       0,      65535,   0,               0},  // seed 000 1, 5.2: 0 = no watchdog (factory)
  {85,  "SERR",  DataType::usign8,    Category::ram_actual,   0,      255,     0,               kAttrShowHex},  // seed 000 9.2 bits
  {91,  "TYPE",  DataType::usign16,   Category::ram_actual,   0,      65535,   kMc6000TypeCode, 0},  // value chosen
  {107, "UNIT",  DataType::usign8,    Category::ram_control,  0,      255,     0,               kAttrShowText},  // seed 000 11.2.1
  {108, "STEXT", DataType::usign8,    Category::ram_control,  0,      255,     0,               0},  // seed 000 11.3
  {300, "CFCON", DataType::usign8,    Category::eeprom,       1,      6,       kCfconScon,      kAttrShowText | kAttrInitControl},  // codes follow the structure filter
  {402, "CLSEL", DataType::usign8,    Category::eeprom,       0,      5,       kClselOpt1,      kAttrShowText},  // seed 001 3.2.1: OPT1
  {405, "SUPI",  DataType::usign8,    Category::eeprom,       0,      12,      11,              0},  // seed 001 3.2.2; effective at power-on
  {406, "IBCNF", DataType::usign8,    Category::eeprom,       0,      4,       2,               0},  // seed 001 3.2.3, 5.3.3: Q16 is the default
  {407, "IBSTU", DataType::usign16,   Category::ram_control,  0,      65535,   0,               kAttrShowHex},  // seed 001 4.2.1 (the control word)
  {408, "IBSTA", DataType::usign16,   Category::ram_actual,   0,      65535,   0,               kAttrShowHex},  // seed 001 4.2.1
  {409, "BUTWD", DataType::usign16,   Category::eeprom,       0,      65535,   0,               0},  // seed 001 3.2.4: ms, 0 = off; rest chosen
  {416, "SCTL1", DataType::usign16,   Category::ram_control,  0,      65535,   0,               kAttrShowHex},  // seed 000 7.2, 8.1.2
  {417, "RSSL1", DataType::usign8,    Category::eeprom,       0,      7,       kRsslRcon,       kAttrShowText},  // seed 001 3.2.1
  {418, "RSSL2", DataType::usign8,    Category::eeprom,       0,      7,       kRsslRcon,       kAttrShowText},
  {419, "RSSL3", DataType::usign8,    Category::eeprom,       0,      7,       kRsslOpt1,       kAttrShowText},
  {420, "RSSL4", DataType::usign8,    Category::eeprom,       0,      7,       kRsslRcon,       kAttrShowText},
  {428, "RSIO",  DataType::int32q16,  Category::ram_control,  kQ16Min, kQ16Max, 0,              0},  // seed 000 7.2.1
  {439, "FIS00", DataType::usign8,    Category::eeprom,       0,      255,     kFunctionRopt1,  kAttrShowText},  // seed 001 3.2.1, 5.3.2
  {440, "FIS01", DataType::usign8,    Category::eeprom,       0,      255,     kFunctionRopt1,  kAttrShowText},
  {443, "FIF0",  DataType::usign8,    Category::eeprom,       0,      255,     kFunctionOff,    kAttrShowText},
  {444, "FIF1",  DataType::usign8,    Category::eeprom,       0,      255,     kFunctionOff,    kAttrShowText},
  {445, "FOS00", DataType::usign8,    Category::eeprom,       0,      255,     kFunctionRopt1,  kAttrShowText},  // seed 001 3.2.1, 5.3.1
  {446, "FOS01", DataType::usign8,    Category::eeprom,       0,      255,     kFunctionRopt1,  kAttrShowText},
}};
// clang-format on
// The table has no FLOAT_IEEE, MC_ERROR or PASSWORD parameter because the seeds name none; the
// server takes any table, and the tests give it one with those types.

// Looks a parameter up by number or by index; nullptr when the table has none.
const ParameterInfo* find_parameter(std::span<const ParameterInfo> table, std::uint16_t number);
const ParameterInfo* find_by_index(std::span<const ParameterInfo> table, std::uint16_t index);

}  // namespace ibs::pcp
