#include "ibs/od/siof.hpp"

#include <cstdio>

namespace ibs::od {

std::string_view to_string(SiofBit b) {
  switch (b) {
    case SiofBit::power_on:
      return "power on";
    case SiofBit::watchdog:
      return "watchdog";
    case SiofBit::eeprom_busy:
      return "EEPROM busy";
    case SiofBit::checksum:
      return "checksum error (unintended control bits)";
    case SiofBit::no_parameter:
      return "no parameter";
    case SiofBit::no_change:
      return "no change permitted";
    case SiofBit::invalid_value:
      return "invalid value";
  }
  return "?";
}

std::string describe_siof(std::uint8_t siof) {
  char head[8];
  std::snprintf(head, sizeof head, "%02XH: ", static_cast<unsigned>(siof));
  std::string s = head;
  if (siof == 0) return s + "no error bit";
  bool first = true;
  for (unsigned bit = 0; bit < 8; ++bit) {
    if ((siof & (1U << bit)) == 0) continue;
    if (!first) s += ", ";
    first = false;
    bool named = false;
    for (const SiofBit b : kSiofBits) {
      if (static_cast<unsigned>(b) == bit) {
        s += to_string(b);
        named = true;
      }
    }
    if (!named) s += "undefined bit " + std::to_string(bit);
  }
  return s;
}

}  // namespace ibs::od
