// A CANLust master (CANLust manual) in a program of its own: one parameter read from a CDA3000 over CAN
// over UDP (cannelloni's format; a real cannelloni bridges it to a CAN interface).
//
//   canlust_read LOCALPORT PEERPORT ADDR PARAM      e.g.  canlust_read 29700 29701 1 360
//
// The parameter client is sans-I/O (ibs/canlust/parameter_client.hpp): this program hands its
// frames to the transport, feeds received frames and the time back, and gives up after an overall
// deadline. Exit 0 with the value printed, 1 for a refusal or no answer, 2 for bad arguments.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "ibs/can/udp.hpp"
#include "ibs/canlust/parameter_client.hpp"

namespace cl = ibs::canlust;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: canlust_read LOCALPORT PEERPORT ADDR PARAM\n");
    return 2;
  }
  const long local = std::strtol(argv[1], nullptr, 10);
  const long peer = std::strtol(argv[2], nullptr, 10);
  const long addr = std::strtol(argv[3], nullptr, 10);
  const long param = std::strtol(argv[4], nullptr, 10);
  if (local < 1 || local > 65535 || peer < 1 || peer > 65535 || addr < 1 || addr > 99 || param < 0 ||
      param > 65535) {
    std::fprintf(stderr, "canlust_read: ports 1..65535, ADDR 1..99, PARAM 0..65535\n");
    return 2;
  }
  ibs::can::UdpConfig u;
  u.local_port = static_cast<std::uint16_t>(local);
  u.remote_port = static_cast<std::uint16_t>(peer);
  auto opened = ibs::can::UdpCanTransport::open(u);
  if (!opened) {
    std::fprintf(stderr, "canlust_read: %s\n", opened.error.c_str());
    return 2;
  }
  ibs::can::CanTransport& bus = *opened.transport;
  cl::ParameterClient client{cl::ClientConfig{}};
  const auto sub = client.submit(cl::read(static_cast<cl::Address>(addr), static_cast<std::uint16_t>(param)));
  if (!sub) return 2;
  const Clock::time_point t0 = Clock::now();
  const auto now = [&t0] { return ibs::Time{Clock::now() - t0}; };
  // The client's own timeout ends a silent bus; the deadline ends a bus full of other traffic.
  const ibs::Time deadline{std::chrono::seconds(2)};
  while (now() < deadline) {
    client.step(now());
    while (auto f = client.take_frame()) bus.send(*f);
    const auto p = client.poll(sub.id);
    if (p.state == cl::RequestState::done) {
      if (p.outcome->kind != cl::OutcomeKind::done) {
        std::fprintf(stderr, "canlust_read: CDA %ld parameter %ld: %s\n", addr, param, cl::describe(*p.outcome).c_str());
        return 1;
      }
      std::printf("CDA %ld parameter %ld: %u\n", addr, param, static_cast<unsigned>(p.outcome->value));
      return 0;
    }
    const ibs::Time next = std::min(client.next_deadline(), deadline);
    const auto wait = std::clamp<ibs::Duration>(next - now(), ibs::Duration::zero(), std::chrono::milliseconds(10));
    const auto r = bus.receive(wait);
    if (r.status == ibs::can::IoStatus::ok) client.receive(r.frame, now());
  }
  std::fprintf(stderr, "canlust_read: CDA %ld parameter %ld: no answer before the deadline\n", addr, param);
  return 1;
}
