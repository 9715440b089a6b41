// VALUE strings and the parameter data types of the LUSTBUS manual 2.3: VF1000 values are exactly four
// capital hex digits; MC6000 values are 1..100 characters, leading zeros optional. Every data type
// of 2.3.1 and 2.3.2, both ways. Allocation-free; refusals are return values.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "ibs/lustbus/chars.hpp"
#include "ibs/drive/data_types.hpp"

namespace ibs::lustbus {

// 2.3: "between 1 and 100 characters".
inline constexpr std::size_t kMaxValueLength = 100;

// A VALUE string in a fixed buffer: at most 100 characters, each is_value_char().
class Value {
 public:
  constexpr Value() = default;
  // nullopt when longer than 100 or holding a character a VALUE cannot carry.
  static constexpr std::optional<Value> from(std::string_view s) {
    Value v;
    for (const char c : s) {
      if (!v.push_back(static_cast<std::uint8_t>(c))) return std::nullopt;
    }
    return v;
  }
  // false when full or `c` is not a VALUE character.
  constexpr bool push_back(std::uint8_t c) {
    if (size_ >= kMaxValueLength || !is_value_char(c)) return false;
    chars_[size_++] = static_cast<char>(c);
    return true;
  }
  // A binary element of an 11.2 description (LB-D10): any 7-bit byte, frame characters included.
  // false when full or `c` >= 80H (a 7-bit line cannot carry it).
  constexpr bool push_binary(std::uint8_t c) {
    if (size_ >= kMaxValueLength || c >= 0x80U) return false;
    chars_[size_++] = static_cast<char>(c);
    return true;
  }
  constexpr void clear() { size_ = 0; }
  // The `n` (<= 100) last hexadecimal digits of `raw`, zeros in front, from `digits` (16
  // characters, each a VALUE character): for the formatting in value.cpp.
  constexpr void fill_hex(std::uint32_t raw, std::size_t n, const char* digits) {
    n = n < kMaxValueLength ? n : kMaxValueLength;
    size_ = static_cast<std::uint8_t>(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t shift = 4 * (n - 1 - i);
      chars_[i] = shift < 32 ? digits[(raw >> shift) & 0xFU] : '0';
    }
  }
  [[nodiscard]] constexpr std::size_t size() const { return size_; }
  [[nodiscard]] constexpr bool empty() const { return size_ == 0; }
  [[nodiscard]] constexpr std::string_view view() const { return {chars_.data(), size_}; }
  friend constexpr bool operator==(const Value& a, const Value& b) { return a.view() == b.view(); }

