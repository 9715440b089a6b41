#include "ibs/od/data_set.hpp"

#include <utility>

namespace ibs::od {

namespace {

bool space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// The words of a line without its comment (at most three are needed to tell).
std::size_t words(std::string_view line, std::string_view (&w)[3]) {
  if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
  std::size_t n = 0;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && space(line[i])) ++i;
    const std::size_t b = i;
    while (i < line.size() && !space(line[i])) ++i;
    if (i > b) {
      if (n < 3) w[n] = line.substr(b, i - b);
      ++n;
    }
  }
  return n;
}

}  // namespace

DataSet parse_data_set(std::string_view text, const DataSetResolver& resolve) {
  DataSet p;
  const auto fail = [&p](std::size_t line, std::string why) {
    p.records.clear();
    p.error_line = line;
    p.error = std::move(why);
    return std::move(p);
  };
  std::size_t n = 0;
  while (!text.empty()) {
    ++n;
    const auto nl = text.find('\n');
    const std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    if (line.size() > kMaxDataSetLine) {
      return fail(n, "the line has " + std::to_string(line.size()) + " characters, at most " +
                         std::to_string(kMaxDataSetLine) + " are read");
    }
    if (line.find('\0') != std::string_view::npos)
      return fail(n, "a NUL byte: this is no data set text");
    std::string_view w[3];
    const std::size_t count = words(line, w);
    if (count == 0) continue;
    if (count != 2) return fail(n, "expected `PARAM VALUE`");
    ResolvedRecord r = resolve(w[0], w[1]);
    if (!r.error.empty()) return fail(n, std::move(r.error));
    for (const DataSetRecord& earlier : p.records) {
      if (earlier.number == r.number) {
        return fail(n, "parameter " + std::to_string(r.number) + " is given twice (first on line " +
                           std::to_string(earlier.line) + ")");
      }
    }
    if (p.records.size() == kMaxDataSetRecords)
      return fail(n, "more than " + std::to_string(kMaxDataSetRecords) + " records");
    p.records.push_back({r.number, r.raw, n});
  }
  if (p.records.empty()) return fail(0, "no `PARAM VALUE` line: the data set is empty");
  return p;
}

DataSet parse_data_set(std::string_view text, const Dictionary& dictionary,
                       const DataSetOptions& options) {
  const auto resolve = [&](std::string_view param, std::string_view value) -> ResolvedRecord {
    const Entry* e = dictionary.find(param);
    if (e == nullptr) {
      return {0, 0,
              "'" + std::string(param) + "' is not a" +
                  (options.title.empty() ? std::string(" parameter")
                                         : " " + std::string(options.title) + " parameter")};
    }
    if (!e->in_data_set) {
      return {0, 0,
              display_name(*e, options.style) +
                  " cannot be part of a data set (it is not Card Writeable)"};
    }
    ParsedValue v = parse_value(*e, value, {options.check_limits, options.style});
    if (!v) return {0, 0, std::move(v.error)};
    return {e->number, *v.raw, {}};
  };
  return parse_data_set(text, resolve);
}

}  // namespace ibs::od
