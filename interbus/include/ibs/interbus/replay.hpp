// Replay of an `ibs-trace 1` file against one emulated side (../shared/specs/trace-format.md,
// "Timing convention", "Gaps", "Replay"). The engine is generic: each protocol supplies a
// DeviceSide or MasterSide adapter and an Explainer for its words; the engine owns the timing
// convention, the gaps, the comparisons and the messages, once for all of them.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/interbus/trace.hpp"

namespace ibs::trace {

// Explains words in a row for `decode` and for mismatch messages.
class Explainer {
 public:
  virtual ~Explainer() = default;
  // The words a row of this trace kind carries each way; decode() checks every row against
  // them as replay does, so that an explainer only ever sees rows of the right size.
  [[nodiscard]] virtual std::size_t m2s_words() const = 0;
  [[nodiscard]] virtual std::size_t s2m_words() const = 0;
  [[nodiscard]] virtual std::string explain_m2s(std::span<const Word> m2s) const = 0;
  [[nodiscard]] virtual std::string explain_s2m(std::span<const Word> s2m) const = 0;
  // A `! write PNR VALUE` in words ("409-BUTWD = 100 ms"); empty: nothing to add.
  [[nodiscard]] virtual std::string explain_write(std::uint16_t /*parameter*/, std::int64_t /*value*/) const {
    return {};
  }
};

// The device side of a trace: s2m[0] = initial(); s2m[k] = step(m2s[k-1]).
class DeviceSide {
 public:
  virtual ~DeviceSide() = default;
  [[nodiscard]] virtual std::size_t m2s_words() const = 0;
  [[nodiscard]] virtual std::size_t s2m_words() const = 0;
  virtual void initial(std::span<Word> s2m) = 0;
  virtual void step(std::span<const Word> m2s, std::span<Word> s2m) = 0;
  // Events (trace-format.md, "Events") the side can act on; the trace validation refuses a trace
  // with others (devices/trace_adapters.hpp).
  [[nodiscard]] virtual bool supports(Event::Kind /*kind*/) const { return false; }
  // The event happens now: after the previous row's step, before the next one's. `no-data` is
  // not applied: replay_device runs its steps through step_without_data().
  virtual void apply(const Event& /*event*/) {}
  // One step in which no valid data came from the master (`! no-data N`): the device keeps the
  // words it last took, its timers run on. Only called when supports(Event::Kind::no_data).
  virtual void step_without_data(std::span<Word> /*s2m*/) {}
};

// The master side of a trace: m2s[0] = initial(); m2s[k] = step(s2m[k-1]).
class MasterSide {
 public:
  virtual ~MasterSide() = default;
  [[nodiscard]] virtual std::size_t m2s_words() const = 0;
  [[nodiscard]] virtual std::size_t s2m_words() const = 0;
  virtual void initial(std::span<Word> m2s) = 0;
  // The trace's `request`, handed over at the start of step `request-at`.
  virtual void submit(const Request& request) = 0;
  // `row_m2s` is this step's m2s column of the file: words that are application data rather than
  // master logic (setpoints) are taken from it; protocol words must be computed, not copied.
  virtual void step(std::span<const Word> s2m, std::span<const WordPattern> row_m2s,
                    std::span<Word> m2s) = 0;
  // The master's report on the request so far; nullopt while it is still running.
  [[nodiscard]] virtual std::optional<Outcome> outcome() const = 0;
};

// A gap cannot match once the emulated side's words have stayed the same for this many steps of
// unchanged input: every emulated side settles within seconds (its longest timer is 10 s, a
// master's transition timeout), so 50 000 steps (50 s of MC6000 samples) of nothing is a gap that
// will never end, and replay says so instead of running to `max-gap`.
inline constexpr std::uint64_t kGapSettleSteps = 50'000;

// Where and how a replay failed, for a program to read (`ibs replay --json`, docs/replay.md); the
// same as the message says in words.
struct Mismatch {
  enum class Kind {
    row,      // a row's words in `column` are not the emulated side's
    gap,      // the emulated side did not reach the row after a gap (within max-gap, or settled)
    gap_hold, // during a gap the master did not keep sending the previous row's m2s
    outcome,  // after the last row the master's report is not the header's `outcome`
  };
  Kind kind = Kind::row;
  std::uint64_t step = 0;  // the row's step (row, gap: the row after the gap; outcome: the last row)
  std::size_t line = 0;    // that row's line in the file
  std::string column;      // "m2s" or "s2m"; empty for outcome
  std::vector<WordPattern> expected;  // the file's words in `column`; empty for outcome
  std::vector<Word> actual;           // the emulated side's words (in a gap its last ones)
  std::string expected_outcome;       // outcome: the header's
  std::optional<std::string> actual_outcome;  // outcome: the master's report; nullopt: none yet
};

std::string_view to_string(Mismatch::Kind kind);

struct ReplayResult {
  bool matched = false;
  std::size_t steps_matched = 0;  // rows compared and matched
  std::string message;            // the mismatch report, or `replay: N steps matched`
  std::optional<Mismatch> mismatch;  // set when !matched
};

// What a trace must be whichever side is emulated and whether it is decoded: an `outcome` needs
// a `request`, and the `request-at` step must be a row of the file. Throws TraceError naming the
// header's line. The devices' trace validation (devices/trace_adapters.hpp) calls it.
void validate(const Trace& t);

// Replays the trace against the device side; the trace's m2s column drives it.
// Throws TraceError when the trace does not fit the adapter (word counts, '?' in driving words).
ReplayResult replay_device(const Trace& t, DeviceSide& device, const Explainer& explain);
// Replays the trace against the master side; the trace's s2m column drives it.
ReplayResult replay_master(const Trace& t, MasterSide& master, const Explainer& explain);

// The trace with every row's remark replaced by the explainer's reading of its words
// (the original remark kept after ` | `), and every `! write` event's text by its reading
// (likewise), ready for write(). A row or event that already carries this reading is left as it
// is, so decode(decode(t)) == decode(t). Throws TraceError (FILE:LINE) for a
// row whose word counts are not the explainer's.
Trace decode(const Trace& t, const Explainer& explain);

}  // namespace ibs::trace
