// A DFS-1 host (DFS-1 manual) in a program of its own: command 81 (status) to one controller.
//
//   dfs1_status PORT UID      e.g.  dfs1_status /dev/ttyUSB0 1
//
// The transaction is sans-I/O (ibs/dfs1/host.hpp): this program sends its bytes, feeds the
// port's bytes and the time back, and gives up after an overall deadline.
// Exit 0 with the status printed, 1 for a NAK or no answer, 2 for bad arguments or no port.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <exception>

#include "ibs/dfs1/host.hpp"
#include "ibs/dfs1/protocol.hpp"
#include "ibs/serial/serial_port.hpp"

namespace d1 = ibs::dfs1;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: dfs1_status PORT UID\n");
    return 2;
  }
  const long uid = std::strtol(argv[2], nullptr, 10);
  if (uid < 1 || uid > 255) {
    std::fprintf(stderr, "dfs1_status: UID must be 1..255\n");
    return 2;
  }
  try {
    ibs::serial::SerialPort port = ibs::serial::SerialPort::open(argv[1], {9600, ibs::serial::k8N1, false});
    const Clock::time_point t0 = Clock::now();
    const auto now = [&t0] { return ibs::Time{Clock::now() - t0}; };
    d1::HostTransaction t;
    if (t.start(d1::request::status(static_cast<std::uint8_t>(uid)), now()) != d1::StartStatus::accepted) return 2;
    port.discard_input();
    port.write(t.tx());
    t.transmitted(now());
    // The response and inter-byte timeouts end a quiet line; the deadline ends a babbling one.
    const ibs::Time deadline{std::chrono::seconds(1)};
    std::array<std::uint8_t, 256> buf{};
    while (!t.done() && now() < deadline) {
      const ibs::Time next = std::min(t.next_deadline().value_or(deadline), deadline);
      const auto wait = std::max(next - now(), ibs::Duration(std::chrono::microseconds(100)));
      const std::size_t n = port.read(buf, std::min<ibs::Duration>(wait, std::chrono::milliseconds(10)));
      t.receive(std::span<const std::uint8_t>(buf.data(), n), now());
      t.poll(now());
    }
    const auto r = t.take_result();
    if (!r || r->outcome != d1::Outcome::ack) {
      std::fprintf(stderr, "dfs1_status: uid %ld: %s\n", uid,
                   r ? std::string(d1::to_string(r->outcome)).c_str() : "no answer before the deadline");
      return 1;
    }
    // Command 81's data: commanded speed, actual speed, load, then ST2 and ST1 (docs/dfs1.md).
    std::printf("uid %ld: commanded %d rpm, actual %d rpm, load %u %%, ST2 %02XH, ST1 %02XH\n", uid,
                static_cast<int>(d1::to_signed(r->response.value_at(0))),
                static_cast<int>(d1::to_signed(r->response.value_at(4))),
                static_cast<unsigned>(r->response.value_at(8)), static_cast<unsigned>(r->response.data[14]),
                static_cast<unsigned>(r->response.data[15]));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dfs1_status: %s\n", e.what());
    return 2;
  }
}
