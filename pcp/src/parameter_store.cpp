#include "ibs/pcp/parameter_store.hpp"

#include <stdexcept>
#include <string>

namespace ibs::pcp {

namespace {

Error refuse(ErrorCode code, const ParameterInfo& p, const std::string& why) {
  return {code,
          "parameter table: " + std::to_string(p.number) + "-" + std::string(p.name) + ": " + why};
}

bool fits(const ParameterInfo& p, std::int64_t v) {
  if (p.type == DataType::float_ieee) return v >= 0 && v <= 0xFFFFFFFFLL;
  return value_from_signed_raw(p.type, v).has_value();
}

std::uint32_t raw_of(const ParameterInfo& p, std::int64_t v) {
  if (p.type == DataType::float_ieee) return static_cast<std::uint32_t>(v);
  return value_from_signed_raw(p.type, v)->raw;
}

}  // namespace

Error ParameterStore::validate(std::span<const ParameterInfo> table) {
  if (table.size() > kMaxParameters) {
    return {ErrorCode::table_too_large, "parameter table has " + std::to_string(table.size()) +
                                            " rows; the store holds at most " +
                                            std::to_string(kMaxParameters)};
  }
  for (std::size_t i = 0; i < table.size(); ++i) {
    const ParameterInfo& p = table[i];
    if (p.number > kMaxParameterNumber)
      return refuse(ErrorCode::table_number_out_of_range, p, "number above 999");
    if (p.name.empty() || p.name.size() > 5) {
      return refuse(ErrorCode::table_bad_name, p, "name must have 1 to 5 characters");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (table[j].number == p.number)
        return refuse(ErrorCode::table_number_repeated, p, "number appears twice");
    }
    if (!fits(p, p.min) || !fits(p, p.max) || !fits(p, p.default_value)) {
      return refuse(ErrorCode::table_limits_outside_type, p,
                    "a limit or the default does not fit " + std::string(to_string(p.type)));
    }
    if (compare(p.type, raw_of(p, p.min), raw_of(p, p.max)) > 0) {
      return refuse(ErrorCode::table_min_above_max, p, "min above max");
    }
    const std::uint32_t d = raw_of(p, p.default_value);
    if (compare(p.type, d, raw_of(p, p.min)) < 0 || compare(p.type, d, raw_of(p, p.max)) > 0) {
      return refuse(ErrorCode::table_default_outside_limits, p, "default outside min..max");
    }
  }
  return {};
}

ParameterStore::ParameterStore(std::span<const ParameterInfo> table) : table_(table) {
  detail::require<std::invalid_argument>(validate(table));
  slots_.fill(kNoSlot);
  for (std::size_t i = 0; i < table_.size(); ++i) slots_[table_[i].number] = static_cast<std::uint8_t>(i);
  factory_defaults();
}

std::uint32_t ParameterStore::to_raw(const ParameterInfo& p, std::int64_t number) {
  return fits(p, number) ? raw_of(p, number) : 0;
}

std::optional<std::size_t> ParameterStore::slot(std::uint16_t number) const {
  if (number > kMaxParameterNumber || slots_[number] == kNoSlot) return std::nullopt;
  return slots_[number];
}

const ParameterInfo* ParameterStore::info(std::uint16_t number) const {
  const auto s = slot(number);
  return s ? &table_[*s] : nullptr;
}

std::optional<Value> ParameterStore::get(std::uint16_t number) const {
  const auto s = slot(number);
  if (!s) return std::nullopt;
  return Value{table_[*s].type, ram_[*s]};
}

bool ParameterStore::set(std::uint16_t number, std::uint32_t raw) {
  const auto s = slot(number);
  if (!s) return false;
  const std::size_t bytes = size_of(table_[*s].type);
  ram_[*s] = bytes >= 4 ? raw : (raw & ((1U << (8U * bytes)) - 1U));
  return true;
}

std::optional<Value> ParameterStore::eeprom(std::uint16_t number) const {
  const auto s = slot(number);
  if (!s || table_[*s].category != Category::eeprom) return std::nullopt;
  return Value{table_[*s].type, eeprom_[*s]};
}

bool ParameterStore::commit_eeprom(std::uint16_t number, std::uint32_t raw) {
  const auto s = slot(number);
  if (!s || table_[*s].category != Category::eeprom) return false;
  eeprom_[*s] = raw;
  return true;
}

void ParameterStore::power_on() {
  for (std::size_t i = 0; i < table_.size(); ++i) {
    const ParameterInfo& p = table_[i];
    if (p.category == Category::eeprom) {
      ram_[i] = eeprom_[i];
    } else if (p.category != Category::ram_control || (p.attributes & kAttrNoInit) == 0) {
      ram_[i] = default_raw(p);
    }
  }
}

void ParameterStore::factory_defaults() {
  for (std::size_t i = 0; i < table_.size(); ++i) {
    ram_[i] = default_raw(table_[i]);
    eeprom_[i] = ram_[i];
  }
}

}  // namespace ibs::pcp
