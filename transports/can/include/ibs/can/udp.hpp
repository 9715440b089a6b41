// CAN over UDP in cannelloni's format v2 (cannelloni.hpp): one UDP socket bound to a local
// address and port, sending to one peer. Two of them - two processes, or two sockets in one
// process - pointed at each other form one bus; a real cannelloni pointed at one of them bridges
// it to a real CAN interface (docs/canlust.md "Transports"). Each send() is one datagram with one
// frame and the next sequence number; every frame of a received datagram is returned in turn.
#pragma once

#include <netinet/in.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ibs/can/cannelloni.hpp"
#include "ibs/can/transport.hpp"

namespace ibs::can {

struct UdpConfig {
  std::string local_host = "127.0.0.1";
  std::uint16_t local_port = 0;  // 0: any free port (local_port() tells which)
  std::string remote_host = "127.0.0.1";
  std::uint16_t remote_port = 0;  // 0: the sender of the first datagram received
};

class UdpCanTransport final : public CanTransport {
 public:
  static Opened<UdpCanTransport> open(const UdpConfig& config);
  ~UdpCanTransport() override;
  UdpCanTransport(const UdpCanTransport&) = delete;
  UdpCanTransport& operator=(const UdpCanTransport&) = delete;

  IoStatus send(const CanFrame& f) override;
  Received receive(Duration timeout) override;
  [[nodiscard]] std::string_view name() const override { return name_; }
  [[nodiscard]] std::string_view last_error() const override { return error_; }
  [[nodiscard]] std::uint16_t local_port() const { return local_port_; }
  // Datagrams dropped whole because they failed to decode (a header that disagrees with the
  // content: cannelloni::DecodeStatus), frames skipped (extended / FD / error), and frames lost
  // because the receive queue was full.
  [[nodiscard]] std::uint32_t bad_datagrams() const { return bad_datagrams_; }
  [[nodiscard]] std::uint32_t skipped_frames() const { return skipped_frames_; }
  [[nodiscard]] std::uint32_t overflow_frames() const { return overflow_frames_; }

 private:
  UdpCanTransport() = default;
  int fd_ = -1;
  std::string name_;
  std::string error_;
  std::uint16_t local_port_ = 0;
  bool have_peer_ = false;
  sockaddr_in peer_{};
  std::uint8_t sequence_ = 0;
  std::array<CanFrame, 128> pending_{};
  std::size_t pending_head_ = 0;
  std::size_t pending_size_ = 0;
  std::vector<std::uint8_t> rx_buffer_;
  std::vector<CanFrame> rx_frames_;  // every frame a datagram of rx_buffer_'s size can hold
  std::uint32_t bad_datagrams_ = 0;
  std::uint32_t skipped_frames_ = 0;
  std::uint32_t overflow_frames_ = 0;
};

}  // namespace ibs::can
