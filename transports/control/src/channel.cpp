#include "ibs/control/channel.hpp"

#include <fcntl.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ostream>

namespace ibs::control {

std::ostream& operator<<(std::ostream& os, const Origin& o) { return os << o.name << ':' << o.line; }

std::string to_string(const Origin& o) { return std::string(o.name) + ":" + std::to_string(o.line); }

struct Channel::Client {
  explicit Client(std::size_t max_line) : buffer(max_line) {}
  int fd = -1;
  bool standard_input = false;  // may be shared and blocking: read only what select() says is there
  std::uint32_t number = 0;
  char name[32] = {};
  std::size_t name_length = 0;
  LineBuffer buffer;
  [[nodiscard]] Origin origin(std::size_t line) const { return {number, line, {name, name_length}}; }
};

Channel::Channel(const Limits& limits) : limits_(limits) {
  overlong_text_ = "longer than " + std::to_string(limits.max_line) + " characters; skipped";
}

std::unique_ptr<Channel> Channel::streams(const Limits& limits) {
  std::unique_ptr<Channel> c(new Channel(limits));
  c->name_ = "streams";
  c->clients_.reserve(limits.max_clients);
  for (std::size_t i = 0; i < limits.max_clients; ++i) c->clients_.emplace_back(limits.max_line);
  return c;
}

std::unique_ptr<Channel> Channel::open(const std::string& spec, std::string& error, const Limits& limits) {
  if (limits.max_line == 0 || limits.max_clients == 0 || limits.read_budget == 0 || limits.lines_per_poll == 0) {
    error = "every limit of a control channel is at least 1";
    return nullptr;
  }
  if (spec == "-") {
    std::unique_ptr<Channel> c(new Channel(limits));
    c->name_ = "standard input";
    c->clients_.emplace_back(limits.max_line);
    Client& in = c->clients_.back();
    in.fd = STDIN_FILENO;
    in.standard_input = true;
    in.name_length = static_cast<std::size_t>(std::snprintf(in.name, sizeof in.name, "control"));
    return c;
  }
  if (spec.rfind("unix:", 0) != 0 || spec.size() == 5) {
    error = "give - (standard input) or unix:PATH (a socket to create)";
    return nullptr;
  }
  const std::string path = spec.substr(5);
  sockaddr_un addr{};
  if (path.size() >= sizeof(addr.sun_path)) {
    error = "the socket path is " + std::to_string(path.size()) +
            " characters long; a Unix socket's path holds at most " + std::to_string(sizeof(addr.sun_path) - 1);
    return nullptr;
  }
  // Never replace anything: a path that exists (a file, a socket of another run) is refused.
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    error = path + " exists; remove it or name another path (the socket is created anew and removed at exit)";
    return nullptr;
  }
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) {
    error = std::string("cannot make a socket: ") + std::strerror(errno);
    return nullptr;
  }
  addr.sun_family = AF_UNIX;
  std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
  // Owner only, whatever the umask: the file is made 0600 by bind (the umask for that call only),
  // so no other user can connect even for an instant; chmod says it once more.
  const mode_t before = ::umask(0177);
  const int bound = ::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr));
  const int bind_errno = errno;
  ::umask(before);
  if (bound != 0) {
    error = "cannot create the socket " + path + ": " + std::strerror(bind_errno);
    ::close(fd);
    return nullptr;
  }
  const auto backlog = static_cast<int>(std::min<std::size_t>(limits.max_clients + 4, 128));
  if (::chmod(path.c_str(), 0600) != 0 || ::listen(fd, backlog) != 0 || ::lstat(path.c_str(), &st) != 0) {
    error = "cannot listen on " + path + ": " + std::strerror(errno);
    ::close(fd);
    ::unlink(path.c_str());
    return nullptr;
  }
  std::unique_ptr<Channel> c(new Channel(limits));
  c->name_ = spec;
  c->socket_path_ = path;
  c->socket_inode_ = st.st_ino;
  c->listen_fd_ = fd;
  c->clients_.reserve(limits.max_clients);
  for (std::size_t i = 0; i < limits.max_clients; ++i) c->clients_.emplace_back(limits.max_line);
  return c;
}

Channel::~Channel() {
  for (Client& c : clients_) {
    if (c.fd >= 0 && !c.standard_input) ::close(c.fd);
  }
  if (listen_fd_ >= 0) ::close(listen_fd_);
  if (!socket_path_.empty()) {
    // Only our socket: a path someone has since replaced is theirs.
    struct stat st {};
    if (::lstat(socket_path_.c_str(), &st) == 0 && S_ISSOCK(st.st_mode) &&
        st.st_ino == socket_inode_) {
      ::unlink(socket_path_.c_str());
    }
  }
}

std::size_t Channel::clients() const {
  return static_cast<std::size_t>(std::count_if(clients_.begin(), clients_.end(), [](const Client& c) { return c.fd >= 0; }));
}

