// The CDA3000 parameters that CANLust manual (CM-CAN1 manual, fragments) and the notes name, as the
// drive serves them over the CANLust parameter channel and as the master checks them before it
// sends a write. Values are the 32-bit wire images of 4.1.1 (INT32Q16: the raw Q16 number).
//
// Where the seed prints a range, a factory setting, a unit, a data type or a substitution-text
// code, the row uses it and `source` cites it; everything else is a modelling choice marked
// `invented` with what was invented (docs/canlust.md, "The CDA3000 wing", decisions D21-D33).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "ibs/canlust/data_types.hpp"
#include "ibs/devices/cda3000/dictionary.hpp"

namespace ibs::devices::cda3000 {

using canlust::DataType;

// CANLust manual 4.3 tables: "Memory type FLASH" (saved by 150-SAVE, loaded at power-on) or RAM.
enum class Memory : std::uint8_t { flash, ram };
enum class Access : std::uint8_t { read_write, read_only };
// 7.1.1 / 7.1.2 step 4-5: "Back up settings in device (150-SAVE), mains reset to reinitialize":
// the bus settings act after a mains reset; the others at once.
enum class Effect : std::uint8_t { at_once, after_mains_reset };

// A substitution text of a selector parameter (4.1: "numerical value = substitution text"): the
// dictionary's (dictionary.hpp holds the texts).
using Choice = od::Choice;

struct ParameterInfo {
  std::uint16_t number;
  std::string_view name;        // the manual's short name, e.g. "CAWDG" (shown as 574-CAWDG)
  std::string_view text;
  DataType type;
  std::int64_t min;             // limits and factory setting as numbers of the wire image's type
  std::int64_t max;             //   (INT32Q16: raw Q16; STRING: length 0..99)
  std::int64_t factory;
  std::string_view unit;
  Memory memory;
  Access access;
  Effect effect;
  std::span<const Choice> choices;  // empty: any number in min..max
  bool invented;                // some of type / range / factory / unit / codes is a choice
  std::string_view source;      // where the row comes from, and what is invented

