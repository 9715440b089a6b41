// Times, numbers, strings and names as scenario files write them.
#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "ibs/sim/scenario.hpp"
#include "scenario_internal.hpp"

namespace ibs::sim {

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

std::string_view bus_text(interbus::BusKind b) {
  return b == interbus::BusKind::local ? "local" : "remote";
}

std::string_view to_string(Action a) {
  switch (a) {
    case Action::state:
      return "state";
    case Action::emergency_stop:
      return "emergency_stop";
    case Action::block_power:
      return "block_power";
    case Action::speed:
      return "speed";
    case Action::frequency:
      return "frequency";
    case Action::read:
      return "read";
    case Action::write:
      return "write";
    case Action::describe:
      return "describe";
    case Action::wait_state:
      return "wait_state";
    case Action::fault_corrupt:
      return "fault_corrupt";
    case Action::fault_power_cycle:
      return "fault_power_cycle";
    case Action::fault_device:
      return "fault_device";
    case Action::fault_lost:
      return "fault_lost";
    case Action::master_restart:
      return "master_restart";
  }
  return "?";
}

namespace detail {

std::string_view fault_name(Action a) {
  switch (a) {
    case Action::fault_corrupt:
      return "corrupt";
    case Action::fault_power_cycle:
      return "power-cycle";
    case Action::fault_device:
      return "device";
    case Action::fault_lost:
      return "lost";
    default:
      return {};
  }
}

std::string format_number(double v) {
  std::array<char, 64> buf{};
  const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  std::string text(buf.data(), ec == std::errc{} ? end : buf.data());
  // Keep it a float in TOML: "50" would read back as an integer (equal, but not what was meant).
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

std::string quote(std::string_view s) {
  static constexpr std::string_view kHex = "0123456789ABCDEF";
  std::string out = "\"";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\f':
        out += "\\f";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (u < 0x20 || u == 0x7F) {
          out += "\\u00";
          out += kHex[u >> 4U];
          out += kHex[u & 0x0FU];
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string_view closest_name(std::string_view given, const std::vector<std::string_view>& known) {
  std::string_view best;
  std::size_t best_distance = 3;
  for (const std::string_view k : known) {
    // Levenshtein distance, one row at a time.
    std::vector<std::size_t> row(k.size() + 1);
    for (std::size_t j = 0; j <= k.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= given.size(); ++i) {
      std::size_t diagonal = row[0];
      row[0] = i;
      for (std::size_t j = 1; j <= k.size(); ++j) {
        const std::size_t up = row[j];
        const std::size_t cost = given[i - 1] == k[j - 1] ? 0 : 1;
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + cost});
        diagonal = up;
      }
    }
    if (row[k.size()] < best_distance) {
      best_distance = row[k.size()];
      best = k;
    }
  }
  return best;
}

}  // namespace detail

}  // namespace ibs::sim
