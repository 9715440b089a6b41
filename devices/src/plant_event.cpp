// The checks of plant_event.hpp: a cause, an input by the drive's own list.
#include "ibs/devices/plant_event.hpp"

#include <charconv>

namespace ibs::devices {

namespace {

std::string range_text(const EventFacts& f) {
  std::string out = std::to_string(f.min_error) + ".." + std::to_string(f.max_error);
  for (const ErrorCause& e : f.errors) out += ", " + std::string(e.name);
  return out;
}

}  // namespace

CauseCheck check_cause(const EventFacts& f, std::string_view title, std::string_view text) {
  CauseCheck c;
  if (f.max_error < f.min_error) {
    c.error = "a " + std::string(title) + " takes no fault cause";
    return c;
  }
  for (const ErrorCause& e : f.errors) {
    if (e.name == text) {
      c.number = e.number;
      return c;
    }
  }
  int n = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), n);
  if (!text.empty() && r.ec == std::errc{} && r.ptr == text.data() + text.size() && n >= f.min_error &&
      n <= f.max_error) {
    c.number = n;
    return c;
  }
  c.error = "'" + std::string(text) + "' is not an error of the " + std::string(title) + " (" + range_text(f) +
            "; " + std::string(f.error_source) + ")";
  return c;
}

std::string cause_text(const EventFacts& f, int number) {
  for (const ErrorCause& e : f.errors) {
    if (e.number == number) return std::to_string(number) + " (" + std::string(e.name) + ")";
  }
  return std::to_string(number);
}

std::optional<std::size_t> find_input(const EventFacts& f, std::string_view name) {
  for (std::size_t i = 0; i < f.inputs.size(); ++i) {
    if (f.inputs[i] == name) return i;
  }
  return std::nullopt;
}

std::string input_names(const EventFacts& f) {
  std::string out;
  for (std::size_t i = 0; i < f.inputs.size(); ++i) {
    if (i > 0) out += i + 1 == f.inputs.size() ? " or " : ", ";
    out += "\"" + std::string(f.inputs[i]) + "\"";
  }
  return out;
}

}  // namespace ibs::devices
