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

}  // namespace

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
    now = since(t0);
    const std::span<const std::uint8_t> read(buf.data(), n);
    for (base::LineDevice* d : devices) {
      d->advance(now);
      const std::uint32_t rate = d->line_baud();
      if (rate != 0 && rate != port.baud()) continue;  // another rate: nothing it can read
      d->receive(read, now);
    }
    now = since(t0);
    for (base::LineDevice* d : devices) {
      const auto out = d->output(now);
      if (out.empty()) continue;
      port.write(out);
      d->written(out.size());
    }
    if (devices.size() == 1 && devices[0]->line_baud() != 0 && !devices[0]->next_due()) {
      port.set_baud(devices[0]->line_baud());
    }
  }
}

}  // namespace ibs::serial
