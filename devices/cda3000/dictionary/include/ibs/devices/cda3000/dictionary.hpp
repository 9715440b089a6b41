// The CDA3000's object dictionary (issue 38): every parameter that CANLust manual (CM-CAN1 manual,
// fragments) and the notes name, one od::Entry each, as the drive serves it over the CANLust
// parameter channel (the CANLust codec, canlust/od_codec.hpp, encodes it) and as the master, the
// command line and the reports read it. Values are numbers of the entry's type (INT32Q16: the raw
// Q16 number), which on CANLust are the 32-bit wire images of the CANLust manual 4.1.1 as they are.
//
// Where the seed prints a range, a factory setting, a unit, a data type or a substitution-text
// code, the entry uses it and `source` cites it; everything else is a modelling choice marked
// `invented` with what was invented (docs/canlust.md, "The CDA3000 wing", decisions D21-D39).
//
// How CANLust manual's columns become the entry's fields:
// - "Memory type FLASH" (4.3: saved by 150-SAVE, loaded at power-on) is Storage::flash; a RAM
//   value is ram_control when it can be written, ram_actual when only the drive sets it
//   (406-REFF, 95-ERR1, 577-CAWRN, 578-OPTN2);
// - the bus settings that act "after a mains reset" (7.1.1 steps 4-5) are Effect::at_restart;
// - a selector takes only its substitution texts (4.1, "numerical value = substitution text"):
//   choices_only;
// - "Card Writeable" (4.x, the data set of a download, D39) is in_data_set: the writable numbers
//   kept in flash;
// - 04-PROG, 150-SAVE and 80-SLOAD have the roles od's rules and the core act on.
// This drive keeps no 85-SIOF/SERR (CANLust answers each request with its own status).
//
// The named numbers and codes below are the wing's: the core, the master and the tests use them.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "ibs/od/dictionary.hpp"

