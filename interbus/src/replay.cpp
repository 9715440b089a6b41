#include "ibs/interbus/replay.hpp"

#include <vector>

namespace ibs::trace {

namespace {

std::vector<Word> values_of(const std::vector<WordPattern>& p) {
  std::vector<Word> v;
  v.reserve(p.size());
  for (const auto& w : p) v.push_back(w.value);
  return v;
}

bool matches(const std::vector<WordPattern>& expected, std::span<const Word> actual) {
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (!expected[i].matches(actual[i])) return false;
  }
  return true;
}

bool all_exact(const std::vector<WordPattern>& p) {
  for (const auto& w : p) {
    if (!w.is_exact()) return false;
  }
  return true;
}

std::string where(const Trace& t, const Row& r) {
  return "step " + std::to_string(r.step) + " (" + t.file + ":" + std::to_string(r.line) + ")";
}

enum class Column { m2s, s2m };

std::string explain(const Explainer& e, Column c, std::span<const Word> w) {
  return c == Column::m2s ? e.explain_m2s(w) : e.explain_s2m(w);
}

std::string mismatch(const Trace& t, const Row& r, Column c, const std::vector<WordPattern>& expected,
                     std::span<const Word> actual, const Explainer& e) {
  const std::string col = c == Column::m2s ? "m2s" : "s2m";
  const auto expected_values = values_of(expected);
  std::string m = "mismatch at " + where(t, r) + " in " + col + ":\n";
  m += "  expected " + format_patterns(expected) + "  " + explain(e, c, expected_values);
  if (!all_exact(expected)) m += " (masked bits shown as 0)";
  m += "\n  actual   " + format_words(actual) + "  " + explain(e, c, actual);
  if (!r.remark.empty()) m += "\n  remark: " + r.remark;
  return m;
}

void check_counts(const Trace& t, std::size_t m2s_words, std::size_t s2m_words) {
  for (const Row& r : t.rows) {
    if (r.gap) continue;
    if (r.m2s.size() != m2s_words || r.s2m.size() != s2m_words) {
      throw TraceError(t.file, r.line,
                       "this " + t.header.device + " with words: " +
                           std::string(to_string(t.header.words)) + " exchanges " +
                           std::to_string(m2s_words) + " m2s and " + std::to_string(s2m_words) +
                           " s2m words per row; the row has " + std::to_string(r.m2s.size()) +
                           " and " + std::to_string(r.s2m.size()));
    }
  }
}

ReplayResult matched(std::size_t n) {
  return {true, n, "replay: " + std::to_string(n) + " steps matched", std::nullopt};
}

ReplayResult failed(std::size_t n, std::string message, Mismatch what) {
  return {false, n, std::move(message), std::move(what)};
}

Mismatch words_mismatch(Mismatch::Kind kind, const Row& r, Column c, const std::vector<WordPattern>& expected,
                        std::span<const Word> actual) {
  Mismatch m;
  m.kind = kind;
  m.step = r.step;
  m.line = r.line;
  m.column = c == Column::m2s ? "m2s" : "s2m";
  m.expected = expected;
  m.actual.assign(actual.begin(), actual.end());
  return m;
}

Mismatch outcome_mismatch(const Row& last, const Outcome& expected, const std::optional<Outcome>& actual) {
  Mismatch m;
  m.kind = Mismatch::Kind::outcome;
  m.step = last.step;
  m.line = last.line;
  m.expected_outcome = to_string(expected);
  if (actual) m.actual_outcome = to_string(*actual);
  return m;
}

}  // namespace

std::string_view to_string(Mismatch::Kind kind) {
  switch (kind) {
    case Mismatch::Kind::row: return "row";
    case Mismatch::Kind::gap: return "gap";
    case Mismatch::Kind::gap_hold: return "gap-hold";
    case Mismatch::Kind::outcome: return "outcome";
  }
  return "row";
}

void validate(const Trace& t) {
  const Header& h = t.header;
  if (h.outcome && !h.request) {
    throw TraceError(t.file, h.lines.outcome, "header 'outcome' needs a 'request' to judge");
  }
  if (h.request) {
    bool found = false;
    for (const Row& r : t.rows) found = found || (!r.gap && r.step == h.request_at);
    if (!found) {
      throw TraceError(t.file, h.lines.request_at != 0 ? h.lines.request_at : h.lines.request,
                       "request-at: step " + std::to_string(h.request_at) + " does not appear in the trace");
    }
  }
}

