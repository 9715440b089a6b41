// A pseudo-terminal pair (openpty) standing in for a serial line in tests and for `--pty`: the
// master side is a SerialPort, the slave's path is what another program opens. The slave is
// made raw and one descriptor of it is held open, so that the master does not see a hang-up
// (EIO) while no client has the slave open.
#pragma once

#include <string>

#include "ibs/serial/serial_port.hpp"

namespace ibs::serial {

class PtyPair {
 public:
  // Throws std::runtime_error when openpty fails.
  static PtyPair open(const PortOptions& options = {});

  PtyPair(PtyPair&&) noexcept;
  PtyPair& operator=(PtyPair&&) noexcept;
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;
  ~PtyPair();

  SerialPort& master() { return master_; }
  const std::string& slave_path() const { return slave_path_; }

 private:
  PtyPair(SerialPort master, int slave_fd, std::string slave_path);
  SerialPort master_;
  int slave_fd_ = -1;
  std::string slave_path_;
};

// A stable name for a pty's changing /dev/pts/N, as socat's `pty,link=PATH` gives one: a symbolic
// link made when the pty is, removed when this is destroyed. It never replaces anything: a path
// that exists (a file, a link, even a dangling one) is refused, and at the end the link is removed
// only while it is still the one made here (a link to the same pty), never a file put in its place.
class PtyLink {
 public:
  // Throws std::runtime_error naming `link` and the reason (it exists; its folder is missing; ...).
  PtyLink(std::string link, std::string target);
  PtyLink(const PtyLink&) = delete;
  PtyLink& operator=(const PtyLink&) = delete;
  ~PtyLink();

  const std::string& path() const { return link_; }

 private:
  std::string link_;
  std::string target_;
};

}  // namespace ibs::serial
