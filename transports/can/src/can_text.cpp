#include "ibs/can/can_text.hpp"

#include <cstdio>
#include <limits>

namespace ibs::can {

namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// `c` as the user typed it, quoted, or a word for what cannot be shown.
std::string shown(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u < 0x20 || u >= 0x7F) {
    char b[16];
    std::snprintf(b, sizeof b, "byte %02XH", static_cast<unsigned>(u));
    return b;
  }
  return std::string("'") + c + "'";
}

TextError at(std::size_t index, std::string what) { return {index + 1, std::move(what)}; }

FrameText refuse(std::size_t index, std::string what) { return {std::nullopt, at(index, std::move(what))}; }

// Hex digits of text[from, to) as a number (at most 8 digits); or the error at the first bad one.
std::optional<TextError> read_hex(std::string_view text, std::size_t from, std::size_t to, const char* what,
                                  std::uint32_t& value) {
  if (from == to) return at(from, std::string(what) + " is missing");
  if (to - from > 8) return at(from + 8, std::string(what) + " has more than 8 hex digits");
  value = 0;
  for (std::size_t i = from; i < to; ++i) {
    const int v = hex_value(text[i]);
    if (v < 0) return at(i, shown(text[i]) + " is not a hex digit (" + what + ")");
    value = (value << 4U) | static_cast<std::uint32_t>(v);
  }
  return std::nullopt;
}

}  // namespace

FrameText parse_cansend(std::string_view text) {
  const auto hash = text.find('#');
  const std::size_t id_end = hash == std::string_view::npos ? text.size() : hash;
  // The identifier: exactly three hex digits (an 11-bit one; eight would be a 29-bit one).
  for (std::size_t i = 0; i < id_end; ++i) {
    if (hex_value(text[i]) < 0) return refuse(i, shown(text[i]) + " is not a hex digit (the identifier)");
  }
  if (hash == std::string_view::npos) {
    return refuse(text.size(), text.empty() ? "empty: expected ID#DATA" : "no '#' after the identifier");
  }
  if (id_end == 8) {
    return refuse(0, "an 8-digit identifier is an extended (29-bit) one: CANLust uses 11-bit identifiers, 3 hex digits");
  }
  if (id_end != 3) {
    return refuse(0, "the identifier is 3 hex digits (000..7FF), not " + std::to_string(id_end));
  }
  std::uint32_t id = 0;
  (void)read_hex(text, 0, 3, "the identifier", id);
  if (id > canlust::kMaxStandardId) {
    return refuse(0, "identifier " + std::string(text.substr(0, 3)) + " is above 7FF (11 bits)");
  }
  canlust::CanFrame f;
  f.id = static_cast<std::uint16_t>(id);
  std::size_t i = hash + 1;
  if (i < text.size() && text[i] == '#') return refuse(i, "'##' is a CAN FD frame: CANLust uses classic frames only");
  if (i < text.size() && (text[i] == 'R' || text[i] == 'r')) {
    f.rtr = true;
    ++i;
    if (i < text.size()) {
      if (text[i] < '0' || text[i] > '8') return refuse(i, "a remote frame's length is one digit 0..8, not " + shown(text[i]));
      f.dlc = static_cast<std::uint8_t>(text[i] - '0');
      ++i;
    }
    if (i < text.size()) return refuse(i, shown(text[i]) + " after the remote frame's length");
    return {f, {}};
  }
  std::size_t n = 0;
  while (i < text.size()) {
    if (text[i] == '.') {
      ++i;
      continue;
    }
    if (hex_value(text[i]) < 0) return refuse(i, shown(text[i]) + " is not a hex digit (the data)");
    if (n == canlust::kMaxDlc) return refuse(i, "more than 8 data bytes");
    if (i + 1 >= text.size() || text[i + 1] == '.') {
      return refuse(i, "half a byte: each data byte is 2 hex digits");
    }
    if (hex_value(text[i + 1]) < 0) return refuse(i + 1, shown(text[i + 1]) + " is not a hex digit (the data)");
    f.data[n++] = static_cast<std::uint8_t>(hex_value(text[i]) * 16 + hex_value(text[i + 1]));
    i += 2;
  }
  f.dlc = static_cast<std::uint8_t>(n);
  return {f, {}};
}

