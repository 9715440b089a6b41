#include "ibs/drive/data_types.hpp"

#include <cmath>

namespace ibs::drive {

std::string_view to_string(DataType t) {
  switch (t) {
    case DataType::binary8:
      return "PT_BINARY8";
    case DataType::fixpoint16:
      return "PT_FIXPOINT16";
    case DataType::usign16:
      return "PT_USIGN16";
    case DataType::usign8:
      return "PT_USIGN8";
    case DataType::vf_error:
      return "PT_VF_ERROR";
    case DataType::password:
      return "PT_PASSWORD";
    case DataType::integer16:
      return "PT_INTEGER16";
  }
  return "?";
}

std::string_view to_string(Category c) {
  switch (c) {
    case Category::ram_control:
      return "RAM control variable";
    case Category::ram_actual:
      return "RAM actual value";
    case Category::eeprom:
      return "EEPROM";
    case Category::eeprom_ram:
      return "EEPROM/RAM variable";
    case Category::ram_control_specific:
      return "RAM control variable (inverter-specific)";
    case Category::ram_actual_specific:
      return "RAM actual value (inverter-specific)";
    case Category::eeprom_specific:
      return "EEPROM (inverter-specific)";
    case Category::eeprom_ram_specific:
      return "EEPROM/RAM variable (inverter-specific)";
  }
  return "?";
}

std::optional<double> to_engineering(DataType t, Word raw, double scale) {
  if (t == DataType::vf_error) return std::nullopt;
  return static_cast<double>(raw_as_number(t, raw)) * scale;
}

std::optional<Word> from_engineering(DataType t, double value, double scale) {
  if (t == DataType::vf_error || !std::isfinite(value) || !std::isfinite(scale) || scale == 0.0) {
    return std::nullopt;
  }
  const double steps = std::round(value / scale);
  const auto lo = static_cast<double>(raw_as_number(t, type_min_raw(t)));
  const auto hi = static_cast<double>(raw_as_number(t, type_max_raw(t)));
  if (steps < lo || steps > hi) return std::nullopt;
  const auto n = static_cast<std::int32_t>(steps);
  return static_cast<Word>(static_cast<std::uint32_t>(n) & 0xFFFFU);
}

}  // namespace ibs::drive
