#include "ibs/od/value_text.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "ibs/od/dictionary.hpp"

namespace ibs::od {

namespace {

// Integer types read at face value: no step, no scale (the error structures' raw numbers too).
bool whole(const Entry& e) {
  return e.type != Type::float_ieee && info(e.type).per_unit == 1.0 && e.scale == 1.0;
}

// The Raw as a number at 32 bits (signed types sign-extended from bit 31): what a value outside
// the type's width reads as, so that a refusal shows what arrived (CDA3000 check_value).
std::int64_t wide(const Entry& e, Raw r) {
  return is_signed(e.type) ? std::int64_t{static_cast<std::int32_t>(r)} : std::int64_t{r};
}

std::string printf_g(int digits, double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string printf_2f(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string with_unit(const Entry& e, std::string v) {
  if (!e.unit.empty()) {
    v += ' ';
    v += e.unit;
  }
  return v;
}

std::optional<std::int64_t> parse_integer(std::string_view s, int base = 10) {
  if (base == 10 && !s.empty() && s.front() == '+') s.remove_prefix(1);
  long long v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, base);
  if (s.empty() || r.ec != std::errc{} || r.ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

std::optional<double> parse_decimal(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc{} || r.ptr != s.data() + s.size() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

const Choice* choice_named(const Entry& e, std::string_view name) {
  for (const Choice& c : e.choices) {
    if (detail::iequal(c.name, name)) return &c;
  }
  return nullptr;
}

std::string choice_names(const Entry& e) {
  std::string names;
  for (const Choice& c : e.choices) {
    if (!names.empty()) names += ", ";
    names += c.name;
  }
  return names;
}

ParsedValue failed(std::string why) {
  return {std::nullopt, std::move(why)};
}

}  // namespace

std::string display_name(const Entry& e, const TextStyle& style) {
  std::string n = std::to_string(e.number);
  if (static_cast<int>(n.size()) < style.min_digits)
    n.insert(0, static_cast<std::size_t>(style.min_digits) - n.size(), '0');
  return n + "-" + std::string(e.name);
}

std::string number_text(const Entry& e, Raw r) {
  if (!info(e.type).numeric) return "";
  if (whole(e)) return std::to_string(wide(e, r));
  // FIXPOINT16 in its 0.05 steps as the manuals print it (23.15 Hz).
  const double v = e.type == Type::float_ieee
                       ? static_cast<double>(std::bit_cast<float>(r)) * e.scale
                       : static_cast<double>(wide(e, r)) / info(e.type).per_unit * e.scale;
  if (e.type == Type::fixpoint16 && e.scale == 1.0) return printf_2f(v);
  // Six significant digits (20.5 Hz, 2500.25 rpm), more where six would read back as another
  // value (32767.99998 Hz, the top of an INT32Q16, is not 32768): the text is the value.
  std::string text = printf_g(6, v);
  if (!is_canonical(e.type, r)) return text;
  for (int digits = 7; digits <= 17; ++digits) {
    const auto back = parse_decimal(text);
    if (back && from_engineering(e.type, *back, e.scale).raw == r &&
        from_engineering(e.type, *back, e.scale).ok())
      break;
    text = printf_g(digits, v);
  }
  return text;
}

std::string format_value(const Entry& e, Raw r, const TextStyle& style) {
  if (e.type == Type::error32) {
    // LUSTBUS manual 2.3.2 / CANLust manual 4.1.1: error number, location, hours of operation.
    const ErrorRecord rec = error_record(r);
    if (rec.number == 0) return "0 (no error)";
    const std::string_view name =
        style.error_name != nullptr ? style.error_name(rec.number) : std::string_view{};
    return std::to_string(rec.number) + (name.empty() ? "" : " " + std::string(name)) +
           " at location " + std::to_string(rec.location) + ", " + std::to_string(rec.hours) + " h";
  }
  if (e.type == Type::error16) {
    // INTERBUS manual 4.1.3.3 footnote: the code, and the time in tenths of an hour after power-on.
    const VfError v = vf_error(r);
    if (!v.code) return "no error";
    std::string s = "error " + std::to_string(*v.code);
    if (v.time_tenths) s += ", " + std::to_string(*v.time_tenths * 6U) + " min after power-on";
    return s;
  }
  if (e.is_text()) return "";
  const std::string v = number_text(e, r);
  if (const Choice* c = e.choice(r); c != nullptr && wide(e, r) == number(e.type, r)) {
    return v + " (" + std::string(c->name) + ")";
  }
  return with_unit(e, v);
}

std::string refusal_text(const Entry& e, Raw r, Refusal refusal, const TextStyle& style) {
  const std::string who = display_name(e, style);
  const std::string v = with_unit(e, number_text(e, r));
  switch (refusal) {
    case Refusal::none:
      return who + ": " + v + " is accepted";
    case Refusal::latched:
      return who + ": refused while 85-SIOF/SERR holds error bits (read 85 first)";
    case Refusal::no_parameter:
      return who + ": no such parameter";
    case Refusal::read_only:
      return who + " is read-only";
    case Refusal::not_now:
      return who + ": no change permitted now";
    case Refusal::wrong_kind:
      return who + (e.is_text() ? ": a STRING parameter takes text, not a number (string write)"
                                : ": a number, not a text");
    case Refusal::busy:
      return who + ": EEPROM busy, the last value is still being saved";
    case Refusal::transfer_error:
      return who + ": error in the data transfer";
    case Refusal::bad_value:
      return who + ": " + v + " does not fit its data type " + std::string(to_string(e.type));
    case Refusal::too_high:
      return who + ": " + v + " is above the maximum " + with_unit(e, number_text(e, e.max_raw()));
    case Refusal::too_low:
      return who + ": " + v + " is below the minimum " + with_unit(e, number_text(e, e.min_raw()));
    case Refusal::not_a_choice: {
      std::string list;
      for (const Choice& c : e.choices) {
        if (!list.empty()) list += ", ";
        list += number_text(e, c.code) + " " + std::string(c.name);
      }
      return who + ": " + v + " is not one of its values (" + list + ")";
    }
  }
  return who + ": " + v;
}

std::string fit_text(const Entry& e, Raw r, const TextStyle& style) {
  const Fit f = fit(e, r);
  return f == Fit::ok ? std::string() : refusal_text(e, r, refusal_of(f), style);
}

ParsedValue parse_value(const Entry& e, std::string_view text, const ParseOptions& options) {
  const std::string who = display_name(e, options.style) + ": ";
  if (e.is_text())
    return failed(who + "a STRING parameter takes text, not a number (string write)");
  if (text.empty()) return failed(who + "no value given");
  Raw r = 0;
  if (const Choice* c = choice_named(e, text)) {
    r = c->code;
  } else if (text.size() >= 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    // The raw pattern, at most the type's width (LUSTBUS's and the command line's 0x form).
    const auto v = parse_integer(text.substr(2), 16);
    const unsigned width = bits(e.type);
    if (!v || *v < 0 || (width < 32 && (*v >> width) != 0) || *v > 0xFFFFFFFFLL) {
      return failed(who + "raw value '" + std::string(text) + "' is not a " +
                    std::to_string(width) + "-bit hex number");
    }
    r = canonical(e.type, static_cast<Raw>(*v));
  } else if (whole(e)) {
    auto n = parse_integer(text);
    if (!n) {
      const auto d = parse_decimal(text);
      if (!d) {
        const std::string names = choice_names(e);
        return failed(who + "'" + std::string(text) + "' is not a number" +
                      (names.empty() ? "" : " or one of " + names));
      }
      if (std::floor(*d) != *d)
        return failed(who + "'" + std::string(text) + "' is not a whole number");
      if (std::fabs(*d) < 9.0e18) {
        n = static_cast<std::int64_t>(*d);  // "1e3"
      } else {
        // A whole number beyond 64 bits: beyond the type and its limits.
        const std::string v = with_unit(e, std::string(text));
        if (!options.check_limits)
          return failed(who + v + " does not fit its data type " + std::string(to_string(e.type)));
        return failed(who + v +
                      (*d < 0
                           ? " is below the minimum " + with_unit(e, number_text(e, e.min_raw()))
                           : " is above the maximum " + with_unit(e, number_text(e, e.max_raw()))));
      }
    }
    if (!fits(e.type, *n)) {
      if (!options.check_limits) {
        return failed(who + with_unit(e, std::to_string(*n)) + " does not fit its data type " +
                      std::string(to_string(e.type)));
      }
      // Outside the type is outside the limits too: say which limit, as for any other value.
      return failed(who + with_unit(e, std::to_string(*n)) +
                    (*n < e.min
                         ? " is below the minimum " + with_unit(e, number_text(e, e.min_raw()))
                         : " is above the maximum " + with_unit(e, number_text(e, e.max_raw()))));
    }
    r = raw(e.type, *n);
  } else {
    const auto d = parse_decimal(text);
    if (!d) {
      const std::string names = choice_names(e);
      return failed(who + "'" + std::string(text) + "' is not a number of " +
                    (e.unit.empty() ? std::string("the parameter") : std::string(e.unit)) +
                    (names.empty() ? "" : " or one of " + names));
    }
    const Converted conv = from_engineering(e.type, *d, e.scale);
    if (!conv.ok()) {
      const std::string v = with_unit(e, std::string(text));
      if (!options.check_limits) {
        return failed(who + v + " does not fit its data type " + std::string(to_string(e.type)) +
                      " (" + std::string(to_string(conv.error)) + ")");
      }
      return failed(who + v +
                    (conv.error == Conversion::too_low
                         ? " is below the minimum " + with_unit(e, number_text(e, e.min_raw()))
                         : " is above the maximum " + with_unit(e, number_text(e, e.max_raw()))));
    }
    r = conv.raw;
  }
  if (options.check_limits) {
    const Fit f = fit(e, r);
    if (f != Fit::ok) return failed(refusal_text(e, r, refusal_of(f), options.style));
  }
  return {r, {}};
}

}  // namespace ibs::od
