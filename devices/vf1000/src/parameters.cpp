#include "ibs/devices/vf1000/parameters.hpp"

#include <array>

namespace ibs::devices::vf1000 {

namespace {

using drive::ParameterInfo;
using C = drive::Category;
using T = drive::DataType;

// Frequencies in PT_FIXPOINT16 are limited to 999.95 Hz (kFixpointDisplayMax, dictionary.hpp).

// The table. Rows the manuals specify completely cite them; every other value is a modelling
// choice listed in docs/vf1000_channel.md ("Parameter table").
constexpr std::array kVf1000Parameters = {
    // 3.1.1: INTERBUS default 4; LUSTBUS manual 7.1: 0 = terminals or serial interface.
    ParameterInfo{pnr::kMode, "MODE", "", C::eeprom, T::usign8, 0, 4, 4, 1.0, "Mode select"},
    // 3.1.1: INTERBUS default 5; LUSTBUS manual 7.1: 3 = serial interface.
    ParameterInfo{pnr::kCsel, "CSEL", "", C::eeprom, T::usign8, 0, 5, 5, 1.0,
                  "Control location selector"},
    // LUSTBUS manual 7.1: 128 = start clockwise; a bit pattern of one byte.
    ParameterInfo{pnr::kCntl, "CNTL", "", C::ram_control, T::binary8, 0, 0xFF, 0, 1.0,
                  "Control word (serial interface)"},
    // 3.1.1: INTERBUS default 25; LUSTBUS manual 7.1: 8 = reference from 5-FSSIO.
    ParameterInfo{pnr::kFssel, "FSSEL", "", C::eeprom, T::usign8, 0, 25, 25, 1.0,
                  "Frequency reference selector"},
    // LUSTBUS manual 6.2.2 / 7.1: 50.00 Hz = 03E8H, 23.15 Hz = 463; an EEPROM/RAM (FSEL) variable.
    ParameterInfo{pnr::kFssio, "FSSIO", "Hz", C::eeprom_ram, T::fixpoint16, 0, kFixpointDisplayMax,
                  0, 0.05, "Frequency reference (serial interface)"},
    // LUSTBUS manual 8.1.1: written with 000FH to reset a fault, so it is a control variable.
    ParameterInfo{pnr::kStat, "STAT", "", C::ram_control, T::binary8, 0, 0xFF, 0, 1.0,
                  "Inverter status / fault reset"},
    // LUSTBUS manual 6.1.1.1: "the rotary-field frequency (parameter 12)", 03E8H = 50.00 Hz, so
    // PT_FIXPOINT16; the seed gives no name: "FOUT" is invented (docs/lustbus.md, LB-D19).
    ParameterInfo{pnr::kFout, "FOUT", "Hz", C::ram_actual, T::fixpoint16, 0, 0xFFFF, 0, 0.05,
                  "Rotary-field frequency (name invented)"},
    // 4.1.3.1.1: actual value 3E8H (50.00 Hz); 4.1.3.2.1: 1F4H = 25 Hz, so PT_FIXPOINT16.
    ParameterInfo{pnr::kFmax1, "FMAX1", "Hz", C::eeprom, T::fixpoint16, 0, kFixpointDisplayMax,
                  1000, 0.05, "Maximum frequency 1"},
    // 5.2.1: 36-RSTOP <> 0 programs a stop ramp, 0 disables the power stage. No manual gives the
    // factory value; 50.00 Hz/s (a modelling choice) lets EMERGENCY STOP brake as 5.2.1 describes.
    ParameterInfo{pnr::kRstop, "RSTOP", "Hz/s", C::eeprom, T::fixpoint16, 0, kFixpointDisplayMax, 1000,
                  0.05, "Stop function / stop ramp"},
    // 4.1.3.3.1, completely: "VB2", "%", EEPROM, decimal, 0, 1F4H, A0H.
    ParameterInfo{pnr::kVb2, "VB2", "%", C::eeprom, T::fixpoint16, 0, 0x01F4, 0x00A0, 0.05,
                  "Voltage boost 2"},
    // LUSTBUS manual 4: 7 switches the RS-485 data direction.
    ParameterInfo{pnr::kSouta, "SOUTA", "", C::eeprom, T::usign8, 0, 15, 0, 1.0,
                  "Function of output A"},
    // LUSTBUS manual 10, exception 1: 1 loads the factory settings.
    ParameterInfo{pnr::kProg, "PROG", "", C::eeprom, T::usign8, 0, 1, 0, 1.0,
                  "Load factory settings"},
    // LUSTBUS manual 4 and 5.2: 81..85 and 91 are numerically compatible across the drive family
    // (1): the rate in baud, as the servo's 81-SBAUD; the steps 2400, 4800, 9600 (4; LB-E18).
    ParameterInfo{pnr::kSioc, "SIOC", "Bd", C::eeprom, T::usign16, 2400, 9600, 9600, 1.0,
                  "Baud rate (2400, 4800, 9600 Bd)"},
    ParameterInfo{pnr::kSioa, "SIOA", "", C::eeprom, T::usign8, 1, 30, 1, 1.0, "Serial address"},
    ParameterInfo{pnr::kSiow, "SIOW", "", C::ram_control, T::usign16, 0, 0xFFFF, 0, 1.0,
                  "Dummy / watchdog trigger"},
    ParameterInfo{pnr::kSiot, "SIOT", "ms", C::eeprom, T::usign16, 0, 0xFFFF, 0, 1.0,
                  "Serial watchdog time (0: off)"},
    // LUSTBUS manual 9.2: the error bits; read-only, cleared by reading.
    ParameterInfo{pnr::kSiof, "SIOF", "", C::ram_actual, T::binary8, 0, 0xFF, 0, 1.0,
                  "Serial interface error flags"},
    ParameterInfo{pnr::kType, "TYPE", "", C::ram_actual, T::usign16, 0, 0xFFFF, 1000, 1.0,
                  "Device type"},
    // 4.1.1, completely (Integer 16 of 905/912 see DataType::integer16).
    ParameterInfo{pnr::kIcntl, "ICNTL", "", C::ram_control, T::usign16, 0x0000, 0xFFFF, 0x0000, 1.0,
                  "DRIVECOM control word"},
    ParameterInfo{pnr::kFdriv, "FDRIV", "Hz", C::ram_control, T::integer16, 0x8000, 0x7FFF, 0, 0.05,
                  "Frequency reference"},
    ParameterInfo{pnr::kIbWd, "IB-WD", "ms", C::eeprom, T::usign16, 8, 0xFFFF, 200, 1.0,
                  "PD monitoring time"},
    ParameterInfo{pnr::kIbcod, "IBCOD", "", C::eeprom, T::usign16, 0, 3, 0, 1.0,
                  "PD monitoring selection code"},
    ParameterInfo{pnr::kIbsta, "IBSTA", "", C::ram_actual, T::usign16, 0x0000, 0xFFFF, 0, 1.0,
                  "DRIVECOM status word"},
    ParameterInfo{pnr::kFist, "FIST", "Hz", C::ram_actual, T::integer16, 0x8000, 0x7FFF, 0, 0.05,
                  "Actual speed"},
};

// The same table with the standard factory values of the three parameters INTERBUS manual 3.1.1 says the
// INTERBUS software package changes (1-MODE 4, 2-CSEL 5, 4-FSSEL 25). No seed lists the standard
// values (decision VF-E20): 1-MODE 0 is LUSTBUS manual 7.1's "Clamp or SIO", the mode of the terminals
// that 3.1.1 says the INTERBUS values take away; 2-CSEL 0 and 4-FSSEL 0 are neither the serial
// interface's 3 nor FSSIO's 8, which 7.1 has the host set before it controls.
constexpr auto kStandaloneParameters = [] {
  auto t = kVf1000Parameters;
  for (ParameterInfo& p : t) {
    if (p.number == pnr::kMode || p.number == pnr::kCsel || p.number == pnr::kFssel) p.default_value = 0;
  }
  return t;
}();

}  // namespace

std::span<const drive::ParameterInfo> parameters() { return kVf1000Parameters; }
std::span<const drive::ParameterInfo> standalone_parameters() { return kStandaloneParameters; }

}  // namespace ibs::devices::vf1000
