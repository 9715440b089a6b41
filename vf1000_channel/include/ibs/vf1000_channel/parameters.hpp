// The VF1000 parameter model: the parameter table (number, name, unit, category, type, min, max,
// default, scaling), an O(1) index by number, the value store with its RAM/EEPROM rules, the
// write checks that decide ACK or NAK, and the 18-byte description record (seed 001, 4.1.3.3).
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/interbus/words.hpp"
#include "ibs/vf1000_channel/comm_word.hpp"
#include "ibs/vf1000_channel/data_types.hpp"
#include "ibs/vf1000_channel/siof.hpp"

namespace ibs::vf1000_channel {

struct ParameterInfo {
  std::uint16_t number = 0;  // 0..3FFH
  std::string_view name;     // at most 5 characters (4.1.3.3)
  std::string_view unit;     // at most 5 characters, "" for none
  Category category = Category::ram_control;
  DataType type = DataType::usign16;
  Word min = 0;  // raw, compared as the type's numbers
  Word max = 0xFFFF;
  Word default_value = 0;    // the INTERBUS factory default (seed 001, 3.1.1)
  double scale = 1.0;        // engineering value = raw number x scale
  std::string_view meaning;  // what the parameter is, for reports
};

// Numbers of the parameters the manuals name.
namespace pnr {
inline constexpr std::uint16_t kMode = 1;     // 1-MODE
inline constexpr std::uint16_t kCsel = 2;     // 2-CSEL
inline constexpr std::uint16_t kCntl = 3;     // 3-CNTL
inline constexpr std::uint16_t kFssel = 4;    // 4-FSSEL
inline constexpr std::uint16_t kFssio = 5;    // 5-FSSIO
inline constexpr std::uint16_t kStat = 11;    // 11-STAT
inline constexpr std::uint16_t kFmax1 = 22;   // FMAX1: 16H in the examples of 4.1.3.1.1 / 4.1.3.2.1
inline constexpr std::uint16_t kRstop = 36;   // 36-RSTOP
inline constexpr std::uint16_t kVb2 = 45;     // 45-VB2
inline constexpr std::uint16_t kSouta = 61;   // 61-SOUTA
inline constexpr std::uint16_t kProg = 71;    // 71-PROG
inline constexpr std::uint16_t kSioc = 81;    // 81-SIOC
inline constexpr std::uint16_t kSioa = 82;    // 82-SIOA
inline constexpr std::uint16_t kSiow = 83;    // 83-SIOW
inline constexpr std::uint16_t kSiot = 84;    // 84-SIOT
inline constexpr std::uint16_t kSiof = 85;    // 85-SIOF
inline constexpr std::uint16_t kType = 91;    // 91-TYPE
inline constexpr std::uint16_t kIcntl = 901;  // 901-ICNTL
inline constexpr std::uint16_t kFdriv = 905;  // 905-FDRIV
inline constexpr std::uint16_t kIbWd = 906;   // 906-IB-WD
inline constexpr std::uint16_t kIbcod = 907;  // 907-IBCOD
inline constexpr std::uint16_t kIbsta = 911;  // 911-IBSTA
inline constexpr std::uint16_t kFist = 912;   // 912-FIST
}  // namespace pnr

// The VF1000 parameter table with the INTERBUS factory defaults (sorted by number; static data).
std::span<const ParameterInfo> vf1000_parameters();

// Writing 1 to 71-PROG loads the factory defaults into every parameter (seed 000, 10, exception 1).
inline constexpr Word kProgLoadDefaults = 1;

// 907-IBCOD: the reaction to the process-data watchdog (seed 001, 4.1.1).
enum class IbCod : std::uint8_t {
  no_action = 0,
  shutdown_e_ibs = 1,  // shutdown with error E-IBS (no. 12)
  block_power = 2,     // device control command "Block power"
  emergency_stop = 3,  // device control command "Emergency Stop"
};
inline constexpr std::uint8_t kErrorEIbs = 12;
// 906-IB-WD: the monitoring time the inverter actually uses. It counts in 50 ms steps, rounding
// up (IB-WD = 65 -> 100 ms); the maximum value 65535 switches the monitoring off (nullopt).
constexpr std::optional<std::chrono::milliseconds> ib_wd_monitoring_time(Word ib_wd) {
  if (ib_wd == 0xFFFF) return std::nullopt;
  const unsigned steps = (static_cast<unsigned>(ib_wd) + 49U) / 50U;
  return std::chrono::milliseconds(50U * steps);
}

// Engineering value of a parameter's raw word (raw number x scale); nullopt for vf_error.
std::optional<double> to_engineering(const ParameterInfo& p, Word raw);
// Raw word of an engineering value; nullopt when outside the type's range (min/max not applied).
std::optional<Word> from_engineering(const ParameterInfo& p, double value);
constexpr bool in_range(const ParameterInfo& p, Word raw) {
  return raw_in_range(p.type, raw, p.min, p.max);
}

// The answer a value transfer gets from the parameter model (4.1.4; seed 000, 9.2), in the order
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

// The 18 bytes of a description scan (4.1.3.3): name (5 ASCII, blank-padded), unit (5 ASCII,
// blanks when none), category (1 ASCII), type (1 ASCII), then min, max, default, each binary,
// high byte first.
using DescriptionRecord = std::array<std::uint8_t, kDescriptionLength>;
constexpr std::uint8_t description_byte(const ParameterInfo& p, std::size_t index) {
  const auto text = [](std::string_view s, std::size_t i) -> std::uint8_t {
    return i < s.size() ? static_cast<std::uint8_t>(s[i]) : std::uint8_t{' '};
  };
  if (index < 5) return text(p.name, index);
  if (index < 10) return text(p.unit, index - 5);
  if (index == 10) return static_cast<std::uint8_t>(category_code(p.category));
  if (index == 11) return static_cast<std::uint8_t>(type_code(p.type));
  const Word w = index < 14 ? p.min : index < 16 ? p.max : p.default_value;
  return (index % 2 == 0) ? high_byte(w) : low_byte(w);
}
DescriptionRecord make_description(const ParameterInfo& p);

// A description record taken apart; category/type are nullopt when the byte is no valid code.
struct Description {
  std::string name;  // trailing blanks removed
  std::string unit;
  std::optional<Category> category;
  std::optional<DataType> type;
  Word min = 0;
  Word max = 0;
  Word default_value = 0;
};
// Takes a record apart (allocates; not for the cycle path).
Description decode_description(const DescriptionRecord& record);

// Index of a parameter table by number: find() is one array lookup.
class ParameterTable {
 public:
  // Checks the table: numbers unique and <= 3FFH, names 1-5 and units 0-5 printable characters,
  // min <= default <= max within the type's range; throws std::invalid_argument naming the
  // parameter and what is wrong.
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
  void power_up();
  // 71-PROG = 1: every value, RAM and EEPROM, back to its default.
  void load_defaults();

 private:
  struct Cell {
    Word ram = 0;
    Word eeprom = 0;
  };
  std::span<const ParameterInfo> params_;
  std::vector<Cell> cells_;
};

}  // namespace ibs::vf1000_channel
