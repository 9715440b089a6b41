// The one data-type family of the LUST drives' parameters, whichever bus carries them: the
// standard family's types (LUSTBUS manual 2.3.1; INTERBUS manual 4.1.3.3), the enhanced family's (LUSTBUS manual,
// 2.3.2; PCP, INTERBUS manual 4.2), CANLust's (CANLust manual 4.1.1) and the DFS-1's plain 32-bit numbers
// (DFS-1 manual). Each bus has its own codes and byte order for them: those live in the bus's codec,
// not here. Allocation-free and constexpr: usable on the cycle path and in compile-time tables.
//
// A value's bits are a Raw: 32 bits, signed types sign-extended, unsigned ones zero-extended --
// CANLust's wire image as it is (CANLust manual 4.1.1: "INT8/16 sign-filled"); PCP, LUSTBUS and the
// communication word mask it to the type's width. number() reads only the type's width, so a
// zero-extended 16-bit pattern (0xFFFF of an INT16) reads as the same number (-1) as its canonical
// image (0xFFFFFFFF).
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

namespace ibs::od {

using Raw = std::uint32_t;

enum class Type : std::uint8_t {
  binary8,     // 8-bit pattern (PT_BINARY8, LUSTBUS manual 2.3.1)
  usign8,      // 0..255
  int8,        // -128..127 (CANLust)
  usign16,     // 0..65535
  int16,       // -32768..32767 (PCP INTEGER16; the VF1000's 901-912 "Integer 16", INTERBUS manual 4.1.1)
  usign32,     // 0..4294967295 (CANLust; the DFS-1's values)
  int32,       // signed 32 bits (CANLust)
  fixpoint16,  // unsigned, 0.05 a step: 0.00..3276.75 (LUSTBUS manual 2.3.1/2.3.2; CANLust manual p. 32)
  int32q16,    // signed 32 bits, 1/65536 a step (LUSTBUS manual 2.3.2, CANLust manual 4.1.1)
  float_ieee,  // the 32-bit IEEE 754 pattern (LUSTBUS manual 2.3.2)
  password,    // unsigned 16 bits (PT_PASSWORD)
  error16,     // PT_VF_ERROR: error code and time of error, one word (LUSTBUS manual 2.3.1; VfError)
  error32,     // PT_MC_ERROR = CANLust ERR_STRUC: number, location, time (one layout; ErrorRecord)
  string,      // text, by the buses' string transfers (CANLust manual 4.1.1); numbers are its length
};
inline constexpr std::size_t kTypeCount = 14;

struct TypeInfo {
  Type type;
  std::uint8_t bits;  // of the pattern: 8, 16 or 32 (string: 0)
  bool is_signed;     // two's complement
  double per_unit;    // numbers per engineering unit: fixpoint16 20 (0.05 a step), int32q16 65536
  bool numeric;       // has an engineering value (not the error structures, not text)
  std::string_view name;  // the manuals' name without the PT_ of the LUSTBUS manual: "FIXPOINT16"
};

inline constexpr std::array<TypeInfo, kTypeCount> kTypes{{
    {Type::binary8, 8, false, 1.0, true, "BINARY8"},
    {Type::usign8, 8, false, 1.0, true, "USIGN8"},
    {Type::int8, 8, true, 1.0, true, "INT8"},
    {Type::usign16, 16, false, 1.0, true, "USIGN16"},
    {Type::int16, 16, true, 1.0, true, "INT16"},
    {Type::usign32, 32, false, 1.0, true, "USIGN32"},
    {Type::int32, 32, true, 1.0, true, "INT32"},
    {Type::fixpoint16, 16, false, 20.0, true, "FIXPOINT16"},
    {Type::int32q16, 32, true, 65536.0, true, "INT32Q16"},
    {Type::float_ieee, 32, false, 1.0, true, "FLOAT_IEEE"},
    {Type::password, 16, false, 1.0, true, "PASSWORD"},
    {Type::error16, 16, false, 1.0, false, "VF_ERROR"},
    {Type::error32, 32, false, 1.0, false, "MC_ERROR"},
    {Type::string, 0, false, 1.0, false, "STRING"},
}};

constexpr const TypeInfo& info(Type t) {
  return kTypes[static_cast<std::size_t>(t)];
}
constexpr std::string_view to_string(Type t) {
  return info(t).name;
}
constexpr unsigned bits(Type t) {
  return info(t).bits;
}
constexpr bool is_signed(Type t) {
  return info(t).is_signed;
}
// Bytes of the value's pattern: 1, 2 or 4 (string: 0).
constexpr unsigned bytes(Type t) {
  return info(t).bits / 8U;
}
constexpr bool is_text(Type t) {
  return t == Type::string;
}

// Longest text a string entry can hold (its max); each bus's codec has its own limit below it
// (CANLust: 99 characters, CANLust manual 4.1.1).
inline constexpr std::int64_t kMaxTextLength = 255;

// The smallest and largest number of the type (float_ieee: its patterns 0..FFFFFFFFH; string:
// lengths).
constexpr std::int64_t min_number(Type t) {
  if (t == Type::string) return 0;
  const unsigned b = bits(t);
  return is_signed(t) ? -(std::int64_t{1} << (b - 1U)) : 0;
}
constexpr std::int64_t max_number(Type t) {
  if (t == Type::string) return kMaxTextLength;
  const unsigned b = bits(t);
  return is_signed(t) ? (std::int64_t{1} << (b - 1U)) - 1 : (std::int64_t{1} << b) - 1;
}
constexpr bool fits(Type t, std::int64_t n) {
  return n >= min_number(t) && n <= max_number(t);
}

// The raw bits read as a number of the type: the low bits(t) bits, sign-extended for the signed
// types (a string's Raw is its length).
constexpr std::int64_t number(Type t, Raw r) {
  switch (bits(t)) {
    case 8:
      return is_signed(t) ? std::int64_t{static_cast<std::int8_t>(r & 0xFFU)}
                          : std::int64_t{r & 0xFFU};
    case 16:
      return is_signed(t) ? std::int64_t{static_cast<std::int16_t>(r & 0xFFFFU)}
                          : std::int64_t{r & 0xFFFFU};
    case 32:
      return is_signed(t) ? std::int64_t{static_cast<std::int32_t>(r)} : std::int64_t{r};
    default:
      return r;
  }
}
// A number of the type as its canonical Raw (signed: sign-extended to 32 bits). A number that
// does not fit (fits() false) keeps its low 32 bits: check first.
constexpr Raw raw(Type /*t*/, std::int64_t n) {
  return static_cast<Raw>(static_cast<std::uint64_t>(n) & 0xFFFFFFFFULL);
}
// The canonical image of any Raw: what raw(number()) gives.
constexpr Raw canonical(Type t, Raw r) {
  return raw(t, number(t, r));
}
constexpr bool is_canonical(Type t, Raw r) {
  return t != Type::string && canonical(t, r) == r;
}
// The type's bit pattern, zero-extended: what PCP, LUSTBUS and the communication word carry.
constexpr Raw pattern(Type t, Raw r) {
  const unsigned b = bits(t);
  return b >= 32 || b == 0 ? r : (r & ((Raw{1} << b) - 1U));
}

// A value a bus carried in `bus_bits` bits (the communication word's 16, PCP's and LUSTBUS's
// type width) as the Raw a drive checks: signed types sign-extended from the bus's top bit,
// unsigned ones as they came -- so that 0105H for a USIGN8 stays 261 and is refused as above its
// maximum, not masked into range (INTERBUS manual 4.1.4: "invalid value").
constexpr Raw from_bus(Type t, Raw r, unsigned bus_bits) {
  if (!is_signed(t) || bus_bits >= 32 || bus_bits == 0) return r;
  const Raw sign = Raw{1} << (bus_bits - 1U);
  const Raw low = r & ((sign << 1U) - 1U);
  return (low ^ sign) - sign;
}

// Orders two Raws of one type as the type's numbers (float_ieee as floats; a NaN above every
// other value): negative, zero or positive like strcmp.
constexpr int compare(Type t, Raw a, Raw b) {
  if (t == Type::float_ieee) {
    const auto fa = std::bit_cast<float>(a);
    const auto fb = std::bit_cast<float>(b);
    const bool na = fa != fa;
    const bool nb = fb != fb;
    if (na || nb) return na == nb ? 0 : (na ? 1 : -1);
    return fa < fb ? -1 : (fa > fb ? 1 : 0);
  }
  const std::int64_t x = number(t, a);
  const std::int64_t y = number(t, b);
  return x < y ? -1 : (x > y ? 1 : 0);
}

// Engineering value: the number / per_unit x scale (float_ieee: the float x scale). nullopt for
// the error structures and text.
constexpr std::optional<double> engineering(Type t, Raw r, double scale = 1.0) {
  if (!info(t).numeric) return std::nullopt;
  if (t == Type::float_ieee) return static_cast<double>(std::bit_cast<float>(r)) * scale;
  return static_cast<double>(number(t, r)) / info(t).per_unit * scale;
}
// The engineering value of one step of the number (fixpoint16: 0.05 x scale).
constexpr double step(Type t, double scale = 1.0) {
  return scale / info(t).per_unit;
}

// Why an engineering value has no Raw.
enum class Conversion : std::uint8_t { ok, too_high, too_low, not_a_number, wrong_type };
constexpr std::string_view to_string(Conversion c) {
  switch (c) {
    case Conversion::ok:
      return "ok";
    case Conversion::too_high:
      return "value too high";
    case Conversion::too_low:
      return "value too low";
    case Conversion::not_a_number:
      return "not a number";
    case Conversion::wrong_type:
      return "no engineering value for this type";
  }
  return "?";
}
struct Converted {
  Raw raw = 0;
  Conversion error = Conversion::ok;
  [[nodiscard]] constexpr bool ok() const { return error == Conversion::ok; }
};
// The Raw of an engineering value, rounded to the nearest step (halves away from zero, as the
// standard family's and CANLust's conversions round; LUSTBUS manual's C truncates, LB-D8); refused
// outside the type's range, for NaN and infinities, and for the types without an engineering value.
Converted from_engineering(Type t, double value, double scale = 1.0);

// A typed value (replaces pcp::Value): the type and its canonical Raw.
struct Value {
  Type type = Type::usign16;
  Raw raw = 0;
  [[nodiscard]] constexpr std::int64_t number() const { return od::number(type, raw); }
  friend constexpr bool operator==(const Value&, const Value&) = default;
};
// nullopt when `n` does not fit the type.
constexpr std::optional<Value> make_value(Type t, std::int64_t n) {
  if (t == Type::string || !fits(t, n)) return std::nullopt;
  return Value{t, raw(t, n)};
}

// PT_VF_ERROR (INTERBUS manual 4.1.3.3 footnote; LUSTBUS manual 2.3.1): high byte low nibble the error code
// 00H-0EH (0FH: no error), low byte low nibble the time of the error since power-on in tenths of
// an hour (0FH: the basic state). An erased EEPROM reads FFH (LUSTBUS manual 2.3.1): only the low
// nibbles count.
inline constexpr std::uint8_t kVfNoError = 0x0F;
inline constexpr Raw kVfErrorNone = 0x0F0F;
struct VfError {
  std::optional<std::uint8_t> code;         // 0-14; nullopt: no error
  std::optional<std::uint8_t> time_tenths;  // 0-14 tenths of an hour; nullopt: the basic state
  friend constexpr bool operator==(const VfError&, const VfError&) = default;
};
constexpr VfError vf_error(Raw r) {
  const auto code = static_cast<std::uint8_t>((r >> 8U) & 0x0FU);
  const auto time = static_cast<std::uint8_t>(r & 0x0FU);
  VfError e;
  if (code != kVfNoError) e.code = code;
  if (time != kVfNoError) e.time_tenths = time;
  return e;
}
// nullopt when a field is above 14.
constexpr std::optional<Raw> vf_error_raw(const VfError& e) {
  if ((e.code && *e.code >= kVfNoError) || (e.time_tenths && *e.time_tenths >= kVfNoError))
    return std::nullopt;
  return (Raw{e.code.value_or(kVfNoError)} << 8U) | e.time_tenths.value_or(kVfNoError);
}

// PT_MC_ERROR (LUSTBUS manual 2.3.2, the C union on a little-endian host, PCP-E6) = CANLust ERR_STRUC
// (CANLust manual 4.1.1, p. 32: E-OP2 at location 172 after 85 h = 10 AC 55 00): the number in bits 0-7,
// the location in bits 8-15, the time (hours of operation) in bits 16-31.
struct ErrorRecord {
  std::uint8_t number = 0;
  std::uint8_t location = 0;
  std::uint16_t hours = 0;
  friend constexpr bool operator==(const ErrorRecord&, const ErrorRecord&) = default;
};
constexpr ErrorRecord error_record(Raw r) {
  return {static_cast<std::uint8_t>(r & 0xFFU), static_cast<std::uint8_t>((r >> 8U) & 0xFFU),
          static_cast<std::uint16_t>(r >> 16U)};
}
constexpr Raw error_record_raw(const ErrorRecord& e) {
  return Raw{e.number} | (Raw{e.location} << 8U) | (Raw{e.hours} << 16U);
}

}  // namespace ibs::od
