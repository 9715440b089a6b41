// The MC6000's object dictionary (issue 38): every parameter the seeds name for the MASTERDRIVE
// MC6000 and the three error reactions LUSTBUS manual 8 asks for, once, as od::Entry rows -- the PCP
// table's number, name, type, kind, range, default and attributes (INTERBUS manual 3.2, 4.2) merged with
// the KEYPAD service structure of the LUSTBUS manual 11.2.1 (unit index, level, filters, subject and
// activity area: od::Keypad) and the value substitution texts of 11.3 (od::Choice). The lowest
// library of the wing (ibs_mc6000_dictionary, header-only, embedded-safe): the parameter numbers
// and the named values the wing acts on, the dictionary every bus's codec encodes, and the factory
// defaults of a servo without its INTERBUS card (3.2.1, decision MC-D10). Where a seed gives a
// parameter's name but not its type, range or default, `invented` says so and docs/pcp.md ("MC6000
// parameter model") lists the choice; the service structure's values are all chosen (LB-D21).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "ibs/od/dictionary.hpp"
#include "ibs/od/siof.hpp"

namespace ibs::devices::mc6000 {

// ---- numbers ---------------------------------------------------------------------------------
inline constexpr std::uint16_t kProg = 4;     // LUSTBUS manual 10 and 11.5
inline constexpr std::uint16_t kPlrdy = 15;   // INTERBUS manual 4.2
inline constexpr std::uint16_t kSpeed = 77;   // LUSTBUS manual 6.1.1.2
inline constexpr std::uint16_t kSload = 80;   // LUSTBUS manual 11.4
inline constexpr std::uint16_t kSbaud = 81;   // LUSTBUS manual 4, 11.5
inline constexpr std::uint16_t kSaddr = 82;   // LUSTBUS manual 4.2
inline constexpr std::uint16_t kSdmmy = 83;   // LUSTBUS manual 5.2
inline constexpr std::uint16_t kSwdgt = 84;   // LUSTBUS manual 5.2
inline constexpr std::uint16_t kSerr = od::kSiofNumber;  // LUSTBUS manual 9.2
inline constexpr std::uint16_t kType = 91;    // LUSTBUS manual 5.2
inline constexpr std::uint16_t kUnit = 107;   // LUSTBUS manual 11.2.1
inline constexpr std::uint16_t kStext = 108;  // LUSTBUS manual 11.3
inline constexpr std::uint16_t kCfcon = 300;  // LUSTBUS manual 7.2.1
inline constexpr std::uint16_t kClsel = 402;  // LUSTBUS manual 7.2.1
inline constexpr std::uint16_t kSupi = 405;   // INTERBUS manual 3.2.2
inline constexpr std::uint16_t kIbcnf = 406;  // INTERBUS manual 3.2.3
inline constexpr std::uint16_t kIbstu = 407;  // INTERBUS manual 4.2.1
inline constexpr std::uint16_t kIbsta = 408;  // INTERBUS manual 4.2.1
inline constexpr std::uint16_t kButwd = 409;  // INTERBUS manual 3.2.4: the bus watchdog, ms, 0 = off
inline constexpr std::uint16_t kSctl1 = 416;  // LUSTBUS manual 7.2, 8.1.2
inline constexpr std::uint16_t kRssl1 = 417;  // LUSTBUS manual 7.2.1
inline constexpr std::uint16_t kRssl2 = 418;
inline constexpr std::uint16_t kRssl3 = 419;
inline constexpr std::uint16_t kRssl4 = 420;
inline constexpr std::uint16_t kRsio = 428;   // LUSTBUS manual 7.2.1
inline constexpr std::uint16_t kFis00 = 439;  // INTERBUS manual 3.2.1, 5.3.2
inline constexpr std::uint16_t kFis01 = 440;
inline constexpr std::uint16_t kFif0 = 443;   // INTERBUS manual 3.2.1
inline constexpr std::uint16_t kFif1 = 444;
inline constexpr std::uint16_t kFos00 = 445;  // INTERBUS manual 3.2.1, 5.3.1
inline constexpr std::uint16_t kFos01 = 446;
// The error reactions (LUSTBUS manual 8: "programmable, in five steps, for every error"; 5.2: the
// watchdog's "error reaction of the device via parameter"). The seeds give neither numbers nor
// names: chosen (docs/errata.md MC-D7), one per error the servo raises.
inline constexpr std::uint16_t kReop1 = 510;  // error 16 E-OP1 (INTERBUS manual 3.2.4: the bus watchdog)
inline constexpr std::uint16_t kResio = 511;  // the serial watchdog 84-SWDGT (LUSTBUS manual 5.2)
inline constexpr std::uint16_t kRedev = 512;  // every other device error (a cause 0..255 but 16)

// ---- named values ----------------------------------------------------------------------------
// LUSTBUS manual 4: "from 2400 Baud to 57600 Baud for Servocontrollers" (81-SBAUD, in baud: LB-E18).
inline constexpr std::uint32_t kHighestBaud = 57600;
// Selector values the seeds name. RCON 0, RSIO 3, OPT1 6 (reference selectors: LUSTBUS manual 7.2,
// INTERBUS manual 5.3.4), SIO 2, OPT1 4 (402-CLSEL: same places), SCON 2 (300-CFCON: LUSTBUS manual 7.2.1).
// The function selectors' codes (OFF, ROPT1) are not in the seeds: chosen, docs/pcp.md.
inline constexpr std::int64_t kRsslRcon = 0;
inline constexpr std::int64_t kRsslRsio = 3;
inline constexpr std::int64_t kRsslOpt1 = 6;
inline constexpr std::int64_t kClselSio = 2;
inline constexpr std::int64_t kClselOpt1 = 4;
inline constexpr std::int64_t kCfconScon = 2;
inline constexpr std::int64_t kFunctionOff = 0;
inline constexpr std::int64_t kFunctionRopt1 = 6;
// The five reaction steps (LUSTBUS manual 8); 8.1.2 names step 5 "RESET", 1-4 are chosen (MC-D7).
inline constexpr std::int64_t kReactionWarn = 1;   // WARN: status bit 7 (alarm), the drive runs on
inline constexpr std::int64_t kReactionStop = 2;   // STOP: brake to standstill, then FAULT
inline constexpr std::int64_t kReactionOff = 3;    // OFF: power stage off at once, FAULT, coasting
inline constexpr std::int64_t kReactionLock = 4;   // LOCK: as OFF; only a power-on ends it
inline constexpr std::int64_t kReactionReset = 5;  // RESET: as OFF; the fault reset boots the servo
// 91-TYPE: the seeds name the parameter, not the MC6000's code: chosen.
inline constexpr std::int64_t kMc6000TypeCode = 6000;

namespace dictionary_rows {
using namespace std::string_view_literals;
using od::Choice;
using od::Effect;
using od::Entry;
using od::Keypad;
using od::Role;
using od::Storage;
using od::Type;
namespace attr = od::attr;

inline constexpr std::int64_t kQ16Min = od::min_number(Type::int32q16);
inline constexpr std::int64_t kQ16Max = od::max_number(Type::int32q16);

// 11.3 texts (chosen; SIO 2, OPT1 4, RCON 0, RSIO 3, SCON 2, ROPT1 6 are the seeds' codes); the
// text of value 0, 1, ... is the choice of that code.
// 107-UNIT: the units the other parameters' KEYPAD `unit` indexes.
inline constexpr std::array kUnitTexts{
    Choice{0, "-"},  Choice{1, "rpm"}, Choice{2, "Hz"}, Choice{3, "ms"}, Choice{4, "s"},
    Choice{5, "V"},  Choice{6, "A"},   Choice{7, "%"},  Choice{8, "Nm"}, Choice{9, "Bd"}};
inline constexpr std::uint8_t kUnitNone = 0, kUnitRpm = 1, kUnitMs = 3, kUnitBaud = 9;
// 300-CFCON: the control types in the order of the structure filter's bits (docs/pcp.md).
inline constexpr std::array kCfconTexts{Choice{0, "-"},     Choice{1, "TCON"},  Choice{2, "SCON"},
                                        Choice{3, "PCON"},  Choice{4, "VFCON"}, Choice{5, "EMAST"},
                                        Choice{6, "ESLAV"}};
inline constexpr std::array kClselTexts{Choice{0, "TERM"}, Choice{1, "KPAD"}, Choice{2, "SIO"},
                                        Choice{3, "CAN"},  Choice{4, "OPT1"}, Choice{5, "OPT2"}};
inline constexpr std::array kRsslTexts{Choice{0, "RCON"}, Choice{1, "RA0"},  Choice{2, "RA1"},
                                       Choice{3, "RSIO"}, Choice{4, "RFIX"}, Choice{5, "RCAN"},
                                       Choice{6, "OPT1"}, Choice{7, "OPT2"}};
inline constexpr std::array kInputTexts{Choice{0, "OFF"},   Choice{1, "START"}, Choice{2, "INV"},
                                        Choice{3, "QSTOP"}, Choice{4, "RESET"}, Choice{5, "FIX0"},
                                        Choice{6, "ROPT1"}};
inline constexpr std::array kOutputTexts{Choice{0, "OFF"},   Choice{1, "REF"},   Choice{2, "LIMIT"},
                                         Choice{3, "ERROR"}, Choice{4, "ACTIV"}, Choice{5, "BRAKE"},
                                         Choice{6, "ROPT1"}};
// 510..512: the five reaction steps of the LUSTBUS manual 8 (8.1.2: 5 "RESET"; the others chosen, MC-D7).
inline constexpr std::array kReactionTexts{Choice{0, "-"},    Choice{1, "WARN"}, Choice{2, "STOP"},
                                           Choice{3, "OFF"},  Choice{4, "LOCK"}, Choice{5, "RESET"}};

// 11.2.1 subject areas and activity areas the rows use (the tables of lustbus/description.hpp).
inline constexpr std::uint8_t kConf = 0, kOpt1 = 2, kSio = 9, kScty = 12, kSys = 14, kRef = 15,
                              kMenu = 20, kVal = 21;
inline constexpr std::uint8_t kScNothing = 0, kScOpt1 = 1, kScSys = 4, kScDrive = 5, kScRef = 6;
// The service structure of each row: read level 1, write level 2, no hardware dependence (a
// decision: 11.2.1 names only the bits), every control type; the areas and the unit by row.
inline constexpr Keypad kConfPad{.subject = kConf};
inline constexpr Keypad kConfDrivePad{.subject = kConf, .activity = kScDrive};
inline constexpr Keypad kValRpmPad{.unit = kUnitRpm, .subject = kVal};
inline constexpr Keypad kSioPad{.subject = kSio};
inline constexpr Keypad kSioRpmPad{.unit = kUnitRpm, .subject = kSio};
inline constexpr Keypad kSioMsPad{.unit = kUnitMs, .subject = kSio};
inline constexpr Keypad kSioBaudPad{.unit = kUnitBaud, .subject = kSio};
inline constexpr Keypad kSysPad{.subject = kSys};
inline constexpr Keypad kMenuPad{.subject = kMenu};
inline constexpr Keypad kOpt1Pad{.subject = kOpt1};
inline constexpr Keypad kOpt1SetPad{.subject = kOpt1, .activity = kScOpt1};
inline constexpr Keypad kOpt1SetMsPad{.unit = kUnitMs, .subject = kOpt1, .activity = kScOpt1};
inline constexpr Keypad kRefSetPad{.subject = kRef, .activity = kScRef};
// 11.2.1: SCTY 12, "Security-and-error-reaction parameter"; a system setting of the data set.
inline constexpr Keypad kSctySetPad{.subject = kScty, .activity = kScSys};

// A selector of the 11.3 texts `t` (ShowText) in the data set of `pad`: EEPROM, USIGN8.
constexpr Entry selector(std::uint16_t number, std::string_view name, std::string_view text,
                         std::int64_t min, std::int64_t max, std::int64_t default_value,
                         std::span<const Choice> t, const Keypad* pad, std::string_view source,
                         bool invented = true) {
  return Entry{.number = number, .name = name, .text = text, .type = Type::usign8, .min = min,
               .max = max, .default_value = default_value, .storage = Storage::eeprom,
               .attributes = attr::kShowText, .in_data_set = true, .choices = t, .keypad = pad,
               .invented = invented, .source = source};
}

// clang-format off
inline constexpr std::array kEntries{
    Entry{.number = kProg, .name = "PROG", .text = "Program command (1: factory settings, 111: "
          "activate 81-SBAUD)", .type = Type::usign8, .min = 0, .max = 255, .default_value = 0,
          .storage = Storage::ram_control, .role = Role::load_defaults, .keypad = &kConfPad,
          .invented = true, .source = "LUSTBUS manual 10 exception 1, 11.5 (commands 1, 111); type and "
          "range chosen"},
    Entry{.number = kPlrdy, .name = "PLRDY", .text = "READY mode (1: recalculate the controller)",
          .type = Type::usign8, .min = 0, .max = 1, .default_value = 1,
          .storage = Storage::ram_control, .attributes = attr::kInitControl, .keypad = &kConfPad,
          .invented = true, .source = "INTERBUS manual 4.2; reads READY mode, 1 after a start; type "
          "chosen (MC-D11)"},
    Entry{.number = kSpeed, .name = "SPEED", .text = "Actual speed", .type = Type::int32q16,
          .min = kQ16Min, .max = kQ16Max, .default_value = 0, .unit = "rpm",
          .storage = Storage::ram_actual, .keypad = &kValRpmPad,
          .source = "LUSTBUS manual 6.1.1.2 (Q16 rpm, type from the example)"},
    Entry{.number = kSload, .name = "SLOAD", .text = "Data set download (-1 begin, -2 end; 0 or "
          "the first implausible parameter)", .type = Type::int16, .min = -2, .max = 999,
          .default_value = 0, .storage = Storage::ram_control, .role = Role::download,
          .keypad = &kSioPad, .source = "LUSTBUS manual 11.4 (values and meaning)"},
    // The serial interface's own settings are no data set's: a download must not move the link.
    Entry{.number = kSbaud, .name = "SBAUD", .text = "Baud rate (2400 to 57600 Bd in steps)",
          .type = Type::usign16, .min = 2400, .max = kHighestBaud, .default_value = 9600,
          .unit = "Bd", .storage = Storage::eeprom, .effect = Effect::at_restart,
          .keypad = &kSioBaudPad, .source = "LUSTBUS manual 4 (range, factory 9600), 11.5 (active "
          "after a restart or 4-PROG = 111); the rate in baud (LB-E18)"},
    Entry{.number = kSaddr, .name = "SADDR", .text = "Serial address", .type = Type::usign8,
          .min = 1, .max = 30, .default_value = 1, .storage = Storage::eeprom, .keypad = &kSioPad,
          .invented = true, .source = "LUSTBUS manual 4.2 (addresses 1..30); default chosen"},
    Entry{.number = kSdmmy, .name = "SDMMY", .text = "Dummy (free RAM word)",
          .type = Type::usign16, .min = 0, .max = 65535, .default_value = 0,
          .storage = Storage::ram_control, .keypad = &kSioPad,
          .source = "LUSTBUS manual 5.2 (free RAM word)"},
    Entry{.number = kSwdgt, .name = "SWDGT", .text = "Serial watchdog time (0: off)",
          .type = Type::usign16, .min = 0, .max = 65535, .default_value = 0, .unit = "ms",
          .storage = Storage::eeprom, .keypad = &kSioMsPad,
          .source = "LUSTBUS manual 1, 5.2 (0 = no watchdog, factory)"},
    Entry{.number = kSerr, .name = "SERR", .text = "Serial interface error flags",
          .type = Type::usign8, .min = 0, .max = 255, .default_value = 0,
          .storage = Storage::ram_actual, .role = Role::error_flags,
          .attributes = attr::kShowHex, .keypad = &kSioPad, .source = "LUSTBUS manual 9.2 (the bits)"},
    Entry{.number = kType, .name = "TYPE", .text = "Device type", .type = Type::usign16, .min = 0,
          .max = 65535, .default_value = kMc6000TypeCode, .storage = Storage::ram_actual,
          .keypad = &kSysPad, .invented = true, .source = "LUSTBUS manual 5.2 names it; the code is chosen"},
    Entry{.number = kUnit, .name = "UNIT", .text = "Unit texts (11.2.1 unit index)",
          .type = Type::usign8, .min = 0, .max = 255, .default_value = 0,
          .storage = Storage::ram_control, .attributes = attr::kShowText, .choices = kUnitTexts,
          .keypad = &kMenuPad, .invented = true, .source = "LUSTBUS manual 11.2.1; the texts chosen"},
    Entry{.number = kStext, .name = "STEXT", .text = "Substitution text index (11.3)",
          .type = Type::usign8, .min = 0, .max = 255, .default_value = 0,
          .storage = Storage::ram_control, .keypad = &kMenuPad, .source = "LUSTBUS manual 11.3"},
    Entry{.number = kCfcon, .name = "CFCON", .text = "Control type", .type = Type::usign8,
          .min = 1, .max = 6, .default_value = kCfconScon, .storage = Storage::eeprom,
          .attributes = attr::kShowText | attr::kInitControl, .in_data_set = true,
          .choices = kCfconTexts, .keypad = &kConfDrivePad, .invented = true,
          .source = "LUSTBUS manual 7.2.1 (SCON = 2); the codes follow 11.2.1's structure filter"},
    selector(kClsel, "CLSEL", "Control location selector", 0, 5, kClselOpt1, kClselTexts,
             &kConfDrivePad, "LUSTBUS manual 7.2.1, INTERBUS manual 5.3.4 (SIO 2, OPT1 4); default INTERBUS manual "
             "3.2.1"),
    Entry{.number = kSupi, .name = "SUPI", .text = "INTERBUS process data layout",
          .type = Type::usign8, .min = 0, .max = 12, .default_value = 11,
          .storage = Storage::eeprom, .effect = Effect::at_restart, .in_data_set = true,
          .keypad = &kOpt1SetPad, .invented = true,
          .source = "INTERBUS manual 3.2.2 (range; effective at power-on); default as 5.3.4"},
    Entry{.number = kIbcnf, .name = "IBCNF", .text = "INTERBUS process data configuration",
          .type = Type::usign8, .min = 0, .max = 4, .default_value = 2,
          .storage = Storage::eeprom, .effect = Effect::at_restart, .in_data_set = true,
          .keypad = &kOpt1SetPad, .source = "INTERBUS manual 3.2.3, 5.3.3 (Q16 is the default)"},
    Entry{.number = kIbstu, .name = "IBSTU", .text = "DRIVECOM control word",
          .type = Type::usign16, .min = 0, .max = 65535, .default_value = 0,
          .storage = Storage::ram_control, .attributes = attr::kShowHex, .keypad = &kOpt1Pad,
          .source = "INTERBUS manual 4.2.1"},
    Entry{.number = kIbsta, .name = "IBSTA", .text = "DRIVECOM status word",
          .type = Type::usign16, .min = 0, .max = 65535, .default_value = 0,
          .storage = Storage::ram_actual, .attributes = attr::kShowHex, .keypad = &kOpt1Pad,
          .source = "INTERBUS manual 4.2.1"},
    Entry{.number = kButwd, .name = "BUTWD", .text = "Bus watchdog time (0: off)",
          .type = Type::usign16, .min = 0, .max = 65535, .default_value = 0, .unit = "ms",
          .storage = Storage::eeprom, .in_data_set = true, .keypad = &kOpt1SetMsPad,
          .invented = true, .source = "INTERBUS manual 3.2.4 (ms, 0 = off); type and range chosen"},
    Entry{.number = kSctl1, .name = "SCTL1", .text = "Serial control word (bit 0 start, bit 7 "
          "reset)", .type = Type::usign16, .min = 0, .max = 65535, .default_value = 0,
          .storage = Storage::ram_control, .attributes = attr::kShowHex, .keypad = &kSioPad,
          .source = "LUSTBUS manual 7.2, 8.1.2"},
    selector(kRssl1, "RSSL1", "Reference selector 1", 0, 7, kRsslRcon, kRsslTexts, &kRefSetPad,
             "LUSTBUS manual 7.2, INTERBUS manual 5.3.4 (RCON 0, RSIO 3, OPT1 6); default INTERBUS manual 3.2.1"),
    selector(kRssl2, "RSSL2", "Reference selector 2", 0, 7, kRsslRcon, kRsslTexts, &kRefSetPad,
             "LUSTBUS manual 7.2, INTERBUS manual 5.3.4 (RCON 0, RSIO 3, OPT1 6); default INTERBUS manual 3.2.1"),
    selector(kRssl3, "RSSL3", "Reference selector 3", 0, 7, kRsslOpt1, kRsslTexts, &kRefSetPad,
             "LUSTBUS manual 7.2, INTERBUS manual 5.3.4 (RCON 0, RSIO 3, OPT1 6); default INTERBUS manual 3.2.1"),
    selector(kRssl4, "RSSL4", "Reference selector 4", 0, 7, kRsslRcon, kRsslTexts, &kRefSetPad,
             "LUSTBUS manual 7.2, INTERBUS manual 5.3.4 (RCON 0, RSIO 3, OPT1 6); default INTERBUS manual 3.2.1"),
    Entry{.number = kRsio, .name = "RSIO", .text = "Speed reference (serial interface)",
          .type = Type::int32q16, .min = kQ16Min, .max = kQ16Max, .default_value = 0,
          .unit = "rpm", .storage = Storage::ram_control, .keypad = &kSioRpmPad,
          .source = "LUSTBUS manual 7.2.1"},
    selector(kFis00, "FIS00", "Function of input 0", 0, 255, kFunctionRopt1, kInputTexts,
             &kRefSetPad, "INTERBUS manual 3.2.1 (default ROPT1), 5.3.2; the codes chosen"),
    selector(kFis01, "FIS01", "Function of input 1", 0, 255, kFunctionRopt1, kInputTexts,
             &kRefSetPad, "INTERBUS manual 3.2.1 (default ROPT1), 5.3.2; the codes chosen"),
    selector(kFif0, "FIF0", "Function of input F0", 0, 255, kFunctionOff, kInputTexts,
             &kRefSetPad, "INTERBUS manual 3.2.1 (default OFF); the codes chosen"),
    selector(kFif1, "FIF1", "Function of input F1", 0, 255, kFunctionOff, kInputTexts,
             &kRefSetPad, "INTERBUS manual 3.2.1 (default OFF); the codes chosen"),
    selector(kFos00, "FOS00", "Function of output 0", 0, 255, kFunctionRopt1, kOutputTexts,
             &kRefSetPad, "INTERBUS manual 3.2.1 (default ROPT1), 5.3.1; the codes chosen"),
    selector(kFos01, "FOS01", "Function of output 1", 0, 255, kFunctionRopt1, kOutputTexts,
             &kRefSetPad, "INTERBUS manual 3.2.1 (default ROPT1), 5.3.1; the codes chosen"),
    selector(kReop1, "REOP1", "Reaction to error 16 E-OP1", 1, 5, kReactionStop, kReactionTexts,
             &kSctySetPad, "LUSTBUS manual 8 (five steps), 8.1.2 (5 = RESET); number, name, steps 1-4 "
             "and the default chosen (MC-D7)"),
    selector(kResio, "RESIO", "Reaction to the serial watchdog", 1, 5, kReactionStop,
             kReactionTexts, &kSctySetPad, "LUSTBUS manual 8, 8.1.2, 5.2 (the watchdog's reaction by "
             "parameter); number, name, steps 1-4 and the default chosen (MC-D7)"),
    selector(kRedev, "REDEV", "Reaction to any other device error", 1, 5, kReactionStop,
             kReactionTexts, &kSctySetPad, "LUSTBUS manual 8, 8.1.2; number, name, steps 1-4 and the "
             "default chosen (MC-D7)"),
};
// clang-format on
}  // namespace dictionary_rows

// The MC6000's parameters, sorted by number, with the factory defaults of a servo that detected its
// INTERBUS card (INTERBUS manual 3.2.1): the enhanced family's conventions (PCP, LUSTBUS enhanced).
inline constexpr const auto& kDictionaryEntries = dictionary_rows::kEntries;
inline constexpr od::Dictionary kDictionary{kDictionaryEntries, od::Profile::lust_enhanced};
static_assert(od::check(kDictionaryEntries).ok(), "the MC6000's dictionary");

// INTERBUS manual 3.2.1 "Modified Factory Default": the parameters the servo changes for INTERBUS
// operation the first time it detects the INTERBUS card at power-on (the entries' defaults), and
// resets "to their factory defaults the next time the device is powered-up" after the card was
// withdrawn. The seeds give the values with the card only; without it every selector is code 0,
// the one that names no option: CLSEL TERM, RSSLx RCON (LUSTBUS manual 7.2: "0 (i.e., RCON)"), the
// function selectors OFF (docs/errata.md MC-D10).
inline constexpr std::array<od::DefaultOverride, 11> kWithoutCardDefaults{{
    {kClsel, 0},
    {kRssl1, kRsslRcon},
    {kRssl2, kRsslRcon},
    {kRssl3, kRsslRcon},
    {kRssl4, kRsslRcon},
    {kFis00, kFunctionOff},
    {kFis01, kFunctionOff},
    {kFos00, kFunctionOff},
    {kFos01, kFunctionOff},
    {kFif0, kFunctionOff},
    {kFif1, kFunctionOff},
}};

}  // namespace ibs::devices::mc6000
