// The trace reader (`ibs-trace 1`, ../shared/specs/trace-format.md) and everything behind it:
// arbitrary text is parsed; a trace the reader accepts is written and read back, decoded with
// its explainer (devices::make_explainer + trace::decode, as `ibs decode` does), and replayed
// against the project's device model and master logic (devices::make_device_side /
// make_master_side + trace::replay_device / replay_master, as `ibs replay` does).
//
// Asserts:
// - every refusal, at every stage, is a trace::TraceError whose what() is `FILE:LINE: message`
//   with this file, a line of the input (1..number of lines) and a message; anything else that
//   escapes (std::invalid_argument, std::out_of_range, ...) is a finding; so is a crash or an
//   out-of-bounds read (AddressSanitizer), e.g. an explainer reading past the end of a row;
// - a parsed trace has rows, and write() gives text that parses again and writes the same text
//   (the writer's round trip) -- `setting: NAME VALUE` headers and `! write PNR VALUE` events
//   included (issue 41);
// - the reader with the registry's vocabulary (devices::parse_trace, what `ibs` reads with)
//   refuses only with FILE:LINE, and what it accepts the plain reader accepts alike (its rows and
//   `setting:` headers);
// - decode() gives a trace that write() and parse() accept, with the same events (kind, steps,
//   parameter and value; only a write's text gains its reading);
// - replay ends: it runs at most `rows + gaps * (max-gap + 1) + no-data steps` steps, and a trace that the reader
//   accepts must not allow more than 10^10 of them (hours of replay: it would never end).
//   Each replay is given a budget of steps here so that an input runs in milliseconds; a replay
//   that needs more stops quietly unless the trace allows the endless kind.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "ibs/devices/trace_adapters.hpp"
#include "ibs/interbus/replay.hpp"
#include "ibs/interbus/trace.hpp"

namespace {

using namespace ibs;
using ibs::fuzz::fail;

const std::string kFile = "fuzz.trace";

// The steps one replay may take here before it is stopped.
constexpr std::uint64_t kStepBudget = 50'000;
// A trace accepted by the reader must not let a replay run longer than this.
constexpr double kEndlessSteps = 1e10;

struct BudgetExceeded {};

// Counts the steps of the emulated side; throws BudgetExceeded past the budget.
class CountingDevice final : public trace::DeviceSide {
 public:
  explicit CountingDevice(trace::DeviceSide& d) : d_(d) {}
  std::size_t m2s_words() const override { return d_.m2s_words(); }
  std::size_t s2m_words() const override { return d_.s2m_words(); }
  void initial(std::span<Word> s2m) override { d_.initial(s2m); }
  void step(std::span<const Word> m2s, std::span<Word> s2m) override {
    if (++steps_ > kStepBudget) throw BudgetExceeded{};
    d_.step(m2s, s2m);
  }
  bool supports(trace::Event::Kind kind) const override { return d_.supports(kind); }
  void apply(const trace::Event& e) override { d_.apply(e); }
  void step_without_data(std::span<Word> s2m) override {
    if (++steps_ > kStepBudget) throw BudgetExceeded{};
    d_.step_without_data(s2m);
  }

 private:
  trace::DeviceSide& d_;
  std::uint64_t steps_ = 0;
};

class CountingMaster final : public trace::MasterSide {
 public:
  explicit CountingMaster(trace::MasterSide& m) : m_(m) {}
  std::size_t m2s_words() const override { return m_.m2s_words(); }
  std::size_t s2m_words() const override { return m_.s2m_words(); }
  void initial(std::span<Word> m2s) override { m_.initial(m2s); }
  void submit(const trace::Request& r) override { m_.submit(r); }
  void step(std::span<const Word> s2m, std::span<const trace::WordPattern> row_m2s, std::span<Word> m2s) override {
    if (++steps_ > kStepBudget) throw BudgetExceeded{};
    m_.step(s2m, row_m2s, m2s);
  }
  std::optional<trace::Outcome> outcome() const override { return m_.outcome(); }

