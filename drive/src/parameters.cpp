#include "ibs/drive/parameters.hpp"

#include <array>
#include <stdexcept>
#include <string>

namespace ibs::drive {

namespace {

bool printable(std::string_view s) {
  for (const char c : s) {
    if (c < 0x20 || c > 0x7E) return false;
  }
  return true;
}

std::string label(const ParameterInfo& p) {
  return "parameter " + std::to_string(p.number) + "-" + std::string(p.name);
}

}  // namespace

std::optional<double> to_engineering(const ParameterInfo& p, Word raw) {
  return to_engineering(p.type, raw, p.scale);
}

std::optional<Word> from_engineering(const ParameterInfo& p, double value) {
  return from_engineering(p.type, value, p.scale);
}

std::string_view to_string(WriteCheck c) {
  switch (c) {
    case WriteCheck::ok:
      return "ok";
    case WriteCheck::no_parameter:
      return "no parameter";
    case WriteCheck::no_change:
      return "no change permitted";
    case WriteCheck::invalid_value:
      return "invalid value";
  }
  return "?";
}

Error ParameterTable::validate(std::span<const ParameterInfo> params) {
  if (params.size() > static_cast<std::size_t>(kMaxParameterNumber) + 1) {
    return {ErrorCode::table_too_large, "parameter table: " + std::to_string(params.size()) +
                                            " entries, but numbers only run from 0 to 3FFH"};
  }
  std::array<bool, kMaxParameterNumber + 1> seen{};
  for (std::size_t i = 0; i < params.size(); ++i) {
    const ParameterInfo& p = params[i];
    const auto refuse = [&](ErrorCode code, const std::string& what) -> Error {
      return {code, "parameter table entry " + std::to_string(i) + " (" + label(p) + "): " + what};
    };
    if (p.number > kMaxParameterNumber) {
      return refuse(ErrorCode::table_number_out_of_range, "number above 3FFH (INTERBUS manual 4.1.3)");
    }
    if (seen[p.number]) return refuse(ErrorCode::table_number_repeated, "number used twice");
    seen[p.number] = true;
    if (p.name.empty() || p.name.size() > 5 || !printable(p.name)) {
      return refuse(ErrorCode::table_bad_name,
                    "name must be 1 to 5 printable characters (4.1.3.3)");
    }
    if (p.unit.size() > 5 || !printable(p.unit)) {
      return refuse(ErrorCode::table_bad_unit,
                    "unit must be at most 5 printable characters (4.1.3.3)");
    }
    const auto n = [&p](Word w) { return raw_as_number(p.type, w); };
    if (n(p.min) < n(type_min_raw(p.type)) || n(p.max) > n(type_max_raw(p.type))) {
      return refuse(ErrorCode::table_limits_outside_type,
                    "min/max outside the range of " + std::string(to_string(p.type)));
    }
    if (n(p.min) > n(p.max)) return refuse(ErrorCode::table_min_above_max, "min above max");
    if (!in_range(p, p.default_value)) {
      return refuse(ErrorCode::table_default_outside_limits, "default outside min/max");
    }
    if (!(p.scale > 0.0))
      return refuse(ErrorCode::table_scale_not_positive, "scale must be positive");
  }
  return {};
}

ParameterTable::ParameterTable(std::span<const ParameterInfo> params) : params_(params) {
  detail::require<std::invalid_argument>(validate(params));
  index_.fill(-1);
  for (std::size_t i = 0; i < params.size(); ++i)
    index_[params[i].number] = static_cast<std::int16_t>(i);
}

ParameterStore::ParameterStore(std::span<const ParameterInfo> params)
    : params_(params), cells_(params.size()) {
  factory_defaults();
}

void ParameterStore::write(std::size_t slot, Word raw, bool power_stage_enabled) {
  Cell& c = cells_[slot];
  c.ram = raw;
  switch (storage(params_[slot].category)) {
    case Storage::eeprom:
      c.eeprom = raw;
      break;
    case Storage::eeprom_ram:
      if (!power_stage_enabled) c.eeprom = raw;
      break;
    case Storage::ram_control:
    case Storage::ram_actual:
      break;
  }
}

void ParameterStore::set(std::size_t slot, Word raw) {
  Cell& c = cells_[slot];
  c.ram = raw;
  const Storage s = storage(params_[slot].category);
  if (s == Storage::eeprom || s == Storage::eeprom_ram) c.eeprom = raw;
}

void ParameterStore::power_on() {
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    const Storage s = storage(params_[i].category);
    cells_[i].ram = (s == Storage::eeprom || s == Storage::eeprom_ram) ? cells_[i].eeprom
                                                                       : params_[i].default_value;
  }
}

void ParameterStore::factory_defaults() {
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    cells_[i].ram = params_[i].default_value;
    cells_[i].eeprom = params_[i].default_value;
  }
}

}  // namespace ibs::drive
