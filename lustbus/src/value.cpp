#include "ibs/lustbus/value.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace ibs::lustbus {

namespace {

constexpr char kHex[] = "0123456789ABCDEF";

// 2.3: "The digits A-F are valid only as capital letters."
int hex_digit(char c, ValueError& e) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  e = (c >= 'a' && c <= 'f') ? ValueError::lower_case : ValueError::not_hex;
  return -1;
}

void fill_hex_value(Value& v, std::uint32_t raw, std::size_t min_width) {
  // Capital hex digits, at least `min_width` (<= 100) of them: known VALUE characters, written
  // into the value's buffer at once rather than checked one by one.
  const auto digits = static_cast<std::size_t>((std::bit_width(raw) + 3) / 4);
  const std::size_t n = std::max<std::size_t>(std::max<std::size_t>(digits, 1), min_width);
  v.fill_hex(raw, n, kHex);
}

Value hex_value(std::uint32_t raw, std::size_t min_width) {
  Value v;
  fill_hex_value(v, raw, min_width);
  return v;
}

constexpr std::uint32_t width_max(DataType t) {
  const unsigned w = width_bits(t);
  return w >= 32 ? 0xFFFFFFFFU : (1U << w) - 1U;
}

}  // namespace

std::string_view to_string(Family f) {
  return f == Family::standard ? "VF1000" : "MC6000";
}

std::string_view to_string(ValueError e) {
  switch (e) {
    case ValueError::none:
      return "none";
    case ValueError::empty:
      return "empty VALUE";
    case ValueError::too_long:
      return "VALUE too long";
    case ValueError::wrong_length:
      return "VALUE not exactly four characters";
    case ValueError::not_hex:
      return "not a hex digit";
    case ValueError::lower_case:
      return "lower-case hex digit";
    case ValueError::out_of_range:
      return "out of range";
    case ValueError::not_finite:
      return "not finite";
    case ValueError::wrong_type:
      return "not for this data type";
  }
  return "?";
}

std::string_view to_string(DataType t) {
  switch (t) {
    case DataType::binary8:
      return "PT_BINARY8";
    case DataType::usign8:
      return "PT_USIGN8";
    case DataType::usign16:
      return "PT_USIGN16";
    case DataType::fixpoint16:
      return "PT_FIXPOINT16";
    case DataType::integer16:
      return "PT_INTEGER16";
    case DataType::int32q16:
      return "PT_INT32Q16";
    case DataType::float_ieee:
      return "PT_FLOAT_IEEE";
    case DataType::vf_error:
      return "PT_VF_ERROR";
    case DataType::mc_error:
      return "PT_MC_ERROR";
    case DataType::password:
      return "PT_PASSWORD";
  }
  return "?";
}

ValueError format_raw(Value& v, Family f, std::uint32_t raw) {
  if (f == Family::standard) {
    if (raw > 0xFFFFU) return ValueError::out_of_range;
    fill_hex_value(v, raw, 4);  // sprintf("%04X") of 2.3.1
    return ValueError::none;
  }
  fill_hex_value(v, raw, 1);  // sprintf("%X") of 2.3.2
  return ValueError::none;
}

Result<Value> format_raw(Family f, std::uint32_t raw) {
  Result<Value> r;  // an empty VALUE with an error
  r.error = format_raw(r.value, f, raw);
  return r;
}

Result<Value> format_raw_width(std::uint32_t raw, std::size_t min_width) {
  if (min_width > kMaxValueLength) return {{}, ValueError::too_long};
  return {hex_value(raw, min_width), ValueError::none};
}

Result<std::uint32_t> parse_raw(Family f, std::string_view s) {
  if (s.empty()) return {0, ValueError::empty};
  if (f == Family::standard && s.size() != 4) return {0, ValueError::wrong_length};
  if (s.size() > kMaxValueLength) return {0, ValueError::too_long};
  std::uint32_t raw = 0;
  std::size_t significant = 0;
  for (const char c : s) {
    ValueError e = ValueError::none;
    const int d = hex_digit(c, e);
    if (d < 0) return {0, e};
    if (significant > 0 || d != 0) ++significant;
    if (significant > 8) return {0, ValueError::too_long};
    raw = (raw << 4) | static_cast<std::uint32_t>(d);
  }
  return {raw, ValueError::none};
}

