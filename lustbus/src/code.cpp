#include "ibs/lustbus/code.hpp"

namespace ibs::lustbus {

namespace {
unsigned digit(const Code& c, std::size_t i) { return static_cast<unsigned>(c.digit(i) - '0'); }
}  // namespace

// 2.4.1: specifier 0/1, data set 0, device 1 (or 0 for basis parameters, 11.1), two digits.
std::optional<VfCode> as_vf_code(Code c) {
  const unsigned s = digit(c, 0);
  if (s > 1 || digit(c, 1) != 0 || digit(c, 2) > 1) return std::nullopt;
  return VfCode{static_cast<VfSpecifier>(s), static_cast<std::uint8_t>(digit(c, 2)),
                static_cast<std::uint8_t>(digit(c, 3) * 10 + digit(c, 4))};
}

std::optional<Code> vf_code(unsigned parameter, VfSpecifier s, std::uint8_t device) {
  if (parameter > 99 || device > 1) return std::nullopt;
  return Code::from_number(static_cast<unsigned>(s) * 10000U + device * 100U + parameter);
}

// 2.4.2 with 5.2 (000xx), 11.3 (61xxx) and 11.6 (49999).
std::optional<McCode> as_mc_code(Code c) {
  const unsigned n = c.number();
  if (n == kPosmodCode.number()) return McCode{McCodeKind::posmod, 0};
  const auto p = static_cast<std::uint16_t>(n % 1000);
  switch (n / 1000) {
    case 0:
      if (is_shared_parameter(p)) return McCode{McCodeKind::shared, p};
      return std::nullopt;
    case 20:
      return McCode{McCodeKind::value, p};
    case 30:
      return McCode{McCodeKind::description, p};
    case 60:
      return McCode{McCodeKind::special, p};
    case 61:
      return McCode{McCodeKind::substitution_text, p};
    default:
      return std::nullopt;
  }
}

std::optional<Code> mc_code(McCodeKind k, unsigned parameter) {
  if (parameter > 999) return std::nullopt;
  switch (k) {
    case McCodeKind::value:
      return Code::from_number(20000 + parameter);
    case McCodeKind::description:
      return Code::from_number(30000 + parameter);
    case McCodeKind::special:
      return Code::from_number(60000 + parameter);
    case McCodeKind::substitution_text:
      return Code::from_number(61000 + parameter);
    case McCodeKind::shared:
      if (!is_shared_parameter(parameter)) return std::nullopt;
      return Code::from_number(parameter);
    case McCodeKind::posmod:
      return kPosmodCode;
  }
  return std::nullopt;
}

}  // namespace ibs::lustbus
