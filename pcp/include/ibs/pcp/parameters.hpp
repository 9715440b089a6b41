// A parameter as PCP addresses and serves it (INTERBUS manual 4.2): the object index of a parameter
// number (index = number + 5C00H), the parameter kinds and attributes of the LUSTBUS manual 11.2.1, and a
// table's row. Which parameters a drive has is its wing's (devices/mc6000/parameters.hpp); the
// server serves any table (server.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "ibs/pcp/data_types.hpp"

namespace ibs::pcp {

inline constexpr std::uint16_t kParameterIndexOffset = 0x5C00;  // INTERBUS manual 4.2
inline constexpr std::uint16_t kMaxParameterNumber = 999;       // LUSTBUS manual 2.4.2: 3 digits

constexpr std::uint16_t index_of(std::uint16_t number) {
  return static_cast<std::uint16_t>(number + kParameterIndexOffset);
}
constexpr std::optional<std::uint16_t> number_of(std::uint16_t index) {
  if (index < kParameterIndexOffset || index > kParameterIndexOffset + kMaxParameterNumber) {
    return std::nullopt;
  }
  return static_cast<std::uint16_t>(index - kParameterIndexOffset);
}

// A parameter addressed by its number or directly by its object index.
struct ParameterRef {
  std::uint16_t index = 0;
  static constexpr ParameterRef number(std::uint16_t n) { return {index_of(n)}; }
  static constexpr ParameterRef object(std::uint16_t i) { return {i}; }
  friend bool operator==(const ParameterRef&, const ParameterRef&) = default;
};

// LUSTBUS manual 11.2.1 ("The parameter kind"); the enumerator values are the ASCII codes given there.
enum class Category : std::uint8_t { ram_actual = '0', ram_control = '1', eeprom = '2' };
std::string_view to_string(Category c);

// Attribute bits of the LUSTBUS manual 11.2.1 ("The attribute").
inline constexpr std::uint16_t kAttrShowParaText = 0x0004;
inline constexpr std::uint16_t kAttrShowText = 0x0020;
inline constexpr std::uint16_t kAttrInitControl = 0x0040;
inline constexpr std::uint16_t kAttrNoInit = 0x0080;
inline constexpr std::uint16_t kAttrShowHex = 0x0100;
inline constexpr std::uint16_t kAttrPassword = 0x0200;

struct ParameterInfo {
  std::uint16_t number = 0;
  std::string_view name;  // at most 5 characters (LUSTBUS manual 11.2.1)
  DataType type = DataType::usign16;
  Category category = Category::ram_control;
  // Limits and default as signed_raw() numbers (FLOAT_IEEE: the float's bit pattern).
  std::int64_t min = 0;
  std::int64_t max = 0;
  std::int64_t default_value = 0;
  std::uint16_t attributes = 0;

  [[nodiscard]] constexpr std::uint16_t index() const { return index_of(number); }
  [[nodiscard]] constexpr bool writable() const { return category != Category::ram_actual; }
};

// Looks a parameter up by number or by index; nullptr when the table has none.
const ParameterInfo* find_parameter(std::span<const ParameterInfo> table, std::uint16_t number);
const ParameterInfo* find_by_index(std::span<const ParameterInfo> table, std::uint16_t index);

}  // namespace ibs::pcp
