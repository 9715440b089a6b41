// The description record of a VF1000 description scan (INTERBUS manual 4.1.3.3): the 18 bytes the
// inverter sends for a parameter of its table, built from the table's row (drive/parameters.hpp)
// and taken apart again by the master.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "ibs/drive/parameters.hpp"
#include "ibs/base/words.hpp"
#include "ibs/vf1000_channel/comm_word.hpp"

namespace ibs::vf1000_channel {

// The 18 bytes of a description scan (4.1.3.3): name (5 ASCII, blank-padded), unit (5 ASCII,
// blanks when none), category (1 ASCII), type (1 ASCII), then min, max, default, each binary,
// high byte first.
using DescriptionRecord = std::array<std::uint8_t, kDescriptionLength>;
constexpr std::uint8_t description_byte(const drive::ParameterInfo& p, std::size_t index) {
  const auto text = [](std::string_view s, std::size_t i) -> std::uint8_t {
    return i < s.size() ? static_cast<std::uint8_t>(s[i]) : std::uint8_t{' '};
  };
  if (index < 5) return text(p.name, index);
  if (index < 10) return text(p.unit, index - 5);
  if (index == 10) return static_cast<std::uint8_t>(drive::category_code(p.category));
  if (index == 11) return static_cast<std::uint8_t>(drive::type_code(p.type));
  const Word w = index < 14 ? p.min : index < 16 ? p.max : p.default_value;
  return (index % 2 == 0) ? high_byte(w) : low_byte(w);
}
DescriptionRecord make_description(const drive::ParameterInfo& p);

// A description record taken apart; category/type are nullopt when the byte is no valid code.
struct Description {
  std::string name;  // trailing blanks removed
  std::string unit;
  std::optional<drive::Category> category;
  std::optional<drive::DataType> type;
  Word min = 0;
  Word max = 0;
  Word default_value = 0;
};
// Takes a record apart (allocates; not for the cycle path).
Description decode_description(const DescriptionRecord& record);

}  // namespace ibs::vf1000_channel
