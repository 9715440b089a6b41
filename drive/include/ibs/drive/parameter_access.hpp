// What a parameter channel needs from the drive it serves (the VF1000 communication word today;
// any channel of the standard family): the table, the value a read returns, the 85-SIOF bits, the
// write rule and the write itself. A channel that serves a drive's parameters through this
// interface keeps only its own protocol state: the drive's one store, its SIOF latch and its
// rules stay with the drive, so that every channel of one drive serves the same values
// (../shared/design.md, "One drive, many faces"). Drive-neutral. Calls are on the cycle path:
// implementations allocate nothing and throw nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"
#include "ibs/drive/parameters.hpp"
#include "ibs/drive/siof.hpp"

namespace ibs::drive {

// What a value transfer that the drive took did.
struct WriteEffect {
  bool eeprom_changed = false;  // the EEPROM copy took a different value
  Duration storing{};           // how long the drive takes before it can acknowledge (EEPROM, PROG)
};

class ParameterAccess {
 public:
  virtual ~ParameterAccess() = default;

  [[nodiscard]] virtual const ParameterTable& table() const = 0;
  // The value a value inquiry returns now (a stored value, or an actual value the drive forms).
  [[nodiscard]] virtual Word read(std::size_t slot) const = 0;
  // 85-SIOF: any bit refuses every value transfer (LUSTBUS manual 6 and 9.2; INTERBUS manual 4.1.4).
  [[nodiscard]] virtual std::uint8_t siof() const = 0;
  virtual void raise_siof(std::uint8_t bits) = 0;
  // A read of 85-SIOF returned `bits`: they are erased, bits set since stay (LUSTBUS manual 9.2).
  virtual void clear_siof(std::uint8_t bits) = 0;
  // May `raw` be written now? drive::check_write plus any rule of the drive's own.
  [[nodiscard]] virtual WriteCheck check_write(const ParameterInfo* p, Word raw,
                                               bool power_stage_enabled) const {
    return drive::check_write(p, raw, power_stage_enabled);
  }
  // A value transfer that passed check_write takes effect at `now`.
  virtual WriteEffect write(std::size_t slot, Word raw, bool power_stage_enabled, Time now) = 0;
  // The device itself sets a value, bypassing the checks (actual values, settings).
  virtual void set(std::size_t slot, Word raw) = 0;
};

// The plain model: one store behind a table, 85-SIOF kept in the store's own cell, and
// optionally a PROG parameter whose value kLoadDefaults loads every factory default (LUSTBUS manual,
// 10, exception 1) except 85-SIOF. What a channel serves when it is given no drive of its own
// (the channel's tests and fuzz targets), and what a drive's core builds on.
class StoredParameters final : public ParameterAccess {
 public:
  // Allocates (the store); throws std::invalid_argument for a table without 85-SIOF or one that
  // drive::ParameterTable refuses.
  StoredParameters(std::span<const ParameterInfo> params,
                   std::optional<std::uint16_t> factory_defaults_parameter);

  [[nodiscard]] const ParameterTable& table() const override { return table_; }
  [[nodiscard]] Word read(std::size_t slot) const override { return store_.value(slot); }
  [[nodiscard]] std::uint8_t siof() const override {
    return static_cast<std::uint8_t>(store_.value(siof_slot_));
  }
  void raise_siof(std::uint8_t bits) override;
  void clear_siof(std::uint8_t bits) override;
  WriteEffect write(std::size_t slot, Word raw, bool power_stage_enabled, Time now) override;
  void set(std::size_t slot, Word raw) override { store_.set(slot, raw); }

  // A new start: EEPROM values back, RAM values to their defaults, only the power-on bit in
  // 85-SIOF (LUSTBUS manual 9.2; INTERBUS manual 6.1).
  void power_on();
  // Every value back to its factory default, 85-SIOF as it was.
  void factory_defaults();
  // Whether `slot` is the PROG parameter and `raw` its load-defaults command.
  [[nodiscard]] bool loads_defaults(std::size_t slot, Word raw) const {
    return static_cast<int>(slot) == prog_slot_ && raw == kLoadDefaults;
  }

  // By number: nullopt / false for a number the table lacks.
  [[nodiscard]] std::optional<Word> value(std::uint16_t number) const;
  bool set_value(std::uint16_t number, Word raw);

  [[nodiscard]] const ParameterStore& store() const { return store_; }
  [[nodiscard]] std::size_t siof_slot() const { return siof_slot_; }

 private:
  ParameterTable table_;
  ParameterStore store_;
  std::size_t siof_slot_ = 0;
  int prog_slot_ = -1;
};

}  // namespace ibs::drive
