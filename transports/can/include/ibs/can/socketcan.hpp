// SocketCAN: a raw CAN socket (PF_CAN, SOCK_RAW, CAN_RAW) bound to an interface such as `can0`
// or `vcan0` - the transport for real CAN hardware. On a kernel without CAN (this project's build
// machine) open() fails with the reason, e.g. "socket(PF_CAN): Address family not supported by
// protocol". Extended, error and CAN FD frames are skipped on receive (CANLust is CAN 2.0A).
#pragma once

#include <string>
#include <string_view>

#include "ibs/can/transport.hpp"

namespace ibs::can {

class SocketCan final : public CanTransport {
 public:
  static Opened<SocketCan> open(std::string_view interface_name);
  ~SocketCan() override;
  SocketCan(const SocketCan&) = delete;
  SocketCan& operator=(const SocketCan&) = delete;

  IoStatus send(const CanFrame& f) override;
  Received receive(Duration timeout) override;
  [[nodiscard]] std::string_view name() const override { return name_; }
  [[nodiscard]] std::string_view last_error() const override { return error_; }

 private:
  SocketCan(int fd, std::string name) : fd_(fd), name_(std::move(name)) {}
  int fd_ = -1;
  std::string name_;
  std::string error_;
};

// True when this kernel can create a CAN socket; otherwise false and `reason`.
bool socketcan_available(std::string* reason = nullptr);

}  // namespace ibs::can
