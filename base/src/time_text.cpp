// Times as files and messages write them (scenario files, trace headers): configuration-time
// text work, not in the embedded build.
#include "ibs/base/time_text.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace ibs {

namespace {

struct TimeUnit {
  std::string_view name;
  std::int64_t ns;
  int decimals;  // log10(ns): how many fraction digits still give whole nanoseconds
};
// Largest first: format_time picks the first unit not larger than the value.
constexpr std::array<TimeUnit, 4> kTimeUnits{{
    {"s", 1'000'000'000, 9},
    {"ms", 1'000'000, 6},
    {"us", 1'000, 3},
    {"ns", 1, 0},
}};

constexpr std::int64_t kMaxTimeNs = 86'400LL * 1'000'000'000LL;  // 24 h

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

std::string quoted(std::string_view s) {
  return "\"" + std::string(s) + "\"";
}

[[noreturn]] void bad_time(std::string_view text, const std::string& what) {
  throw std::invalid_argument(quoted(text) + " " + what);
}

}  // namespace

Duration parse_time(std::string_view text) {
  static const std::string kForm =
      "a number and a unit (ns, us, ms, s), e.g. \"250 ms\" or \"8.2 ms\"";
  if (text.empty()) throw std::invalid_argument("an empty time: write " + kForm);
  if (text.front() == '-') bad_time(text, "is negative: times here are never negative");
  std::size_t i = 0;
  while (i < text.size() && is_digit(text[i])) ++i;
  const std::string_view whole = text.substr(0, i);
  std::string_view fraction;
  if (i < text.size() && text[i] == '.') {
    const std::size_t start = ++i;
    while (i < text.size() && is_digit(text[i])) ++i;
    fraction = text.substr(start, i - start);
    if (fraction.empty()) bad_time(text, "is not a time: write " + kForm);
  }
  if (whole.empty()) bad_time(text, "is not a time: write " + kForm);
  while (i < text.size() && text[i] == ' ') ++i;
  const std::string_view unit_text = text.substr(i);
  if (unit_text.empty()) {
    bad_time(text, "has no unit: write \"" + std::string(whole) +
                       (fraction.empty() ? "" : "." + std::string(fraction)) +
                       " s\" (or ms, us, ns)");
  }
  const auto unit = std::find_if(kTimeUnits.begin(), kTimeUnits.end(),
                                 [&](const TimeUnit& u) { return u.name == unit_text; });
  if (unit == kTimeUnits.end()) {
    bad_time(text, "has the unknown unit '" + std::string(unit_text) + "' (ns, us, ms, s)");
  }
  const std::string too_long = "is longer than 24 h";
  // Leading zeros do not count towards the length check.
  const std::size_t first = std::min(whole.find_first_not_of('0'), whole.size());
  if (whole.size() - first > 15) bad_time(text, too_long);
  std::int64_t whole_value = 0;
  (void)std::from_chars(whole.data(), whole.data() + whole.size(), whole_value);
  if (whole_value > kMaxTimeNs / unit->ns) bad_time(text, too_long);
  std::int64_t ns = whole_value * unit->ns;

  const std::size_t last = fraction.find_last_not_of('0');
  fraction = last == std::string_view::npos ? std::string_view{} : fraction.substr(0, last + 1);
  if (fraction.size() > static_cast<std::size_t>(unit->decimals)) {
    bad_time(text, "is not a whole number of nanoseconds");
  }
  if (!fraction.empty()) {
    std::int64_t f = 0;
    (void)std::from_chars(fraction.data(), fraction.data() + fraction.size(), f);
    for (std::size_t k = fraction.size(); k < static_cast<std::size_t>(unit->decimals); ++k) {
      f *= 10;
    }
    ns += f;
  }
  if (ns > kMaxTimeNs) bad_time(text, too_long);
  return Duration{ns};
}

std::string format_time(Duration d) {
  std::int64_t ns = d.count();
  std::string sign;
  if (ns < 0) {
    sign = "-";
    ns = -ns;
  }
  if (ns == 0) return "0 s";
  const auto unit = std::find_if(kTimeUnits.begin(), kTimeUnits.end(),
                                 [&](const TimeUnit& u) { return ns >= u.ns; });
  std::string text = sign + std::to_string(ns / unit->ns);
  const std::int64_t rest = ns % unit->ns;
  if (rest != 0) {
    std::string digits = std::to_string(rest);
    digits.insert(0, static_cast<std::size_t>(unit->decimals) - digits.size(), '0');
    digits.erase(digits.find_last_not_of('0') + 1);
    text += "." + digits;
  }
  return text + " " + std::string(unit->name);
}

}  // namespace ibs
