// 85-SIOF (VF1000) / 85-SERR (MC6000), the serial-interface error bits (LUSTBUS manual 9.2). The bit
// meanings are the drive-neutral ones every parameter channel shares (drive/siof.hpp: the same
// parameter); this header reuses them and adds the LUSTBUS rules the host acts on: the
// "what to do" column of 9.2. Keeping the bits (the latch) is the drive's business (Responder).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "ibs/base/time.hpp"
#include "ibs/drive/siof.hpp"

namespace ibs::lustbus {

using drive::kSiofBits;
using drive::siof_has;
using drive::siof_mask;
using drive::SiofBit;

// 9.2, "What to do".
enum class SiofRemedy : std::uint8_t {
  none,              // 01H power on: information only
  fix_host,          // 02H watchdog: the host is too slow or broken
  wait_and_repeat,   // 04H EEPROM busy: wait (> 60 ms) and repeat the telegram
  repeat,            // 08H checksum: repeat the telegram
  host_error,        // 20H no parameter: service error or error in the host's software
  check_writability, // 40H no change: not writable at all, or not in this operating state
  other_value,       // 80H invalid value: choose a different value
};
constexpr SiofRemedy remedy(SiofBit b) {
  switch (b) {
    case SiofBit::power_on:
      return SiofRemedy::none;
    case SiofBit::watchdog:
      return SiofRemedy::fix_host;
    case SiofBit::eeprom_busy:
      return SiofRemedy::wait_and_repeat;
    case SiofBit::checksum:
      return SiofRemedy::repeat;
    case SiofBit::no_parameter:
      return SiofRemedy::host_error;
    case SiofBit::no_change:
      return SiofRemedy::check_writability;
    case SiofBit::invalid_value:
      return SiofRemedy::other_value;
  }
  return SiofRemedy::none;
}
std::string_view to_string(SiofRemedy r);

// 9.2: "Wait (> 60 ms)" before repeating after EEPROM busy.
inline constexpr Duration kEepromBusyMinWait = 60ms;

// Whether a SELECT refused with this 85-SIOF (read after the NAK) may be sent again: only when
// every bit set is one the telegram itself is not to blame for: power on / watchdog (the latch
// refused it, 6: "as long as an error bit is set, no parameter can be changed"; the read cleared
// it), EEPROM busy (wait first), checksum (repeat). Never for 20H, 40H, 80H, nor for 00H (a NAK
// without a cause on record: the host cannot tell what happened).
constexpr bool select_may_be_repeated(std::uint8_t siof) {
  constexpr std::uint8_t kFinal = siof_mask(SiofBit::no_parameter) |
                                  siof_mask(SiofBit::no_change) |
                                  siof_mask(SiofBit::invalid_value);
  return siof != 0 && (siof & kFinal) == 0;
}
// Whether the repetition must wait for the EEPROM first.
constexpr bool select_needs_eeprom_wait(std::uint8_t siof) {
  return siof_has(siof, SiofBit::eeprom_busy);
}

// "80H: invalid value", as drive::describe_siof (configuration-time text, allocates).
std::string describe_siof(std::uint8_t siof);

}  // namespace ibs::lustbus
