#include "ibs/serial/dfs1_host.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <span>
#include <stdexcept>
#include <string>

namespace ibs::serial {

namespace {

using Clock = std::chrono::steady_clock;

Time since(Clock::time_point t0) { return std::chrono::duration_cast<Duration>(Clock::now() - t0); }

}  // namespace

dfs1::HostResult transact(SerialPort& port, const dfs1::Frame& request, dfs1::HostTimeouts timeouts) {
  const Clock::time_point t0 = Clock::now();
  dfs1::HostTransaction t(timeouts);
  if (t.start(request, since(t0)) != dfs1::StartStatus::accepted) {
    throw std::invalid_argument("dfs1: request refused: " + std::string(dfs1::to_string(dfs1::check_request(request))));
  }
  port.discard_input();  // stale bytes are no answer to this request (nanoMODBUS flushes too)
  port.write(t.tx());
  t.transmitted(since(t0));
  std::array<std::uint8_t, 256> buf{};
  while (!t.done()) {
    const Time now = since(t0);
    const Duration wait = std::max(t.next_deadline().value_or(now) - now, Duration(100us));
    const std::size_t n = port.read(buf, wait);
    t.receive(std::span<const std::uint8_t>(buf.data(), n), since(t0));
    t.poll(since(t0));
  }
  return *t.take_result();
}

}  // namespace ibs::serial