 private:
  std::array<char, kMaxValueLength> chars_{};
  std::uint8_t size_ = 0;
};

// The VALUE of a constant known to be valid (tests, tables); empty when it is not.
constexpr Value make_value(std::string_view s) { return Value::from(s).value_or(Value{}); }

// The two protocol families of the LUSTBUS manual (1): the standard protocol and the enhanced, downward-
// compatible one. Which drive speaks which is its wing's fact (the registry's LUSTBUS face):
// the inverter the standard, the servo the enhanced.
enum class Family : std::uint8_t { standard, enhanced };
std::string_view to_string(Family f);

// Why a VALUE or a number was refused.
enum class ValueError : std::uint8_t {
  none,
  empty,         // no character (2.3: at least 1)
  too_long,      // VF1000: not exactly 4; MC6000: more than 100 characters or 8 significant digits
  wrong_length,  // VF1000: not exactly four characters
  not_hex,       // a character other than 0-9 A-F
  lower_case,    // a-f: "valid only as capital letters" (2.3)
  out_of_range,  // does not fit the type's width or range
  not_finite,    // NaN or infinity for a numeric type
  wrong_type,    // the conversion does not apply to this type (e.g. engineering of an error struct)
};
std::string_view to_string(ValueError e);

template <typename T>
struct Result {
  T value{};
  ValueError error = ValueError::none;
  [[nodiscard]] constexpr bool ok() const { return error == ValueError::none; }
};

// ---- raw numbers <-> VALUE strings (2.3) -------------------------------------------------------
// VF1000: "%04X", only 0..FFFFH (2.3.1). MC6000: "%X", no leading zeros (2.3.2).
Result<Value> format_raw(Family f, std::uint32_t raw);
// The same written into `v` in place (the VALUE of an answer being built), which an error leaves
// as it was.
ValueError format_raw(Value& v, Family f, std::uint32_t raw);
// MC6000 with a minimum width (leading zeros are optional, 2.3; 11.2 sends 8 characters).
Result<Value> format_raw_width(std::uint32_t raw, std::size_t min_width);
// VF1000: exactly four capital hex digits. MC6000: 1..100 capital hex digits, leading zeros
// optional, at most 8 significant digits (32 bits).
Result<std::uint32_t> parse_raw(Family f, std::string_view value);

// ---- the data types of 2.3.1 and 2.3.2 ---------------------------------------------------------
enum class DataType : std::uint8_t {
  binary8,     // VF: bit field, 0..255
  usign8,      // both: 0..255
  usign16,     // both: 0..65535
  fixpoint16,  // both: unsigned 16 bits, 0.05 per step, 0.00..3276.75 (LB-E6)
  integer16,   // MC: signed 16 bits, sent as its 16-bit two's complement ("%X" of a 16-bit int)
  int32q16,    // MC: signed 32 bits, 1/65536 per step, sent as 32-bit two's complement
  float_ieee,  // MC: the 32-bit IEEE pattern
  vf_error,    // VF: high byte error number, low byte time of error (2.3.1)
  mc_error,    // MC: number bits 0-7, location 8-15, time 16-31 (as pcp, PCP-E6)
  password,    // both: unsigned 16 bits
};
std::string_view to_string(DataType t);  // "PT_FIXPOINT16", ...

// Which family's table (2.3.1 / 2.3.2) lists the type.
constexpr bool family_has(Family f, DataType t) {
  switch (t) {
    case DataType::usign8:
    case DataType::usign16:
    case DataType::fixpoint16:
    case DataType::password:
      return true;
    case DataType::binary8:
    case DataType::vf_error:
      return f == Family::standard;
    case DataType::integer16:
    case DataType::int32q16:
    case DataType::float_ieee:
    case DataType::mc_error:
      return f == Family::enhanced;
  }
  return false;
}
// Bits of the type's pattern: 8, 16 or 32.
constexpr unsigned width_bits(DataType t) {
  switch (t) {
    case DataType::binary8:
    case DataType::usign8:
      return 8;
    case DataType::int32q16:
    case DataType::float_ieee:
    case DataType::mc_error:
      return 32;
    default:
      return 16;
  }
}

// A VALUE as a type's bit pattern (zero-extended): refuses patterns wider than the type.
Result<std::uint32_t> parse_typed(Family f, DataType t, std::string_view value);
// A bit pattern as a VALUE: refuses patterns wider than the type, and 32-bit types on a VF1000.
Result<Value> format_typed(Family f, DataType t, std::uint32_t bits);

// Engineering value of a bit pattern: integers as numbers (INTEGER16 signed), FIXPOINT16 / 20,
// INT32Q16 signed / 65536, FLOAT_IEEE the float. wrong_type for the error structures.
Result<double> to_engineering(DataType t, std::uint32_t bits);
// Bit pattern of an engineering value, rounded to the nearest step (the manual's C truncates:
// 23.15 * 20 in float is 462.99.., LB-D8). Refuses values outside the type's range.
Result<std::uint32_t> from_engineering(DataType t, double value);

// VALUE <-> engineering in one step.
Result<double> decode(Family f, DataType t, std::string_view value);
Result<Value> encode(Family f, DataType t, double value);

// PT_VF_ERROR (2.3.1): the coding the INTERBUS channel shares (drive/data_types.hpp; INTERBUS manual,
// 4.1.3.3; VF-E6).
using VfError = drive::VfError;
// (Named apart from drive's, which argument-dependent lookup also finds.)
constexpr VfError vf_error_of(std::uint32_t bits) {
  return drive::decode_vf_error(static_cast<std::uint16_t>(bits));
}
constexpr std::optional<std::uint32_t> vf_error_bits(const VfError& e) {
  const auto w = drive::encode_vf_error(e);
  if (!w) return std::nullopt;
  return *w;
}

// PT_MC_ERROR (2.3.2): error number, error location, error time (hours of the time-in-operation
// counter); the manual's C union on a little-endian host, as docs/pcp.md decided (PCP-E6).
struct McError {
  std::uint8_t number = 0;
  std::uint8_t location = 0;
  std::uint16_t time = 0;
  friend constexpr bool operator==(const McError&, const McError&) = default;
};
constexpr McError decode_mc_error(std::uint32_t bits) {
  return {static_cast<std::uint8_t>(bits & 0xFFU), static_cast<std::uint8_t>((bits >> 8) & 0xFFU),
          static_cast<std::uint16_t>(bits >> 16)};
}
constexpr std::uint32_t encode_mc_error(const McError& e) {
  return static_cast<std::uint32_t>(e.number) | (static_cast<std::uint32_t>(e.location) << 8) |
         (static_cast<std::uint32_t>(e.time) << 16);
}

}  // namespace ibs::lustbus
