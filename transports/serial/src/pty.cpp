#include "ibs/serial/pty.hpp"

#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace ibs::serial {

PtyPair PtyPair::open(const PortOptions& options) {
  int master = -1;
  int slave = -1;
  std::array<char, 256> name{};
  termios raw{};
  ::cfmakeraw(&raw);  // no echo, no line editing, no CR/NL translation: a byte is a byte
  if (::openpty(&master, &slave, name.data(), &raw, nullptr) != 0) {
    throw std::runtime_error(std::string("pseudo-terminal: openpty failed: ") +
                             std::strerror(errno));
  }
  try {
    SerialPort port = SerialPort::adopt(master, "pty-master", options);
    return PtyPair(std::move(port), slave, std::string(name.data()));
  } catch (...) {
    ::close(slave);
    throw;
  }
}

PtyPair::PtyPair(SerialPort master, int slave_fd, std::string slave_path)
    : master_(std::move(master)), slave_fd_(slave_fd), slave_path_(std::move(slave_path)) {}

PtyPair::PtyPair(PtyPair&& o) noexcept
    : master_(std::move(o.master_)),
      slave_fd_(std::exchange(o.slave_fd_, -1)),
      slave_path_(std::move(o.slave_path_)) {}

PtyPair& PtyPair::operator=(PtyPair&& o) noexcept {
  if (this != &o) {
    if (slave_fd_ >= 0) ::close(slave_fd_);
    master_ = std::move(o.master_);
    slave_fd_ = std::exchange(o.slave_fd_, -1);
    slave_path_ = std::move(o.slave_path_);
  }
  return *this;
}

PtyPair::~PtyPair() {
  if (slave_fd_ >= 0) ::close(slave_fd_);
}

PtyLink::PtyLink(std::string link, std::string target) : link_(std::move(link)), target_(std::move(target)) {
  if (link_.empty()) throw std::runtime_error("--pty-link: give a path");
  // symlink() never replaces: an existing path (a dangling link too) fails with EEXIST.
  if (::symlink(target_.c_str(), link_.c_str()) != 0) {
    const int e = errno;
    throw std::runtime_error("--pty-link " + link_ + ": " +
                             (e == EEXIST ? std::string("exists already (give a path that does not exist; nothing was replaced)")
                                          : std::string("cannot make the link: ") + std::strerror(e)));
  }
}

PtyLink::~PtyLink() {
  // Only our link: still a symbolic link to the same pty (someone may have put a file there).
  std::array<char, 512> now{};
  const ssize_t n = ::readlink(link_.c_str(), now.data(), now.size() - 1);
  if (n >= 0 && std::string(now.data(), static_cast<std::size_t>(n)) == target_) ::unlink(link_.c_str());
}

}  // namespace ibs::serial
