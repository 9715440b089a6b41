#include "ibs/tool/format.hpp"

#include <iterator>

namespace ibs::tool {

std::string hex(std::uint64_t v, int digits) { return fmt::format("{:0{}X}", v, digits); }

std::string hex_bytes(std::span<const std::uint8_t> bytes) {
  std::string s;
  s.reserve(bytes.size() * 3);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (i != 0) s += ' ';
    fmt::format_to(std::back_inserter(s), "{:02X}", bytes[i]);
  }
  return s;
}

std::string fixed(double v, int decimals) { return fmt::format("{:.{}f}", v, decimals); }

std::string fixed(double v, int decimals, std::string_view unit) {
  return fmt::format("{:.{}f} {}", v, decimals, unit);
}

std::string seconds(Time t) { return fixed(static_cast<double>(t.count()) / 1e9, 3, "s"); }

}  // namespace ibs::tool
