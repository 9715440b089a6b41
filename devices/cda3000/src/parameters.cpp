#include "ibs/devices/cda3000/parameters.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "ibs/canlust/errors.hpp"

namespace ibs::devices::cda3000 {

namespace {

bool iequal(std::string_view a, std::string_view b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::toupper(static_cast<unsigned char>(x)) == std::toupper(static_cast<unsigned char>(y));
         });
}

bool is_signed(DataType t) {
  return t == DataType::int8 || t == DataType::int16 || t == DataType::int32 || t == DataType::int32q16;
}

std::optional<long long> parse_integer(std::string_view s) {
  long long v = 0;
  const char* first = s.data();
  const char* last = s.data() + s.size();
  if (first != last && *first == '+') ++first;
  const auto r = std::from_chars(first, last, v);
  if (first == last || r.ec != std::errc{} || r.ptr != last) return std::nullopt;
  return v;
}

std::string number_text(const ParameterInfo& p, std::int64_t n) {
  if (p.type == DataType::int32q16) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.6g", canlust::double_from_q16(static_cast<std::int32_t>(n)));
    return buf;
  }
  return std::to_string(n);
}

std::string with_unit(const ParameterInfo& p, const std::string& v) {
  return p.unit.empty() ? v : v + " " + std::string(p.unit);
}

}  // namespace

std::optional<std::uint16_t> response_parameter(std::uint8_t error) {
  switch (error) {
    case canlust::kErrorOti: return kRoti;
    case canlust::kErrorPls: return kRpls;
    case canlust::kErrorPar: return kRpar;
    case canlust::kErrorFlt: return kRflt;
    case canlust::kErrorPwr: return kRpwr;
    case canlust::kErrorOp2: return kRop2;
    default: return std::nullopt;
  }
}

const ParameterInfo* find_parameter(std::uint16_t number) {
  const auto i = parameter_index(number);
  return i ? &kParameters[*i] : nullptr;
}

const ParameterInfo* find_parameter(std::string_view text) {
  const auto dash = text.find('-');
  const std::string_view num = dash == std::string_view::npos ? text : text.substr(0, dash);
  const std::string_view name = dash == std::string_view::npos ? std::string_view{} : text.substr(dash + 1);
  if (const auto n = parse_integer(num); n && *n >= 0 && *n <= 0xFFFF) {
    const ParameterInfo* p = find_parameter(static_cast<std::uint16_t>(*n));
    if (p != nullptr && !name.empty() && !iequal(name, p->name)) return nullptr;
    return p;
  }
  if (dash != std::string_view::npos) return nullptr;
  for (const auto& p : kParameters) {
    if (iequal(text, p.name)) return &p;
  }
  return nullptr;
}

std::string display_name(const ParameterInfo& p) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%03u", static_cast<unsigned>(p.number));
  // The manual writes 150-SAVE, 04-PROG: at least two digits.
  const std::string n = p.number < 100 ? std::string(buf + 1) : std::string(buf);
  return n + "-" + std::string(p.name);
}

const Choice* find_choice(const ParameterInfo& p, std::uint32_t code) {
  for (const auto& c : p.choices) {
    if (c.code == code) return &c;
  }
  return nullptr;
}

const Choice* find_choice(const ParameterInfo& p, std::string_view name) {
  for (const auto& c : p.choices) {
    if (iequal(c.name, name)) return &c;
  }
  return nullptr;
}

std::int64_t number_of(const ParameterInfo& p, std::uint32_t wire) {
  if (is_signed(p.type)) return static_cast<std::int32_t>(wire);
  return wire;
}

std::uint32_t wire_of(const ParameterInfo& p, std::int64_t number) {
  (void)p;
  return static_cast<std::uint32_t>(static_cast<std::uint64_t>(number) & 0xFFFFFFFFULL);
}

std::string_view to_string(ValueCheck c) {
  switch (c) {
    case ValueCheck::ok: return "ok";
    case ValueCheck::wrong_type: return "does not fit the data type";
    case ValueCheck::below_min: return "below the minimum";
    case ValueCheck::above_max: return "above the maximum";
    case ValueCheck::not_a_choice: return "not one of the substitution texts";
  }
  return "?";
}

