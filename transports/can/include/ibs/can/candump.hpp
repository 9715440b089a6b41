// candump's log format (can-utils `candump -l`, read back by `canplayer`), the frame log of
// `ibs canlust ... --log` and one input of `ibs decode`: one frame a line,
//
//   (SECONDS.MICROS) IFACE ID#DATA        e.g. "(1700000000.123456) can0 297#0F00008014"
//
// ID three hex digits (a standard identifier; eight are an extended one), DATA 0..8 bytes in two
// hex digits each, or R / R0..R8 for a remote frame; ID##... is a CAN FD frame. Extended and CAN FD
// frames are lines of a log but no CANLust frames (CM-CAN1 uses 11-bit identifiers only).
// Floor 4 beside the transports that produce such logs; no I/O here: text in, text out.
#pragma once

#include <chrono>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/canlust/frame.hpp"

namespace ibs::can {

// The line of one frame sent or received at `at` (wall-clock time) on `interface_name`.
std::string candump_line(const canlust::CanFrame& f, std::chrono::system_clock::time_point at,
                         std::string_view interface_name);

struct CandumpRecord {
  std::string time;  // as written, SECONDS.MICROS
  std::string interface_name;
  bool classic = true;  // false: an extended-identifier or CAN FD frame; `frame` is then empty
  canlust::CanFrame frame{};
};

// One line read: the record, or what is wrong with the line (`error`, static text).
struct CandumpParsed {
  std::optional<CandumpRecord> record;
  std::string_view error;
};
CandumpParsed read_candump_line(std::string_view line);
// The record alone; nullopt when the line is none.
std::optional<CandumpRecord> parse_candump_line(std::string_view line);

// A whole log, from its text lines (without their '\n'). Blank lines are skipped; reading stops
// at the first line that is not a candump line, which `error` names (1-based number, the line as
// it was, what is wrong).
struct CandumpEntry {
  std::size_t line = 0;
  std::string text;  // the line without trailing blanks and CR
  CandumpRecord record;
};
struct CandumpError {
  std::size_t line = 0;
  std::string text;
  std::string what;
};
struct CandumpLog {
  std::vector<CandumpEntry> entries;
  std::optional<CandumpError> error;
};
CandumpLog read_candump_log(std::span<const std::string> lines);
// Whether the lines are meant as a candump log: the first line that is not blank is a candump
// line (how `ibs decode` tells one from a trace file).
bool is_candump_log(std::span<const std::string> lines);

}  // namespace ibs::can
