// Parameter data types in data bytes 3-6 of the parameter channel (CANLust manual 4.1.1, table 4.1
// and the examples of p. 32; public-facts "CANLust", "Data in bytes 3-6"): every type travels as
// 32 bits in Intel order. USIGN8/16 zero-filled, INT8/16 sign-filled, INT32Q16 as post-point
// low, post-point high, pre-point low, pre-point high (= the signed 32-bit raw value, Q16),
// FIXPOINT16 as the value x 20 (10.05 -> 201 = C9 00 00 00), ERR_STRUC as error number, error
// location, operating hours low, high. STRING goes by the string transfer (string.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace ibs::canlust {

enum class DataType : std::uint8_t {
  usign8,
  int8,
  usign16,
  int16,
  usign32,
  int32,
  int32q16,
  fixpoint16,
  err_struc,
  string,
};
std::string_view to_string(DataType t);

// True when `wire` is a well-formed 32-bit image of a value of type `t` (the fill bytes right).
bool wire_fits(DataType t, std::uint32_t wire);

// Signed integers as their 32-bit image (sign-filled); unsigned zero-filled.
constexpr std::uint32_t wire_from_signed(std::int32_t v) { return static_cast<std::uint32_t>(v); }
constexpr std::int32_t signed_from_wire(std::uint32_t w) { return static_cast<std::int32_t>(w); }

// INT32Q16 (p. 32: 10.5 -> 00 80 0A 00). Rounds to the nearest 1/65536; saturates.
std::int32_t q16_from_double(double v);
constexpr double double_from_q16(std::int32_t raw) { return static_cast<double>(raw) / 65536.0; }

// FIXPOINT16 (p. 32: 10.05 -> 201): 0.05 steps, 0..3276.75. nullopt outside.
std::optional<std::uint16_t> fixpoint16_from_double(double v);
constexpr double double_from_fixpoint16(std::uint16_t raw) { return static_cast<double>(raw) / 20.0; }

// ERR_STRUC (p. 32: E-OP2 at location 172 after 85 hours -> 10 AC 55 00).
struct ErrStruc {
  std::uint8_t number = 0;
  std::uint8_t location = 0;
  std::uint16_t hours = 0;
  friend constexpr bool operator==(const ErrStruc&, const ErrStruc&) = default;
};
constexpr std::uint32_t wire_from_err_struc(const ErrStruc& e) {
  return static_cast<std::uint32_t>(e.number) | (static_cast<std::uint32_t>(e.location) << 8U) |
         (static_cast<std::uint32_t>(e.hours) << 16U);
}
constexpr ErrStruc err_struc_from_wire(std::uint32_t w) {
  return {static_cast<std::uint8_t>(w & 0xFFU), static_cast<std::uint8_t>((w >> 8U) & 0xFFU),
          static_cast<std::uint16_t>(w >> 16U)};
}

// 4.1.1: "max 100 bytes in bus operation incl. zero terminator".
inline constexpr std::size_t kMaxStringBytes = 100;
inline constexpr std::size_t kMaxStringChars = kMaxStringBytes - 1;

}  // namespace ibs::canlust
