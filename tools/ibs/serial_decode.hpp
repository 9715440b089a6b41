// The file side of `ibs decode` for the serial lines: a byte log of `--log` (docs/lustbus.md,
// "Reading a byte log") and a capture of `--pcap` (docs/pcap.md, "Serial lines"), each telegram
// explained on a line of its own. The reading and the explaining are the libraries'
// (lustbus::read_byte_log, serial::read_line_capture, lustbus::explain_line,
// devices::dfs1::FrameExplainer); this parses the file's name and prints.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>

namespace ibs::cli {

// `ibs decode FILE` for a byte log: nullopt when FILE is no byte log (the caller tries the other
// formats); otherwise every telegram and answer explained, one per line, and the exit code (2: a
// malformed line, named file:line).
std::optional<int> decode_lustbus_log(const std::string& file, std::ostream& out, std::ostream& err);

// `ibs decode FILE` for a capture of a LUSTBUS or DFS-1 line: nullopt when FILE is no pcap file;
// otherwise every packet explained, one per line ("SECONDS host|device ..." from the first
// packet), and the exit code: 2 for a pcap file that is no serial line's capture (another link
// type) or holds a broken packet, named by its number.
std::optional<int> decode_line_capture(const std::string& file, std::ostream& out, std::ostream& err);

}  // namespace ibs::cli