ReplayResult replay_device(const Trace& t, DeviceSide& device, const Explainer& e) {
  validate(t);
  check_counts(t, device.m2s_words(), device.s2m_words());
  for (const Row& r : t.rows) {
    for (const Event& ev : r.events_before) {
      if (!device.supports(ev.kind)) {
        throw TraceError(t.file, ev.line,
                         "event '" + std::string(to_string(ev.kind)) + "': the emulated " +
                             t.header.device + " with words: " +
                             std::string(to_string(t.header.words)) + " cannot act on it");
      }
    }
  }
  for (const Row& r : t.rows) {
    if (r.gap) continue;
    for (const auto& w : r.m2s) {
      if (!w.is_exact()) {
        throw TraceError(t.file, r.line,
                         "m2s word '" + w.to_string() +
                             "' is a pattern; with --emulate device the m2s column drives the "
                             "device and must hold plain words");
      }
    }
  }
  std::vector<Word> s2m(device.s2m_words());
  std::vector<Word> prev_m2s;
  std::size_t n = 0;
  bool pending_gap = false;
  for (const Row& r : t.rows) {
    if (r.gap) {
      pending_gap = true;
      continue;
    }
    // The steps between the previous row and this one, in the file's order (trace-format.md,
    // "Timing convention", "Events"): each step answers the m2s of the step before it -- the
    // previous row's words first, then, for each step without data (`no-data N`), nothing the
    // device may take. An event acts before the step that follows it.
    bool data_pending = true;  // the step still to come answers the previous row's m2s
    for (const Event& ev : r.events_before) {
      if (ev.kind != Event::Kind::no_data) {
        device.apply(ev);
        continue;
      }
      for (std::uint64_t k = 0; k < ev.steps; ++k) {
        if (data_pending) {
          device.step(prev_m2s, s2m);
        } else {
          device.step_without_data(s2m);
        }
        data_pending = false;
      }
    }
    if (n == 0) {
      device.initial(s2m);
    } else if (!data_pending) {
      device.step_without_data(s2m);
    } else if (!pending_gap) {
      device.step(prev_m2s, s2m);
    } else {
      // During a gap the master keeps sending the previous row's m2s; s2m is not checked until
      // it matches this row (trace-format.md, "Gaps").
      bool found = false;
      std::uint64_t unchanged = 0;
      std::vector<Word> before = s2m;
      for (std::uint64_t g = 0; g <= t.header.max_gap; ++g) {
        device.step(prev_m2s, s2m);
        if (matches(r.s2m, s2m)) {
          found = true;
          break;
        }
        unchanged = s2m == before ? unchanged + 1 : 0;
        before = s2m;
        if (unchanged >= kGapSettleSteps) {
          return failed(n, "gap before " + where(t, r) + ": s2m cannot reach " + format_patterns(r.s2m) +
                               ": the device's words have not changed for " + std::to_string(kGapSettleSteps) +
                               " steps (" + std::to_string(g + 1) + " into the gap)\n  last actual " +
                               format_words(s2m) + "  " + e.explain_s2m(s2m),
                      words_mismatch(Mismatch::Kind::gap, r, Column::s2m, r.s2m, s2m));
        }
      }
      if (!found) {
        return failed(n, "gap before " + where(t, r) + ": s2m did not reach " +
                             format_patterns(r.s2m) + " within max-gap " +
                             std::to_string(t.header.max_gap) + " steps\n  last actual " +
                             format_words(s2m) + "  " + e.explain_s2m(s2m),
                      words_mismatch(Mismatch::Kind::gap, r, Column::s2m, r.s2m, s2m));
      }
      pending_gap = false;
    }
    if (!matches(r.s2m, s2m)) return failed(n, mismatch(t, r, Column::s2m, r.s2m, s2m, e),
                                             words_mismatch(Mismatch::Kind::row, r, Column::s2m, r.s2m, s2m));
    prev_m2s = values_of(r.m2s);
    ++n;
  }
  return matched(n);
}

