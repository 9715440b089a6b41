// A CAN transport for real I/O (floor 4): send a frame, receive one with a timeout. Implemented
// by SocketCAN (socketcan.hpp) and CAN over UDP in cannelloni's format (udp.hpp). The in-process
// virtual bus (virtual_bus.hpp) is a simulation component with time passed in and is not one.
// Errors are return values with a reason; opening reports why it failed (no exceptions).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "ibs/canlust/frame.hpp"
#include "ibs/base/time.hpp"

namespace ibs::can {

using canlust::CanFrame;

enum class IoStatus : std::uint8_t {
  ok,
  timeout,  // nothing arrived within the timeout
  error,    // see last_error()
};
std::string_view to_string(IoStatus s);

struct Received {
  IoStatus status = IoStatus::timeout;
  CanFrame frame{};
};

class CanTransport {
 public:
  virtual ~CanTransport() = default;
  virtual IoStatus send(const CanFrame& f) = 0;
  // Waits up to `timeout` (wall-clock) for one frame; Duration::zero() polls.
  virtual Received receive(Duration timeout) = 0;
  [[nodiscard]] virtual std::string_view name() const = 0;
  [[nodiscard]] virtual std::string_view last_error() const = 0;
};

// What open() gives: the transport, or nullptr and the reason.
template <typename T>
struct Opened {
  std::unique_ptr<T> transport;
  std::string error;
  explicit operator bool() const { return transport != nullptr; }
};

}  // namespace ibs::can