 private:
  trace::MasterSide& m_;
  std::uint64_t steps_ = 0;
};

// The most steps a replay of `t` may take.
double possible_steps(const trace::Trace& t) {
  double gaps = 0;
  double without_data = 0;  // the steps of `! no-data N`
  for (const trace::Row& r : t.rows) {
    gaps += r.gap ? 1 : 0;
    for (const trace::Event& e : r.events_before) without_data += static_cast<double>(e.steps);
  }
  return static_cast<double>(t.rows.size()) + gaps * (static_cast<double>(t.header.max_gap) + 1.0) + without_data;
}

// Runs one stage; a refusal must be a TraceError naming this file and one of its lines.
template <typename F>
void stage(const char* name, std::size_t lines, const trace::Trace* t, F&& f) {
  try {
    f();
  } catch (const trace::TraceError& e) {
    const std::string why = ibs::fuzz::file_line_problem(e.what(), kFile, lines);
    if (!why.empty()) fail(std::string(name) + ": the refusal '" + e.what() + "' " + why);
    if (e.file() != kFile || e.line() < 1 || e.line() > lines) {
      fail(std::string(name) + ": TraceError names " + e.file() + " line " + std::to_string(e.line()));
    }
  } catch (const BudgetExceeded&) {
    if (t != nullptr && possible_steps(*t) > kEndlessSteps) {
      fail(std::string(name) + ": the reader accepted a trace whose replay may run " +
           std::to_string(possible_steps(*t)) + " steps (max-gap " + std::to_string(t->header.max_gap) +
           "): it does not end");
    }
  } catch (const std::exception& e) {
    fail(std::string(name) + ": an exception other than TraceError escaped: " + e.what());
  } catch (...) {
    fail(std::string(name) + ": a non-standard exception escaped");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::size_t lines = ibs::fuzz::count_lines(text);
  std::unique_ptr<trace::Trace> t;
  stage("parse", lines, nullptr, [&] { t = std::make_unique<trace::Trace>(trace::parse(text, kFile)); });
  if (!t) return 0;
  if (t->rows.empty()) fail("parse accepted a trace without rows");
  for (const trace::Row& r : t->rows) {
    if (r.line < 1 || r.line > lines) fail("a row names line " + std::to_string(r.line));
  }

  // The registry's vocabulary: the names it knows (drives, targets, settings) on their lines.
  std::unique_ptr<trace::Trace> named;
  stage("parse with the vocabulary", lines, nullptr,
        [&] { named = std::make_unique<trace::Trace>(devices::parse_trace(text, kFile)); });
  if (named && (named->rows.size() != t->rows.size() || named->header.device_settings != t->header.device_settings)) {
    fail("the vocabulary's reader read another trace");
  }

  // The writer's round trip.
  const std::string written = trace::write(*t);
  try {
    const trace::Trace again = trace::parse(written, kFile);
    if (trace::write(again) != written) fail("write(parse(write(t))) differs from write(t):\n" + written);
  } catch (const std::exception& e) {
    fail(std::string("the written trace does not parse again: ") + e.what() + "\n" + written);
  }

  std::unique_ptr<trace::Explainer> explain;
  stage("make_explainer", lines, t.get(), [&] { explain = devices::make_explainer(*t); });
  if (!explain) return 0;
  stage("decode", lines, t.get(), [&] {
    const trace::Trace decoded = trace::decode(*t, *explain);
    for (std::size_t i = 0; i < t->rows.size(); ++i) {
      const auto& before = t->rows[i].events_before;
      const auto& after = decoded.rows[i].events_before;
      if (before.size() != after.size()) fail("decode changed the events of a row");
      for (std::size_t k = 0; k < before.size(); ++k) {
        if (before[k].kind != after[k].kind || before[k].steps != after[k].steps ||
            before[k].parameter != after[k].parameter || before[k].value != after[k].value) {
          fail("decode changed an event");
        }
      }
    }
    const std::string out = trace::write(decoded);
    try {
      (void)trace::parse(out, kFile);
    } catch (const std::exception& e) {
      fail(std::string("the decoded trace does not parse: ") + e.what() + "\n" + out);
    }
  });
  stage("replay device", lines, t.get(), [&] {
    const std::unique_ptr<trace::DeviceSide> device = devices::make_device_side(*t);
    CountingDevice counting(*device);
    (void)trace::replay_device(*t, counting, *explain);
  });
  stage("replay master", lines, t.get(), [&] {
    const std::unique_ptr<trace::MasterSide> master = devices::make_master_side(*t);
    CountingMaster counting(*master);
    (void)trace::replay_master(*t, counting, *explain);
  });
  return 0;
}
