// A live control channel of text lines for a program that must not wait on it (docs/testbench.md,
// "Control channel"): standard input (`-`) or a Unix stream socket (`unix:PATH`) that serves many
// clients at once. The program calls poll() between its own work (a real-time loop once per
// cycle); poll() never waits, never allocates, and its work is bounded by Limits whatever the
// clients do:
//
// - every connected client is read in each poll, with its own LineBuffer (line_buffer.hpp) and its
//   own line numbers, and named in every line it gave: "control:CLIENT:LINE" (CLIENT counts the
//   socket's clients from 1 in the order they connected); standard input is "control:LINE";
// - a line is at most Limits::max_line characters; a longer one is reported at once as that
//   client's bad line and skipped to its newline, and the client goes on;
// - at most Limits::max_clients clients at once; the next one is told why in one line
//   ("ibs: refused: ...") and closed, and the program is told too (notice);
// - from each client at most read_budget bytes a poll, and at most lines_per_poll lines from all
//   of them, shared out from a starting client that moves on each poll: a client that floods or
//   sends an endless line takes its share and no more; one that stalls takes nothing.
//
// The socket is created owner-only (mode 0600 whatever the umask: only its user may connect), a
// PATH that exists is refused (nothing is replaced), and the socket is removed when the channel
// ends, unless something else has taken its path meanwhile.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/control/line_buffer.hpp"

namespace ibs::control {

struct Limits {
  std::size_t max_line = 64 * 1024;   // characters of one line, its newline not counted
  std::size_t max_clients = 16;       // socket clients served at once
  std::size_t read_budget = 16 * 1024;  // bytes read from one client in one poll
  std::size_t lines_per_poll = 64;    // lines handed out in one poll, all clients together
};

// Where a line came from.
struct Origin {
  std::uint32_t client = 0;  // 0: standard input; 1, 2, ...: the socket's clients
  std::size_t line = 0;      // its number in that client's input, from 1
  std::string_view name;     // "control" (standard input) or "control:CLIENT": a message's prefix
};
// "control:LINE" or "control:CLIENT:LINE".
std::ostream& operator<<(std::ostream& os, const Origin& o);
std::string to_string(const Origin& o);

struct Counters {
  std::uint64_t bytes = 0;          // read from all clients
  std::uint64_t lines = 0;          // handed out (blank and comment lines not)
  std::uint64_t overlong = 0;       // lines reported as too long
  std::uint64_t accepted = 0;       // clients taken
  std::uint64_t refused = 0;        // clients turned away (max_clients connected)
  std::uint64_t closed = 0;         // clients that ended their input
};

class Channel {
 public:
  using LineFn = std::function<void(const Origin&, std::string_view text)>;
  using ErrorFn = std::function<void(const Origin&, std::string_view what)>;
  using NoticeFn = std::function<void(std::string_view text)>;

  // Opens `spec` ("-" or "unix:PATH"); nullptr with `error` saying why (a PATH that exists, a
  // socket that cannot be made, a limit of 0, another form of spec).
  static std::unique_ptr<Channel> open(const std::string& spec, std::string& error, const Limits& limits = {});
  // A channel of no socket and no standard input: its clients are the streams given to adopt()
  // (tests, and a program that connects its own).
  static std::unique_ptr<Channel> streams(const Limits& limits = {});
  ~Channel();
  Channel(const Channel&) = delete;
  Channel& operator=(const Channel&) = delete;

  // Takes `fd` (a connected stream, made non-blocking here) as the next client; false, and `fd`
  // closed, when max_clients are connected.
  bool adopt(int fd);

  // Accepts waiting clients, reads what has arrived, and calls `line` for each complete line and
  // `error` for each line too long, in each client's order; `notice` (may be empty) hears of
  // clients connected and refused ("control:3: connected (pid 1234)", "control: a client refused:
  // ..."). Never waits.
  void poll(const LineFn& line, const ErrorFn& error, const NoticeFn& notice = {});

  // What a message names the channel by: "standard input", "unix:PATH".
  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] const Limits& limits() const { return limits_; }
  [[nodiscard]] const Counters& counters() const { return counters_; }
  [[nodiscard]] std::size_t clients() const;  // connected now
  // The socket's path; empty for standard input and streams().
  [[nodiscard]] const std::string& path() const { return socket_path_; }

 private:
  struct Client;
  explicit Channel(const Limits& limits);
  void accept_waiting(const NoticeFn& notice);
  bool take(int fd, const NoticeFn& notice);
  std::size_t serve(Client& c, std::size_t lines, const LineFn& line, const ErrorFn& error);
  void close_client(Client& c);

  Limits limits_;
  std::string name_;
  std::string socket_path_;
  std::uint64_t socket_inode_ = 0;  // the socket made at socket_path_: removed at the end only if still there
  int listen_fd_ = -1;
  std::vector<Client> clients_;  // max_clients slots (1 for standard input), their buffers made once
  std::uint32_t next_number_ = 1;
  std::size_t start_ = 0;  // the slot served first in the next poll
  std::string overlong_text_;
  Counters counters_;
};

}  // namespace ibs::control
