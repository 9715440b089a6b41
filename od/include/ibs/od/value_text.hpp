// A parameter's value as a person writes and reads it, from its dictionary entry: the command
// line, scenario files, data-set files, the drivers' describe() and the reports. Parsing takes a
// substitution text ("OPTN2"), a number in the entry's unit ("20.5" Hz of an INT32Q16, "23.15" of a
// FIXPOINT16, "80" ms) or the raw pattern ("0x1F4"); formatting gives "20.5 Hz", "6 (OPTN2)",
// "80 ms"; a refusal names the parameter, the value and the limit ("574-CAWDG: 300 ms is above
// the maximum 255 ms"). Library ibs_od_text: configuration time -- it allocates, but throws
// nothing and uses no iostreams, so the master's build keeps it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "ibs/od/entry.hpp"
#include "ibs/od/served.hpp"

namespace ibs::od {

// How a drive's manual writes its parameters.
struct TextStyle {
  // Digits of the number at least: 1 for the LUSTBUS manual's "4-PROG", 2 for the CANLust manual's "04 PROG".
  int min_digits = 1;
  // The name of an error number of an error32 value ("E-OP2" for 16, CANLust manual 6.2); nullptr or ""
  // for none. The drive's wing knows its errors; od does not.
  std::string_view (*error_name)(std::uint8_t number) = nullptr;
};

// "574-CAWDG", "04-PROG" (min_digits 2), "906-IB-WD".
std::string display_name(const Entry& e, const TextStyle& style = {});
// The value as a number in the entry's unit, without the unit: "255", "-3", "20.5" (INT32Q16,
// six significant digits), "23.15" (FIXPOINT16, two decimals), "1.5" (FLOAT_IEEE); the error
// structures and texts have none: "".
std::string number_text(const Entry& e, Raw r);
// The value for a person: "80 ms", "20.5 Hz", "6 (OPTN2)" (a substitution text instead of the
// unit), "16 E-OP2 at location 172, 85 h" / "0 (no error)" (error32), "error 3, 18 min after
// power-on" / "no error" (error16).
std::string format_value(const Entry& e, Raw r, const TextStyle& style = {});

struct ParseOptions {
  // false: only the type is checked (a data set the drive tests as a whole, LUSTBUS manual 11.4).
  bool check_limits = true;
  TextStyle style{};
};
struct ParsedValue {
  std::optional<Raw> raw;  // canonical
  std::string error;       // why not: "574-CAWDG: 300 ms is above the maximum 255 ms"
  explicit operator bool() const { return raw.has_value(); }
};
// A value given as text: a substitution text of the entry (any case); "0x"/"0X" and hexadecimal
// digits, the type's bit pattern (at most its width; an INT16's 0xFFFF is -1); or a decimal
// number of the unit, rounded to the nearest step (an integer type with no scale takes whole
// numbers only). Then the limits and, for choices_only, the choices. A text entry takes no value.
ParsedValue parse_value(const Entry& e, std::string_view text, const ParseOptions& options = {});

// Why an access was refused, for a person: "575-CASCY: 32001 ms is above the maximum 32000 ms",
// "260-CLSEL: 3 is not one of its values (0 TERM, 6 OPTN2)", "91-TYPE is read-only".
std::string refusal_text(const Entry& e, Raw r, Refusal refusal, const TextStyle& style = {});
// The value's fit as a refusal text ("" for Fit::ok).
std::string fit_text(const Entry& e, Raw r, const TextStyle& style = {});

}  // namespace ibs::od
