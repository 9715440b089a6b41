#include "ibs/serial/serve.hpp"

#include <algorithm>
#include <array>
#include <chrono>

namespace ibs::serial {

namespace {

using Clock = std::chrono::steady_clock;

// The shortest wait: an answer due now is still given the chance of bytes in flight.
constexpr Duration kMinWait = 100us;

Time since(Clock::time_point t0) { return std::chrono::duration_cast<Duration>(Clock::now() - t0); }

// The devices' part of a turn: `read` (the bytes that came) heard at `heard`, then what is due at
// `due` written.
void turn(SerialPort& port, std::span<base::LineDevice* const> devices, std::span<const std::uint8_t> read,
          Time heard, Time due) {
  for (base::LineDevice* d : devices) {
    d->advance(heard);
    const std::uint32_t rate = d->line_baud();
    if (rate != 0 && rate != port.baud()) continue;  // another rate: nothing it can read
    d->receive(read, heard);
  }
  for (base::LineDevice* d : devices) {
    const auto out = d->output(due);
    if (out.empty()) continue;
    port.write(out);
    d->written(out.size());
  }
  if (devices.size() == 1 && devices[0]->line_baud() != 0 && !devices[0]->next_due()) {
    port.set_baud(devices[0]->line_baud());
  }
}

}  // namespace

std::size_t serve_turn(SerialPort& port, std::span<base::LineDevice* const> devices, Time now) {
  std::array<std::uint8_t, 256> buf{};
  const std::size_t n = port.read(buf, Duration{0});
  turn(port, devices, std::span<const std::uint8_t>(buf.data(), n), now, now);
  return n;
}

void serve(SerialPort& port, std::span<base::LineDevice* const> devices, const std::function<bool()>& stop) {
  const Clock::time_point t0 = Clock::now();
  std::array<std::uint8_t, 256> buf{};
  while (!stop()) {
    Time now = since(t0);
    Duration wait = kServePoll;
    for (const base::LineDevice* d : devices) {
      if (const auto due = d->next_due()) wait = std::min(wait, std::max(*due - now, Duration(0)));
    }
    const std::size_t n = port.read(buf, std::max(wait, kMinWait));
    const Time heard = since(t0);
    turn(port, devices, std::span<const std::uint8_t>(buf.data(), n), heard, since(t0));
  }
}

}  // namespace ibs::serial
