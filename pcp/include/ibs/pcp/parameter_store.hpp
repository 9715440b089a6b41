// A drive's parameter memory behind the PCP server: a RAM value per parameter and an EEPROM
// copy per EEPROM parameter (LUSTBUS manual 11.2.1: "each have an EEPROM address and a RAM address").
// Fixed size; the table is checked once at construction (configuration time).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "ibs/base/error.hpp"
#include "ibs/pcp/data_types.hpp"
#include "ibs/pcp/parameters.hpp"

namespace ibs::pcp {

inline constexpr std::size_t kMaxParameters = 64;

class ParameterStore {
 public:
  // Refuses (ErrorCode::table_*, naming the parameter) a table of more than kMaxParameters rows,
  // a duplicate number, a number above 999, an empty or over-long name, limits that do not fit
  // the type, min > max, or a default outside min..max.
  [[nodiscard]] static Error validate(std::span<const ParameterInfo> table);
  // A store of a table validate() accepts: otherwise it throws std::invalid_argument with
  // validate()'s message, or, in the embedded build, aborts.
  explicit ParameterStore(std::span<const ParameterInfo> table);

  [[nodiscard]] std::span<const ParameterInfo> table() const { return table_; }
  [[nodiscard]] const ParameterInfo* info(std::uint16_t number) const;

  // The RAM value, the one every access sees.
  [[nodiscard]] std::optional<Value> get(std::uint16_t number) const;
  // Sets the RAM value without any check but existence: the device model's door for actual
  // values (408-IBSTA, 77-SPEED) and for reading back control values.
  bool set(std::uint16_t number, std::uint32_t raw);
  // The EEPROM copy of an EEPROM parameter (nullopt for RAM parameters).
  [[nodiscard]] std::optional<Value> eeprom(std::uint16_t number) const;
  bool commit_eeprom(std::uint16_t number, std::uint32_t raw);

  // Power-on: EEPROM values copied to RAM, RAM control values and actual values set to their
  // defaults (LUSTBUS manual 11.2.1) -- but for RAM control values with the attribute NoInit, which
  // "will not be pre-initialized, during start up, with the factory setting" (11.2.1).
  void power_on();
  // 4-PROG = 1: every value, RAM and EEPROM, back to its default (LUSTBUS manual 10).
  void factory_defaults();

  // A table number (min, max, default: signed_raw numbers or float bits) as the raw value.
  [[nodiscard]] static std::uint32_t to_raw(const ParameterInfo& p, std::int64_t number);
  [[nodiscard]] static std::uint32_t default_raw(const ParameterInfo& p) {
    return to_raw(p, p.default_value);
  }

 private:
  [[nodiscard]] std::optional<std::size_t> slot(std::uint16_t number) const;

  static constexpr std::uint8_t kNoSlot = 0xFF;
  static_assert(kMaxParameters < kNoSlot);

  std::span<const ParameterInfo> table_;
  // A parameter's slot by its number, filled at construction: the drive core and the servers
  // look values up on every sample, and a walk over the table there cost the MC6000's sample a
  // quarter more instructions than before the drive core (docs/performance.md).
  std::array<std::uint8_t, kMaxParameterNumber + 1> slots_{};
  std::array<std::uint32_t, kMaxParameters> ram_{};
  std::array<std::uint32_t, kMaxParameters> eeprom_{};
};

}  // namespace ibs::pcp
