// The MC6000's own settings (devices/settings.hpp): 405-SUPI and 406-IBCNF, the two parameters
// the servo reads at power-on to lay out its INTERBUS words (INTERBUS manual 3.2.2, 3.2.3), and on its
// LUSTBUS face whether a KEYPAD is plugged in (LUSTBUS manual 10). The scenario reader, the trace
// header, `ibs layout` and the docs' tables take the INTERBUS face's from kSettings; `ibs lustbus
// emulate` takes the LUSTBUS face's from kLustbusSettings.
#pragma once

#include <array>
#include <span>

#include "ibs/devices/descriptor.hpp"

namespace ibs::devices::mc6000 {

// 405-SUPI: how the four bus words split into process data and PCP (3.2.2); 11 is the factory
// setting (2 process-data words, 2 PCP words).
inline constexpr SettingSpec kSupiSetting{
    .name = "supi",
    .kind = SettingKind::integer,
    .min = 0,
    .max = 12,
    .fallback = 11,
    .unit = "",
    .parameter = "405-SUPI",
    .seed = "INTERBUS manual 3.2.2",
    .faces = static_cast<std::uint8_t>(SettingFace::interbus),
    .meaning = "the split of the four bus words",
    .range = "0..12",
    .elsewhere = "'supi' is an MC6000 setting; {a} has no 405-SUPI",
    .places_device = true,
};
// 406-IBCNF: how reference and actual words read (3.2.3); 2 (Q16) is the factory setting.
// 4 (LISIM) is declared, as the manual lists it; the layout refuses it as not modelled.
inline constexpr SettingSpec kIbcnfSetting{
    .name = "ibcnf",
    .kind = SettingKind::integer,
    .min = 0,
    .max = 4,
    .fallback = 2,
    .unit = "",
    .parameter = "406-IBCNF",
    .seed = "INTERBUS manual 3.2.3",
    .faces = static_cast<std::uint8_t>(SettingFace::interbus),
    .meaning = "how reference and actual words read",
    .range = "0..4",
    .elsewhere = "'ibcnf' is an MC6000 setting; {a} has no 406-IBCNF",
    .places_device = true,
};
inline constexpr std::array kSettings{kSupiSetting, kIbcnfSetting};

// A KEYPAD plugged in: LUSTBUS manual 10's table gives the servo reaction times of 1...30 ms with it,
// 1...25 ms without. LUSTBUS only: INTERBUS manual gives the servo's PCP times no KEYPAD row, so the
// INTERBUS face does not declare it and a scenario or trace refuses it (in the VF1000's words).
inline constexpr SettingSpec kLustbusKeypadSetting{
    .name = "keypad",
    .kind = SettingKind::boolean,
    .min = 0,
    .max = 1,
    .fallback = 0,
    .unit = "",
    .parameter = "",
    .seed = "LUSTBUS manual 10",
    .faces = static_cast<std::uint8_t>(SettingFace::lustbus),
    .meaning = "a KEYPAD plugged in: LUSTBUS reaction times of 1...30 ms instead of 1...25 ms",
    .range = "true or false",
    .elsewhere = "'keypad' is an MC6000 setting on LUSTBUS only (LUSTBUS manual 10); {a} has no such setting",
};
inline constexpr std::array kLustbusSettings{kLustbusKeypadSetting};

// The wing's typed reads (configuration time).
inline int supi_of(const DeviceSettings& s) { return s.drive.integer(kSupiSetting); }
inline int ibcnf_of(const DeviceSettings& s) { return s.drive.integer(kIbcnfSetting); }
inline void set_layout(DeviceSettings& s, int supi, int ibcnf) {
  s.drive.set_integer(kSupiSetting.name, supi);
  s.drive.set_integer(kIbcnfSetting.name, ibcnf);
}

}  // namespace ibs::devices::mc6000