  [[nodiscard]] constexpr bool writable() const { return access == Access::read_write; }
  [[nodiscard]] constexpr bool is_string() const { return type == DataType::string; }
};

// The named numbers, codes and substitution texts are the dictionary's (dictionary.hpp).

// The response parameter of an error of table 5.9; nullopt for a number the table lacks.
std::optional<std::uint16_t> response_parameter(std::uint8_t error);

// Q16 limits of 406-REFF (the drive's +-fmax is a setting of the emulator).
inline constexpr std::int64_t kQ16Min = -2147483648LL;
inline constexpr std::int64_t kQ16Max = 2147483647LL;

// clang-format off
inline constexpr std::array<ParameterInfo, 28> kParameters{{
  {kProg, "PROG", "reset to factory settings", DataType::usign8, 0, 1, 0, "",
   Memory::ram, Access::read_write, Effect::at_once, kChoicesProg, true,
   "CANLust manual p. 13: 1 makes the drive overwrite all settings with their defaults, the reply "
   "comes when that is done; type, range, names invented"},
  {kSload, "SLOAD", "parameter data set download (handshake)", DataType::int16, -2, 999, 0, "",
   Memory::ram, Access::read_write, Effect::at_once, {}, true,
   "CANLust manual 4.x 'Downloading parameter data sets': values taken without individual checking, "
   "the whole set checked for plausibility at the end, then into the EEPROM with the attribute "
   "Card Writeable; number, name and codes invented after the LUSTBUS manual 11.4's 80-SLOAD (D39)"},
  {kName, "NAME", "device name (user text)", DataType::string, 0, 99, 0, "",
   Memory::flash, Access::read_write, Effect::at_once, {}, true,
   "invented: CANLust manual names no string parameter that can be written (D24)"},
  {kErr1, "ERR1", "last error (number, location, operating hours)", DataType::err_struc, 0,
   0xFFFFFFFFLL, 0, "", Memory::ram, Access::read_only, Effect::at_once, {}, true,
   "CANLust manual 4.1.1 gives the ERR_STRUC type (E-OP2 at 172 after 85 h = 10 AC 55 00) and 6.2 "
   "the error numbers; the parameter's number and name invented (D34)"},
  {kSave, "SAVE", "back up the settings in the device", DataType::usign8, 0, 1, 0, "",
   Memory::ram, Access::read_write, Effect::at_once, kChoicesSave, true,
   "CANLust manual 3.5.1: '150-SAVE = 1 START', 'takes a few hundred milliseconds', 7.1.1 step 4 "
   "'1 BUSY'; READY and the codes invented"},
  {kAstpr, "ASTPR", "original application data set", DataType::usign8, 0, 1, kDataSetDrv1, "",
   Memory::flash, Access::read_write, Effect::at_once, kChoicesDataSet, true,
   "CANLust manual 4.2 table: factory DRV_1, changed value BUS_1; codes and the preset it loads "
   "invented (D23)"},
  {kAster, "ASTER", "current application data set", DataType::usign8, 0, 1, kDataSetDrv1, "",
   Memory::flash, Access::read_write, Effect::at_once, kChoicesDataSet, true,
   "CANLust manual 4.2 table: factory DRV_1, changed value BUS_1; codes invented"},
  {kFisa0, "FISA0", "function selector analog standard input 0", DataType::usign8, 0, 6,
   kFunctionOff, "", Memory::flash, Access::read_write, Effect::at_once, kChoicesFisa0, true,
   "CANLust manual 4.2 table: factory OFF, changed value OPTN2; codes invented"},
  {kClsel, "CLSEL", "control location", DataType::usign8, 0, 6, kClselTerm, "",
   Memory::flash, Access::read_write, Effect::at_once, kChoicesClsel, true,
   "CANLust manual 4.3.2: 'with CLSEL = OPTN2 the control word is formed from bytes 0 and 1 of the "
   "control identifier'; TERM, the codes and the factory setting invented"},
  {kRssl1, "RSSL1", "reference selector 1", DataType::usign8, 0, 11, kRsslFmax, "",
   Memory::flash, Access::read_write, Effect::at_once, kChoicesRssl1, true,
   "CANLust manual 4.3.2 row '_28RS 0 FCON 11 FMAX 11 FMAX USIGN8 FLASH', 1 FA0, 2 FA1, 4 FPOT; 5.4.1 "
   "'7 TBSEL'; OPTN2 = 6 invented (D22)"},
  {kDisp, "DISP", "parameter shown as the continuous actual value", DataType::usign16, 0, 999,
   kReff, "", Memory::flash, Access::read_write, Effect::at_once, {}, true,
   "CANLust manual 7.1.3: reads 406 (406-REFF), the example writes 14; type and range 0..999 "
   "(a parameter number, 4.4) invented"},
  {kReff, "REFF", "current reference frequency", DataType::int32q16, kQ16Min, kQ16Max, 0, "Hz",
   Memory::ram, Access::read_only, Effect::at_once, {}, true,
   "CANLust manual 7.1.3: '406-REFF current reference frequency'; type INT32Q16 in Hz invented"},
  {kClbdr, "CLBDR", "CAN bus baud rate", DataType::usign16, 25, 500, 500, "kBaud",
   Memory::flash, Access::read_write, Effect::after_mains_reset, {}, false,
   "CANLust manual 4.3.1: 25..500, factory 500; 7.1.1: save, then mains reset"},
  {kCacnf, "CACNF", "control and reference configuration", DataType::usign8, 1, 4, 2, "",
   Memory::flash, Access::read_write, Effect::after_mains_reset, kChoicesCacnf, true,
   "CANLust manual 4.3.2, 5.5.5, 7.1: 2 DRIVECOM (7.1.2), 4 EasyDrive (7.1.1); map D5; factory 2 "
   "invented"},
  {kRoti, "ROTI", "error response to E-OTI (drive unit overheating)", DataType::usign8, 0, 3,
   kResponseDefault, "", Memory::flash, Access::read_write, Effect::at_once, kChoicesResponse, true,
   "CANLust manual 6.1: 'programmable for each error in four stages', default: the power stage "
   "disabled; number, name and codes invented (CAN-E16)"},
  {kRpls, "RPLS", "error response to E-PLS (plausibility error)", DataType::usign8, 0, 3,
   kResponseDefault, "", Memory::flash, Access::read_write, Effect::at_once, kChoicesResponse, true,
   "CANLust manual 6.1 (as 520-ROTI); number, name and codes invented (CAN-E16)"},
  {kRpar, "RPAR", "error response to E-PAR (faulty parameter setting)", DataType::usign8, 0, 3,
   kResponseDefault, "", Memory::flash, Access::read_write, Effect::at_once, kChoicesResponse, true,
   "CANLust manual 6.1 (as 520-ROTI); number, name and codes invented (CAN-E16)"},
  {kRflt, "RFLT", "error response to E-FLT (floating point error)", DataType::usign8, 0, 3,
   kResponseDefault, "", Memory::flash, Access::read_write, Effect::at_once, kChoicesResponse, true,
   "CANLust manual 6.1 (as 520-ROTI); number, name and codes invented (CAN-E16)"},
  {kRpwr, "RPWR", "error response to E-PWR (power pack not recognized)", DataType::usign8, 0, 3,
   kResponseDefault, "", Memory::flash, Access::read_write, Effect::at_once, kChoicesResponse, true,
   "CANLust manual 6.1 (as 520-ROTI); number, name and codes invented (CAN-E16)"},
  {kRop2, "ROP2", "error response to E-OP2 (option module, bus watchdog)", DataType::usign8, 0, 3,
   kResponseDefault, "", Memory::flash, Access::read_write, Effect::at_once, kChoicesResponse, true,
   "CANLust manual 6.1 and table 5.9 (E-OP2); also the reaction to 574-CAWDG running out (D15); "
   "number, name, codes and the factory PWOFF invented (CAN-E16)"},
  {kCamod, "CAMOD", "function selection of the option module", DataType::usign8, 0, 1,
   kCamodSlave, "", Memory::flash, Access::read_write, Effect::after_mains_reset, kChoicesCamod,
   true, "CANLust manual 4.3.1: 'Function selection option module CANLUST Slave Ma...'; codes invented"},
  {kCladr, "CLADR", "CAN address (0: the connector's)", DataType::usign8, 0, 99, 0, "",
   Memory::flash, Access::read_write, Effect::after_mains_reset, {}, true,
   "CANLust manual 2.1: the connector's address 0..7 is used when CLADR = 0; 4.3.1; 7.1: mains reset; "
   "range 0..99 from the notes' addresses, factory 0 invented"},
  {kCawdg, "CAWDG", "CAN bus watchdog time", DataType::usign8, 0, 255, 0, "ms",
   Memory::flash, Access::read_write, Effect::at_once, {}, false,
   "CANLust manual 4.3.1: 0..255 ms, factory 0, 0 deactivates the watchdog"},
  {kCascy, "CASCY", "sampling time of the status message", DataType::usign16, 1, 32000, 80, "ms",
   Memory::flash, Access::read_write, Effect::at_once, {}, false,
   "CANLust manual 4.3.1: 1..32000 ms, factory 80"},
  {kCawmk, "CAWMK", "warnings reported on the CAN (mask)", DataType::usign16, 0, 0xFFFF, 0xFFFF, "",
   Memory::flash, Access::read_write, Effect::at_once, {}, true,
   "CANLust manual 6.3 'parameterizable warnings on the CAN', masks 0004H I2t, 0008H motor "
   "temperature, 0010H heat sink temperature; number, name and factory (all) invented (CAN-E17)"},
  {kCawrn, "CAWRN", "warnings present (6.3 bits)", DataType::usign16, 0, 0xFFFF, 0, "",
   Memory::ram, Access::read_only, Effect::at_once, {}, true,
   "CANLust manual 6.3 bits 0004H, 0008H, 0010H; number and name invented (CAN-E17)"},
  {kOptn2, "OPTN2", "module found at option slot 2", DataType::string, 0, 99, 0, "",
   Memory::ram, Access::read_only, Effect::at_once, {}, true,
   "CANLust manual 3.3: 'verify the value in parameter 578-OPTN2 (LCAN)'; a read-only STRING 'LCAN' "
   "invented (D24)"},
  {kCdssl, "CDSSL", "characteristic data set selection", DataType::usign8, 0, 6, 0, "",
   Memory::flash, Access::read_write, Effect::at_once, kChoicesCdssl, true,
   "CANLust manual 5.4.1 footnote 2: '651-CDSSL = 6 OPTN2' lets the CUSEL bit switch data sets 1 and "
   "2; CDS1, CDS2 and the factory setting invented"},
}};
// clang-format on

// 4.x "Card Writeable": the parameters a data set holds, the writable values kept in flash
// (D39); RAM commands (04-PROG, 150-SAVE, 80-SLOAD), read-only values and 90-NAME (a STRING,
// written by the string transfer) are not.
constexpr bool card_writeable(const ParameterInfo& p) {
  return p.writable() && !p.is_string() && p.memory == Memory::flash;
}

// The row of a parameter; nullptr when the CDA3000 has none here (reply status 20H).
const ParameterInfo* find_parameter(std::uint16_t number);
// By "574", "CAWDG" or "574-CAWDG" (case-insensitive names); nullptr when none matches.
const ParameterInfo* find_parameter(std::string_view text);
namespace detail {
// Every parameter's row by its number, made at compile time from kParameters: the parameter
// channel looks a number up on every request (issue 26), a walk of the table took more than the
// rest of the drive's read.
inline constexpr std::uint16_t kHighestNumber = [] {
  std::uint16_t m = 0;
  for (const auto& p : kParameters) m = std::max(m, p.number);
  return m;
}();
inline constexpr std::uint8_t kNoRow = 0xFF;
static_assert(kParameters.size() < kNoRow);
inline constexpr auto kRowByNumber = [] {
  std::array<std::uint8_t, kHighestNumber + 1> rows{};
  rows.fill(kNoRow);
  for (std::size_t i = 0; i < kParameters.size(); ++i) rows[kParameters[i].number] = static_cast<std::uint8_t>(i);
  return rows;
}();
}  // namespace detail

// The row's position in kParameters (for per-parameter storage); nullopt when none. Inline
// (issue 26: one lookup per parameter request).
inline std::optional<std::size_t> parameter_index(std::uint16_t number) {
  if (number > detail::kHighestNumber || detail::kRowByNumber[number] == detail::kNoRow) return std::nullopt;
  return detail::kRowByNumber[number];
}
// "574-CAWDG".
std::string display_name(const ParameterInfo& p);

const Choice* find_choice(const ParameterInfo& p, std::uint32_t code);
const Choice* find_choice(const ParameterInfo& p, std::string_view name);

// The number a wire image stands for: sign-extended for the signed types (INT32Q16: raw Q16).
std::int64_t number_of(const ParameterInfo& p, std::uint32_t wire);
// The wire image of a number (the inverse of number_of for numbers of the type).
std::uint32_t wire_of(const ParameterInfo& p, std::int64_t number);

// Why a value is refused (4.5 reply status 80H "impermissible value"): it does not fit the data
// type, lies outside min..max, or is no substitution-text code of a selector.
enum class ValueCheck : std::uint8_t { ok, wrong_type, below_min, above_max, not_a_choice };
std::string_view to_string(ValueCheck c);
// No allocation: the drive checks every write with it, the master before it sends one.
ValueCheck check_value(const ParameterInfo& p, std::uint32_t wire);

// "20.5 Hz", "6 (OPTN2)", "80 ms" (allocates: for reports).
std::string format_value(const ParameterInfo& p, std::uint32_t wire);
// "574-CAWDG: 300 ms is above the maximum 255 ms" for a refused value.
std::string describe_refusal(const ParameterInfo& p, std::uint32_t wire, ValueCheck c);

// A value given as text (command line, scenario): a number, a substitution text ("OPTN2"), or for
// INT32Q16 a decimal number of the unit ("20.5"). Checked against the row: `error` says which
// parameter, which value and which limit when it is refused.
struct ParsedValue {
  std::optional<std::uint32_t> wire;
  std::string error;
};
ParsedValue parse_value(const ParameterInfo& p, std::string_view text);

}  // namespace ibs::devices::cda3000