ValueCheck check_value(const ParameterInfo& p, std::uint32_t wire) {
  if (p.is_string()) return ValueCheck::wrong_type;
  const std::int64_t n = number_of(p, wire);
  if (n < p.min) return ValueCheck::below_min;
  if (n > p.max) return ValueCheck::above_max;
  if (!canlust::wire_fits(p.type, wire)) return ValueCheck::wrong_type;
  if (!p.choices.empty() && find_choice(p, wire) == nullptr) return ValueCheck::not_a_choice;
  return ValueCheck::ok;
}

std::string format_value(const ParameterInfo& p, std::uint32_t wire) {
  if (p.type == DataType::err_struc) {
    // 4.1.1: error number, location, operating hours; the number named as table 5.9 does (6.2).
    const canlust::ErrStruc e = canlust::err_struc_from_wire(wire);
    if (e.number == 0) return "0 (no error)";
    const auto info = canlust::find_error(e.number);
    return std::to_string(e.number) + (info ? " " + std::string(info->name) : std::string()) + " at location " +
           std::to_string(e.location) + ", " + std::to_string(e.hours) + " h";
  }
  const std::string v = number_text(p, number_of(p, wire));
  if (const Choice* c = find_choice(p, wire)) return v + " (" + std::string(c->name) + ")";
  return with_unit(p, v);
}

std::string describe_refusal(const ParameterInfo& p, std::uint32_t wire, ValueCheck c) {
  const std::string who = display_name(p) + ": ";
  const std::string v = with_unit(p, number_text(p, number_of(p, wire)));
  switch (c) {
    case ValueCheck::ok: return who + v + " is accepted";
    case ValueCheck::wrong_type:
      return who + v + " does not fit its data type " + std::string(canlust::to_string(p.type));
    case ValueCheck::below_min:
      return who + v + " is below the minimum " + with_unit(p, number_text(p, p.min));
    case ValueCheck::above_max:
      return who + v + " is above the maximum " + with_unit(p, number_text(p, p.max));
    case ValueCheck::not_a_choice: {
      std::string list;
      for (const auto& ch : p.choices) {
        list += (list.empty() ? "" : ", ") + std::to_string(ch.code) + " " + std::string(ch.name);
      }
      return who + v + " is not one of its values (" + list + ")";
    }
  }
  return who + v;
}

ParsedValue parse_value(const ParameterInfo& p, std::string_view text) {
  ParsedValue r;
  const std::string who = display_name(p) + ": ";
  if (p.is_string()) {
    r.error = who + "a STRING parameter takes text, not a number (string write)";
    return r;
  }
  if (text.empty()) {
    r.error = who + "no value given";
    return r;
  }
  std::int64_t n = 0;
  if (const Choice* c = find_choice(p, text)) {
    n = c->code;
  } else if (const auto i = parse_integer(text); i && p.type != DataType::int32q16) {
    n = *i;
  } else if (p.type == DataType::int32q16) {
    double d = 0;
    const auto res = std::from_chars(text.data(), text.data() + text.size(), d);
    if (res.ec != std::errc{} || res.ptr != text.data() + text.size() || !std::isfinite(d)) {
      r.error = who + "'" + std::string(text) + "' is not a number of " +
                (p.unit.empty() ? std::string("the parameter") : std::string(p.unit));
      return r;
    }
    const double raw = std::round(d * 65536.0);
    if (raw < static_cast<double>(p.min) || raw > static_cast<double>(p.max)) {
      r.error = who + std::string(text) + " " + std::string(p.unit) + " is outside " +
                number_text(p, p.min) + ".." + number_text(p, p.max) + " " + std::string(p.unit);
      return r;
    }
    n = static_cast<std::int64_t>(raw);
  } else {
    std::string names;
    for (const auto& ch : p.choices) names += (names.empty() ? "" : ", ") + std::string(ch.name);
    r.error = who + "'" + std::string(text) + "' is not a number" +
              (names.empty() ? std::string() : " or one of " + names);
    return r;
  }
  if (n < p.min || n > p.max) {
    const std::string v = with_unit(p, std::to_string(n));
    r.error = who + v + (n < p.min ? " is below the minimum " + with_unit(p, number_text(p, p.min))
                                   : " is above the maximum " + with_unit(p, number_text(p, p.max)));
    return r;
  }
  const std::uint32_t wire = wire_of(p, n);
  const ValueCheck c = check_value(p, wire);
  if (c != ValueCheck::ok) {
    r.error = describe_refusal(p, wire, c);
    return r;
  }
  r.wire = wire;
  return r;
}

}  // namespace ibs::devices::cda3000
