// The live control channel of the test bench (docs/testbench.md): `--control -` (standard input)
// or `--control unix:PATH` (a Unix stream socket the command creates at PATH and removes at exit;
// one client at a time, the next one once the first has closed). It carries JSON lines; this class
// only cuts them out of what arrives, never waiting: each command reads it between its own work
// (the real-time runner once per bus cycle, the emulators' serve loop every few milliseconds).
// Lines are numbered from 1 across the whole channel (all clients of the socket one after the
// other), so that an error reads `control:LINE: what is wrong`. End of input does not end
// anything: standard input is simply read no more, the socket waits for its next client.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace ibs::cli {

class ControlInput {
 public:
  // The longest line: a longer one is reported (as "longer than 4096 characters") and skipped.
  static constexpr std::size_t kMaxLine = 4096;

  // Opens `spec` ("-" or "unix:PATH"); nullptr with `error` saying why (a PATH that exists, a
  // socket that cannot be made, another form of spec), for the caller to print after
  // "--control SPEC: ".
  static std::unique_ptr<ControlInput> open(const std::string& spec, std::string& error);
  ~ControlInput();
  ControlInput(const ControlInput&) = delete;
  ControlInput& operator=(const ControlInput&) = delete;

  // Reads what has arrived, without waiting, and calls `line(number, text)` for each complete
  // line (without its newline; a trailing '\r' removed; empty lines and lines starting with '#'
  // skipped but counted) and `error(number, what)` for a line too long.
  void poll(const std::function<void(std::size_t number, std::string_view text)>& line,
            const std::function<void(std::size_t number, std::string_view what)>& error);

  // What a message names the channel by: "standard input", "unix:PATH".
  [[nodiscard]] const std::string& name() const { return name_; }

 private:
  ControlInput() = default;
  void take(const char* data, std::size_t n,
            const std::function<void(std::size_t, std::string_view)>& line,
            const std::function<void(std::size_t, std::string_view)>& error);
  void end_of_client(const std::function<void(std::size_t, std::string_view)>& line,
                     const std::function<void(std::size_t, std::string_view)>& error);

  std::string name_;
  std::string socket_path_;  // empty: standard input
  int listen_fd_ = -1;
  int fd_ = -1;             // standard input, or the client connected now
  bool stdin_open_ = true;  // standard input not yet at its end
  std::string partial_;     // a line not yet complete
  bool overlong_ = false;   // the current line is already too long: skipped to its end
  std::size_t number_ = 0;  // of the last line taken
};

}  // namespace ibs::cli