bool Channel::take(int fd, const NoticeFn& notice) {
  const auto free = std::find_if(clients_.begin(), clients_.end(), [](const Client& c) { return c.fd < 0; });
  char text[160];
  if (free == clients_.end() || free->standard_input) {
    ++counters_.refused;
    const int n = std::snprintf(text, sizeof text,
                                "ibs: refused: %zu clients are connected, the most this channel serves at once; "
                                "try again when one has closed\n",
                                limits_.max_clients);
    // One try, never waiting: the client is told if its socket has room (it has: nothing is queued).
    (void)!::send(fd, text, static_cast<std::size_t>(n), MSG_NOSIGNAL | MSG_DONTWAIT);
    ::close(fd);
    if (notice) {
      const int k = std::snprintf(text, sizeof text, "control: a client refused: %zu clients are connected (the most)",
                                  limits_.max_clients);
      notice({text, static_cast<std::size_t>(k)});
    }
    return false;
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags | O_NONBLOCK);
  ::fcntl(fd, F_SETFD, FD_CLOEXEC);
  Client& c = *free;
  c.fd = fd;
  c.number = next_number_++;
  c.name_length = static_cast<std::size_t>(std::snprintf(c.name, sizeof c.name, "control:%u", c.number));
  c.buffer.reset();
  ++counters_.accepted;
  if (notice) {
    ucred cred{};
    socklen_t len = sizeof cred;
    int k = 0;
    if (::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &len) == 0 && cred.pid > 0) {
      k = std::snprintf(text, sizeof text, "control:%u: connected (pid %ld)", c.number, static_cast<long>(cred.pid));
    } else {
      k = std::snprintf(text, sizeof text, "control:%u: connected", c.number);
    }
    notice({text, static_cast<std::size_t>(k)});
  }
  return true;
}

bool Channel::adopt(int fd) { return take(fd, {}); }

void Channel::accept_waiting(const NoticeFn& notice) {
  if (listen_fd_ < 0) return;
  // Bounded: a storm of connections costs one poll at most this many accepts.
  for (std::size_t i = 0; i < limits_.max_clients + 4; ++i) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (fd < 0) return;  // nobody waiting (or an error of that one connection)
    take(fd, notice);
  }
}

void Channel::close_client(Client& c) {
  if (!c.standard_input) ::close(c.fd);
  c.fd = -1;
  ++counters_.closed;
}

// Serves one client: lines from what it has sent, reading more while there is budget. Returns the
// lines handed out.
std::size_t Channel::serve(Client& c, std::size_t lines, const LineFn& line, const ErrorFn& error) {
  std::size_t given = 0;
  std::size_t budget = limits_.read_budget;
  while (given < lines) {
    const LineBuffer::Item item = c.buffer.next();
    if (item.kind == LineBuffer::Kind::line) {
      ++given;
      ++counters_.lines;
      line(c.origin(item.number), item.text);
      continue;
    }
    if (item.kind == LineBuffer::Kind::overlong) {
      ++given;
      ++counters_.overlong;
      error(c.origin(item.number), overlong_text_);
      continue;
    }
    if (budget == 0) break;
    if (c.standard_input) {
      fd_set set;
      FD_ZERO(&set);
      FD_SET(c.fd, &set);
      timeval zero{};
      if (::select(c.fd + 1, &set, nullptr, nullptr, &zero) <= 0) break;
    }
    const std::span<char> room = c.buffer.space();
    const ssize_t n = ::read(c.fd, room.data(), std::min(room.size(), budget));
    if (n > 0) {
      budget -= static_cast<std::size_t>(n);
      counters_.bytes += static_cast<std::uint64_t>(n);
      c.buffer.commit(static_cast<std::size_t>(n));
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) break;  // EWOULDBLOCK is EAGAIN on Linux
    // End of this input (or an error reading it): what is left is its last line.
    const LineBuffer::Item last = c.buffer.finish();
    if (last.kind == LineBuffer::Kind::line) {
      ++counters_.lines;
      line(c.origin(last.number), last.text);
    }
    close_client(c);
    break;
  }
  return given;
}

void Channel::poll(const LineFn& line, const ErrorFn& error, const NoticeFn& notice) {
  accept_waiting(notice);
  const std::size_t slots = clients_.size();
  std::size_t active = 0;
  for (const Client& c : clients_) active += c.fd >= 0 ? 1U : 0U;
  if (active == 0) return;
  // Each client's share of this poll's lines; a client that has fewer leaves them to the next.
  std::size_t left = limits_.lines_per_poll;
  const std::size_t first = start_ % slots;
  start_ = first + 1;
  for (std::size_t k = 0; k < slots && left > 0; ++k) {
    Client& c = clients_[(first + k) % slots];
    if (c.fd < 0) continue;
    const std::size_t share = std::max<std::size_t>(1, left / active);
    left -= serve(c, share, line, error);
    --active;
    if (active == 0) break;
  }
}

}  // namespace ibs::control
