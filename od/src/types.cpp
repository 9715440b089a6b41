#include "ibs/od/types.hpp"

#include <bit>
#include <cmath>

namespace ibs::od {

Converted from_engineering(Type t, double value, double scale) {
  if (!info(t).numeric) return {0, Conversion::wrong_type};
  if (std::isnan(value) || std::isnan(scale) || !(scale > 0.0) || std::isinf(scale)) {
    return {0, Conversion::not_a_number};
  }
  if (t == Type::float_ieee) {
    const double v = value / scale;
    constexpr double kMax = static_cast<double>(std::numeric_limits<float>::max());
    if (v > kMax) return {0, Conversion::too_high};
    if (v < -kMax) return {0, Conversion::too_low};
    return {std::bit_cast<Raw>(static_cast<float>(v)), Conversion::ok};
  }
  // +-infinity compares above and below every bound.
  const double steps = std::round(value * info(t).per_unit / scale);
  if (steps > static_cast<double>(max_number(t))) return {0, Conversion::too_high};
  if (steps < static_cast<double>(min_number(t))) return {0, Conversion::too_low};
  return {raw(t, static_cast<std::int64_t>(steps)), Conversion::ok};
}

}  // namespace ibs::od
