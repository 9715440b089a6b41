#include "ibs/pcp/data_types.hpp"

#include <bit>
#include <cmath>
#include <limits>

namespace ibs::pcp {

std::string_view to_string(DataType t) {
  switch (t) {
    case DataType::usign8:
      return "USIGN8";
    case DataType::usign16:
      return "USIGN16";
    case DataType::fixpoint16:
      return "FIXPOINT16";
    case DataType::integer16:
      return "INTEGER16";
    case DataType::int32q16:
      return "INT32Q16";
    case DataType::float_ieee:
      return "FLOAT_IEEE";
    case DataType::mc_error:
      return "MC_ERROR";
    case DataType::password:
      return "PASSWORD";
  }
  return "?";
}

std::optional<DataType> data_type_from_code(std::uint8_t code) {
  if (code < 1 || code > 8) return std::nullopt;
  return static_cast<DataType>(code);
}

std::string_view to_string(ConversionError e) {
  switch (e) {
    case ConversionError::none:
      return "none";
    case ConversionError::too_high:
      return "value too high";
    case ConversionError::too_low:
      return "value too low";
    case ConversionError::not_a_number:
      return "not a number";
    case ConversionError::wrong_type:
      return "no engineering scale for this type";
  }
  return "?";
}

std::int64_t signed_raw(Value v) {
  switch (v.type) {
    case DataType::integer16:
      return static_cast<std::int16_t>(static_cast<std::uint16_t>(v.raw & 0xFFFFU));
    case DataType::int32q16:
      return static_cast<std::int32_t>(v.raw);
    case DataType::usign8:
      return v.raw & 0xFFU;
    case DataType::usign16:
    case DataType::fixpoint16:
    case DataType::password:
      return v.raw & 0xFFFFU;
    case DataType::float_ieee:
    case DataType::mc_error:
      return v.raw;
  }
  return v.raw;
}

std::optional<Value> value_from_signed_raw(DataType t, std::int64_t raw) {
  const std::size_t bits = size_of(t) * 8U;
  if (is_signed(t)) {
    const std::int64_t lo = -(std::int64_t{1} << (bits - 1U));
    const std::int64_t hi = (std::int64_t{1} << (bits - 1U)) - 1;
    if (raw < lo || raw > hi) return std::nullopt;
    const auto u = static_cast<std::uint64_t>(raw) & ((std::uint64_t{1} << bits) - 1U);
    return Value{t, static_cast<std::uint32_t>(u)};
  }
  if (raw < 0 || static_cast<std::uint64_t>(raw) >= (std::uint64_t{1} << bits)) return std::nullopt;
  return Value{t, static_cast<std::uint32_t>(raw)};
}

Value to_value(McError e) {
  return {DataType::mc_error, (static_cast<std::uint32_t>(e.time) << 16U) |
                                  (static_cast<std::uint32_t>(e.location) << 8U) | e.number};
}

McError to_mc_error(Value v) {
  return {static_cast<std::uint8_t>(v.raw & 0xFFU),
          static_cast<std::uint8_t>((v.raw >> 8U) & 0xFFU),
          static_cast<std::uint16_t>(v.raw >> 16U)};
}

namespace {

Converted scaled(DataType t, double value, double steps_per_unit, double lo, double hi) {
  if (std::isnan(value)) return {{t, 0}, ConversionError::not_a_number};
  const double steps = std::nearbyint(value * steps_per_unit);
  if (steps > hi) return {{t, 0}, ConversionError::too_high};
  if (steps < lo) return {{t, 0}, ConversionError::too_low};
  const auto v = value_from_signed_raw(t, static_cast<std::int64_t>(steps));
  return {*v, ConversionError::none};
}

}  // namespace

Converted from_engineering(DataType t, double value) {
  switch (t) {
    case DataType::usign8:
      return scaled(t, value, 1.0, 0.0, 255.0);
    case DataType::usign16:
    case DataType::password:
      return scaled(t, value, 1.0, 0.0, 65535.0);
    // LUSTBUS manual 2.3.2: "scaling a normal unsigned 16-bit integer to 0.05"; the top step is 3276.75
    // (the table's 3276.80 is one step past 65535: docs/pcp.md, errata).
    case DataType::fixpoint16:
      return scaled(t, value, 20.0, 0.0, 65535.0);
    case DataType::integer16:
      return scaled(t, value, 1.0, -32768.0, 32767.0);
    // LUSTBUS manual 2.3.2: "signed long with the scaling of 1/65536", the full signed 32-bit range.
    case DataType::int32q16:
      return scaled(t, value, 65536.0, -2147483648.0, 2147483647.0);
    case DataType::float_ieee: {
      if (std::isnan(value)) return {{t, 0}, ConversionError::not_a_number};
      constexpr double kMax = static_cast<double>(std::numeric_limits<float>::max());
      if (value > kMax) return {{t, 0}, ConversionError::too_high};
      if (value < -kMax) return {{t, 0}, ConversionError::too_low};
      return {{t, std::bit_cast<std::uint32_t>(static_cast<float>(value))}, ConversionError::none};
    }
    case DataType::mc_error:
      return {{t, 0}, ConversionError::wrong_type};
  }
  return {{t, 0}, ConversionError::wrong_type};
}

double to_engineering(Value v) {
  switch (v.type) {
    case DataType::fixpoint16:
      return static_cast<double>(v.raw & 0xFFFFU) / 20.0;
    case DataType::int32q16:
      return static_cast<double>(signed_raw(v)) / 65536.0;
    case DataType::float_ieee:
      return static_cast<double>(std::bit_cast<float>(v.raw));
    case DataType::usign8:
    case DataType::usign16:
    case DataType::integer16:
    case DataType::password:
    case DataType::mc_error:
      return static_cast<double>(signed_raw(v));
  }
  return 0.0;
}

std::size_t encode(Value v, std::span<std::uint8_t> out) {
  const std::size_t n = size_of(v.type);
  if (out.size() < n) return 0;
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = static_cast<std::uint8_t>((v.raw >> (8U * (n - 1U - i))) & 0xFFU);
  }
  return n;
}

std::optional<Value> decode(DataType t, std::span<const std::uint8_t> in) {
  const std::size_t n = size_of(t);
  if (in.size() != n) return std::nullopt;
  std::uint32_t raw = 0;
  for (std::size_t i = 0; i < n; ++i) raw = (raw << 8U) | in[i];
  return Value{t, raw};
}

int compare(DataType t, std::uint32_t a, std::uint32_t b) {
  if (t == DataType::float_ieee) {
    const auto fa = std::bit_cast<float>(a);
    const auto fb = std::bit_cast<float>(b);
    if (std::isnan(fa)) return std::isnan(fb) ? 0 : 1;
    if (std::isnan(fb)) return -1;
    return fa < fb ? -1 : (fa > fb ? 1 : 0);
  }
  const std::int64_t sa = signed_raw({t, a});
  const std::int64_t sb = signed_raw({t, b});
  return sa < sb ? -1 : (sa > sb ? 1 : 0);
}

}  // namespace ibs::pcp
