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

}  // namespace ibs::serial
