// The parameter model of the standard LUST drive family (the VF1000's; LUSTBUS manual 2.3.1, 9.2,
// 11.1; INTERBUS manual 4.1.3): a parameter table's row (number, name, unit, category, type, min, max,
// default, scaling), an O(1) index by number, the value store with its RAM/EEPROM rules and the
// write checks that decide ACK or NAK. Drive-neutral: a drive's wing holds its table
// (devices/vf1000/parameters.hpp), and every channel that serves it -- the VF1000 communication
// word today, LUSTBUS tomorrow -- serves it through this table and store.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/drive/data_types.hpp"
#include "ibs/drive/siof.hpp"
#include "ibs/base/error.hpp"
#include "ibs/base/words.hpp"

namespace ibs::drive {

// Parameter numbers of a table run from 0 to 3FFH: the most the VF1000 communication word can
// address (10 bits, INTERBUS manual 4.1.2.1), beyond LUSTBUS's three digits (LUSTBUS manual 2.4.2).
inline constexpr std::uint16_t kMaxParameterNumber = 0x3FF;

struct ParameterInfo {
  std::uint16_t number = 0;  // 0..kMaxParameterNumber
  std::string_view name;     // at most 5 characters (4.1.3.3)
  std::string_view unit;     // at most 5 characters, "" for none
  Category category = Category::ram_control;
  DataType type = DataType::usign16;
  Word min = 0;  // raw, compared as the type's numbers
  Word max = 0xFFFF;
  Word default_value = 0;    // the INTERBUS factory default (INTERBUS manual 3.1.1)
  double scale = 1.0;        // engineering value = raw number x scale
  std::string_view meaning;  // what the parameter is, for reports
};

// The value of a drive's PROG command parameter that loads every parameter's factory default
// (LUSTBUS manual 10, exception 1; the VF1000's 71-PROG, the MC6000's 4-PROG).
inline constexpr Word kLoadDefaults = 1;
// 81-SIOC/SBAUD, the line's transmission rate (LUSTBUS manual 4): "The transfer rates can be set in
// steps ranging from 2400 Baud to 9600 Baud for frequency Inverters, and from 2400 Baud to 57600
// Baud for Servocontrollers. The configuration is set via parameter 81-SIOC/SBAUD"; 1: the
// parameters for network control, the transmission rate among them, are "numerically compatible"
// across the family. The value is the rate in baud on every drive (docs/errata.md LB-E18), and a
// drive takes the steps up to its own highest rate.
inline constexpr std::uint16_t kBaudRateNumber = 81;
inline constexpr std::uint32_t kFamilyBaudRates[] = {2400, 4800, 9600, 19200, 38400, 57600};
constexpr bool is_baud_step(std::uint32_t baud, std::uint32_t highest) {
  for (const std::uint32_t r : kFamilyBaudRates) {
    if (r == baud) return baud <= highest;
  }
  return false;
}
// The download handshake of a drive's SLOAD parameter (LUSTBUS manual 11.4; the MC6000's 80-SLOAD): the
// master writes -1 to begin a parameter download and -2 to end it.
inline constexpr std::int64_t kDownloadBegin = -1;
inline constexpr std::int64_t kDownloadEnd = -2;

// Engineering value of a parameter's raw word (raw number x scale); nullopt for vf_error.
std::optional<double> to_engineering(const ParameterInfo& p, Word raw);
// Raw word of an engineering value; nullopt when outside the type's range (min/max not applied).
std::optional<Word> from_engineering(const ParameterInfo& p, double value);
constexpr bool in_range(const ParameterInfo& p, Word raw) {
  return raw_in_range(p.type, raw, p.min, p.max);
}

// The answer a value transfer gets from the parameter model (4.1.4; LUSTBUS manual 9.2), in the order
// the inverter checks: the number, the permission, the value.
enum class WriteCheck : std::uint8_t { ok, no_parameter, no_change, invalid_value };
std::string_view to_string(WriteCheck c);
// The 85-SIOF bit a refused transfer sets (0 for ok).
constexpr std::uint8_t siof_bits_for(WriteCheck c) {
  switch (c) {
    case WriteCheck::ok:
      return 0;
    case WriteCheck::no_parameter:
      return siof_mask(SiofBit::no_parameter);
    case WriteCheck::no_change:
      return siof_mask(SiofBit::no_change);
    case WriteCheck::invalid_value:
      return siof_mask(SiofBit::invalid_value);
  }
  return 0;
}
// May this parameter be written at all now (number and permission; p == nullptr: no parameter)?
constexpr WriteCheck check_access(const ParameterInfo* p, bool power_stage_enabled) {
  if (p == nullptr) return WriteCheck::no_parameter;
  if (!writable(p->category)) return WriteCheck::no_change;
  if (power_stage_enabled && needs_power_stage_disabled(p->category)) return WriteCheck::no_change;
  return WriteCheck::ok;
}
constexpr WriteCheck check_write(const ParameterInfo* p, Word raw, bool power_stage_enabled) {
  const WriteCheck access = check_access(p, power_stage_enabled);
  if (access != WriteCheck::ok) return access;
  return in_range(*p, raw) ? WriteCheck::ok : WriteCheck::invalid_value;
}

// Index of a parameter table by number: find() is one array lookup.
class ParameterTable {
 public:
  // Checks the table: numbers unique and <= 3FFH, names 1-5 and units 0-5 printable characters,
  // min <= default <= max within the type's range, a positive scale. The refusal
  // (ErrorCode::table_*) names the entry, the parameter and what is wrong.
  [[nodiscard]] static Error validate(std::span<const ParameterInfo> params);
  // A table that validate() accepts. Otherwise it throws std::invalid_argument with validate()'s
  // message, or, in the embedded build, aborts (validate first).
  explicit ParameterTable(std::span<const ParameterInfo> params);

