#include "ibs/lustbus/description.hpp"

namespace ibs::lustbus {

namespace {

// 11.1 / 11.2.1: "Combinations of digits, capital letters, underscores (_), and hyphens (-)".
bool is_name_char(char c) {
  return (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || c == '_' || c == '-';
}
bool is_printable(char c) { return c >= 0x20 && c <= 0x7E; }

bool parse_hex(std::string_view s, std::uint32_t& out) {
  std::uint32_t v = 0;
  for (const char c : s) {
    unsigned d = 0;
    if (c >= '0' && c <= '9') {
      d = static_cast<unsigned>(c - '0');
    } else if (c >= 'A' && c <= 'F') {
      d = static_cast<unsigned>(c - 'A' + 10);
    } else {
      return false;
    }
    v = (v << 4) | d;
  }
  out = v;
  return true;
}

void push_hex(Value& v, std::uint32_t x, unsigned digits) {
  constexpr char kHex[] = "0123456789ABCDEF";
  for (unsigned i = digits; i-- > 0;) {
    v.push_back(static_cast<std::uint8_t>(kHex[(x >> (4 * i)) & 0xFU]));
  }
}

// A right-justified, blank-padded field of `width`: the text after the padding.
bool right_justified(std::string_view field, std::string_view& text) {
  std::size_t i = 0;
  while (i < field.size() && field[i] == ' ') ++i;
  text = field.substr(i);
  return text.find(' ') == std::string_view::npos || text.empty();
}

template <std::size_t N>
void copy_text(std::array<char, N>& to, std::string_view from) {
  std::size_t i = 0;
  for (; i < from.size() && i + 1 < N; ++i) to[i] = from[i];
  for (; i < N; ++i) to[i] = '\0';
}

}  // namespace

std::string_view to_string(DescriptionError e) {
  switch (e) {
    case DescriptionError::none:
      return "none";
    case DescriptionError::wrong_length:
      return "wrong length";
    case DescriptionError::bad_name:
      return "bad parameter name";
    case DescriptionError::bad_unit:
      return "bad unit";
    case DescriptionError::bad_kind:
      return "bad parameter kind";
    case DescriptionError::bad_type:
      return "bad parameter type";
    case DescriptionError::bad_value:
      return "bad minimum, maximum or default";
    case DescriptionError::not_7bit:
      return "an element a 7-bit line cannot carry";
  }
  return "?";
}

std::optional<DataType> vf_type_from_char(char c) {
  switch (c) {  // 11.1, "Parameter type"
    case '1':
      return DataType::binary8;
    case '2':
      return DataType::fixpoint16;
    case '3':
      return DataType::usign16;
    case '4':
      return DataType::usign8;
    case '5':
      return DataType::vf_error;
    case '6':
      return DataType::password;
    default:
      return std::nullopt;
  }
}

Parsed<VfDescription> parse_vf_description(std::string_view s) {
  Parsed<VfDescription> r;
  auto fail = [&r](DescriptionError e) {
    r.error = e;
    return r;
  };
  if (s.size() != kVfDescriptionLength) return fail(DescriptionError::wrong_length);
  std::string_view name;
  std::string_view unit;
  if (!right_justified(s.substr(0, 6), name) || name.empty()) return fail(DescriptionError::bad_name);
  for (const char c : name) {
    if (!is_name_char(c)) return fail(DescriptionError::bad_name);
  }
  if (!right_justified(s.substr(6, 6), unit)) return fail(DescriptionError::bad_unit);
  for (const char c : unit) {
    if (!is_printable(c)) return fail(DescriptionError::bad_unit);
  }
  copy_text(r.value.name, name);
  copy_text(r.value.unit, unit);
  r.value.kind = s[12];
  r.value.type = s[13];
  if (r.value.kind < '0' || r.value.kind > '7') return fail(DescriptionError::bad_kind);
  if (!vf_type_from_char(r.value.type)) return fail(DescriptionError::bad_type);
  std::uint32_t min = 0;
  std::uint32_t max = 0;
  std::uint32_t basis = 0;
  if (!parse_hex(s.substr(14, 4), min) || !parse_hex(s.substr(18, 4), max) ||
      !parse_hex(s.substr(22, 4), basis)) {
    return fail(DescriptionError::bad_value);
  }
  r.value.min = static_cast<std::uint16_t>(min);
  r.value.max = static_cast<std::uint16_t>(max);
  r.value.basis = static_cast<std::uint16_t>(basis);
  return r;
}

std::optional<Value> format_vf_description(std::string_view name, std::string_view unit,
                                           char kind, char type, std::uint16_t min,
                                           std::uint16_t max, std::uint16_t basis) {
  if (name.empty() || name.size() > kVfNameLength || unit.size() > kVfNameLength) {
    return std::nullopt;
  }
  for (const char c : name) {
    if (!is_name_char(c)) return std::nullopt;
  }
  for (const char c : unit) {
    if (!is_printable(c) || c == ' ') return std::nullopt;
  }
  if (kind < '0' || kind > '7' || !vf_type_from_char(type)) return std::nullopt;
  Value v;
  for (std::size_t i = name.size(); i < kVfNameLength; ++i) v.push_back(' ');
  for (const char c : name) v.push_back(static_cast<std::uint8_t>(c));
  for (std::size_t i = unit.size(); i < kVfNameLength; ++i) v.push_back(' ');
  for (const char c : unit) v.push_back(static_cast<std::uint8_t>(c));
  v.push_back(static_cast<std::uint8_t>(kind));
  v.push_back(static_cast<std::uint8_t>(type));
  push_hex(v, min, 4);
  push_hex(v, max, 4);
  push_hex(v, basis, 4);
  return v;
}

std::optional<Value> format_vf_description(const VfDescription& d) {
  return format_vf_description(d.name_view(), d.unit_view(), d.kind, d.type, d.min, d.max,
                               d.basis);
}

// 11.2 offsets: name 0-5, unit 6, kind 7, type 8, min 9-16, max 17-24, reference 25-32,
// level 33, attribute 34-35, hardware filter 36-37, structure filter 38-39, subject 40,
// activity 41; a 43rd character is ignored (LB-E9).
Parsed<McDescription> parse_mc_description(std::string_view s) {
  Parsed<McDescription> r;
  auto fail = [&r](DescriptionError e) {
    r.error = e;
    return r;
  };
  if (s.size() != kMcDescriptionElements && s.size() != kMcDescriptionLength) {
    return fail(DescriptionError::wrong_length);
  }
  const std::size_t nul = s.substr(0, 6).find('\0');
  if (nul == std::string_view::npos || nul == 0) return fail(DescriptionError::bad_name);
  for (const char c : s.substr(0, nul)) {
    if (!is_name_char(c)) return fail(DescriptionError::bad_name);
  }
  copy_text(r.value.name, s.substr(0, nul));
  auto byte = [&s](std::size_t i) { return static_cast<std::uint8_t>(s[i]); };
  auto word = [&byte](std::size_t i) {
    return static_cast<std::uint16_t>((byte(i) << 8) | byte(i + 1));
  };
  r.value.unit = byte(6);
  r.value.kind = s[7];
  if (r.value.kind < '0' || r.value.kind > '2') return fail(DescriptionError::bad_kind);
  r.value.type = byte(8);
  if (!parse_hex(s.substr(9, 8), r.value.min) || !parse_hex(s.substr(17, 8), r.value.max) ||
      !parse_hex(s.substr(25, 8), r.value.reference)) {
    return fail(DescriptionError::bad_value);
  }
  r.value.level = byte(33);
  r.value.attribute = word(34);
  r.value.hardware_filter = word(36);
  r.value.structure_filter = word(38);
  r.value.subject_area = byte(40);
  r.value.activity_area = byte(41);
  return r;
}

std::optional<Value> format_mc_description(const McDescription& d) {
  const std::string_view name = d.name_view();
  if (name.empty() || name.size() > kMcNameLength) return std::nullopt;
  for (const char c : name) {
    if (!is_name_char(c)) return std::nullopt;
  }
  if (d.kind < '0' || d.kind > '2') return std::nullopt;
  Value v;
  for (const char c : name) v.push_back(static_cast<std::uint8_t>(c));
  for (std::size_t i = name.size(); i < 6; ++i) v.push_back('\0');
  bool ok = true;
  // LB-D10: the binary elements travel as bytes, frame characters included (the host reads them
  // by their known length); only a byte >= 80H cannot travel on a 7-bit line.
  auto bin = [&v, &ok](std::uint8_t b) { ok = ok && v.push_binary(b); };
  bin(d.unit);
  bin(static_cast<std::uint8_t>(d.kind));
  bin(d.type);
  push_hex(v, d.min, 8);
  push_hex(v, d.max, 8);
  push_hex(v, d.reference, 8);
  bin(d.level);
  for (const std::uint16_t w : {d.attribute, d.hardware_filter, d.structure_filter}) {
    bin(static_cast<std::uint8_t>(w >> 8));
    bin(static_cast<std::uint8_t>(w & 0xFFU));
  }
  bin(d.subject_area);
  bin(d.activity_area);
  bin('\0');
  if (!ok) return std::nullopt;
  return v;
}

std::string_view substitution_text(std::string_view value) {
  std::size_t n = value.size();
  while (n > 0 && (value[n - 1] == ' ' || value[n - 1] == '\0')) --n;
  return value.substr(0, n);
}

}  // namespace ibs::lustbus
