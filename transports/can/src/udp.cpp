#include "ibs/can/udp.hpp"

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

namespace ibs::can {

namespace {

std::string errno_text(const std::string& what) { return what + ": " + std::strerror(errno); }

bool make_address(const std::string& host, std::uint16_t port, sockaddr_in& out, std::string& error) {
  out = sockaddr_in{};
  out.sin_family = AF_INET;
  out.sin_port = htons(port);
  if (::inet_pton(AF_INET, host.c_str(), &out.sin_addr) != 1) {
    error = "UDP: '" + host + "' is not an IPv4 address";
    return false;
  }
  return true;
}

}  // namespace

Opened<UdpCanTransport> UdpCanTransport::open(const UdpConfig& config) {
  Opened<UdpCanTransport> r;
  sockaddr_in local{};
  if (!make_address(config.local_host, config.local_port, local, r.error)) return r;
  std::unique_ptr<UdpCanTransport> t(new UdpCanTransport());
  t->rx_buffer_.resize(65536);  // a whole datagram, up to the UDP maximum
  // The smallest frame is 5 bytes (identifier and length): decoding never runs out of room.
  t->rx_frames_.resize((t->rx_buffer_.size() - cannelloni::kHeaderSize) / 5);
  if (config.remote_port != 0) {
    if (!make_address(config.remote_host, config.remote_port, t->peer_, r.error)) return r;
    t->have_peer_ = true;
  }
  t->fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (t->fd_ < 0) {
    r.error = errno_text("socket(AF_INET, SOCK_DGRAM)");
    return r;
  }
  if (::bind(t->fd_, reinterpret_cast<const sockaddr*>(&local), sizeof local) < 0) {
    r.error = errno_text("bind " + config.local_host + ":" + std::to_string(config.local_port));
    return r;
  }
  sockaddr_in bound{};
  socklen_t len = sizeof bound;
  ::getsockname(t->fd_, reinterpret_cast<sockaddr*>(&bound), &len);
  t->local_port_ = ntohs(bound.sin_port);
  t->name_ = "udp:" + config.local_host + ":" + std::to_string(t->local_port_) + "->" +
             (config.remote_port != 0
                  ? config.remote_host + ":" + std::to_string(config.remote_port)
                  : std::string("first sender"));
  r.transport = std::move(t);
  return r;
}

UdpCanTransport::~UdpCanTransport() {
  if (fd_ >= 0) ::close(fd_);
}

IoStatus UdpCanTransport::send(const CanFrame& f) {
  if (!have_peer_) {
    error_ = "UDP: no peer yet (remote port 0 and nothing received)";
    return IoStatus::error;
  }
  std::array<std::uint8_t, cannelloni::kHeaderSize + 13> buf{};
  const auto n = cannelloni::encode(std::span(&f, 1), sequence_, buf);
  if (!n) {
    error_ = "invalid frame";
    return IoStatus::error;
  }
  ++sequence_;
  const auto sent = ::sendto(fd_, buf.data(), *n, 0, reinterpret_cast<const sockaddr*>(&peer_),
                             sizeof peer_);
  if (sent != static_cast<ssize_t>(*n)) {
    error_ = errno_text("sendto");
    return IoStatus::error;
  }
  return IoStatus::ok;
}

Received UdpCanTransport::receive(Duration timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    if (pending_size_ > 0) {
      const CanFrame f = pending_[pending_head_];
      pending_head_ = (pending_head_ + 1) % pending_.size();
      --pending_size_;
      return {IoStatus::ok, f};
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    pollfd p{fd_, POLLIN, 0};
    const int n = ::poll(&p, 1, left.count() > 0 ? static_cast<int>(left.count()) : 0);
    if (n == 0) return {IoStatus::timeout, {}};
    if (n < 0) {
      if (errno == EINTR) continue;
      error_ = errno_text("poll");
      return {IoStatus::error, {}};
    }
    sockaddr_in from{};
    socklen_t from_len = sizeof from;
    auto& buf = rx_buffer_;
    const ssize_t got = ::recvfrom(fd_, buf.data(), buf.size(), 0,
                                   reinterpret_cast<sockaddr*>(&from), &from_len);
    if (got < 0) {
      if (errno == EINTR) continue;
      error_ = errno_text("recvfrom");
      return {IoStatus::error, {}};
    }
    const auto r = cannelloni::decode(std::span(buf.data(), static_cast<std::size_t>(got)), rx_frames_);
    if (r.status != cannelloni::DecodeStatus::ok) {
      // A header that disagrees with its content (a count the bytes do not hold, a frame cut
      // after its identifier, bytes left over): none of its frames is trusted, and its sender
      // does not become the peer.
      ++bad_datagrams_;
      continue;
    }
    if (!have_peer_) {
      peer_ = from;
      have_peer_ = true;
    }
    skipped_frames_ += static_cast<std::uint32_t>(r.skipped);
    for (std::size_t i = 0; i < r.frames; ++i) {
      if (pending_size_ == pending_.size()) {
        ++overflow_frames_;
        continue;
      }
      pending_[(pending_head_ + pending_size_) % pending_.size()] = rx_frames_[i];
      ++pending_size_;
    }
  }
}

}  // namespace ibs::can