Result<std::uint32_t> parse_typed(Family f, DataType t, std::string_view value) {
  auto r = parse_raw(f, value);
  if (!r.ok()) return r;
  if (r.value > width_max(t)) return {0, ValueError::out_of_range};
  return r;
}

Result<Value> format_typed(Family f, DataType t, std::uint32_t bits) {
  if (f == Family::standard && width_bits(t) > 16) return {{}, ValueError::wrong_type};
  if (bits > width_max(t)) return {{}, ValueError::out_of_range};
  return format_raw(f, bits);
}

Result<double> to_engineering(DataType t, std::uint32_t bits) {
  if (bits > width_max(t)) return {0.0, ValueError::out_of_range};
  switch (t) {
    case DataType::binary8:
    case DataType::usign8:
    case DataType::usign16:
    case DataType::password:
      return {static_cast<double>(bits), ValueError::none};
    case DataType::fixpoint16:
      return {static_cast<double>(bits) / 20.0, ValueError::none};  // 0.05 per step (2.3)
    case DataType::integer16:
      return {static_cast<double>(static_cast<std::int16_t>(bits)), ValueError::none};
    case DataType::int32q16:
      return {static_cast<double>(static_cast<std::int32_t>(bits)) / 65536.0, ValueError::none};
    case DataType::float_ieee: {
      const float f = std::bit_cast<float>(bits);
      if (!std::isfinite(f)) return {0.0, ValueError::not_finite};
      return {static_cast<double>(f), ValueError::none};
    }
    case DataType::vf_error:
    case DataType::mc_error:
      return {0.0, ValueError::wrong_type};
  }
  return {0.0, ValueError::wrong_type};
}

Result<std::uint32_t> from_engineering(DataType t, double value) {
  if (!std::isfinite(value)) return {0, ValueError::not_finite};
  auto in = [](double r, double lo, double hi) { return r >= lo && r <= hi; };
  switch (t) {
    case DataType::binary8:
    case DataType::usign8:
    case DataType::usign16:
    case DataType::password: {
      const double r = std::round(value);
      if (!in(r, 0.0, static_cast<double>(width_max(t)))) return {0, ValueError::out_of_range};
      return {static_cast<std::uint32_t>(r), ValueError::none};
    }
    case DataType::fixpoint16: {
      // 0.00 .. 3276.75 (LB-E6: the table's 3276,80 does not fit 16 bits).
      const double r = std::round(value * 20.0);
      if (!in(r, 0.0, 65535.0)) return {0, ValueError::out_of_range};
      return {static_cast<std::uint32_t>(r), ValueError::none};
    }
    case DataType::integer16: {
      const double r = std::round(value);
      if (!in(r, -32768.0, 32767.0)) return {0, ValueError::out_of_range};
      return {static_cast<std::uint16_t>(static_cast<std::int16_t>(r)), ValueError::none};
    }
    case DataType::int32q16: {
      // The full signed 32-bit range (LB-E7, as PCP-E5).
      const double r = std::round(value * 65536.0);
      if (!in(r, -2147483648.0, 2147483647.0)) return {0, ValueError::out_of_range};
      return {static_cast<std::uint32_t>(static_cast<std::int32_t>(r)), ValueError::none};
    }
    case DataType::float_ieee: {
      if (std::fabs(value) > static_cast<double>(std::numeric_limits<float>::max())) {
        return {0, ValueError::out_of_range};
      }
      return {std::bit_cast<std::uint32_t>(static_cast<float>(value)), ValueError::none};
    }
    case DataType::vf_error:
    case DataType::mc_error:
      return {0, ValueError::wrong_type};
  }
  return {0, ValueError::wrong_type};
}

Result<double> decode(Family f, DataType t, std::string_view value) {
  const auto bits = parse_typed(f, t, value);
  if (!bits.ok()) return {0.0, bits.error};
  return to_engineering(t, bits.value);
}

Result<Value> encode(Family f, DataType t, double value) {
  const auto bits = from_engineering(t, value);
  if (!bits.ok()) return {{}, bits.error};
  return format_typed(f, t, bits.value);
}

}  // namespace ibs::lustbus
