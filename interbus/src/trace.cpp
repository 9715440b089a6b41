#include "ibs/interbus/trace.hpp"

#include "trace_text.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <limits>

#include "ibs/base/number_text.hpp"
#include "ibs/base/text_file.hpp"
#include "ibs/base/time_text.hpp"

namespace ibs::trace {

using namespace detail;

namespace {

// The line a header key was first given on (0: not yet).
std::size_t* header_line(Header& h, std::string_view key) {
  auto& l = h.lines;
  if (key == "device") return &l.device;
  if (key == "words") return &l.words;
  if (key == "init") return &l.init;
  if (key == "request") return &l.request;
  if (key == "request-at") return &l.request_at;
  if (key == "outcome") return &l.outcome;
  if (key == "max-gap") return &l.max_gap;
  if (key == "watchdog_ms") return &l.watchdog_ms;
  if (key == "step-time") return &l.step_time;
  return nullptr;
}

void parse_header(Header& h, std::string_view key, std::string_view value, const std::string& file,
                  std::size_t line, const Vocabulary& vocabulary) {
  // A header given twice is an error: which one a reader took would silently change a test.
  if (const std::size_t* first = header_line(h, key); first != nullptr && *first != 0) {
    fail(file, line, "header '" + std::string(key) + "' given twice (first on line " + std::to_string(*first) + ")");
  }
  if (const HeaderSetting* first = h.setting(key)) {
    fail(file, line, "header '" + std::string(key) + "' given twice (first on line " + std::to_string(first->line) + ")");
  }
  if (key == "device") {
    h.lines.device = line;
    if (!known(value, vocabulary.devices)) {
      fail(file, line, "device: '" + std::string(value) + "' is not one of " + listed(vocabulary.devices));
    }
    h.device = std::string(value);
  } else if (key == "words") {
    h.lines.words = line;
    const auto w = lookup(value, kWords);
    if (!w) fail(file, line, "words: '" + std::string(value) + "' is not one of " + choices(kWords));
    h.words = *w;
  } else if (key == "init") {
    h.lines.init = line;
    const auto i = lookup(value, kInits);
    if (!i) fail(file, line, "init: '" + std::string(value) + "' is not one of " + choices(kInits));
    h.init = *i;
    h.init_given = true;
  } else if (key == "request") {
    h.lines.request = line;
    h.request = parse_request(value, file, line, vocabulary);
  } else if (key == "request-at") {
    h.lines.request_at = line;
    h.request_at = parse_count(value, key, file, line);
    h.request_at_given = true;
  } else if (key == "outcome") {
    h.lines.outcome = line;
    h.outcome = parse_outcome(value, file, line);
  } else if (key == "max-gap") {
    h.lines.max_gap = line;
    h.max_gap = parse_count(value, key, file, line);
    if (h.max_gap > kMaxGapLimit) {
      fail(file, line, "max-gap: " + std::to_string(h.max_gap) + " is more than the " +
                           std::to_string(kMaxGapLimit) + " steps a gap may stand for");
    }
    h.max_gap_given = true;
  } else if (key == "watchdog_ms") {
    // Only an integer here: which values the device takes (its range, its "off") is the drive's,
    // checked by the replay adapters against its wing's declarations.
    h.lines.watchdog_ms = line;
    const std::uint64_t ms = parse_count(value, key, file, line);
    if (ms > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
      fail(file, line, "watchdog_ms: " + std::string(value) + " is not a watchdog time in ms of any device");
    }
    h.watchdog_ms = static_cast<int>(ms);
  } else if (key == "step-time") {
    h.lines.step_time = line;
    Duration d{0};
    try {
      d = parse_time(value);
    } catch (const std::invalid_argument& e) {
      fail(file, line, std::string("step-time: ") + e.what());
    }
    if (d <= Duration{0} || d > kMaxStepTime) {
      fail(file, line, "step-time: '" + std::string(value) + "' must lie above 0 s and be at most " +
                           format_time(kMaxStepTime));
    }
    h.step_time = d;
  } else if (key == "setting") {
    parse_device_setting(h, value, file, line, vocabulary);
  } else if (header_name(key) && (vocabulary.settings.empty() || known(key, vocabulary.settings))) {
    // A drive's setting: its range is the drive's (the replay adapters check it); the format
    // holds 0..255.
    const auto n = parse_number(value);
    if (!n || *n < 0 || *n > 255) {
      fail(file, line, std::string(key) + ": '" + std::string(value) + "' is not an integer 0..255");
    }
    // In the vocabulary's order, so that a header written again reads the same.
    const auto rank = [&vocabulary](std::string_view k) {
      return std::find(vocabulary.settings.begin(), vocabulary.settings.end(), k) - vocabulary.settings.begin();
    };
    auto at = h.settings.end();
    if (!vocabulary.settings.empty()) {
      at = std::find_if(h.settings.begin(), h.settings.end(),
                        [&](const HeaderSetting& s) { return rank(s.key) > rank(key); });
    }
    h.settings.insert(at, HeaderSetting{std::string(key), static_cast<int>(*n), line});
  } else {
    fail(file, line, "unknown header '" + printable(key) + "'");
  }
}

}  // namespace

const DeviceSetting* Header::device_setting(std::string_view name) const {
  const auto it = std::find_if(device_settings.begin(), device_settings.end(),
                               [name](const DeviceSetting& d) { return d.name == name; });
  return it == device_settings.end() ? nullptr : &*it;
}

void Header::set_device_setting(std::string_view name, std::string_view value) {
  for (DeviceSetting& d : device_settings) {
    if (d.name == name) {
      d.value = std::string(value);
      return;
    }
  }
  device_settings.push_back({std::string(name), std::string(value), 0});
}

const HeaderSetting* Header::setting(std::string_view key) const {
  for (const HeaderSetting& s : settings) {
    if (s.key == key) return &s;
  }
  return nullptr;
}

void Header::set_setting(std::string_view key, int value) {
  for (HeaderSetting& s : settings) {
    if (s.key == key) {
      s.value = value;
      return;
    }
  }
  settings.push_back({std::string(key), value, 0});
}

std::string_view to_string(WordsKind w) { return name_of(w, kWords); }
std::string_view to_string(DeviceStart s) { return name_of(s, kInits); }
std::string_view to_string(Event::Kind k) { return name_of(k, kEvents); }

std::string to_string(const Request& r) {
  switch (r.kind) {
    case Request::Kind::read: return "read " + std::to_string(r.parameter);
    case Request::Kind::write:
      return "write " + std::to_string(r.parameter) + " " + std::to_string(r.value);
    case Request::Kind::describe: return "describe " + std::to_string(r.parameter);
    case Request::Kind::state: return "state " + r.target;
  }
  return "?";
}

std::string to_string(const Outcome& o) {
  switch (o.kind) {
    case Outcome::Kind::ok: return o.value ? "ok " + std::to_string(*o.value) : "ok";
    case Outcome::Kind::nak: return "nak";
    case Outcome::Kind::timeout: return "timeout";
  }
  return "?";
}

std::string WordPattern::to_string() const {
  if (mask == 0xFFFF) return hex4(value);
  // Whole-nibble masks are written with '?', anything else as VALUE/MASK.
  bool nibbles = true;
  for (unsigned i = 0; i < 4; ++i) {
    const unsigned m = (mask >> (4 * i)) & 0xFU;
    if (m != 0 && m != 0xF) nibbles = false;
  }
  if (!nibbles) return hex4(value) + "/" + hex4(mask);
  std::string s = hex4(value);
  for (unsigned i = 0; i < 4; ++i) {
    if (((mask >> (4 * (3 - i))) & 0xFU) == 0) s[i] = '?';
  }
  return s;
}

std::string format_words(std::span<const Word> words) {
  std::string s;
  for (const Word w : words) {
    if (!s.empty()) s += ' ';
    s += hex4(w);
  }
  return s;
}

std::string format_patterns(std::span<const WordPattern> words) {
  std::string s;
  for (const auto& w : words) {
    if (!s.empty()) s += ' ';
    s += w.to_string();
  }
  return s;
}

TraceError::TraceError(const std::string& file, std::size_t line, const std::string& what)
    : std::runtime_error(file + ":" + std::to_string(line) + ": " + what), file_(file), line_(line) {}

std::vector<WordPattern> parse_words(std::string_view field, const std::string& file,
                                     std::size_t line) {
  std::vector<WordPattern> out;
  for (const auto token : split_spaces(field)) {
    const auto slash = token.find('/');
    if (slash == std::string_view::npos) {
      out.push_back(parse_hex4(token, true, file, line));
      continue;
    }
    const WordPattern v = parse_hex4(token.substr(0, slash), false, file, line);
    const WordPattern m = parse_hex4(token.substr(slash + 1), false, file, line);
    out.push_back({static_cast<Word>(v.value & m.value), m.value});
  }
  if (out.empty()) fail(file, line, "a data row needs at least one word in each of m2s and s2m");
  return out;
}

Request parse_request(std::string_view text, const std::string& file, std::size_t line,
                      const Vocabulary& vocabulary) {
  const auto parts = split_spaces(text);
  if (parts.empty()) fail(file, line, "request: empty");
  Request r;
  const std::string_view verb = parts[0];
  auto pnr = [&](std::string_view s) {
    const auto n = parse_number(s);
    if (!n || *n < 0 || *n > 0xFFFF) {
      fail(file, line, "request: parameter number '" + std::string(s) + "' is not 0..65535");
    }
    return static_cast<std::uint16_t>(*n);
  };
  if (verb == "read" || verb == "describe") {
    if (parts.size() != 2) fail(file, line, "request: '" + std::string(verb) + "' takes one parameter number");
    r.kind = verb == "read" ? Request::Kind::read : Request::Kind::describe;
    r.parameter = pnr(parts[1]);
  } else if (verb == "write") {
    if (parts.size() != 3) fail(file, line, "request: 'write' takes a parameter number and a value");
    r.kind = Request::Kind::write;
    r.parameter = pnr(parts[1]);
    const auto v = parse_number(parts[2]);
    if (!v) fail(file, line, "request: write value '" + std::string(parts[2]) + "' is not a number");
    r.value = *v;
  } else if (verb == "state") {
    if (parts.size() != 2) fail(file, line, "request: 'state' takes one target");
    if (!known(parts[1], vocabulary.targets)) {
      fail(file, line, "request: state target '" + std::string(parts[1]) + "' is not one of " +
                           listed(vocabulary.targets));
    }
    r.kind = Request::Kind::state;
    r.target = std::string(parts[1]);
  } else {
    fail(file, line, "request: '" + std::string(verb) + "' is not one of read, write, describe, state");
  }
  return r;
}

Outcome parse_outcome(std::string_view text, const std::string& file, std::size_t line) {
  const auto parts = split_spaces(text);
  if (parts.empty()) fail(file, line, "outcome: empty");
  Outcome o;
  if (parts[0] == "ok") {
    o.kind = Outcome::Kind::ok;
    if (parts.size() == 2) {
      const auto v = parse_number(parts[1]);
      if (!v) fail(file, line, "outcome: value '" + std::string(parts[1]) + "' is not a number");
      o.value = *v;
    } else if (parts.size() > 2) {
      fail(file, line, "outcome: 'ok' takes at most one value");
    }
  } else if (parts[0] == "nak" || parts[0] == "timeout") {
    if (parts.size() != 1) fail(file, line, "outcome: '" + std::string(parts[0]) + "' takes no value");
    o.kind = parts[0] == "nak" ? Outcome::Kind::nak : Outcome::Kind::timeout;
  } else {
    fail(file, line, "outcome: '" + std::string(parts[0]) + "' is not one of ok, nak, timeout");
  }
  return o;
}

Trace parse(std::string_view text, const std::string& file, const Vocabulary& vocabulary) {
  Trace t;
  t.file = file;
  bool format_seen = false;
  bool device_seen = false;
  bool words_seen = false;
  bool in_body = false;
  bool after_gap = false;
  std::size_t m2s_words = 0;
  std::size_t s2m_words = 0;
  std::vector<std::string> pending_comments;
  std::vector<Event> pending_events;
  std::size_t line_no = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const auto nl = text.find('\n', pos);
    const std::string_view raw =
        text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
    ++line_no;
    const std::string_view line = trim(raw);
    if (line.empty()) continue;
    if (line.front() == '#') {
      const std::string_view body = trim(line.substr(1));
      const auto colon = body.find(':');
      const bool header_shape =
          colon != std::string_view::npos && colon > 0 &&
          body.substr(0, colon).find_first_of(" \t") == std::string_view::npos;
      if (!in_body && header_shape) {
        const std::string_view key = body.substr(0, colon);
        const std::string_view value = trim(body.substr(colon + 1));
        if (!format_seen) {
          if (key != "format") fail(file, line_no, "the first header must be 'format: ibs-trace 1'");
          if (value != kFormat) {
            fail(file, line_no, "format: '" + std::string(value) + "' is not '" +
                                    std::string(kFormat) + "'");
          }
          format_seen = true;
          continue;
        }
        if (key == "format") fail(file, line_no, "format: given twice");
        if (key == "device") device_seen = true;
        if (key == "words") words_seen = true;
        parse_header(t.header, key, value, file, line_no, vocabulary);
        continue;
      }
      if (!format_seen) fail(file, line_no, "the first header must be 'format: ibs-trace 1'");
      pending_comments.emplace_back(raw.substr(raw.find('#')));
      continue;
    }
    if (line.front() == '!') {
      // An event (trace-format.md, "Events"): between two data rows, never next to a gap.
      if (!format_seen) fail(file, line_no, "the first header must be 'format: ibs-trace 1'");
      if (t.rows.empty()) {
        fail(file, line_no, "an event must stand between two data rows; this one comes before the first row");
      }
      if (t.rows.back().gap) {
        fail(file, line_no, "an event cannot follow a gap '...': it would happen at no known step");
      }
      pending_events.push_back(parse_event(trim(line.substr(1)), file, line_no));
      continue;
    }
    // A data row.
    if (!format_seen) fail(file, line_no, "the first header must be 'format: ibs-trace 1'");
    if (!in_body) {
      if (!device_seen) fail(file, line_no, "header 'device' is missing before the first row");
      if (!words_seen) fail(file, line_no, "header 'words' is missing before the first row");
      in_body = true;
    }
    Row row;
    row.line = line_no;
    row.comments_before = std::move(pending_comments);
    pending_comments.clear();
    if (line == "..." && !pending_events.empty()) {
      fail(file, line_no, "a gap '...' cannot follow an event (line " + std::to_string(pending_events.back().line) +
                              "): the event would happen at no known step");
    }
    row.events_before = std::move(pending_events);
    pending_events.clear();
    if (line == "...") {
      if (t.rows.empty()) fail(file, line_no, "a gap '...' cannot be the first row");
      if (t.rows.back().gap) fail(file, line_no, "two gaps '...' in a row");
      row.gap = true;
      t.rows.push_back(std::move(row));
      after_gap = true;
      continue;
    }
    std::array<std::string_view, 3> fields{};
    std::string_view rest = line;
    for (std::size_t i = 0; i < 3; ++i) {
      const auto comma = rest.find(',');
      if (comma == std::string_view::npos) {
        if (i < 2) {
          fail(file, line_no, "a data row needs 'step, m2s, s2m[, remark]'; found " +
                                  std::to_string(i + 1) + " field(s)");
        }
        fields[i] = trim(rest);
        rest = {};
        break;
      }
      fields[i] = trim(rest.substr(0, comma));
      rest = rest.substr(comma + 1);
    }
    row.remark = std::string(trim(rest));
    if (fields[0] == "...") fail(file, line_no, "a gap '...' row carries no words");
    const auto step = parse_number(fields[0]);
    if (!step || *step < 0 || fields[0].find_first_not_of("0123456789") != std::string_view::npos) {
      fail(file, line_no, "step '" + std::string(fields[0]) + "' is not a decimal step number");
    }
    row.step = static_cast<std::uint64_t>(*step);
    if (t.rows.empty()) {
      if (row.step != 0) fail(file, line_no, "the first row must be step 0, not " + std::to_string(row.step));
    } else if (!after_gap) {
      // Steps without data (`! no-data N`) count: the row after them is N steps further on.
      std::uint64_t skipped = 0;
      for (const Event& e : row.events_before) skipped += e.steps;
      const std::uint64_t want = t.rows.back().step + 1 + skipped;
      if (row.step != want) {
        fail(file, line_no, "step " + std::to_string(row.step) + " should be " + std::to_string(want) +
                                (skipped == 0 ? " (steps increase by one; use '...' for a gap)"
                                              : " (the step after the previous row's, plus the " +
                                                    std::to_string(skipped) + " step(s) without data)"));
      }
    }
    after_gap = false;
    row.m2s = parse_words(fields[1], file, line_no);
    row.s2m = parse_words(fields[2], file, line_no);
    if (m2s_words == 0) {
      m2s_words = row.m2s.size();
      s2m_words = row.s2m.size();
    } else if (row.m2s.size() != m2s_words || row.s2m.size() != s2m_words) {
      fail(file, line_no, "row has " + std::to_string(row.m2s.size()) + " m2s and " +
                              std::to_string(row.s2m.size()) + " s2m words; earlier rows have " +
                              std::to_string(m2s_words) + " and " + std::to_string(s2m_words));
    }
    t.rows.push_back(std::move(row));
  }
  if (!format_seen) fail(file, line_no, "empty trace: the first header must be 'format: ibs-trace 1'");
  if (t.rows.empty()) fail(file, line_no, "the trace has no data rows");
  if (t.rows.back().gap) fail(file, t.rows.back().line, "a gap '...' cannot be the last row");
  if (!pending_events.empty()) {
    fail(file, pending_events.front().line, "an event must stand between two data rows; no row follows this one");
  }
  t.trailing_comments = std::move(pending_comments);
  return t;
}

