// Reading a whole input file (a trace, a scenario) for a command, with every way it can fail said
// in words: no such file, a directory, something that is not a regular file (a FIFO would block
// the reader forever, a device never end), unreadable, a read error, too large. Configuration-time
// code: it allocates and throws.
#pragma once

#include "ibs/base/build.hpp"
#if IBS_EMBEDDED
#error "traces, replay and file reading are not in the embedded build (docs/embedding.md)"
#endif

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace ibs {

// Why a file could not be read; what() is the reason alone ("it is a directory"), for the caller
// to put after the file name and its own line convention.
class FileReadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The largest input file read (traces and scenarios are text of at most a few MB).
inline constexpr std::size_t kMaxInputFileBytes = std::size_t{256} << 20U;

// The file's bytes; throws FileReadError. Never opens anything but a regular file.
std::string read_text_file(const std::string& path);

// At most the first `max_bytes` of the file, to tell its format before reading it whole (a
// sniffer must not read a 2 GiB file to look at its first line); throws FileReadError as
// read_text_file() does, except for the size.
std::string read_text_head(const std::string& path, std::size_t max_bytes);

// The complete lines of `head` (the text read_text_head() gave, `whole` when it is the whole
// file): a last line cut by the limit is left out.
std::vector<std::string> lines_of(const std::string& head, bool whole = true);

}  // namespace ibs
