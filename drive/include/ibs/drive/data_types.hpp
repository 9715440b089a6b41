// The parameter data types and categories of the standard LUST drive family, the VF1000's (seed
// 000, 2.3.1 and 11.1; INTERBUS manual 4.1.3.3), and the conversions between raw words and engineering
// values. They belong to the drives' parameter tables, not to a bus: the VF1000 communication word
// and LUSTBUS carry the same types. Every parameter is one 16-bit word, high byte first;
// single-byte types have a zero high byte (4.1.3.1).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "ibs/base/words.hpp"

namespace ibs::drive {

enum class DataType : std::uint8_t {
  binary8,     // '1' PT_BINARY8: bit pattern, 1 byte
  fixpoint16,  // '2' PT_FIXPOINT16: unsigned, scaled 0.05
  usign16,     // '3' PT_USIGN16: 0-65535
  usign8,      // '4' PT_USIGN8: 0-255
  vf_error,    // '5' PT_VF_ERROR: error code and time (4.1.3.3 footnote)
  password,    // '6' PT_PASSWORD: 0-65535
  // Not in the VF1000 type list: 901-912 of the INTERBUS manual 4.1.1 are "Integer 16" (-32768..32767).
  // The description scan sends it as '7' (a project decision, docs/vf1000_channel.md).
  integer16,
};

// The ASCII type character of the description record (4.1.3.3).
constexpr char type_code(DataType t) {
  return static_cast<char>('1' + static_cast<int>(t));
}
constexpr std::optional<DataType> data_type_from_code(char c) {
  if (c < '1' || c > '7') return std::nullopt;
  return static_cast<DataType>(c - '1');
}
std::string_view to_string(DataType t);  // "PT_FIXPOINT16", ...

constexpr bool is_single_byte(DataType t) {
  return t == DataType::binary8 || t == DataType::usign8;
}
constexpr bool is_signed(DataType t) {
  return t == DataType::integer16;
}
// The raw range a type can hold at all (parameters narrow it with min/max).
constexpr Word type_max_raw(DataType t) {
  if (is_single_byte(t)) return 0x00FF;
  if (is_signed(t)) return 0x7FFF;
  return 0xFFFF;
}
constexpr Word type_min_raw(DataType t) {
  return is_signed(t) ? Word{0x8000} : Word{0};
}
// The engineering step of one raw unit: 0.05 for PT_FIXPOINT16 (LUSTBUS manual 2.3.1), else 1.
constexpr double natural_scale(DataType t) {
  return t == DataType::fixpoint16 ? 0.05 : 1.0;
}

// The raw word read as a number of the type: two's complement for integer16, unsigned otherwise.
constexpr std::int32_t raw_as_number(DataType t, Word raw) {
  return is_signed(t) ? static_cast<std::int32_t>(static_cast<std::int16_t>(raw))
                      : static_cast<std::int32_t>(raw);
}
// Whether `raw` lies in [min, max], compared as the type's numbers.
constexpr bool raw_in_range(DataType t, Word raw, Word min, Word max) {
  const std::int32_t v = raw_as_number(t, raw);
  return v >= raw_as_number(t, min) && v <= raw_as_number(t, max);
}

// Engineering value of a raw word: raw number x scale. nullopt for vf_error (use decode_vf_error).
std::optional<double> to_engineering(DataType t, Word raw, double scale);
inline std::optional<double> to_engineering(DataType t, Word raw) {
  return to_engineering(t, raw, natural_scale(t));
}
// Raw word of an engineering value, rounded to the nearest step; nullopt when it is not finite or
// falls outside the type's raw range (e.g. 3276.80 for PT_FIXPOINT16, whose largest value is
// 65535 x 0.05 = 3276.75), and for vf_error.
std::optional<Word> from_engineering(DataType t, double value, double scale);
inline std::optional<Word> from_engineering(DataType t, double value) {
  return from_engineering(t, value, natural_scale(t));
}

// PT_VF_ERROR (INTERBUS manual 4.1.3.3 footnote): high byte low nibble = error code 00H-0EH, 0FH = no
// error; low byte low nibble = time of the error since power-on in 6-minute (1/10 h) steps, 0FH
// = the basic state. High nibbles are 0 when written; LUSTBUS manual 2.3.1 notes that an erased
// EEPROM reads FFH, so decoding looks at the low nibbles only.
inline constexpr std::uint8_t kVfNoError = 0x0F;
struct VfError {
  std::optional<std::uint8_t> code;         // 0-14; nullopt: no error
  std::optional<std::uint8_t> time_tenths;  // 0-14 tenths of an hour; nullopt: basic state (0FH)

