#include "control_input.hpp"

#include <sys/select.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace ibs::cli {

std::unique_ptr<ControlInput> ControlInput::open(const std::string& spec, std::string& error) {
  std::unique_ptr<ControlInput> c(new ControlInput());
  if (spec == "-") {
    c->name_ = "standard input";
    c->fd_ = STDIN_FILENO;
    // Standard input is left blocking for whoever shares it; reads wait for nothing (poll below).
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
    error = path + " exists; remove it or name another path (the socket is created "
            "anew and removed at exit)";
    return nullptr;
  }
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) {
    error = std::string("cannot make a socket: ") + std::strerror(errno);
    return nullptr;
  }
  addr.sun_family = AF_UNIX;
  std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr)) != 0 || ::listen(fd, 4) != 0) {
    error = "cannot listen on " + path + ": " + std::strerror(errno);
    ::close(fd);
    return nullptr;
  }
  c->name_ = spec;
  c->socket_path_ = path;
  c->listen_fd_ = fd;
  c->stdin_open_ = false;
  return c;
}

ControlInput::~ControlInput() {
  if (!socket_path_.empty()) {
    if (fd_ >= 0) ::close(fd_);
    if (listen_fd_ >= 0) ::close(listen_fd_);
    ::unlink(socket_path_.c_str());
  }
}

void ControlInput::take(const char* data, std::size_t n,
                        const std::function<void(std::size_t, std::string_view)>& line,
                        const std::function<void(std::size_t, std::string_view)>& error) {
  for (std::size_t i = 0; i < n; ++i) {
    const char ch = data[i];
    if (ch != '\n') {
      if (overlong_) continue;
      if (partial_.size() >= kMaxLine) {
        overlong_ = true;
        partial_.clear();
        continue;
      }
      partial_.push_back(ch);
      continue;
    }
    ++number_;
    if (overlong_) {
      error(number_, "longer than " + std::to_string(kMaxLine) + " characters; skipped");
      overlong_ = false;
      continue;
    }
    std::string_view text(partial_);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    const auto first = text.find_first_not_of(" \t");
    if (first != std::string_view::npos && text[first] != '#') line(number_, text);
    partial_.clear();
  }
}

void ControlInput::end_of_client(const std::function<void(std::size_t, std::string_view)>& line,
                                 const std::function<void(std::size_t, std::string_view)>& error) {
  // A last line without its newline still counts.
  if (!partial_.empty() || overlong_) take("\n", 1, line, error);
}

void ControlInput::poll(const std::function<void(std::size_t number, std::string_view text)>& line,
                        const std::function<void(std::size_t number, std::string_view what)>& error) {
  char buf[1024];
  for (int round = 0; round < 64; ++round) {  // bounded: a flood cannot hold the caller
    if (socket_path_.empty()) {
      if (!stdin_open_) return;
      // Standard input may be shared and blocking: read only what poll says is there.
      fd_set set;
      FD_ZERO(&set);
      FD_SET(fd_, &set);
      timeval zero{};
      if (::select(fd_ + 1, &set, nullptr, nullptr, &zero) <= 0) return;
    } else if (fd_ < 0) {
      const int client = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
      if (client < 0) return;  // nobody waiting
      fd_ = client;
    }
    const ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n > 0) {
      take(buf, static_cast<std::size_t>(n), line, error);
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return;  // EWOULDBLOCK is EAGAIN on Linux
    // End of this input (or an error reading it): what is left is its last line.
    end_of_client(line, error);
    if (socket_path_.empty()) {
      stdin_open_ = false;
      return;
    }
    ::close(fd_);
    fd_ = -1;
  }
}

}  // namespace ibs::cli