namespace ibs::devices::cda3000 {

// ---- numbers with behaviour beyond storing a value ----------------------------------------------
inline constexpr std::uint16_t kProg = 4;  // 1.x exceptions: 1 = factory settings
// 4.x "Downloading parameter data sets": the handshake of a download (number, name and codes
// invented after the MC6000's 80-SLOAD of the LUSTBUS manual 11.4; D39): -1 opens, -2 closes and checks,
// 0 drops an open download; reads -1 while one is open, then 0 (valid, in the EEPROM) or the
// number of the first implausible parameter.
inline constexpr std::uint16_t kSload = 80;
inline constexpr std::uint32_t kSloadStart = 0xFFFFFFFFU;  // -1, INT16 sign-filled (4.1.1)
inline constexpr std::uint32_t kSloadEnd = 0xFFFFFFFEU;    // -2
inline constexpr std::uint32_t kSloadCancel = 0;
inline constexpr std::uint16_t kName = 90;  // invented: a user text (a writable string)
inline constexpr std::uint16_t kErr1 = 95;  // invented: the last error as ERR_STRUC (D34)
inline constexpr std::uint16_t kFisa0 = 180;
inline constexpr std::uint16_t kSave = 150;   // 3.5.1 / 4.3.3
inline constexpr std::uint16_t kAstpr = 151;  // 4.2 table: original application data set
inline constexpr std::uint16_t kAster = 152;  // current application data set
inline constexpr std::uint16_t kClsel = 260;  // 4.3.2 control location
inline constexpr std::uint16_t kRssl1 = 280;  // 4.3.2 reference selector 1
inline constexpr std::uint16_t kDisp = 360;   // 7.1.3 continuous actual value
inline constexpr std::uint16_t kReff = 406;   // 7.1.3 current reference frequency
inline constexpr std::uint16_t kClbdr = 489;  // 4.3.1
inline constexpr std::uint16_t kCacnf = 492;  // 4.3.2
inline constexpr std::uint16_t kCamod = 570;  // 4.3.1
inline constexpr std::uint16_t kCladr = 571;  // 2.1, 4.3.1
inline constexpr std::uint16_t kCawdg = 574;  // 4.3.1
inline constexpr std::uint16_t kCascy = 575;  // 4.3.1
inline constexpr std::uint16_t kOptn2 = 578;  // 3.3: the module found at option slot 2
inline constexpr std::uint16_t kCdssl = 651;  // 5.4.1 footnote 2
// 6.1: "the error response is programmable for each error in four stages": one response per
// error of table 5.9, numbers and names invented (CAN-E16). 525-ROP2 is the bus watchdog's too
// (it reports E-OP2 at 172, D15).
inline constexpr std::uint16_t kRoti = 520;
inline constexpr std::uint16_t kRpls = 521;
inline constexpr std::uint16_t kRpar = 522;
inline constexpr std::uint16_t kRflt = 523;
inline constexpr std::uint16_t kRpwr = 524;
inline constexpr std::uint16_t kRop2 = 525;
// 6.3 "Parameterizable warnings on the CAN": the mask of the warnings reported over the bus and
// the warnings present (bits 0004H, 0008H, 0010H ... of 6.3); numbers and names invented (CAN-E17).
inline constexpr std::uint16_t kCawmk = 576;
inline constexpr std::uint16_t kCawrn = 577;

// ---- substitution texts -------------------------------------------------------------------------
// CANLust manual prints three codes: 280-RSSL1 "7 TBSEL" (5.4.1 footnote 1), the range "0 FCON .. 11
// FMAX" with 1 FA0, 2 FA1, 4 FPOT (4.3.2), and 651-CDSSL "6 OPTN2" (footnote 2). OPTN2 is 6 in
// every selector (the one code the seed gives for it, decision D22).
inline constexpr std::uint32_t kOptn2Code = 6;
inline constexpr std::uint32_t kClselTerm = 0;  // invented
inline constexpr std::uint32_t kRsslFcon = 0;
inline constexpr std::uint32_t kRsslFa0 = 1;
inline constexpr std::uint32_t kRsslTbsel = 7;
inline constexpr std::uint32_t kRsslFmax = 11;
inline constexpr std::uint32_t kDataSetDrv1 = 0;  // invented codes of the application data sets
inline constexpr std::uint32_t kDataSetBus1 = 1;
inline constexpr std::uint32_t kCamodSlave = 0;   // invented
inline constexpr std::uint32_t kCamodMaster = 1;  // invented; the emulator refuses it (D26)
inline constexpr std::uint32_t kFunctionOff = 0;  // invented

inline constexpr std::array<od::Choice, 2> kChoicesProg{
    {{0, "-", "no action"}, {1, "DEF", "overwrite every setting with its factory value"}}};
inline constexpr std::array<od::Choice, 2> kChoicesSave{
    {{0, "READY", "nothing to do / backup finished"},
     {1, "START", "back up the settings (BUSY meanwhile)"}}};
inline constexpr std::array<od::Choice, 2> kChoicesDataSet{
    {{kDataSetDrv1, "DRV_1", "drive data set 1 (terminal operation)"},
     {kDataSetBus1, "BUS_1", "bus data set 1 (control and reference over the bus)"}}};
inline constexpr std::array<od::Choice, 2> kChoicesFisa0{
    {{kFunctionOff, "OFF", "no function"}, {kOptn2Code, "OPTN2", "module at option slot 2"}}};
inline constexpr std::array<od::Choice, 2> kChoicesClsel{
    {{kClselTerm, "TERM", "control terminals"},
     {kOptn2Code, "OPTN2", "module at option slot 2: bytes 0-1 of the control telegram"}}};
inline constexpr std::array<od::Choice, 7> kChoicesRssl1{
    {{kRsslFcon, "FCON", "constant frequency"},
     {kRsslFa0, "FA0", "analog input 0"},
     {2, "FA1", "analog input 1"},
     {4, "FPOT", "MOP function"},
     {kOptn2Code, "OPTN2", "module at option slot 2: bytes 2-5 of the control telegram"},
     {kRsslTbsel, "TBSEL", "table references selected by control bits"},
     {kRsslFmax, "FMAX", "maximum frequency"}}};
inline constexpr std::array<od::Choice, 4> kChoicesCacnf{
    {{1, "DC16", "DRIVECOM, 16-bit reference and actual value"},
     {2, "DCQ16", "DRIVECOM, Q16 reference and actual value"},
     {3, "DCQ16I16", "DRIVECOM, Q16 reference, 16-bit actual value"},
     {4, "EASY", "EasyDrive direct control, Q16 values"}}};
inline constexpr std::array<od::Choice, 2> kChoicesCamod{
    {{kCamodSlave, "SLAVE", "CANLust slave"}, {kCamodMaster, "MASTER", "CANLust master"}}};
inline constexpr std::array<od::Choice, 3> kChoicesCdssl{
    {{0, "CDS1", "characteristic data set 1"},
     {1, "CDS2", "characteristic data set 2"},
     {kOptn2Code, "OPTN2", "selected by the CUSEL bit over the bus"}}};

// The four stages of 6.1 as codes of the error reaction (D7: 0 WRN, 1 STOP, 2 quick stop, 3 the
// power stage off, the default of 6.1); the names besides WRN and STOP invented.
inline constexpr std::uint32_t kResponseDefault = 3;
inline constexpr std::array<od::Choice, 4> kChoicesResponse{
    {{0, "WRN", "warning message: status bit 7, the drive runs on"},
     {1, "STOP", "controlled stop, then FAULT"},
     {2, "QSTOP", "quick stop, then FAULT"},
     {kResponseDefault, "PWOFF", "power stage disabled at once, the motor coasts (6.1 default)"}}};

// The factory text of 90-NAME and the constant of 578-OPTN2 (3.3: the CM-CAN1 shows as LCAN).
inline constexpr std::string_view kNameFactory = "CDA3000";
inline constexpr std::string_view kOptn2Module = "LCAN";

// ---- the entries --------------------------------------------------------------------------------
namespace detail {
// A flash setting of the CANLust manual's tables, writable, in the data set: what most rows are.
constexpr od::Entry setting(std::uint16_t number, std::string_view name, std::string_view text,
                            od::Type type, std::int64_t min, std::int64_t max,
                            std::int64_t factory) {
  return {.number = number,
          .name = name,
          .text = text,
          .type = type,
          .min = min,
          .max = max,
          .default_value = factory,
          .storage = od::Storage::flash,
          .in_data_set = true,
          .invented = true};
}
constexpr od::Entry with_choices(od::Entry e, std::span<const od::Choice> choices) {
  e.choices = choices;
  e.choices_only = true;
  return e;
}
constexpr od::Entry at_restart(od::Entry e) {
  e.effect = od::Effect::at_restart;
  return e;
}
constexpr od::Entry with_unit(od::Entry e, std::string_view unit) {
  e.unit = unit;
  return e;
}
constexpr od::Entry from_manual(od::Entry e, std::string_view source) {
  e.invented = false;
  e.source = source;
  return e;
}
constexpr od::Entry invented(od::Entry e, std::string_view source) {
  e.invented = true;
  e.source = source;
  return e;
}
// 6.1's response to an error of table 5.9 (CAN-E16): a selector of the four stages, PWOFF.
constexpr od::Entry response(std::uint16_t number, std::string_view name, std::string_view text,
                             std::string_view source) {
  return invented(
      with_choices(setting(number, name, text, od::Type::usign8, 0, 3, kResponseDefault),
                   kChoicesResponse),
      source);
}
}  // namespace detail

inline constexpr std::array kEntries{
    od::Entry{.number = kProg,
              .name = "PROG",
              .text = "reset to factory settings",
              .type = od::Type::usign8,
              .min = 0,
              .max = 1,
              .role = od::Role::load_defaults,
              .choices = kChoicesProg,
              .choices_only = true,
              .invented = true,
              .source = "CANLust manual p. 13: 1 makes the drive overwrite all settings with their "
                        "defaults, the reply comes when that is done; type, range, names invented"},
    od::Entry{.number = kSload,
              .name = "SLOAD",
              .text = "parameter data set download (handshake)",
              .type = od::Type::int16,
              .min = -2,
              .max = 999,
              .role = od::Role::download,
              .invented = true,
              .source = "CANLust manual 4.x 'Downloading parameter data sets': values taken without "
                        "individual checking, the whole set checked for plausibility at the end, "
                        "then into the EEPROM with the attribute Card Writeable; number, name and "
                        "codes invented after the LUSTBUS manual 11.4's 80-SLOAD (D39)"},
    od::Entry{.number = kName,
              .name = "NAME",
              .text = "device name (user text)",
              .type = od::Type::string,
              .min = 0,
              .max = 99,
              .default_text = kNameFactory,
              .storage = od::Storage::flash,
              .invented = true,
              .source = "invented: CANLust manual names no string parameter that can be written (D24)"},
    od::Entry{.number = kErr1,
              .name = "ERR1",
              .text = "last error (number, location, operating hours)",
              .type = od::Type::error32,
              .min = 0,
              .max = 0xFFFFFFFFLL,
              .storage = od::Storage::ram_actual,
              .invented = true,
              .source = "CANLust manual 4.1.1 gives the ERR_STRUC type (E-OP2 at 172 after 85 h = 10 AC "
                        "55 00) and 6.2 the error numbers; the parameter's number and name "
                        "invented (D34)"},
    od::Entry{.number = kSave,
              .name = "SAVE",
              .text = "back up the settings in the device",
              .type = od::Type::usign8,
              .min = 0,
              .max = 1,
              .role = od::Role::save,
              .choices = kChoicesSave,
              .choices_only = true,
              .invented = true,
              .source = "CANLust manual 3.5.1: '150-SAVE = 1 START', 'takes a few hundred milliseconds', "
                        "7.1.1 step 4 '1 BUSY'; READY and the codes invented"},
    detail::invented(
        detail::with_choices(detail::setting(kAstpr, "ASTPR", "original application data set",
                                             od::Type::usign8, 0, 1, kDataSetDrv1),
                             kChoicesDataSet),
        "CANLust manual 4.2 table: factory DRV_1, changed value BUS_1; codes and the preset it loads "
        "invented (D23)"),
    detail::invented(
        detail::with_choices(detail::setting(kAster, "ASTER", "current application data set",
                                             od::Type::usign8, 0, 1, kDataSetDrv1),
                             kChoicesDataSet),
        "CANLust manual 4.2 table: factory DRV_1, changed value BUS_1; codes invented"),
    detail::invented(
        detail::with_choices(
            detail::setting(kFisa0, "FISA0", "function selector analog standard input 0",
                            od::Type::usign8, 0, 6, kFunctionOff),
            kChoicesFisa0),
        "CANLust manual 4.2 table: factory OFF, changed value OPTN2; codes invented"),
    detail::invented(
        detail::with_choices(detail::setting(kClsel, "CLSEL", "control location", od::Type::usign8,
                                             0, 6, kClselTerm),
                             kChoicesClsel),
        "CANLust manual 4.3.2: 'with CLSEL = OPTN2 the control word is formed from bytes 0 and 1 of the "
        "control identifier'; TERM, the codes and the factory setting invented"),
    detail::invented(
        detail::with_choices(detail::setting(kRssl1, "RSSL1", "reference selector 1",
                                             od::Type::usign8, 0, 11, kRsslFmax),
                             kChoicesRssl1),
        "CANLust manual 4.3.2 row '_28RS 0 FCON 11 FMAX 11 FMAX USIGN8 FLASH', 1 FA0, 2 FA1, 4 FPOT; "
        "5.4.1 '7 TBSEL'; OPTN2 = 6 invented (D22)"),
    detail::invented(
        detail::setting(kDisp, "DISP", "parameter shown as the continuous actual value",
                        od::Type::usign16, 0, 999, kReff),
        "CANLust manual 7.1.3: reads 406 (406-REFF), the example writes 14; type and range 0..999 "
        "(a parameter number, 4.4) invented"),
    od::Entry{.number = kReff,
              .name = "REFF",
              .text = "current reference frequency",
              .type = od::Type::int32q16,
              .min = od::min_number(od::Type::int32q16),
              .max = od::max_number(od::Type::int32q16),
              .unit = "Hz",
              .storage = od::Storage::ram_actual,
              .invented = true,
              .source = "CANLust manual 7.1.3: '406-REFF current reference frequency'; type INT32Q16 in "
                        "Hz invented"},
    detail::from_manual(
        detail::at_restart(detail::with_unit(
            detail::setting(kClbdr, "CLBDR", "CAN bus baud rate", od::Type::usign16, 25, 500, 500),
            "kBaud")),
        "CANLust manual 4.3.1: 25..500, factory 500; 7.1.1: save, then mains reset"),
    detail::invented(
        detail::at_restart(detail::with_choices(
            detail::setting(kCacnf, "CACNF", "control and reference configuration",
                            od::Type::usign8, 1, 4, 2),
            kChoicesCacnf)),
        "CANLust manual 4.3.2, 5.5.5, 7.1: 2 DRIVECOM (7.1.2), 4 EasyDrive (7.1.1); map D5; factory 2 "
        "invented"),
    detail::response(kRoti, "ROTI", "error response to E-OTI (drive unit overheating)",
                     "CANLust manual 6.1: 'programmable for each error in four stages', default: the "
                     "power stage disabled; number, name and codes invented (CAN-E16)"),
    detail::response(kRpls, "RPLS", "error response to E-PLS (plausibility error)",
                     "CANLust manual 6.1 (as 520-ROTI); number, name and codes invented (CAN-E16)"),
    detail::response(kRpar, "RPAR", "error response to E-PAR (faulty parameter setting)",
                     "CANLust manual 6.1 (as 520-ROTI); number, name and codes invented (CAN-E16)"),
    detail::response(kRflt, "RFLT", "error response to E-FLT (floating point error)",
                     "CANLust manual 6.1 (as 520-ROTI); number, name and codes invented (CAN-E16)"),
    detail::response(kRpwr, "RPWR", "error response to E-PWR (power pack not recognized)",
                     "CANLust manual 6.1 (as 520-ROTI); number, name and codes invented (CAN-E16)"),
    detail::response(kRop2, "ROP2", "error response to E-OP2 (option module, bus watchdog)",
                     "CANLust manual 6.1 and table 5.9 (E-OP2); also the reaction to 574-CAWDG running "
                     "out (D15); number, name, codes and the factory PWOFF invented (CAN-E16)"),
    detail::invented(
        detail::at_restart(detail::with_choices(
            detail::setting(kCamod, "CAMOD", "function selection of the option module",
                            od::Type::usign8, 0, 1, kCamodSlave),
            kChoicesCamod)),
        "CANLust manual 4.3.1: 'Function selection option module CANLUST Slave Ma...'; codes invented"),
    detail::invented(
        detail::at_restart(detail::setting(kCladr, "CLADR", "CAN address (0: the connector's)",
                                           od::Type::usign8, 0, 99, 0)),
        "CANLust manual 2.1: the connector's address 0..7 is used when CLADR = 0; 4.3.1; 7.1: mains "
        "reset; range 0..99 from the notes' addresses, factory 0 invented"),
    detail::from_manual(detail::with_unit(detail::setting(kCawdg, "CAWDG", "CAN bus watchdog time",
                                                          od::Type::usign8, 0, 255, 0),
                                          "ms"),
                        "CANLust manual 4.3.1: 0..255 ms, factory 0, 0 deactivates the watchdog"),
    detail::from_manual(
        detail::with_unit(detail::setting(kCascy, "CASCY", "sampling time of the status message",
                                          od::Type::usign16, 1, 32000, 80),
                          "ms"),
        "CANLust manual 4.3.1: 1..32000 ms, factory 80"),
    detail::invented(
        detail::setting(kCawmk, "CAWMK", "warnings reported on the CAN (mask)", od::Type::usign16,
                        0, 0xFFFF, 0xFFFF),
        "CANLust manual 6.3 'parameterizable warnings on the CAN', masks 0004H I2t, 0008H motor "
        "temperature, 0010H heat sink temperature; number, name and factory (all) invented "
        "(CAN-E17)"),
    od::Entry{
        .number = kCawrn,
        .name = "CAWRN",
        .text = "warnings present (6.3 bits)",
        .type = od::Type::usign16,
        .min = 0,
        .max = 0xFFFF,
        .storage = od::Storage::ram_actual,
        .invented = true,
        .source = "CANLust manual 6.3 bits 0004H, 0008H, 0010H; number and name invented (CAN-E17)"},
    od::Entry{.number = kOptn2,
              .name = "OPTN2",
              .text = "module found at option slot 2",
              .type = od::Type::string,
              .min = 0,
              .max = 99,
              .default_text = kOptn2Module,
              .storage = od::Storage::ram_actual,
              .invented = true,
              .source = "CANLust manual 3.3: 'verify the value in parameter 578-OPTN2 (LCAN)'; a "
                        "read-only STRING 'LCAN' invented (D24)"},
    detail::invented(
        detail::with_choices(detail::setting(kCdssl, "CDSSL", "characteristic data set selection",
                                             od::Type::usign8, 0, 6, 0),
                             kChoicesCdssl),
        "CANLust manual 5.4.1 footnote 2: '651-CDSSL = 6 OPTN2' lets the CUSEL bit switch data sets 1 "
        "and 2; CDS1, CDS2 and the factory setting invented"),
};

// The index, made at compile time: a dictionary od's checks refuse does not compile.
inline constexpr od::Dictionary kDictionary{kEntries};

}  // namespace ibs::devices::cda3000
