// A Value Change Dump writer (IEEE 1364-2005, section 18): the simulator's recording format, read
// by gtkwave and every other waveform viewer.
//
// Use: declare every signal first, in named scopes (one module per device), then record. change()
// sets a signal's value at the current time; advance() closes the current time and writes the
// signals whose value differs from the one last written, under one `#<time>` line. The first
// time written carries every signal in a $dumpvars block. Time is ibs::Time, so the timescale is
// 1 ns and every time is written exactly.
//
// Signal kinds:
//  - wire:  a vector of 1..64 bits (bus words, 1-bit flags), written `b<bits> <id>` with leading
//           zeros dropped (section 18 fills a shorter 0/1 value with 0s on the left), or `0<id>` /
//           `1<id>` for one bit;
//  - real:  a double (speeds in rpm or Hz), written `r<value> <id>` in the shortest form that
//           reads back to the same double;
//  - state: an enumeration, written as a vector of its state number. The standard has no string
//           type, so the names travel in a gtkwave translate filter (translate_filter()); the
//           vector is a whole number of hex digits wide, so the filter's keys are exactly what
//           gtkwave shows in its default hex format (docs/vcd.md).
//
// Recording is not the cycle path: writing allocates (a growing output buffer, the first time a
// signal changes within a time step), and misuse throws VcdError. It is built for millions of
// changes: a change is an index lookup and a compare, and output goes out in 64 KiB blocks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_set>
#include <vector>

#include "ibs/base/time.hpp"

namespace ibs::vcd {

// A misuse of the writer (bad name, value too wide, time going back, declaring after recording
// started) or a failed write; the message says which signal and what.
class VcdError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Handles returned by the declarations; only valid with the writer that made them.
struct WireSignal {
  std::uint32_t index = 0;
};
struct RealSignal {
  std::uint32_t index = 0;
};
struct StateSignal {
  std::uint32_t index = 0;
};

// Text of the header sections. An empty date or comment leaves its section out; an empty version
// writes "ibs <project version>".
struct VcdHeader {
  std::string date;
  std::string version;
  std::string comment;
};

// The only timescale: ibs::Time counts nanoseconds.
inline constexpr std::string_view kTimescale = "1ns";
inline constexpr unsigned kMaxWireWidth = 64;

// The identifier code of the index-th signal: printable ASCII 33..126 ('!'..'~') as a bijective
// base-94 number, least significant character first: 0 -> "!", 93 -> "~", 94 -> "!!",
// 8929 -> "~~", 8930 -> "!!!". Distinct indices get distinct codes; a code ends at the
// whitespace or line end after it, so codes of different lengths do not clash.
std::string identifier_code(std::size_t index);

class VcdWriter {
 public:
  explicit VcdWriter(std::ostream& out, VcdHeader header = {});
  // Finishes the dump if finish() was not called (errors are swallowed here; call finish() to
  // see them).
  ~VcdWriter();
  // Holds the stream by reference: neither copied nor moved (std::optional::emplace or
  // std::unique_ptr for a writer made later).
  VcdWriter(const VcdWriter&) = delete;
  VcdWriter& operator=(const VcdWriter&) = delete;
  VcdWriter(VcdWriter&&) = delete;
  VcdWriter& operator=(VcdWriter&&) = delete;

  // --- declarations (before the first change(), advance() or finish()) ----------------------
  // Names: letters, digits and '_' only, unique within their scope.

  // Opens `$scope module <name>`; scopes nest.
  void begin_scope(std::string_view name);
  void end_scope();

  // A vector of `width` bits (1..64), `initial` must fit.
  WireSignal add_wire(std::string_view name, unsigned width, std::uint64_t initial = 0);
  RealSignal add_real(std::string_view name, double initial = 0.0);
  // An enumeration with the given state names (at least one; printable, without leading or
  // trailing blanks), state numbers 0..size-1. The vector is 4 * ceil(bits / 4) wide.
  StateSignal add_state(std::string_view name, std::vector<std::string> state_names,
                        std::uint64_t initial = 0);

