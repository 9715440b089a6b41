// A serial port for the RS-485 protocols (DFS-1, LUSTBUS): a path opened with a baud rate and a
// framing (8N1, 7E1, ...), reads with a timeout, writes, and RS-485 direction control by
// TIOCSRS485 where the driver has it. Real ports and pseudo-terminals alike; a pty ignores the
// baud rate and refuses 7 data bits (../shared/notes/public-facts.md, "This machine"), which is
// recorded in notes() and otherwise ignored. Built on standalone Asio's serial_port
// (docs/dfs1.md, "Transport", says why not libserialport).
//
// This is floor 4: it does I/O and reads the steady clock for the byte log. Errors at open or
// configuration throw std::runtime_error naming the path and what failed; I/O errors afterwards
// throw std::system_error.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace ibs::serial {

class ByteLog;
class ByteTap;

enum class Parity : std::uint8_t { none, even, odd };

struct Framing {
  int data_bits = 8;
  Parity parity = Parity::none;
  int stop_bits = 1;
  friend bool operator==(const Framing&, const Framing&) = default;
};
inline constexpr Framing k8N1{8, Parity::none, 1};
inline constexpr Framing k7E1{7, Parity::even, 1};
// "8N1", "7E1", "8E1", "7O2", ...; throws std::invalid_argument naming the text.
Framing parse_framing(std::string_view text);
std::string to_string(const Framing& f);

struct PortOptions {
  std::uint32_t baud = 9600;
  Framing framing = k8N1;
  // Ask the driver to switch the RS-485 transmitter itself (TIOCSRS485, RTS on send).
  bool rs485 = false;
};

enum class Rs485Status : std::uint8_t { not_requested, enabled, not_supported };

class SerialPort {
 public:
  // Opens and configures `path`. A pty's refusals (framing, RS-485) go to notes().
  static SerialPort open(const std::string& path, const PortOptions& options);
  // Takes over an open descriptor (the master side of a pty pair): configured like open().
  static SerialPort adopt(int fd, const std::string& name, const PortOptions& options);

  SerialPort(SerialPort&&) noexcept;
  SerialPort& operator=(SerialPort&&) noexcept;
  ~SerialPort();

  // Up to buf.size() bytes that arrive within `timeout`; 0 when none did.
  std::size_t read(std::span<std::uint8_t> buf, std::chrono::nanoseconds timeout);
  // All of `bytes`, then waits until the driver has sent them (tcdrain).
  void write(std::span<const std::uint8_t> bytes);
  // Discards what was received and not yet read.
  void discard_input();
  // Changes the rate after open (LUSTBUS 11.5: a servo's 4-PROG = 111). Output already written
  // is drained first (tcdrain), so it still goes out at the old rate. A pty ignores rates.
  void set_baud(std::uint32_t baud);
  [[nodiscard]] std::uint32_t baud() const;

  const std::string& name() const;
  bool is_pty() const;
  Rs485Status rs485() const;
  // What the port could not do and was ignored (a pty: "7 data bits not supported (pty)", ...).
  const std::vector<std::string>& notes() const;
  int native_handle() const;

  // Every byte read or written goes to `log` (nullptr: none); the log must outlive the port.
  void set_log(ByteLog* log);
  // Every byte read or written also goes to `tap` (nullptr: none): a capture (capture.hpp). The
  // tap must outlive the port's use; what it throws, the read or write throws.
  void set_tap(ByteTap* tap);

  struct Impl;  // the Asio state, defined in serial_port.cpp

 private:
  explicit SerialPort(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace ibs::serial