Trace load(const std::string& path, const Vocabulary& vocabulary) {
  std::string text;
  try {
    text = read_text_file(path);
  } catch (const FileReadError& e) {
    throw TraceError(path, 0, e.what());
  }
  return parse(text, path, vocabulary);
}

std::string write(const Trace& t) {
  std::string out;
  const Header& h = t.header;
  out += "# format: ibs-trace 1\n";
  out += "# device: " + h.device + "\n";
  out += "# words: " + std::string(to_string(h.words)) + "\n";
  for (const HeaderSetting& s : h.settings) out += "# " + s.key + ": " + std::to_string(s.value) + "\n";
  if (h.init_given) out += "# init: " + std::string(to_string(h.init)) + "\n";
  if (h.request) out += "# request: " + to_string(*h.request) + "\n";
  if (h.request_at_given) out += "# request-at: " + std::to_string(h.request_at) + "\n";
  if (h.outcome) out += "# outcome: " + to_string(*h.outcome) + "\n";
  if (h.max_gap_given) out += "# max-gap: " + std::to_string(h.max_gap) + "\n";
  if (h.watchdog_ms) out += "# watchdog_ms: " + std::to_string(*h.watchdog_ms) + "\n";
  if (h.step_time) out += "# step-time: " + format_time(*h.step_time) + "\n";
  for (const DeviceSetting& d : h.device_settings) out += "# setting: " + d.name + " " + d.value + "\n";
  for (const Row& r : t.rows) {
    for (const auto& c : r.comments_before) out += c + "\n";
    for (const Event& e : r.events_before) out += write_event(e) + "\n";
    if (r.gap) {
      out += "...\n";
      continue;
    }
    out += std::to_string(r.step) + ", " + format_patterns(r.m2s) + ", " + format_patterns(r.s2m);
    if (!r.remark.empty()) out += ", " + r.remark;
    out += "\n";
  }
  for (const auto& c : t.trailing_comments) out += c + "\n";
  return out;
}

}  // namespace ibs::trace
