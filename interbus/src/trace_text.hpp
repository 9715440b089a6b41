// The trace reader's text helpers (trace.cpp, trace_lines.cpp): trimming, numbers, words, names
// and the tables of the header values and events. Internal to interbus/src.
#pragma once

#include <algorithm>
#include <array>
#include <charconv>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ibs/base/number_text.hpp"
#include "ibs/interbus/trace.hpp"

namespace ibs::trace::detail {

inline constexpr std::string_view kFormat = "ibs-trace 1";

inline std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

[[noreturn]] inline void fail(const std::string& file, std::size_t line, const std::string& what) {
  throw TraceError(file, line, what);
}

inline int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Four hex digits, `?` allowed where `allow_any`; returns value and mask.
inline WordPattern parse_hex4(std::string_view s, bool allow_any, const std::string& file,
                       std::size_t line) {
  if (s.size() != 4) {
    fail(file, line, "word '" + std::string(s) + "' must be exactly four hex digits");
  }
  unsigned value = 0;
  unsigned mask = 0;
  for (char c : s) {
    value <<= 4U;
    mask <<= 4U;
    if (c == '?') {
      if (!allow_any) fail(file, line, "'?' is not allowed in the mask of '" + std::string(s) + "'");
      continue;
    }
    const int d = hex_digit(c);
    if (d < 0) fail(file, line, "word '" + std::string(s) + "' has a non-hex digit '" + c + "'");
    value |= static_cast<unsigned>(d);
    mask |= 0xFU;
  }
  return {static_cast<Word>(value & mask), static_cast<Word>(mask)};
}

// A decimal or 0x-prefixed hex number.
inline std::optional<std::int64_t> parse_number(std::string_view s) {
  s = trim(s);
  if (s.empty()) return std::nullopt;
  bool negative = false;
  if (s.front() == '-') {
    negative = true;
    s.remove_prefix(1);
  }
  int base = 10;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    base = 16;
    s.remove_prefix(2);
  }
  std::int64_t v = 0;
  const auto* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, v, base);
  if (ec != std::errc{} || ptr != end) return std::nullopt;
  return negative ? -v : v;
}

inline std::vector<std::string_view> split_spaces(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < s.size() && s[i] != ' ' && s[i] != '\t') ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
  return out;
}

template <typename E, std::size_t N>
inline std::optional<E> lookup(std::string_view s, const std::array<std::pair<std::string_view, E>, N>& t) {
  for (const auto& [name, e] : t) {
    if (name == s) return e;
  }
  return std::nullopt;
}

inline constexpr std::array<std::pair<std::string_view, WordsKind>, 3> kWords{
    {{"comm", WordsKind::comm}, {"pd", WordsKind::pd}, {"pcp", WordsKind::pcp}}};
inline constexpr std::array<std::pair<std::string_view, DeviceStart>, 3> kInits{
    {{"operational", DeviceStart::operational},
     {"power-on", DeviceStart::initialised},
     {"fault", DeviceStart::fault}}};
inline constexpr std::array<std::pair<std::string_view, Event::Kind>, 4> kEvents{
    {{"fault", Event::Kind::fault},
     {"fault-cleared", Event::Kind::fault_cleared},
     {"no-data", Event::Kind::no_data},
     {"write", Event::Kind::write}}};
// A name from a vocabulary list, or any single word when the list is empty.
inline bool known(std::string_view name, std::span<const std::string_view> names) {
  if (names.empty()) return !name.empty() && name.find_first_of(" \t") == std::string_view::npos;
  return std::find(names.begin(), names.end(), name) != names.end();
}
inline std::string listed(std::span<const std::string_view> names) {
  if (names.empty()) return "a single word";
  std::string s;
  for (const std::string_view n : names) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

template <typename E, std::size_t N>
inline std::string_view name_of(E e, const std::array<std::pair<std::string_view, E>, N>& t) {
  for (const auto& [name, v] : t) {
    if (v == e) return name;
  }
  return "?";
}

template <typename E, std::size_t N>
inline std::string choices(const std::array<std::pair<std::string_view, E>, N>& t) {
  std::string s;
  for (const auto& [name, v] : t) {
    if (!s.empty()) s += ", ";
    s += name;
  }
  return s;
}

inline std::uint64_t parse_count(std::string_view value, std::string_view key, const std::string& file,
                          std::size_t line) {
  const auto n = parse_number(value);
  if (!n || *n < 0) {
    fail(file, line, std::string(key) + ": '" + std::string(value) +
                         "' is not a non-negative integer");
  }
  return static_cast<std::uint64_t>(*n);
}

inline std::string hex4(unsigned v) { return hex_text(v, 4); }

// Text of a file put into a message: a byte that is not printable is shown as \xNN (a NUL would
// otherwise end the message where a reader sees it).
inline std::string printable(std::string_view text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7F) {
      out += c;
    } else {
      static constexpr std::string_view kHex = "0123456789ABCDEF";
      out += "\\x";
      out += kHex[u >> 4U];
      out += kHex[u & 0xFU];
    }
  }
  return out;
}

// A header name as the format writes them: lower-case letters, digits, '-' and '_'.
inline bool header_name(std::string_view key) {
  return !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
  });
}


// trace_lines.cpp: an event line's body (after '!') and a `setting:` header's value, read as
// trace-format.md says; both throw TraceError naming `file`:`line`.
Event parse_event(std::string_view body, const std::string& file, std::size_t line);
std::string write_event(const Event& e);
void parse_device_setting(Header& h, std::string_view value, const std::string& file, std::size_t line,
                          const Vocabulary& vocabulary);

}  // namespace ibs::trace::detail
