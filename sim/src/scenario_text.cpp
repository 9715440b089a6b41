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
    case Action::mains:
      return "mains";
    case Action::load:
      return "load";
    case Action::input:
      return "input";
    case Action::smartcard:
      return "smartcard";
    case Action::option_card:
      return "option_card";
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
