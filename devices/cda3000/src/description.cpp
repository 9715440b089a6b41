#include "ibs/devices/cda3000/description.hpp"

#include <algorithm>

namespace ibs::devices::cda3000 {

std::uint32_t pack4(std::string_view s) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < std::min<std::size_t>(4, s.size()); ++i) {
    v |= static_cast<std::uint32_t>(static_cast<unsigned char>(s[i])) << (8U * i);
  }
  return v;
}

std::string unpack4(std::uint32_t item) {
  std::string s;
  for (unsigned i = 0; i < 4; ++i) {
    const auto c = static_cast<char>((item >> (8U * i)) & 0xFFU);
    if (c == '\0') break;
    s += c;
  }
  return s;
}

std::optional<Description> read_description(std::span<const std::uint32_t> items) {
  if (items.size() < kDescriptionItems || items[0] > static_cast<std::uint32_t>(canlust::DataType::string)) {
    return std::nullopt;
  }
  Description d;
  d.type = static_cast<canlust::DataType>(items[0]);
  d.min = items[1];
  d.max = items[2];
  d.factory = items[3];
  d.attributes = items[4];
  d.short_name = unpack4(items[5]) + unpack4(items[6]);
  d.unit = unpack4(items[7]);
  return d;
}

}  // namespace ibs::devices::cda3000