std::string cansend_text(const canlust::CanFrame& f) {
  char id[8];
  std::snprintf(id, sizeof id, "%03X#", static_cast<unsigned>(f.id));
  std::string s = id;
  if (f.rtr) return s + "R" + (f.dlc > 0 ? std::to_string(f.dlc) : "");
  for (const auto b : f.payload()) {
    char h[4];
    std::snprintf(h, sizeof h, "%02X", static_cast<unsigned>(b));
    s += h;
  }
  return s;
}

bool CanFilter::matches(const canlust::CanFrame& f) const {
  const std::uint32_t can_id = f.id | (f.rtr ? kCanRtrFlag : 0U);
  const bool same = (can_id & mask) == (id & mask);
  return inverted ? !same : same;
}

bool CanFilterSet::passes(const canlust::CanFrame& f) const {
  if (filters.empty()) return true;
  for (const CanFilter& x : filters) {
    const bool m = x.matches(f);
    if (join && !m) return false;
    if (!join && m) return true;
  }
  return join;
}

std::optional<TextError> add_candump_filters(std::string_view text, CanFilterSet& set) {
  CanFilterSet added = set;
  std::size_t start = 0;
  for (;;) {
    const auto comma = text.find(',', start);
    const std::size_t end = comma == std::string_view::npos ? text.size() : comma;
    const std::string_view token = text.substr(start, end - start);
    if (token.empty()) return at(start, "an empty filter: expected ID:MASK, ID~MASK or j");
    if (token == "j" || token == "J") {
      added.join = true;
    } else if (token[0] == '#') {
      return at(start, "an error frame filter (#MASK): this bus carries no error frames");
    } else {
      CanFilter f;
      std::size_t from = start;
      if (token[0] == '~') {  // ~ID:MASK, the inverted filter with its '~' first
        f.inverted = true;
        ++from;
      }
      std::size_t sep = from;
      while (sep < end && text[sep] != ':' && text[sep] != '~') ++sep;
      if (sep == end) return at(end, "no ':' or '~' between ID and MASK");
      if (text[sep] == '~') {
        if (f.inverted) return at(sep, "'~' twice: write ID~MASK (candump's form) or ~ID:MASK");
        f.inverted = true;
      }
      std::uint32_t id = 0;
      std::uint32_t mask = 0;
      if (auto e = read_hex(text, from, sep, "the ID", id)) return e;
      if (auto e = read_hex(text, sep + 1, end, "the MASK", mask)) return e;
      // candump: an ID of exactly 8 digits is an extended one; the error flag is no filter's.
      f.id = id | (sep - from == 8 ? kCanEffFlag : 0U);
      f.mask = mask & ~kCanErrFlag;
      added.filters.push_back(f);
    }
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  set = std::move(added);
  return std::nullopt;
}

std::optional<std::int64_t> candump_time_us(std::string_view text) {
  const auto dot = text.find('.');
  if (dot == std::string_view::npos || dot == 0 || dot + 1 == text.size() || text.size() - dot - 1 > 6) {
    return std::nullopt;
  }
  constexpr std::int64_t kMaxSeconds = std::numeric_limits<std::int64_t>::max() / 1'000'000 - 1;
  std::int64_t seconds = 0;
  for (std::size_t i = 0; i < dot; ++i) {
    if (text[i] < '0' || text[i] > '9') return std::nullopt;
    seconds = seconds * 10 + (text[i] - '0');
    if (seconds > kMaxSeconds) return std::nullopt;
  }
  std::int64_t fraction = 0;
  std::size_t digits = 0;
  for (std::size_t i = dot + 1; i < text.size(); ++i, ++digits) {
    if (text[i] < '0' || text[i] > '9') return std::nullopt;
    fraction = fraction * 10 + (text[i] - '0');
  }
  for (; digits < 6; ++digits) fraction *= 10;
  return seconds * 1'000'000 + fraction;
}

}  // namespace ibs::can
