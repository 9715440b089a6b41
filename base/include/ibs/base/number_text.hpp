// Numbers a person reads (summaries, status lines): fixed decimals chosen by the unit, never an
// exponent, never "-0.00". Machine-readable outputs (JSON) keep the full double. Report time only:
// it allocates.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace ibs {

// Decimals by unit: what the drives resolve and a reader compares. rpm and Hz: 2 (the MC6000's
// Q16 speeds of the manuals' examples, 2500.25 rpm; the VF1000's 0.05 Hz steps); %: 1; ms: 3 (a
// microsecond); anything else: 3.
inline int decimals_for_unit(std::string_view unit) {
  if (unit == "rpm" || unit == "Hz") return 2;
  if (unit == "%") return 1;
  return 3;
}

// `v` with `decimals` digits after the point; a value that rounds to zero prints without a sign;
// a NaN or an infinity prints as C does ("nan", "inf").
inline std::string fixed_text(double v, int decimals) {
  if (!std::isfinite(v)) return std::isnan(v) ? "nan" : (v < 0 ? "-inf" : "inf");
  const double scale = std::pow(10.0, decimals);
  if (std::round(std::fabs(v) * scale) == 0.0) v = 0.0;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

// "994.60" for 994.5975647 rpm, "0.00" for 8.73332e-09 rpm.
inline std::string quantity_text(double v, std::string_view unit) { return fixed_text(v, decimals_for_unit(unit)); }

// The last `digits` hexadecimal digits of `v`, capital, zeros in front: "03E8" for (1000, 4), as
// the manuals print words and bytes. The libraries' one copy (the command line formats with {fmt},
// tools/format; a library links no formatting package).
inline std::string hex_text(std::uint64_t v, int digits) {
  static constexpr std::string_view kDigits = "0123456789ABCDEF";
  std::string s(static_cast<std::size_t>(digits > 0 ? digits : 0), '0');
  for (auto i = s.size(); i-- > 0; v >>= 4U) s[i] = kDigits[v & 0xFU];
  return s;
}

}  // namespace ibs
