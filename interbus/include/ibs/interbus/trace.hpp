// The cycle trace format `ibs-trace 1` (../shared/specs/trace-format.md): reader, writer and the
// word patterns that expectations use. Reading and writing are configuration-time work (they
// allocate and throw TraceError); nothing here is on the cycle path.
#pragma once

#include "ibs/base/build.hpp"
#if IBS_EMBEDDED
#error "traces, replay and file reading are not in the embedded build (docs/embedding.md)"
#endif

#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/interbus/device_start.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"

namespace ibs::trace {

enum class WordsKind { comm, pd, pcp };
std::string_view to_string(WordsKind w);
// The `init` header's spelling: operational, power-on (DeviceStart::initialised), fault; "?" for
// DeviceStart::power_on, which no trace starts in.
std::string_view to_string(DeviceStart s);

struct Request {
  enum class Kind { read, write, describe, state };
  Kind kind = Kind::read;
  std::uint16_t parameter = 0;  // read, write, describe
  std::int64_t value = 0;       // write: the raw value
  std::string target;           // state: the DRIVECOM target's name ("enabled")

  friend bool operator==(const Request&, const Request&) = default;
};
std::string to_string(const Request& r);

struct Outcome {
  enum class Kind { ok, nak, timeout };
  Kind kind = Kind::ok;
  std::optional<std::int64_t> value;  // `ok VALUE`: the raw value read

  friend bool operator==(const Outcome&, const Outcome&) = default;
};
std::string to_string(const Outcome& o);

// An expected word: compared only in the bits of `mask` (`?` digits and `VALUE/MASK` clear bits).
struct WordPattern {
  Word value = 0;
  Word mask = 0xFFFF;

  static WordPattern exact(Word w) { return {w, 0xFFFF}; }
  [[nodiscard]] bool matches(Word w) const { return ((w ^ value) & mask) == 0; }
  [[nodiscard]] bool is_exact() const { return mask == 0xFFFF; }
  // Written back as the file would hold it: `0A3F`, `0?37` or `0437/FDFF`.
  [[nodiscard]] std::string to_string() const;
  friend bool operator==(const WordPattern&, const WordPattern&) = default;
};

std::string format_words(std::span<const Word> words);
std::string format_patterns(std::span<const WordPattern> words);

// Something that happened to the device that its words cannot show (trace-format.md, "Events"):
// a `! EVENT [text]` line between two data rows, after the previous row's step and before the
// next row's.
// `no-data N` stands for N steps (rows not written) in which the device got no valid data from the
// master; its timers run on. `write PNR VALUE` is a parameter changed through a channel the trace
// does not carry: the device's value is VALUE from the next step on, as if written through its
// own channel (the drive checks it; the format knows numbers only).
struct Event {
  enum class Kind { fault, fault_cleared, no_data, write };
  Kind kind = Kind::fault;
  std::string text;         // the free text after the event's name (and no-data's N; may be empty)
  std::size_t line = 0;     // 1-based line in the file (0 when built in memory)
  std::uint64_t steps = 0;  // no-data: N, 1..kMaxNoDataSteps; 0 for the other kinds
  std::uint16_t parameter = 0;  // write: PNR, 0..65535
  std::int64_t value = 0;       // write: VALUE, the raw value as a channel carries it (kMinWriteValue..kMaxWriteValue)

  friend bool operator==(const Event& a, const Event& b) {
    return a.kind == b.kind && a.text == b.text && a.steps == b.steps && a.parameter == b.parameter &&
           a.value == b.value;
  }
};
// The raw values a `! write` may carry: what a 32-bit value of a channel holds, read signed or not.
inline constexpr std::int64_t kMinWriteValue = -2147483648LL;
inline constexpr std::int64_t kMaxWriteValue = 4294967295LL;
std::string_view to_string(Event::Kind k);

struct Row {
  std::size_t line = 0;  // 1-based line in the file it came from (0 when built in memory)
  bool gap = false;      // a `...` row: no words, stands for 0..max-gap steps
  std::uint64_t step = 0;
  std::vector<WordPattern> m2s;
  std::vector<WordPattern> s2m;
  std::string remark;
  std::vector<std::string> comments_before;  // `#` comment lines that preceded the row
  std::vector<Event> events_before;          // events between the previous row and this one
};

// The most steps a `...` row may stand for (`max-gap`): 10 million steps are 2.8 hours of MC6000
// samples and 23 hours of VF1000 samples, far beyond any table, and bound the replay's work.
inline constexpr std::uint64_t kMaxGapLimit = 10'000'000;
// The most steps one `! no-data N` may stand for: the same bound as a gap's, for the same reason
// (it bounds the replay's work; 10 million steps are hours of any bus).
inline constexpr std::uint64_t kMaxNoDataSteps = kMaxGapLimit;
// `step-time` lies above 0 and is at most 1 s, the bounds of a scenario's bus cycle
// (docs/scenarios.md): an INTERBUS cycle or a drive's sample takes milliseconds.
inline constexpr Duration kMaxStepTime = std::chrono::seconds(1);

// A drive's own setting in the header, `# NAME: VALUE`: which names a drive kind takes, and in
// what range, is its declarations' (devices/settings.hpp), checked by the replay adapters; the
// format only knows an integer 0..255 and the line.
struct HeaderSetting {
  std::string key;
  int value = 0;
  std::size_t line = 0;  // 0: set in code

