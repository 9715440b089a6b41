// The trace files of `ibs replay` and `ibs decode`: `-` for standard input, several files in one
// call, and decode's JSON form (docs/replay.md, "Files and standard input").
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "ibs/interbus/replay.hpp"
#include "ibs/interbus/trace.hpp"

namespace ibs::cli {

// How standard input is named in messages (`<stdin>:12: ...`).
inline constexpr const char* kStdinName = "<stdin>";

// Reads and parses FILE, or standard input for `-` (at most ibs::kMaxInputFileBytes, like a
// file); every problem is a trace::TraceError `FILE:LINE: message`.
trace::Trace load_trace_input(const std::string& file);

// Refuses `-` given more than once (standard input can be read once): the message, or "".
std::string check_inputs(const std::vector<std::string>& files);

// The decoded trace as one JSON object on one line: the file, the headers, and per row its line,
// step (or gap), words each way, each way's reading by the explainer, the original remark, the
// comments and events before it.
void write_decoded_json(const trace::Trace& t, const trace::Explainer& e, std::ostream& out);

}  // namespace ibs::cli
