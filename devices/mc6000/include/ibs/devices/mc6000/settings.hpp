// The MC6000's own settings (devices/settings.hpp): 405-SUPI and 406-IBCNF, the two parameters
// the servo reads at power-on to lay out its INTERBUS words (seed 001 3.2.2, 3.2.3). The scenario
// reader, the trace header, `ibs layout` and the docs' tables take them from this list.
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
    .seed = "seed 001 3.2.2",
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
    .seed = "seed 001 3.2.3",
    .faces = static_cast<std::uint8_t>(SettingFace::interbus),
    .meaning = "how reference and actual words read",
    .range = "0..4",
    .elsewhere = "'ibcnf' is an MC6000 setting; {a} has no 406-IBCNF",
    .places_device = true,
};
inline constexpr std::array kSettings{kSupiSetting, kIbcnfSetting};

// The wing's typed reads (configuration time).
inline int supi_of(const DeviceSettings& s) { return s.drive.integer(kSupiSetting); }
inline int ibcnf_of(const DeviceSettings& s) { return s.drive.integer(kIbcnfSetting); }
inline void set_layout(DeviceSettings& s, int supi, int ibcnf) {
  s.drive.set_integer(kSupiSetting.name, supi);
  s.drive.set_integer(kIbcnfSetting.name, ibcnf);
}

}  // namespace ibs::devices::mc6000