ReplayResult replay_master(const Trace& t, MasterSide& master, const Explainer& e) {
  validate(t);
  check_counts(t, master.m2s_words(), master.s2m_words());
  const Header& h = t.header;
  std::vector<Word> m2s(master.m2s_words());
  std::vector<Word> prev_s2m;
  const Row* prev_row = nullptr;
  std::size_t n = 0;
  bool pending_gap = false;
  bool submitted = false;
  auto submit_if_due = [&](const Row& r) {
    if (h.request && !submitted && r.step == h.request_at) {
      master.submit(*h.request);
      submitted = true;
    }
  };
  for (const Row& r : t.rows) {
    if (r.gap) {
      pending_gap = true;
      continue;
    }
    submit_if_due(r);
    if (n == 0) {
      master.initial(m2s);
    } else if (!pending_gap) {
      master.step(prev_s2m, r.m2s, m2s);
    } else {
      // The device's words during a gap are unknown: the master keeps seeing the previous row's
      // s2m and must keep sending the previous row's m2s until its output matches this row.
      bool found = false;
      std::uint64_t unchanged = 0;
      std::vector<Word> before = m2s;
      for (std::uint64_t g = 0; g <= h.max_gap; ++g) {
        master.step(prev_s2m, prev_row->m2s, m2s);
        if (matches(r.m2s, m2s)) {
          found = true;
          break;
        }
        unchanged = m2s == before ? unchanged + 1 : 0;
        before = m2s;
        if (unchanged >= kGapSettleSteps) {
          return failed(n, "gap before " + where(t, r) + ": m2s cannot reach " + format_patterns(r.m2s) +
                               ": the master's words have not changed for " + std::to_string(kGapSettleSteps) +
                               " steps (" + std::to_string(g + 1) + " into the gap)",
                      words_mismatch(Mismatch::Kind::gap, r, Column::m2s, r.m2s, m2s));
        }
        if (!matches(prev_row->m2s, m2s)) {
          return failed(n, "during the gap before " + where(t, r) +
                               " the master must keep sending the previous row's m2s " +
                               format_patterns(prev_row->m2s) + "\n  actual " + format_words(m2s) +
                               "  " + e.explain_m2s(m2s),
                      words_mismatch(Mismatch::Kind::gap_hold, r, Column::m2s, prev_row->m2s, m2s));
        }
      }
      if (!found) {
        return failed(n, "gap before " + where(t, r) + ": m2s did not reach " +
                             format_patterns(r.m2s) + " within max-gap " +
                             std::to_string(h.max_gap) + " steps",
                      words_mismatch(Mismatch::Kind::gap, r, Column::m2s, r.m2s, m2s));
      }
      pending_gap = false;
    }
    if (!matches(r.m2s, m2s)) return failed(n, mismatch(t, r, Column::m2s, r.m2s, m2s, e),
                                             words_mismatch(Mismatch::Kind::row, r, Column::m2s, r.m2s, m2s));
    prev_s2m = values_of(r.s2m);
    prev_row = &r;
    ++n;
  }
  if (h.outcome) {
    // The master reads the last row's s2m in one more step, then must have its report ready.
    master.step(prev_s2m, prev_row->m2s, m2s);
    const auto got = master.outcome();
    if (!got) {
      return failed(n, "after the last row (" + t.file + ":" + std::to_string(prev_row->line) +
                           ") the master reports no outcome yet; expected '" +
                           to_string(*h.outcome) + "'",
                    outcome_mismatch(*prev_row, *h.outcome, got));
    }
    if (!(*got == *h.outcome)) {
      return failed(n, "after the last row (" + t.file + ":" + std::to_string(prev_row->line) +
                           ") the master reports '" + to_string(*got) + "'; expected '" +
                           to_string(*h.outcome) + "'",
                    outcome_mismatch(*prev_row, *h.outcome, got));
    }
  }
  return matched(n);
}

Trace decode(const Trace& t, const Explainer& e) {
  validate(t);
  check_counts(t, e.m2s_words(), e.s2m_words());
  Trace out = t;
  for (Row& r : out.rows) {
    for (Event& ev : r.events_before) {
      if (ev.kind != Event::Kind::write) continue;
      std::string text = e.explain_write(ev.parameter, ev.value);
      if (text.empty() || ev.text == text || ev.text.rfind(text + " | ", 0) == 0) continue;
      if (!ev.text.empty()) text += " | " + ev.text;
      ev.text = std::move(text);
    }
    if (r.gap) continue;
    const auto m = values_of(r.m2s);
    const auto s = values_of(r.s2m);
    std::string remark = "m2s: " + e.explain_m2s(m);
    if (!all_exact(r.m2s)) remark += " (masked bits shown as 0)";
    remark += "; s2m: " + e.explain_s2m(s);
    if (!all_exact(r.s2m)) remark += " (masked bits shown as 0)";
    // A row decoded before (the same reading, with or without an original remark after ` | `)
    // keeps its remark: decoding a decoded file changes nothing.
    const bool decoded_before =
        r.remark == remark || r.remark.rfind(remark + " | ", 0) == 0;
    if (decoded_before) continue;
    if (!r.remark.empty()) remark += " | " + r.remark;
    r.remark = std::move(remark);
  }
  return out;
}

}  // namespace ibs::trace