  friend bool operator==(const HeaderSetting&, const HeaderSetting&) = default;
};

// A device setting the recording ran with (`setting: NAME VALUE`, repeatable): NAME as the scenario
// file spells it, VALUE its text in the scenario's syntax without quotes ("1", "true", "2 s").
// Which names a drive takes and their ranges are its declarations' (devices/settings.hpp and the
// bus watchdog's reaction), checked by the trace validation (devices/trace_adapters.hpp).
struct DeviceSetting {
  std::string name;
  std::string value;
  std::size_t line = 0;  // 0: set in code

  friend bool operator==(const DeviceSetting& a, const DeviceSetting& b) {
    return a.name == b.name && a.value == b.value;
  }
};

struct Header {
  std::string device;  // the drive kind's name ("vf1000", "mc6000")
  WordsKind words = WordsKind::pd;
  // The drive's settings, in the vocabulary's order (as given, without one); written after
  // `words`.
  std::vector<HeaderSetting> settings;
  DeviceStart init = DeviceStart::operational;
  bool init_given = false;
  std::optional<Request> request;
  std::uint64_t request_at = 1;
  bool request_at_given = false;
  std::optional<Outcome> outcome;
  std::uint64_t max_gap = 100000;
  bool max_gap_given = false;
  // `watchdog_ms`: the device's bus watchdog as the recording ran it (the drive's range and "off"
  // value are its wing's, checked by the replay adapters); nullopt: the device's own default.
  std::optional<int> watchdog_ms;
  // `step-time`: the time one step stands for; nullopt: the adapters' own step time
  // (docs/replay.md, "What one step is").
  std::optional<Duration> step_time;
  // `setting: NAME VALUE` headers, in the file's order (written after `step-time`).
  std::vector<DeviceSetting> device_settings;
  // The line each header was read from (0 = not given), for errors found after parsing.
  struct Lines {
    std::size_t device = 0, words = 0, init = 0, request = 0, request_at = 0, outcome = 0, max_gap = 0,
                watchdog_ms = 0, step_time = 0;
  } lines;

  // A setting by name; nullptr when the header does not give it.
  [[nodiscard]] const HeaderSetting* setting(std::string_view key) const;
  // Gives (or replaces) a setting, appended after the others.
  void set_setting(std::string_view key, int value);
  // A `setting:` by name; nullptr when the header does not give it.
  [[nodiscard]] const DeviceSetting* device_setting(std::string_view name) const;
  // Gives (or replaces) a `setting:`, appended after the others.
  void set_device_setting(std::string_view name, std::string_view value);
};

struct Trace {
  std::string file;  // where it was read from, for messages
  Header header;
  std::vector<Row> rows;
  std::vector<std::string> trailing_comments;
};

// Every malformed input: what() is `FILE:LINE: what is wrong`.
class TraceError : public std::runtime_error {
 public:
  TraceError(const std::string& file, std::size_t line, const std::string& what);
  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] std::size_t line() const { return line_; }

 private:
  std::string file_;
  std::size_t line_;
};

// The names the layers above the format give meaning to: the drive kinds a `device` header may
// name (devices/registry.hpp) and the DRIVECOM targets of `request: state TARGET`
// (drivecom/status_word.hpp). An empty list accepts any single word; the layer that serves the
// trace then refuses what it does not know. The spans must outlive the call.
struct Vocabulary {
  std::span<const std::string_view> devices;
  std::span<const std::string_view> targets;
  // The drives' settings a header may give (`# NAME: VALUE`); empty: any key that is no other
  // header.
  std::span<const std::string_view> settings;
  // The names a `setting: NAME VALUE` header may give; empty: any name of the header's letters.
  std::span<const std::string_view> device_settings{};
};

// Parses a whole trace; `file` names it in errors.
Trace parse(std::string_view text, const std::string& file, const Vocabulary& vocabulary = {});
// Reads and parses a file; a file that cannot be read is a TraceError at line 0.
Trace load(const std::string& path, const Vocabulary& vocabulary = {});
// Writes a trace in the format `parse` reads (round trip: parse(write(t)) == t, less line numbers).
std::string write(const Trace& t);

// Parses one field of words (`0006 09C4 4000`), for tools and tests; throws TraceError.
std::vector<WordPattern> parse_words(std::string_view field, const std::string& file,
                                     std::size_t line);
// Parses `read 22`, `write 0x15 500`, `describe 45`, `state enabled`.
Request parse_request(std::string_view text, const std::string& file, std::size_t line,
                      const Vocabulary& vocabulary = {});
Outcome parse_outcome(std::string_view text, const std::string& file, std::size_t line);

}  // namespace ibs::trace
