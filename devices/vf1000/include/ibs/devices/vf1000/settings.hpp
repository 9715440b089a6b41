// The VF1000's own settings (devices/settings.hpp): whether a KEYPAD is plugged in (INTERBUS manual 7.1's
// KEYPAD rows; LUSTBUS manual 10's reaction times) and how long the self-test after RESET FAULT lasts
// (5.2.1, decision D13). The scenario reader and the docs' tables take them from kSettings (the
// INTERBUS face's), `ibs lustbus emulate` from kLustbusSettings (the LUSTBUS face's).
#pragma once

#include <array>
#include <chrono>
#include <span>

#include "ibs/devices/descriptor.hpp"

namespace ibs::devices::vf1000 {

inline constexpr SettingSpec kKeypadSetting{
    .name = "keypad",
    .kind = SettingKind::boolean,
    .min = 0,
    .max = 1,
    .fallback = 0,
    .unit = "",
    .parameter = "",
    .seed = "INTERBUS manual 7.1",
    .faces = SettingFace::interbus | SettingFace::lustbus,
    .meaning = "a KEYPAD plugged in: the communication word's transfer times of 7.1's KEYPAD rows; on "
               "LUSTBUS reaction times of 1...60 ms instead of 1...30 ms (LUSTBUS manual 10)",
    .range = "true or false",
    .elsewhere = "'keypad' is a VF1000 setting (INTERBUS manual 7.1); {the}'s PCP times have no KEYPAD row",
};
// Above 0 s and at most 60 s; 4 s by default (the self-test of 5.2.1's software reset).
inline constexpr SettingSpec kResetTimeSetting{
    .name = "reset_time",
    .kind = SettingKind::duration,
    .min = 1,
    .max = std::chrono::nanoseconds(std::chrono::seconds(60)).count(),
    .fallback = std::chrono::nanoseconds(std::chrono::seconds(4)).count(),
    .unit = "",
    .parameter = "",
    .seed = "INTERBUS manual 5.2.1",
    .faces = static_cast<std::uint8_t>(SettingFace::interbus),
    .meaning = "the self-test after RESET FAULT; the module error lasts as long",
    .range = "above 0 s and at most 60 s",
    .elsewhere = "'reset_time' is a VF1000 setting (5.2.1: its RESET FAULT is a software reset)",
};
inline constexpr std::array kSettings{kKeypadSetting, kResetTimeSetting};
// The LUSTBUS face's: the same KEYPAD (LUSTBUS manual 10: its reaction times).
inline constexpr std::array kLustbusSettings{kKeypadSetting};

}  // namespace ibs::devices::vf1000
