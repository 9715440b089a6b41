#include "ibs/pcp/parameters.hpp"

namespace ibs::pcp {

std::string_view to_string(Category c) {
  switch (c) {
    case Category::ram_actual:
      return "RAM actual value";
    case Category::ram_control:
      return "RAM control value";
    case Category::eeprom:
      return "EEPROM value";
  }
  return "?";
}

const ParameterInfo* find_parameter(std::span<const ParameterInfo> table, std::uint16_t number) {
  for (const ParameterInfo& p : table) {
    if (p.number == number) return &p;
  }
  return nullptr;
}

const ParameterInfo* find_by_index(std::span<const ParameterInfo> table, std::uint16_t index) {
  const auto number = number_of(index);
  return number ? find_parameter(table, *number) : nullptr;
}

}  // namespace ibs::pcp
