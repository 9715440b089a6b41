// A LUSTBUS host (LUSTBUS manual) in a program of its own: one ENQUIRY to a drive on a serial port.
//
//   lustbus_read PORT ADDR CODE      e.g.  lustbus_read /dev/ttyUSB0 1 00012
//
// The host is sans-I/O (ibs/lustbus/host.hpp): this program moves its bytes between the port and
// the host and gives it the time. It stops after an overall deadline whatever the line does.
// Exit 0 with the VALUE printed, 1 for a NAK or no answer, 2 for bad arguments or no port.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "ibs/lustbus/host.hpp"
#include "ibs/serial/serial_port.hpp"

namespace lb = ibs::lustbus;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: lustbus_read PORT ADDR CODE\n");
    return 2;
  }
  const long addr = std::strtol(argv[2], nullptr, 10);
  const auto code = lb::Code::parse(argv[3]);
  if (addr < 1 || addr > 30 || !code) {
    std::fprintf(stderr, "lustbus_read: ADDR must be 1..30 and CODE five digits (e.g. 00012)\n");
    return 2;
  }
  try {
    // LUSTBUS manual 1: 9600 Bd, 7 data bits, even parity, 1 stop bit (a pty ignores the framing).
    ibs::serial::SerialPort port = ibs::serial::SerialPort::open(argv[1], {9600, ibs::serial::k7E1, false});
    lb::Host host;
    const lb::Submitted s = host.submit(lb::enquiry(static_cast<lb::Address>(addr), *code));
    if (!s) return 2;
    const Clock::time_point t0 = Clock::now();
    const auto now = [&t0] { return ibs::Time{Clock::now() - t0}; };
    const ibs::Time deadline{std::chrono::seconds(2)};  // the retries of HostConfig fit easily
    std::array<std::uint8_t, 256> buf{};
    while ((!host.idle() || host.output_pending()) && now() < deadline) {
      host.step(now());
      const auto tx = host.take_output();
      if (!tx.empty()) {
        port.write(tx);
        host.output_done(now());
        continue;
      }
      const ibs::Time next = std::min(host.next_deadline(), deadline);
      const auto wait = std::max(next - now(), ibs::Duration(std::chrono::microseconds(100)));
      const std::size_t n = port.read(buf, std::min<ibs::Duration>(wait, std::chrono::milliseconds(10)));
      host.receive(std::span<const std::uint8_t>(buf.data(), n), now());
    }
    const lb::Outcome* o = host.outcome(s.id);
    if (o == nullptr || o->kind != lb::OutcomeKind::value) {
      std::fprintf(stderr, "lustbus_read: %s\n", o ? lb::describe(*o).c_str() : "no answer before the deadline");
      return 1;
    }
    std::printf("%ld %s = %.*s\n", addr, argv[3], static_cast<int>(o->value.view().size()), o->value.view().data());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lustbus_read: %s\n", e.what());
    return 2;
  }
}
