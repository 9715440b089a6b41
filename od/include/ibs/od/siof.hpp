// 85-SIOF (VF1000) / 85-SERR (MC6000), the serial-interface error flags every LUST drive of the
// seed-000 family keeps and every one of its parameter channels reports: the VF1000 communication
// word, PCP and LUSTBUS (LUSTBUS manual 9.2 table; INTERBUS manual 4.1.4 and 6.1). Any bit set refuses every
// value transfer until 85-SIOF is read; reading it clears the bits it returned. The bits and the
// number are the same across the family. (drive/siof.hpp forwards here.)
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace ibs::od {

// The parameter's number, the same in every drive of the family (LUSTBUS manual 4 and 9.2).
inline constexpr std::uint16_t kSiofNumber = 85;

enum class SiofBit : std::uint8_t {
  power_on = 0,       // 01H: set on every power-on (LUSTBUS manual 9.2; INTERBUS manual 6.1)
  watchdog = 1,       // 02H: the device's LUSTBUS watchdog (84-SIOT) ran out
  eeprom_busy = 2,    // 04H: EEPROM burn-in in progress
  checksum = 3,       // 08H: error in the data transfer; on the comm word "unintended control bits"
  no_parameter = 5,   // 20H: no parameter with that number
  no_change = 6,      // 40H: change not permitted (read-only, or EEPROM with the power stage on)
  invalid_value = 7,  // 80H: value outside min/max
};

constexpr std::uint8_t siof_mask(SiofBit b) {
  return static_cast<std::uint8_t>(1U << static_cast<unsigned>(b));
}
constexpr bool siof_has(std::uint8_t siof, SiofBit b) {
  return (siof & siof_mask(b)) != 0;
}

inline constexpr SiofBit kSiofBits[] = {
    SiofBit::power_on,     SiofBit::watchdog,  SiofBit::eeprom_busy,  SiofBit::checksum,
    SiofBit::no_parameter, SiofBit::no_change, SiofBit::invalid_value};

// "power on", "invalid value", ...
std::string_view to_string(SiofBit b);
// "80H: invalid value", "21H: power on, no parameter", "00H: no error bit"; bit 4 and any other
// undefined bit are named "undefined bit N". (Allocates: reports.)
std::string describe_siof(std::uint8_t siof);

}  // namespace ibs::od
