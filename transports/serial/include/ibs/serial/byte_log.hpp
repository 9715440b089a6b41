// The byte log of `--log FILE` (docs/dfs1.md, "Byte log"): a header line `ibs-serial-log 1`,
// then one line per read or write:
//
//   <seconds since the log opened, 6 decimals> <tx|rx> <PORT> <bytes as two hex digits each>
//
// e.g. `0.000412 tx /dev/pts/3 10 02 01 81 10 03 7E`. Lines are flushed as written.
#pragma once

#include <chrono>
#include <cstdint>
#include <fstream>
#include <ostream>
#include <span>
#include <string>
#include <string_view>

namespace ibs::serial {

enum class Direction : std::uint8_t { tx, rx };

// What sees every byte a SerialPort reads (rx) or writes (tx) besides its byte log
// (SerialPort::set_tap): a capture of the line's telegrams (capture.hpp). Called on the port's
// thread, after a read and after a write has been handed to the driver.
class ByteTap {
 public:
  virtual void bytes(Direction d, std::span<const std::uint8_t> bytes) = 0;

 protected:
  ByteTap() = default;
  ByteTap(const ByteTap&) = default;
  ByteTap& operator=(const ByteTap&) = default;
  ~ByteTap() = default;
};

class ByteLog {
 public:
  // Throws std::runtime_error "log FILE: cannot open for writing".
  explicit ByteLog(const std::string& path);
  // The log written to `out` (a command's standard output for `--log -`), which must outlive it.
  explicit ByteLog(std::ostream& out);
  ByteLog(const ByteLog&) = delete;  // out_ may point at its own file_
  ByteLog& operator=(const ByteLog&) = delete;
  void record(Direction d, std::string_view port, std::span<const std::uint8_t> bytes);

 private:
  std::ofstream file_;
  std::ostream* out_;
  std::chrono::steady_clock::time_point start_;
};

// One log line without the time: "tx PORT 10 02 ...", for tests and for printing.
std::string format_bytes(std::span<const std::uint8_t> bytes);

}  // namespace ibs::serial
