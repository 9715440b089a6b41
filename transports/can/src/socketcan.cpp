#include "ibs/can/socketcan.hpp"

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace ibs::can {

namespace {
std::string errno_text(const char* what) { return std::string(what) + ": " + std::strerror(errno); }
}  // namespace

bool socketcan_available(std::string* reason) {
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) {
    if (reason) *reason = errno_text("socket(PF_CAN)");
    return false;
  }
  ::close(fd);
  return true;
}

Opened<SocketCan> SocketCan::open(std::string_view interface_name) {
  Opened<SocketCan> r;
  const std::string name(interface_name);
  if (name.empty() || name.size() >= IFNAMSIZ) {
    r.error = "SocketCAN: bad interface name '" + name + "'";
    return r;
  }
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) {
    r.error = errno_text("socket(PF_CAN)");
    return r;
  }
  ifreq ifr{};
  std::memcpy(ifr.ifr_name, name.c_str(), name.size() + 1);
  if (::ioctl(fd, SIOCGIFINDEX, &ifr) < 0) {
    r.error = errno_text(("SIOCGIFINDEX " + name).c_str());
    ::close(fd);
    return r;
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) {
    r.error = errno_text(("bind " + name).c_str());
    ::close(fd);
    return r;
  }
  r.transport.reset(new SocketCan(fd, "socketcan:" + name));
  return r;
}

SocketCan::~SocketCan() {
  if (fd_ >= 0) ::close(fd_);
}

IoStatus SocketCan::send(const CanFrame& f) {
  if (!f.valid()) {
    error_ = "invalid frame";
    return IoStatus::error;
  }
  can_frame cf{};
  cf.can_id = f.id | (f.rtr ? CAN_RTR_FLAG : 0U);
  cf.can_dlc = f.dlc;
  if (!f.rtr) std::memcpy(cf.data, f.data.data(), f.dlc);
  if (::write(fd_, &cf, sizeof cf) != static_cast<ssize_t>(sizeof cf)) {
    error_ = errno_text("write");
    return IoStatus::error;
  }
  return IoStatus::ok;
}

Received SocketCan::receive(Duration timeout) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(timeout).count();
  for (;;) {
    pollfd p{fd_, POLLIN, 0};
    const int n = ::poll(&p, 1, static_cast<int>(ms));
    if (n == 0) return {IoStatus::timeout, {}};
    if (n < 0) {
      if (errno == EINTR) continue;
      error_ = errno_text("poll");
      return {IoStatus::error, {}};
    }
    can_frame cf{};
    const ssize_t got = ::read(fd_, &cf, sizeof cf);
    if (got != static_cast<ssize_t>(sizeof cf)) {
      error_ = errno_text("read");
      return {IoStatus::error, {}};
    }
    if ((cf.can_id & (CAN_EFF_FLAG | CAN_ERR_FLAG)) != 0 || cf.can_dlc > 8) continue;
    CanFrame f;
    f.id = static_cast<std::uint16_t>(cf.can_id & CAN_SFF_MASK);
    f.rtr = (cf.can_id & CAN_RTR_FLAG) != 0;
    f.dlc = cf.can_dlc;
    if (!f.rtr) std::memcpy(f.data.data(), cf.data, f.dlc);
    return {IoStatus::ok, f};
  }
}

}  // namespace ibs::can
