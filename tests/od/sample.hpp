// Dictionaries the od tests share: rows transcribed from the three drives' tables of today (the
// VF1000's drive::ParameterInfo rows, the MC6000's pcp::ParameterInfo and KEYPAD rows, the
// CDA3000's rows with their substitution texts) as the wings will write them (plan W1-W3), plus a
// text entry of each storage kind. od knows no drive: these are test data.
#pragma once

#include <array>
#include <string_view>

#include "ibs/od/dictionary.hpp"

namespace ibs::od::test {

using namespace std::string_view_literals;

// ---- VF1000-like (LUSTBUS manual 11.1, INTERBUS manual 4.1.3.3; devices/vf1000/src/parameters.cpp) ----------
inline constexpr Entry kVfMode{.number = 1,
                               .name = "MODE",
                               .text = "Mode select",
                               .type = Type::usign8,
                               .min = 0,
                               .max = 4,
                               .default_value = 4,
                               .storage = Storage::eeprom};
inline constexpr Entry kVfCntl{.number = 3,
                               .name = "CNTL",
                               .text = "Control word (serial interface)",
                               .type = Type::binary8,
                               .min = 0,
                               .max = 0xFF};
inline constexpr Entry kVfFssel{.number = 4,
                                .name = "FSSEL",
                                .type = Type::usign8,
                                .min = 0,
                                .max = 25,
                                .default_value = 25,
                                .storage = Storage::eeprom};
inline constexpr Entry kVfFssio{.number = 5,
                                .name = "FSSIO",
                                .type = Type::fixpoint16,
                                .min = 0,
                                .max = 19999,
                                .unit = "Hz",
                                .storage = Storage::eeprom_ram};
inline constexpr Entry kVfFout{.number = 12,
                               .name = "FOUT",
                               .type = Type::fixpoint16,
                               .min = 0,
                               .max = 0xFFFF,
                               .unit = "Hz",
                               .storage = Storage::ram_actual,
                               .invented = true};
inline constexpr Entry kVfVb2{.number = 22,
                              .name = "VB2",
                              .text = "Voltage boost 2",
                              .type = Type::fixpoint16,
                              .min = 0,
                              .max = 0x01F4,
                              .default_value = 0xA0,
                              .unit = "%",
                              .storage = Storage::eeprom,
                              .source = "INTERBUS manual 4.1.3.3.1"};
inline constexpr Entry kVfProg{.number = 71,
                               .name = "PROG",
                               .type = Type::usign8,
                               .min = 0,
                               .max = 1,
                               .storage = Storage::eeprom,
                               .role = Role::load_defaults};
inline constexpr Entry kVfSiot{.number = 84,
                               .name = "SIOT",
                               .type = Type::usign16,
                               .min = 0,
                               .max = 0xFFFF,
                               .unit = "ms",
                               .storage = Storage::eeprom};
inline constexpr Entry kVfSiof{.number = 85,
                               .name = "SIOF",
                               .type = Type::binary8,
                               .min = 0,
                               .max = 0xFF,
                               .storage = Storage::ram_actual,
                               .role = Role::error_flags};
inline constexpr Entry kVfType{.number = 91,
                               .name = "TYPE",
                               .type = Type::usign16,
                               .min = 0,
                               .max = 0xFFFF,
                               .default_value = 1000,
                               .storage = Storage::ram_actual};
inline constexpr Entry kVfIbWd{.number = 906,
                               .name = "IB-WD",
                               .type = Type::usign16,
                               .min = 8,
                               .max = 0xFFFF,
                               .default_value = 200,
                               .unit = "ms",
                               .storage = Storage::eeprom};
inline constexpr Entry kVfFdriv{.number = 911,
                                .name = "FDRIV",
                                .type = Type::int16,
                                .min = -32768,
                                .max = 32767,
                                .unit = "Hz",
                                .scale = 0.05};
inline constexpr std::array kVfEntries{kVfMode, kVfCntl, kVfFssel, kVfFssio, kVfFout, kVfVb2,
                                       kVfProg, kVfSiot, kVfSiof,  kVfType,  kVfIbWd, kVfFdriv};
inline constexpr Dictionary kVf{kVfEntries, Profile::lust_standard};
// The standard values of the INTERBUS manual 3.1.1's three (VF-E20).
inline constexpr std::array<DefaultOverride, 2> kVfStandalone{{{1, 0}, {4, 0}}};

// ---- MC6000-like (LUSTBUS manual 2.3.2, 11.2.1, 11.4; devices/mc6000 parameters.hpp, service.cpp) -----
inline constexpr std::array kRsslTexts{
    Choice{0, "RCON", ""}, Choice{1, "RA0", ""},  Choice{2, "RA1", ""},  Choice{3, "RSIO", ""},
    Choice{4, "RFIX", ""}, Choice{5, "RCAN", ""}, Choice{6, "OPT1", ""}, Choice{7, "OPT2", ""}};
inline constexpr Keypad kRefKeypad{.subject = 15, .activity = 6};
inline constexpr Keypad kValKeypad{.unit = 1, .subject = 21};
inline constexpr Entry kMcProg{.number = 4,
                               .name = "PROG",
                               .type = Type::usign8,
                               .min = 0,
                               .max = 255,
                               .role = Role::load_defaults};
inline constexpr Entry kMcPlrdy{.number = 15,
                                .name = "PLRDY",
                                .type = Type::usign8,
                                .min = 0,
                                .max = 1,
                                .attributes = attr::kInitControl};
inline constexpr Entry kMcSpeed{.number = 77,
                                .name = "SPEED",
                                .type = Type::int32q16,
                                .min = -2147483648LL,
                                .max = 2147483647LL,
                                .unit = "rpm",
                                .storage = Storage::ram_actual,
                                .keypad = &kValKeypad};
inline constexpr Entry kMcSload{.number = 80,
                                .name = "SLOAD",
                                .type = Type::int16,
                                .min = -2,
                                .max = 999,
                                .role = Role::download};
inline constexpr Entry kMcSerr{.number = 85,
                               .name = "SERR",
                               .type = Type::usign8,
                               .min = 0,
                               .max = 255,
                               .storage = Storage::ram_actual,
                               .role = Role::error_flags,
                               .attributes = attr::kShowHex};
inline constexpr Entry kMcRssl1{.number = 417,
                                .name = "RSSL1",
                                .type = Type::usign8,
                                .min = 0,
                                .max = 7,
                                .storage = Storage::eeprom,
                                .attributes = attr::kShowText,
                                .in_data_set = true,
                                .choices = kRsslTexts,
                                .keypad = &kRefKeypad};
inline constexpr Entry kMcRssl3{.number = 419,
                                .name = "RSSL3",
                                .type = Type::usign8,
                                .min = 0,
                                .max = 7,
                                .default_value = 6,
                                .storage = Storage::eeprom,
                                .attributes = attr::kShowText,
                                .in_data_set = true,
                                .choices = kRsslTexts,
                                .keypad = &kRefKeypad};
inline constexpr Entry kMcRsio{.number = 428,
                               .name = "RSIO",
                               .type = Type::int32q16,
                               .min = -2147483648LL,
                               .max = 2147483647LL,
                               .unit = "rpm"};
inline constexpr Entry kMcGain{.number = 600,
                               .name = "GAIN",
                               .type = Type::float_ieee,
                               .min = 0x00000000,  // 0.0f
                               .max = 0x42C80000,  // 100.0f
                               .default_value = 0x3F800000,
                               .storage = Storage::eeprom,
                               .invented = true};
inline constexpr std::array kMcEntries{kMcProg,  kMcPlrdy, kMcSpeed, kMcSload, kMcSerr,
                                       kMcRssl1, kMcRssl3, kMcRsio,  kMcGain};
inline constexpr Dictionary kMc{kMcEntries, Profile::lust_enhanced};

// ---- CDA3000-like (CANLust manual 4.3; devices/cda3000/parameters.hpp)
// ----------------------------------
inline constexpr std::array kChoicesProg{Choice{0, "-", "no action"},
                                         Choice{1, "DEF", "factory settings"}};
inline constexpr std::array kChoicesSave{Choice{0, "READY", ""}, Choice{1, "START", ""}};
inline constexpr std::array kChoicesClsel{Choice{0, "TERM", "control terminals"},
                                          Choice{6, "OPTN2", "module at option slot 2"}};
inline constexpr std::array kChoicesRssl1{
    Choice{0, "FCON", ""},  Choice{1, "FA0", ""},   Choice{2, "FA1", ""},  Choice{4, "FPOT", ""},
    Choice{6, "OPTN2", ""}, Choice{7, "TBSEL", ""}, Choice{11, "FMAX", ""}};
inline constexpr Entry kCdaProg{.number = 4,
                                .name = "PROG",
                                .type = Type::usign8,
                                .min = 0,
                                .max = 1,
                                .role = Role::load_defaults,
                                .choices = kChoicesProg,
                                .choices_only = true};
inline constexpr Entry kCdaSload{.number = 80,
                                 .name = "SLOAD",
                                 .type = Type::int16,
                                 .min = -2,
                                 .max = 999,
                                 .role = Role::download};
inline constexpr Entry kCdaName{.number = 90,
                                .name = "NAME",
                                .text = "device name",
                                .type = Type::string,
                                .min = 0,
                                .max = 99,
                                .default_text = "CDA3000",
                                .storage = Storage::flash};
inline constexpr Entry kCdaErr1{.number = 95,
                                .name = "ERR1",
                                .type = Type::error32,
                                .min = 0,
                                .max = 0xFFFFFFFFLL,
                                .storage = Storage::ram_actual};
inline constexpr Entry kCdaSave{.number = 150,
                                .name = "SAVE",
                                .type = Type::usign8,
                                .min = 0,
                                .max = 1,
                                .role = Role::save,
                                .choices = kChoicesSave,
                                .choices_only = true};
inline constexpr Entry kCdaClsel{.number = 260,
                                 .name = "CLSEL",
                                 .type = Type::usign8,
                                 .min = 0,
                                 .max = 6,
                                 .storage = Storage::flash,
                                 .in_data_set = true,
                                 .choices = kChoicesClsel,
                                 .choices_only = true};
inline constexpr Entry kCdaRssl1{.number = 280,
                                 .name = "RSSL1",
                                 .type = Type::usign8,
                                 .min = 0,
                                 .max = 11,
                                 .default_value = 11,
                                 .storage = Storage::flash,
                                 .in_data_set = true,
                                 .choices = kChoicesRssl1,
                                 .choices_only = true};
inline constexpr Entry kCdaReff{.number = 406,
                                .name = "REFF",
                                .type = Type::int32q16,
                                .min = -2147483648LL,
                                .max = 2147483647LL,
                                .unit = "Hz",
                                .storage = Storage::ram_actual};
inline constexpr Entry kCdaClbdr{.number = 489,
                                 .name = "CLBDR",
                                 .type = Type::usign16,
                                 .min = 25,
                                 .max = 500,
                                 .default_value = 500,
                                 .unit = "kBaud",
                                 .storage = Storage::flash,
                                 .effect = Effect::at_restart,
                                 .in_data_set = true};
inline constexpr Entry kCdaCawdg{.number = 574,
                                 .name = "CAWDG",
                                 .type = Type::usign8,
                                 .min = 0,
                                 .max = 255,
                                 .unit = "ms",
                                 .storage = Storage::flash,
                                 .in_data_set = true};
inline constexpr Entry kCdaCascy{.number = 575,
                                 .name = "CASCY",
                                 .type = Type::usign16,
                                 .min = 1,
                                 .max = 32000,
                                 .default_value = 80,
                                 .unit = "ms",
                                 .storage = Storage::flash,
                                 .in_data_set = true};
inline constexpr Entry kCdaOptn2{.number = 578,
                                 .name = "OPTN2",
                                 .type = Type::string,
                                 .min = 0,
                                 .max = 99,
                                 .default_text = "LCAN",
                                 .storage = Storage::ram_actual};
inline constexpr std::array kCdaEntries{kCdaProg,  kCdaSload, kCdaName,  kCdaErr1,
                                        kCdaSave,  kCdaClsel, kCdaRssl1, kCdaReff,
                                        kCdaClbdr, kCdaCawdg, kCdaCascy, kCdaOptn2};
inline constexpr Dictionary kCda{kCdaEntries};

// The CDA3000's error names (CANLust manual table 5.9), as a wing gives them to the text functions.
constexpr std::string_view cda_error_name(std::uint8_t n) {
  return n == 16 ? "E-OP2"sv : ""sv;
}

}  // namespace ibs::od::test