  [[nodiscard]] const ParameterInfo* find(std::uint16_t number) const {
    if (number > kMaxParameterNumber) return nullptr;
    const std::int16_t s = index_[number];
    return s < 0 ? nullptr : &params_[static_cast<std::size_t>(s)];
  }
  // Position of the parameter in params(), or -1.
  [[nodiscard]] int slot(std::uint16_t number) const {
    return number > kMaxParameterNumber ? -1 : index_[number];
  }
  [[nodiscard]] std::span<const ParameterInfo> params() const { return params_; }
  [[nodiscard]] std::size_t size() const { return params_.size(); }

 private:
  std::span<const ParameterInfo> params_;
  std::array<std::int16_t, kMaxParameterNumber + 1> index_{};
};

// The values behind a table: RAM and EEPROM copy per parameter. Construction allocates; the rest
// does not.
class ParameterStore {
 public:
  // All values at their defaults (a factory-fresh inverter).
  explicit ParameterStore(std::span<const ParameterInfo> params);

  [[nodiscard]] Word value(std::size_t slot) const { return cells_[slot].ram; }
  [[nodiscard]] Word eeprom_value(std::size_t slot) const { return cells_[slot].eeprom; }
  // A value transfer that passed check_write: RAM always; EEPROM for EEPROM parameters, and for
  // EEPROM/RAM variables while the power stage is disabled (4.1.3.3).
  void write(std::size_t slot, Word raw, bool power_stage_enabled);
  // The device itself sets a value (actual values, keypad): RAM and, where kept, EEPROM.
  void set(std::size_t slot, Word raw);
  // Power-on: EEPROM-kept values come back from EEPROM, RAM-only values to their defaults.
  void power_on();
  // 71-PROG = 1: every value, RAM and EEPROM, back to its default.
  void factory_defaults();

 private:
  struct Cell {
    Word ram = 0;
    Word eeprom = 0;
  };
  std::span<const ParameterInfo> params_;
  std::vector<Cell> cells_;
};

}  // namespace ibs::drive
