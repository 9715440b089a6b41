#include "ibs/canlust/data_types.hpp"

#include <cmath>
#include <limits>

namespace ibs::canlust {

std::string_view to_string(DataType t) {
  switch (t) {
    case DataType::usign8: return "USIGN8";
    case DataType::int8: return "INT8";
    case DataType::usign16: return "USIGN16";
    case DataType::int16: return "INT16";
    case DataType::usign32: return "USIGN32";
    case DataType::int32: return "INT32";
    case DataType::int32q16: return "INT32Q16";
    case DataType::fixpoint16: return "FIXPOINT16";
    case DataType::err_struc: return "ERR_STRUC";
    case DataType::string: return "STRING";
  }
  return "?";
}

bool wire_fits(DataType t, std::uint32_t wire) {
  const auto s = static_cast<std::int32_t>(wire);
  switch (t) {
    case DataType::usign8: return wire <= 0xFFU;
    case DataType::int8: return s >= -128 && s <= 127;
    case DataType::usign16:
    case DataType::fixpoint16: return wire <= 0xFFFFU;
    case DataType::int16: return s >= -32768 && s <= 32767;
    case DataType::usign32:
    case DataType::int32:
    case DataType::int32q16:
    case DataType::err_struc: return true;
    case DataType::string: return false;
  }
  return false;
}

std::int32_t q16_from_double(double v) {
  const double r = std::round(v * 65536.0);
  if (!(r > static_cast<double>(std::numeric_limits<std::int32_t>::min()))) {
    return std::numeric_limits<std::int32_t>::min();
  }
  if (r >= static_cast<double>(std::numeric_limits<std::int32_t>::max())) {
    return std::numeric_limits<std::int32_t>::max();
  }
  return static_cast<std::int32_t>(r);
}

std::optional<std::uint16_t> fixpoint16_from_double(double v) {
  const double r = std::round(v * 20.0);
  if (!(r >= 0.0) || r > 65535.0) return std::nullopt;
  return static_cast<std::uint16_t>(r);
}

}  // namespace ibs::canlust
