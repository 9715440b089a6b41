// The MC6000 parameter data types (LUSTBUS manual 2.3.2) and their conversions: engineering value <->
// raw value <-> bytes on the PCP channel (big-endian, as every INTERBUS word).
// Everything here is allocation-free and usable on the cycle path.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace ibs::pcp {

// LUSTBUS manual 2.3.2, in the table's order. The numeric codes are this project's (the seeds give the
// MC6000's type codes nowhere); they are what Get-OV long reports (docs/pcp.md).
enum class DataType : std::uint8_t {
  usign8 = 1,
  usign16 = 2,
  fixpoint16 = 3,  // unsigned 16 bits, 0.05 per step
  integer16 = 4,
  int32q16 = 5,  // signed 32 bits, 1/65536 per step
  float_ieee = 6,
  mc_error = 7,  // error number, error location, error time (32 bits)
  password = 8,  // unsigned 16 bits
};

std::string_view to_string(DataType t);
std::optional<DataType> data_type_from_code(std::uint8_t code);

// Bytes of a value of this type on the channel.
constexpr std::size_t size_of(DataType t) {
  switch (t) {
    case DataType::usign8:
      return 1;
    case DataType::usign16:
    case DataType::fixpoint16:
    case DataType::integer16:
    case DataType::password:
      return 2;
    case DataType::int32q16:
    case DataType::float_ieee:
    case DataType::mc_error:
      return 4;
  }
  return 0;
}

constexpr bool is_signed(DataType t) {
  return t == DataType::integer16 || t == DataType::int32q16;
}

inline constexpr std::size_t kMaxValueSize = 4;

// A value as the servo stores it: the bit pattern, zero-extended to 32 bits.
struct Value {
  DataType type = DataType::usign16;
  std::uint32_t raw = 0;

  friend bool operator==(const Value&, const Value&) = default;
};

// The raw value read as a number of its type: sign-extended for INTEGER16 and INT32Q16.
std::int64_t signed_raw(Value v);
// Builds a value from a signed raw number; nullopt when it does not fit the type's bit width.
std::optional<Value> value_from_signed_raw(DataType t, std::int64_t raw);

// PT_MC_ERROR (LUSTBUS manual 2.3.2): the C union of the manual on a little-endian host puts the error
// number in bits 0..7, the location in bits 8..15 and the time in bits 16..31 (docs/pcp.md,
// errata).
struct McError {
  std::uint8_t number = 0;
  std::uint8_t location = 0;
  std::uint16_t time = 0;  // hours of the time-in-operation counter

  friend bool operator==(const McError&, const McError&) = default;
};
Value to_value(McError e);
McError to_mc_error(Value v);

enum class ConversionError : std::uint8_t { none, too_high, too_low, not_a_number, wrong_type };
std::string_view to_string(ConversionError e);

struct Converted {
  Value value{};
  ConversionError error = ConversionError::none;
  [[nodiscard]] bool ok() const { return error == ConversionError::none; }
};

// Engineering value -> raw, rounded to the nearest step. FIXPOINT16: 0.00 .. 3276.75 (0.05 per
// step); INT32Q16: -32768 .. 32767.99998 (full signed 32 bits); FLOAT_IEEE: any finite float;
// the integer types: their integer range. MC_ERROR has no engineering scale (use to_value).
Converted from_engineering(DataType t, double value);
// Raw -> engineering value (MC_ERROR: the raw number).
double to_engineering(Value v);

// Writes the value's size_of(type) bytes, high byte first; returns the bytes written (0 when
// `out` is too small).
std::size_t encode(Value v, std::span<std::uint8_t> out);
// Reads a value of type `t`; nullopt when `in` does not hold exactly size_of(t) bytes.
std::optional<Value> decode(DataType t, std::span<const std::uint8_t> in);

// Orders two raw values of one type as numbers (signed types signed, FLOAT_IEEE as floats):
// negative, zero or positive like strcmp; a NaN compares greater than everything.
int compare(DataType t, std::uint32_t a, std::uint32_t b);

}  // namespace ibs::pcp
