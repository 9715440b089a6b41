#include "ibs/drive/parameter_access.hpp"

#include <algorithm>
#include <stdexcept>

namespace ibs::drive {

namespace {

std::span<const ParameterInfo> with_siof(std::span<const ParameterInfo> params) {
  const bool has_siof = std::any_of(params.begin(), params.end(),
                                    [](const ParameterInfo& p) { return p.number == kSiofNumber; });
  detail::require<std::invalid_argument>(
      has_siof ? Error{}
               : Error{ErrorCode::table_lacks_siof,
                       "drive::StoredParameters: the parameter table has no 85-SIOF, which every "
                       "value transfer depends on (INTERBUS manual 4.1.4)"});
  return params;
}

}  // namespace

StoredParameters::StoredParameters(std::span<const ParameterInfo> params,
                                   std::optional<std::uint16_t> factory_defaults_parameter)
    : table_(with_siof(params)),
      store_(params),
      siof_slot_(static_cast<std::size_t>(table_.slot(kSiofNumber))),
      prog_slot_(factory_defaults_parameter ? table_.slot(*factory_defaults_parameter) : -1) {}

void StoredParameters::raise_siof(std::uint8_t bits) {
  store_.set(siof_slot_, static_cast<Word>(siof() | bits));
}

void StoredParameters::clear_siof(std::uint8_t bits) {
  store_.set(siof_slot_, static_cast<Word>(siof() & ~bits & 0xFFU));
}

WriteEffect StoredParameters::write(std::size_t slot, Word raw, bool power_stage_enabled, Time now) {
  static_cast<void>(now);
  const Word eeprom_before = store_.eeprom_value(slot);
  store_.write(slot, raw, power_stage_enabled);
  WriteEffect e;
  e.eeprom_changed = store_.eeprom_value(slot) != eeprom_before;
  if (loads_defaults(slot, raw)) factory_defaults();
  return e;
}

void StoredParameters::power_on() {
  store_.power_on();
  store_.set(siof_slot_, siof_mask(SiofBit::power_on));
}

void StoredParameters::factory_defaults() {
  const std::uint8_t keep = siof();
  store_.factory_defaults();
  store_.set(siof_slot_, keep);
}

std::optional<Word> StoredParameters::value(std::uint16_t number) const {
  const int s = table_.slot(number);
  if (s < 0) return std::nullopt;
  return store_.value(static_cast<std::size_t>(s));
}

bool StoredParameters::set_value(std::uint16_t number, Word raw) {
  const int s = table_.slot(number);
  if (s < 0) return false;
  store_.set(static_cast<std::size_t>(s), raw);
  return true;
}

}  // namespace ibs::drive
