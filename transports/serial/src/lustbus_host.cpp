#include "ibs/serial/lustbus_host.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace ibs::serial {

namespace {

using Clock = std::chrono::steady_clock;

Time since(Clock::time_point t0) { return std::chrono::duration_cast<Duration>(Clock::now() - t0); }

}  // namespace

lustbus::Outcome transact(SerialPort& port, lustbus::Host& host, const lustbus::Request& request) {
  const Clock::time_point t0 = Clock::now();
  port.discard_input();  // stale bytes are no answer to this request
  const lustbus::Submitted s = host.submit(request);
  if (!s) throw std::invalid_argument("request refused: " + std::string(lustbus::to_string(s.error)));
  std::array<std::uint8_t, 256> buf{};
  while (!host.idle() || host.output_pending()) {
    host.step(since(t0));
    const auto tx = host.take_output();
    if (!tx.empty()) {
      port.write(tx);
      host.output_done(since(t0));
      continue;
    }
    const Time now = since(t0);
    const Time next = host.next_deadline();
    const Duration wait = next == Time::max() ? kHostPoll : std::clamp(next - now, Duration(100us), kHostPoll);
    const std::size_t n = port.read(buf, wait);
    host.receive(std::span<const std::uint8_t>(buf.data(), n), since(t0));
  }
  const lustbus::Outcome* o = host.outcome(s.id);
  return o != nullptr ? *o : lustbus::Outcome{};
}

}  // namespace ibs::serial
