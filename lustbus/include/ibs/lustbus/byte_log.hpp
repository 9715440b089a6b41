// Reading a LUSTBUS byte log (docs/lustbus.md, "Reading a byte log"): the `--log` file of
// `ibs lustbus ...`, whose format is the serial transport's (docs/dfs1.md, "Byte log"):
//
//   ibs-serial-log 1
//   <seconds> <tx|rx> <PORT> <bytes as two hex digits each>
//
// The host's side is the one that sends EOT first (3: every telegram begins with it): rx in the
// log of `emulate`, tx in that of a host command. Its bytes are split into ENQUIRY (6.1) and SELECT
// (6.2), the other side's into answers (LUSTBUS manual 2.2), and each explained: address, CODE and the
// parameter it names, VALUE as the parameter's type reads it, BCC checked, NAK's cause where
// 85-SIOF says it. Sans-I/O and configuration-time code: text lines in, text out (allocates).
// lustbus/ knows no drive: the names, units and types of parameters come from `ParameterLookup`,
// which the caller answers from the drives' tables.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::lustbus {

inline constexpr std::string_view kByteLogHeader = "ibs-serial-log 1";

// A parameter as its drive's table has it.
struct ParameterFacts {
  std::uint16_t number = 0;
  std::string name;
  std::string unit;  // empty: none
  DataType type = DataType::usign16;
};
// The parameter `number` of a drive of family `f`; nullopt when its table has none.
using ParameterLookup = std::function<std::optional<ParameterFacts>(Family f, std::uint16_t number)>;

struct ByteLogError {
  std::size_t line = 0;  // the file's line number (the header is 1); 0: the log as a whole
  std::string what;
};

struct ByteLogReading {
  bool host_tx = false;   // the host's side: tx, or rx
  std::string host_port;  // the PORT of the line with the host's first EOT
  std::string text;       // the telegrams and answers explained, one a line
  std::optional<ByteLogError> error;  // a malformed line, or no EOT at all; `text` is then empty
};

// `lines`: the log's lines after its header (kByteLogHeader), without their '\n'. Empty lines are
// skipped.
ByteLogReading read_byte_log(std::span<const std::string> lines, const ParameterLookup& lookup);

// Bytes one side put on the line, with their time as the text starts each line with: a line of a
// byte log, a packet of a capture (serial/capture.hpp).
struct LineBytes {
  std::string at;  // "0.020601"
  bool from_host = false;
  std::vector<std::uint8_t> bytes;
};
// Every telegram and answer in `chunks` explained, one a line, as read_byte_log() does: the text of
// ByteLogReading.
std::string explain_line(std::span<const LineBytes> chunks, const ParameterLookup& lookup);

// A bit pattern as a person reads it in the type's unit ("1000", "23.15" for FIXPOINT16); empty
// for a type with no engineering value (the error structures).
std::string engineering_text(DataType t, std::uint32_t bits);

}  // namespace ibs::lustbus
