// The event lines and the `setting:` header of ../shared/specs/trace-format.md ("Events",
// "Headers"), read and written; the rest of the format is trace.cpp's.
#include <cstdint>
#include <string>
#include <string_view>

#include "trace_text.hpp"

namespace ibs::trace::detail {

namespace {

// A decimal or 0x-prefixed integer that is all of `word` (no sign for a count).
std::optional<std::int64_t> whole_number(std::string_view word) {
  if (word.empty() || word.find_first_of(" \t") != std::string_view::npos) return std::nullopt;
  return parse_number(word);
}

// `write PNR VALUE [text]`.
void parse_write(Event& e, std::string_view rest, const std::string& file, std::size_t line) {
  const auto words = split_spaces(rest);
  if (words.size() < 2) {
    fail(file, line, "write: needs a parameter number and a value (`! write PNR VALUE`)");
  }
  const auto pnr = whole_number(words[0]);
  if (!pnr || *pnr < 0 || *pnr > 0xFFFF) {
    fail(file, line, "write: parameter number '" + printable(words[0]) + "' is not 0..65535");
  }
  const auto value = whole_number(words[1]);
  if (!value || *value < kMinWriteValue || *value > kMaxWriteValue) {
    fail(file, line, "write: value '" + printable(words[1]) + "' is not an integer " + std::to_string(kMinWriteValue) +
                         ".." + std::to_string(kMaxWriteValue) + " (a channel's raw value)");
  }
  e.parameter = static_cast<std::uint16_t>(*pnr);
  e.value = *value;
  // The free text after the two numbers, as written.
  const std::size_t after = static_cast<std::size_t>(words[1].data() + words[1].size() - rest.data());
  e.text = std::string(trim(rest.substr(after)));
}

}  // namespace

Event parse_event(std::string_view body, const std::string& file, std::size_t line) {
  const auto space = body.find_first_of(" \t");
  const std::string_view name = body.substr(0, space);
  const auto kind = lookup(name, kEvents);
  if (!kind) {
    fail(file, line, "unknown event '" + printable(name) + "' (one of: " + choices(kEvents) + ")");
  }
  std::string_view rest = space == std::string_view::npos ? std::string_view{} : trim(body.substr(space));
  Event e;
  e.kind = *kind;
  e.line = line;
  if (*kind == Event::Kind::write) {
    parse_write(e, rest, file, line);
    return e;
  }
  if (*kind == Event::Kind::no_data) {
    // `no-data N [text]`: N steps without valid data, 1..kMaxNoDataSteps.
    const auto end = rest.find_first_of(" \t");
    const std::string_view count = rest.substr(0, end);
    const auto n = parse_number(count);
    if (count.empty() || !n || *n < 1 || count.find_first_not_of("0123456789") != std::string_view::npos) {
      fail(file, line, "no-data: '" + printable(count) + "' is not a number of steps (N >= 1: `! no-data N`)");
    }
    if (static_cast<std::uint64_t>(*n) > kMaxNoDataSteps) {
      fail(file, line, "no-data: " + std::string(count) + " is more than the " + std::to_string(kMaxNoDataSteps) +
                           " steps one event may stand for");
    }
    e.steps = static_cast<std::uint64_t>(*n);
    rest = end == std::string_view::npos ? std::string_view{} : trim(rest.substr(end));
  }
  e.text = std::string(rest);
  return e;
}

std::string write_event(const Event& e) {
  std::string out = "! " + std::string(name_of(e.kind, kEvents));
  if (e.kind == Event::Kind::no_data) out += " " + std::to_string(e.steps);
  if (e.kind == Event::Kind::write) out += " " + std::to_string(e.parameter) + " " + std::to_string(e.value);
  if (!e.text.empty()) out += " " + e.text;
  return out;
}

void parse_device_setting(Header& h, std::string_view value, const std::string& file, std::size_t line,
                          const Vocabulary& vocabulary) {
  const auto space = value.find_first_of(" \t");
  const std::string_view name = value.substr(0, space);
  std::string_view text = space == std::string_view::npos ? std::string_view{} : trim(value.substr(space));
  if (name.empty() || !header_name(name)) {
    fail(file, line, "setting: '" + printable(name) + "' is not a setting's name (`setting: NAME VALUE`)");
  }
  if (!vocabulary.device_settings.empty() && !known(name, vocabulary.device_settings)) {
    fail(file, line, "setting: unknown setting '" + std::string(name) + "' (known: " +
                         listed(vocabulary.device_settings) + ")");
  }
  // The scenario file's syntax: a time or a choice is quoted there; the header takes it with or
  // without its quotes and keeps the text between them.
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"') text = text.substr(1, text.size() - 2);
  if (text.empty()) fail(file, line, "setting: '" + std::string(name) + "' needs a value (`setting: NAME VALUE`)");
  if (text.find('"') != std::string_view::npos) {
    fail(file, line, "setting: " + std::string(name) + ": '" + printable(text) + "' is not a value (a stray quote)");
  }
  if (const DeviceSetting* first = h.device_setting(name)) {
    fail(file, line, "setting: '" + std::string(name) + "' given twice (first on line " + std::to_string(first->line) +
                         ")");
  }
  h.device_settings.push_back({std::string(name), std::string(text), line});
}

}  // namespace ibs::trace::detail
