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

}  // namespace ibs::serial