  [[nodiscard]] constexpr std::optional<std::uint32_t> time_minutes() const {
    if (!time_tenths) return std::nullopt;
    return static_cast<std::uint32_t>(*time_tenths) * 6U;
  }
  friend constexpr bool operator==(const VfError&, const VfError&) = default;
};
constexpr VfError decode_vf_error(Word raw) {
  const auto code = static_cast<std::uint8_t>(high_byte(raw) & 0x0FU);
  const auto time = static_cast<std::uint8_t>(low_byte(raw) & 0x0FU);
  VfError e;
  if (code != kVfNoError) e.code = code;
  if (time != kVfNoError) e.time_tenths = time;
  return e;
}
// nullopt when a field is out of its range (code or time above 14).
constexpr std::optional<Word> encode_vf_error(const VfError& e) {
  if ((e.code && *e.code >= kVfNoError) || (e.time_tenths && *e.time_tenths >= kVfNoError)) {
    return std::nullopt;
  }
  return make_word(e.code.value_or(kVfNoError), e.time_tenths.value_or(kVfNoError));
}
// The "no error" word 0F0FH.
inline constexpr Word kVfErrorNone = 0x0F0F;

// Parameter categories: the ASCII category character '0'-'7' of the description record
// (INTERBUS manual 4.1.3.3; LUSTBUS manual 11.1). The enumerator's value is the digit.
enum class Category : std::uint8_t {
  ram_control = 0,           // '0' RAM control variable (basic parameter)
  ram_actual = 1,            // '1' RAM actual value (basic)
  eeprom = 2,                // '2' EEPROM (basic)
  eeprom_ram = 3,            // '3' EEPROM/RAM variable (basic)
  ram_control_specific = 4,  // '4'..'7': the same, inverter-specific parameters
  ram_actual_specific = 5,
  eeprom_specific = 6,
  eeprom_ram_specific = 7,
};
enum class Storage : std::uint8_t { ram_control, ram_actual, eeprom, eeprom_ram };

constexpr char category_code(Category c) {
  return static_cast<char>('0' + static_cast<int>(c));
}
constexpr std::optional<Category> category_from_code(char c) {
  if (c < '0' || c > '7') return std::nullopt;
  return static_cast<Category>(c - '0');
}
constexpr Storage storage(Category c) {
  return static_cast<Storage>(static_cast<unsigned>(c) & 0x3U);
}
constexpr bool inverter_specific(Category c) {
  return static_cast<unsigned>(c) >= 4;
}
// RAM actual values are for display only (LUSTBUS manual 11.1 '1'); everything else can be written.
constexpr bool writable(Category c) {
  return storage(c) != Storage::ram_actual;
}
// EEPROM parameters only with the power stage disabled (4.1.3.2); EEPROM/RAM variables are always
// writable: into RAM while the power stage is enabled, into RAM and EEPROM while it is disabled
// (4.1.3.3, "The parameter category").
constexpr bool needs_power_stage_disabled(Category c) {
  return storage(c) == Storage::eeprom;
}
std::string_view to_string(Category c);  // "EEPROM", "RAM actual value (inverter-specific)", ...

}  // namespace ibs::drive
