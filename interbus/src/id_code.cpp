#include "ibs/interbus/id_code.hpp"

#include <string_view>

namespace ibs::interbus {

const char* to_string(BusKind b) {
  switch (b) {
    case BusKind::local:
      return "local bus";
    case BusKind::remote:
      return "remote bus";
  }
  return "?";
}

const char* to_string(Direction d) {
  switch (d) {
    case Direction::none:
      return "no direction";
    case Direction::out:
      return "out";
    case Direction::in:
      return "in";
    case Direction::in_out:
      return "in/out";
  }
  return "?";
}

namespace {
std::string hex(unsigned v, std::size_t min_digits, bool letter_guard = true) {
  constexpr std::string_view kDigits = "0123456789ABCDEF";
  std::string s;
  do {
    s.insert(s.begin(), kDigits[v & 0x0FU]);
    v >>= 4U;
  } while (v != 0);
  if (s.size() < min_digits) s.insert(0, min_digits - s.size(), '0');
  // Manual notation: a leading letter gets a 0 so the number reads as a number (0DBH).
  if (letter_guard && s.front() >= 'A' && s.front() <= 'F') s.insert(s.begin(), '0');
  s += 'H';
  return s;
}

std::string words(int n) {
  return std::to_string(n) + (n == 1 ? " word" : " words");
}
}  // namespace

std::string to_hex(IdCode id) {
  return hex(id.raw, 2);
}

std::string describe(IdCode id) {
  std::string s = to_hex(id) + ": " + to_string(id.bus()) + " device, class " +
                  hex(id.device_class(), 1, false) + ", type " + std::to_string(id.type_bits());
  const auto ring = id.ring_words();
  const auto pcp = id.pcp_words();
  if (id.has_pcp()) {
    s += ", PCP device";
  } else {
    s += std::string(", ") + to_string(id.direction());
  }
  if (!ring) {
    s += ", unknown length code " + hex(id.length_code(), 2);
  }
  if (id.has_pcp() && !pcp) {
    s += ", unassigned PCP width bits 10b";
  }
  if (ring && pcp) {
    if (*pcp > *ring) {
      s += ", PCP channel of " + words(*pcp) + " wider than the " + words(*ring) + " on the bus";
    } else {
      s += ", " + words(*ring - *pcp) + " process data";
      s += *pcp == 0 ? ", no PCP" : " + " + words(*pcp) + " PCP";
    }
  }
  if (id.error_bits() != 0) {
    s += ", error message bits " + std::to_string(id.error_bits());
  }
  return s;
}

}  // namespace ibs::interbus