  // Writes the header up to $enddefinitions. Called by the first change(), advance() or
  // finish(); throws when a scope is still open.
  void end_definitions();

  // --- recording --------------------------------------------------------------------------
  // The value of a signal at now(). Several changes within one time step: the last one counts;
  // a value equal to the one last written writes nothing.
  void change(WireSignal s, std::uint64_t value);
  void change(RealSignal s, double value);
  void change(StateSignal s, std::uint64_t state);
  template <class E>
  requires std::is_enum_v<E>
  void change(StateSignal s, E state) {
    change(s, static_cast<std::uint64_t>(static_cast<std::underlying_type_t<E>>(state)));
  }

  // Closes the time step at now() (writes its changes) and moves to t >= now().
  void advance(Time t);
  // Writes the last time step and a closing `#<now>` (so a viewer shows the dump up to now()),
  // flushes the stream; throws VcdError when the stream failed. Later calls do nothing; later
  // changes throw.
  void finish();

  // --- gtkwave translate filter ------------------------------------------------------------
  // One line per state, "<hex state number> <name>", in the digits gtkwave's hex format shows
  // for this vector, after '#' comment lines naming the signal.
  std::string translate_filter(StateSignal s) const;

  // --- introspection -----------------------------------------------------------------------
  Time now() const { return now_; }
  std::string_view identifier(WireSignal s) const { return info(s.index).id; }
  std::string_view identifier(RealSignal s) const { return info(s.index).id; }
  std::string_view identifier(StateSignal s) const { return info(s.index).id; }
  // "mc6000.status_word": the scopes and the name, '.'-separated.
  std::string_view path(WireSignal s) const { return info(s.index).path; }
  std::string_view path(RealSignal s) const { return info(s.index).path; }
  std::string_view path(StateSignal s) const { return info(s.index).path; }
  unsigned width(WireSignal s) const { return info(s.index).width; }
  unsigned width(StateSignal s) const { return info(s.index).width; }
  std::size_t signal_count() const { return signals_.size(); }
  // Value lines written after the $dumpvars block.
  std::size_t changes_written() const { return changes_written_; }

 private:
  enum class Kind : std::uint8_t { wire, real, state };
  struct Signal {
    Kind kind = Kind::wire;
    unsigned width = 1;
    bool dirty = false;
    std::uint64_t pending = 0;  // value at now(); a real's bit pattern
    std::uint64_t written = 0;  // value last written
    std::string id;
    std::string path;
    std::string name;
    std::vector<std::string> states;  // state signals only
  };
  // The header text as declared, in order: scope opens/closes and vars.
  struct Decl {
    enum class What : std::uint8_t { scope, upscope, var } what;
    std::string scope_name;
    std::uint32_t signal = 0;
  };

  const Signal& info(std::uint32_t index) const;
  Signal& checked(std::uint32_t index, Kind kind, const char* what);
  std::uint32_t declare(std::string_view name, Kind kind, unsigned width, std::uint64_t initial);
  void require_declaring(std::string_view what) const;
  void require_recording();
  void mark(std::uint32_t index, std::uint64_t bits);
  void flush_step();
  void write_time(Time t);
  void write_value(const Signal& s, std::uint64_t bits);
  void spill(bool force);

  std::ostream& out_;
  VcdHeader header_;
  std::vector<Signal> signals_;
  std::vector<Decl> decls_;
  std::vector<std::string> scope_stack_;
  std::unordered_set<std::string> paths_;  // signal and scope paths, for uniqueness
  std::vector<std::uint32_t> dirty_;       // signals changed in the current time step
  std::string buf_;
  Time now_{0};
  Time last_time_written_{0};
  bool header_written_ = false;
  bool dumped_ = false;  // the $dumpvars block is out
  bool finished_ = false;
  std::size_t changes_written_ = 0;
};

}  // namespace ibs::vcd
