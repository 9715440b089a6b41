// The VF1000's object dictionary (issue 38): every parameter the LUSTBUS and INTERBUS manuals name
// for the SMARTDRIVE VF1000, once, as od::Entry rows -- number, name, what it is, data type, range,
// factory default, unit, storage kind, role and the manual's section (INTERBUS manual 3.1.1, 4.1.1,
// 4.1.3; LUSTBUS manual 4, 5.2, 6, 7.1, 8.1.1, 9.2, 10, 11.1 for the family's numbers). The lowest
// library of the wing (ibs_vf1000_dictionary, header-only, embedded-safe): the parameter numbers
// the wing acts on, the dictionary every bus's codec encodes, and the factory defaults of an
// inverter without the INTERBUS software (decision VF-E20). Rows the manuals specify completely
// cite them; every other value is a modelling choice (`invented`, and docs/vf1000_channel.md,
// "Parameter model").
#pragma once

#include <array>
#include <cstdint>

#include "ibs/od/dictionary.hpp"
#include "ibs/od/siof.hpp"

namespace ibs::devices::vf1000 {

// Numbers of the parameters the manuals name.
namespace pnr {
inline constexpr std::uint16_t kMode = 1;     // 1-MODE
inline constexpr std::uint16_t kCsel = 2;     // 2-CSEL
inline constexpr std::uint16_t kCntl = 3;     // 3-CNTL
inline constexpr std::uint16_t kFssel = 4;    // 4-FSSEL
inline constexpr std::uint16_t kFssio = 5;    // 5-FSSIO
inline constexpr std::uint16_t kStat = 11;    // 11-STAT
inline constexpr std::uint16_t kFout = 12;    // 12: rotary-field frequency (LUSTBUS manual 6.1.1.1)
inline constexpr std::uint16_t kFmax1 = 22;   // FMAX1: 16H in the examples of 4.1.3.1.1 / 4.1.3.2.1
inline constexpr std::uint16_t kRstop = 36;   // 36-RSTOP
inline constexpr std::uint16_t kVb2 = 45;     // 45-VB2
inline constexpr std::uint16_t kSouta = 61;   // 61-SOUTA
inline constexpr std::uint16_t kProg = 71;    // 71-PROG
inline constexpr std::uint16_t kSioc = 81;    // 81-SIOC
inline constexpr std::uint16_t kSioa = 82;    // 82-SIOA
inline constexpr std::uint16_t kSiow = 83;    // 83-SIOW
inline constexpr std::uint16_t kSiot = 84;    // 84-SIOT
inline constexpr std::uint16_t kSiof = od::kSiofNumber;  // 85-SIOF
inline constexpr std::uint16_t kType = 91;    // 91-TYPE
inline constexpr std::uint16_t kIcntl = 901;  // 901-ICNTL
inline constexpr std::uint16_t kFdriv = 905;  // 905-FDRIV
inline constexpr std::uint16_t kIbWd = 906;   // 906-IB-WD
inline constexpr std::uint16_t kIbcod = 907;  // 907-IBCOD
inline constexpr std::uint16_t kIbsta = 911;  // 911-IBSTA
inline constexpr std::uint16_t kFist = 912;   // 912-FIST
}  // namespace pnr

// Frequencies in FIXPOINT16 are limited to 999.95 Hz, the KP100's display range for the type
// (LUSTBUS manual 2.3.1), where the manuals give no parameter-specific range.
inline constexpr std::int64_t kFixpointDisplayMax = 19999;

namespace dictionary_rows {
using od::Entry;
using od::Role;
using od::Storage;
using od::Type;

// clang-format off
inline constexpr std::array kEntries{
    Entry{.number = pnr::kMode, .name = "MODE", .text = "Mode select", .type = Type::usign8,
          .min = 0, .max = 4, .default_value = 4, .storage = Storage::eeprom, .invented = true,
          .source = "INTERBUS manual 3.1.1 (INTERBUS default 4); LUSTBUS manual 7.1 (0 = terminals or serial "
                    "interface); range chosen"},
    Entry{.number = pnr::kCsel, .name = "CSEL", .text = "Control location selector",
          .type = Type::usign8, .min = 0, .max = 5, .default_value = 5, .storage = Storage::eeprom,
          .invented = true,
          .source = "INTERBUS manual 3.1.1 (INTERBUS default 5); LUSTBUS manual 7.1 (3 = serial interface); "
                    "range chosen"},
    Entry{.number = pnr::kCntl, .name = "CNTL", .text = "Control word (serial interface)",
          .type = Type::binary8, .min = 0, .max = 0xFF, .default_value = 0,
          .storage = Storage::ram_control, .invented = true,
          .source = "LUSTBUS manual 7.1 (128 = start clockwise); type chosen"},
    Entry{.number = pnr::kFssel, .name = "FSSEL", .text = "Frequency reference selector",
          .type = Type::usign8, .min = 0, .max = 25, .default_value = 25,
          .storage = Storage::eeprom, .invented = true,
          .source = "INTERBUS manual 3.1.1 (INTERBUS default 25); LUSTBUS manual 7.1 (8 = reference from "
                    "5-FSSIO); range chosen"},
    Entry{.number = pnr::kFssio, .name = "FSSIO", .text = "Frequency reference (serial interface)",
          .type = Type::fixpoint16, .min = 0, .max = kFixpointDisplayMax, .default_value = 0,
          .unit = "Hz", .storage = Storage::eeprom_ram,
          .source = "LUSTBUS manual 6.2.2, 7.1 (50.00 Hz = 03E8H, 23.15 Hz = 463); 11.1 (an EEPROM/RAM "
                    "FSEL variable)"},
    Entry{.number = pnr::kStat, .name = "STAT", .text = "Inverter status / fault reset",
          .type = Type::binary8, .min = 0, .max = 0xFF, .default_value = 0,
          .storage = Storage::ram_control, .invented = true,
          .source = "LUSTBUS manual 8.1.1 (written with 000FH to reset a fault); type chosen; read as "
                    "01H ready, 02H running, 04H counter-clockwise, 80H error (LB-D19)"},
    Entry{.number = pnr::kFout, .name = "FOUT", .text = "Rotary-field frequency (name invented)",
          .type = Type::fixpoint16, .min = 0, .max = 0xFFFF, .default_value = 0, .unit = "Hz",
          .storage = Storage::ram_actual, .invented = true,
          .source = "LUSTBUS manual 6.1.1.1 (parameter 12, 03E8H = 50.00 Hz); the name is invented "
                    "(LB-D19)"},
    Entry{.number = pnr::kFmax1, .name = "FMAX1", .text = "Maximum frequency 1",
          .type = Type::fixpoint16, .min = 0, .max = kFixpointDisplayMax, .default_value = 1000,
          .unit = "Hz", .storage = Storage::eeprom, .invented = true,
          .source = "INTERBUS manual 4.1.3.1.1 (3E8H, 50.00 Hz), 4.1.3.2.1 (1F4H = 25 Hz); number: "
                    "erratum E1; range and default chosen"},
    Entry{.number = pnr::kRstop, .name = "RSTOP", .text = "Stop function / stop ramp",
          .type = Type::fixpoint16, .min = 0, .max = kFixpointDisplayMax, .default_value = 1000,
          .unit = "Hz/s", .storage = Storage::eeprom, .invented = true,
          .source = "INTERBUS manual 5.2.1 (0 disables the power stage, else a stop ramp); unit, type and "
                    "the factory value 50.00 Hz/s chosen"},
    Entry{.number = pnr::kVb2, .name = "VB2", .text = "Voltage boost 2", .type = Type::fixpoint16,
          .min = 0, .max = 0x01F4, .default_value = 0x00A0, .unit = "%",
          .storage = Storage::eeprom, .source = "INTERBUS manual 4.1.3.3.1, completely"},
    Entry{.number = pnr::kSouta, .name = "SOUTA", .text = "Function of output A",
          .type = Type::usign8, .min = 0, .max = 15, .default_value = 0,
          .storage = Storage::eeprom, .invented = true,
          .source = "LUSTBUS manual 4 (7 switches the RS-485 data direction); range chosen"},
    Entry{.number = pnr::kProg, .name = "PROG", .text = "Load factory settings",
          .type = Type::usign8, .min = 0, .max = 1, .default_value = 0,
          .storage = Storage::eeprom, .role = Role::load_defaults,
          .source = "LUSTBUS manual 10, exception 1 (1 loads the factory settings)"},
    Entry{.number = pnr::kSioc, .name = "SIOC", .text = "Baud rate (2400, 4800, 9600 Bd)",
          .type = Type::usign16, .min = 2400, .max = 9600, .default_value = 9600, .unit = "Bd",
          .storage = Storage::eeprom,
          .source = "LUSTBUS manual 4 (2400 to 9600 Bd in steps, factory 9600), 1 (numerically "
                    "compatible with the servo's 81-SBAUD): the rate in baud (LB-E18)"},
    Entry{.number = pnr::kSioa, .name = "SIOA", .text = "Serial address", .type = Type::usign8,
          .min = 1, .max = 30, .default_value = 1, .storage = Storage::eeprom,
          .source = "LUSTBUS manual 4.2 (addresses 1 to 30, 0 not to be used)"},
    Entry{.number = pnr::kSiow, .name = "SIOW", .text = "Dummy / watchdog trigger",
          .type = Type::usign16, .min = 0, .max = 0xFFFF, .default_value = 0,
          .storage = Storage::ram_control, .source = "LUSTBUS manual 5.2 (RAM dummy)"},
    Entry{.number = pnr::kSiot, .name = "SIOT", .text = "Serial watchdog time (0: off)",
          .type = Type::usign16, .min = 0, .max = 0xFFFF, .default_value = 0, .unit = "ms",
          .storage = Storage::eeprom, .invented = true,
          .source = "LUSTBUS manual 5.2 (0 = off); unit and type chosen"},
    Entry{.number = pnr::kSiof, .name = "SIOF", .text = "Serial interface error flags",
          .type = Type::binary8, .min = 0, .max = 0xFF, .default_value = 0,
          .storage = Storage::ram_actual, .role = Role::error_flags,
          .source = "LUSTBUS manual 9.2 (the error bits; read-only, cleared by reading); INTERBUS manual 4.1.4"},
    Entry{.number = pnr::kType, .name = "TYPE", .text = "Device type", .type = Type::usign16,
          .min = 0, .max = 0xFFFF, .default_value = 1000, .storage = Storage::ram_actual,
          .invented = true, .source = "LUSTBUS manual 5.2; the value 1000 chosen"},
    Entry{.number = pnr::kIcntl, .name = "ICNTL", .text = "DRIVECOM control word",
          .type = Type::usign16, .min = 0x0000, .max = 0xFFFF, .default_value = 0x0000,
          .storage = Storage::ram_control, .source = "INTERBUS manual 4.1.1, completely"},
    // "Integer 16" (4.1.1): the description scan's type '7' is a decision (docs/vf1000_channel.md).
    Entry{.number = pnr::kFdriv, .name = "FDRIV", .text = "Frequency reference", .type = Type::int16,
          .min = -32768, .max = 32767, .default_value = 0, .unit = "Hz", .scale = 0.05,
          .storage = Storage::ram_control, .invented = true,
          .source = "INTERBUS manual 4.1.1; the scale 0.05 Hz (5.2.3) chosen"},
    Entry{.number = pnr::kIbWd, .name = "IB-WD", .text = "PD monitoring time", .type = Type::usign16,
          .min = 8, .max = 0xFFFF, .default_value = 200, .unit = "ms", .storage = Storage::eeprom,
          .source = "INTERBUS manual 4.1.1, completely"},
    Entry{.number = pnr::kIbcod, .name = "IBCOD", .text = "PD monitoring selection code",
          .type = Type::usign16, .min = 0, .max = 3, .default_value = 0,
          .storage = Storage::eeprom, .source = "INTERBUS manual 4.1.1, completely"},
    Entry{.number = pnr::kIbsta, .name = "IBSTA", .text = "DRIVECOM status word",
          .type = Type::usign16, .min = 0x0000, .max = 0xFFFF, .default_value = 0,
          .storage = Storage::ram_actual, .source = "INTERBUS manual 4.1.1, completely"},
    Entry{.number = pnr::kFist, .name = "FIST", .text = "Actual speed", .type = Type::int16,
          .min = -32768, .max = 32767, .default_value = 0, .unit = "Hz", .scale = 0.05,
          .storage = Storage::ram_actual, .invented = true,
          .source = "INTERBUS manual 4.1.1; the scale 0.05 Hz chosen"},
};
// clang-format on
}  // namespace dictionary_rows

// The VF1000's parameters, sorted by number, with the INTERBUS factory defaults (INTERBUS manual 3.1.1):
// the standard family's conventions (the communication word, LUSTBUS standard).
inline constexpr const auto& kDictionaryEntries = dictionary_rows::kEntries;
inline constexpr od::Dictionary kDictionary{kDictionaryEntries, od::Profile::lust_standard};
static_assert(od::check(kDictionaryEntries).ok(), "the VF1000's dictionary");

// The factory defaults of an inverter without the INTERBUS software package (INTERBUS manual 3.1.1;
// LUSTBUS manual 4.1: a drive on LUSTBUS alone; decision VF-E20): the three parameters 3.1.1 says the
// package changes. No seed lists the standard values: 1-MODE 0 is LUSTBUS manual 7.1's "Clamp or SIO",
// the mode of the terminals the INTERBUS values take away; 2-CSEL 0 and 4-FSSEL 0 are neither the
// serial interface's 3 nor FSSIO's 8, which 7.1 has the host set before it controls.
inline constexpr std::array<od::DefaultOverride, 3> kStandaloneDefaults{{
    {pnr::kMode, 0},
    {pnr::kCsel, 0},
    {pnr::kFssel, 0},
}};

}  // namespace ibs::devices::vf1000
