// A device on a serial byte line, as a loop that owns the line drives it: bytes in with the time
// they came, bytes out once their time has come. Sans-I/O (time is passed in); the protocols put
// their receivers behind it (lustbus::ServedReceiver, devices::dfs1::ServedController) and one
// loop serves them all (serial::serve over a real port; a test can drive it by hand).
//
// One turn of such a loop, at `now`: advance(now); receive(the bytes read, now) unless the
// device's line runs at another rate than the port; then output(now), written to the line, and
// written(n). next_due() tells the loop when to turn again at the latest.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "ibs/base/time.hpp"

namespace ibs::base {

class LineDevice {
 public:
  LineDevice() = default;
  LineDevice(const LineDevice&) = default;
  LineDevice& operator=(const LineDevice&) = default;
  virtual ~LineDevice() = default;

  // When its next bytes are due (an answer waiting for its reaction time); nullopt: none waits.
  [[nodiscard]] virtual std::optional<Time> next_due() const = 0;
  // Time passes for the device, heard or not.
  virtual void advance(Time now) = 0;
  // The bytes read from the line at `now`; empty when none came (time passed all the same).
  virtual void receive(std::span<const std::uint8_t> bytes, Time now) = 0;
  // The bytes due for the line at `now` (empty: none). Valid until the next call on the device.
  virtual std::span<const std::uint8_t> output(Time now) = 0;
  // The first `n` bytes of output() are on the line.
  virtual void written(std::size_t n) = 0;
  // The rate the device's own line runs at (it may change it, LUSTBUS 11.5); 0: the port's.
  [[nodiscard]] virtual std::uint32_t line_baud() const { return 0; }
};

}  // namespace ibs::base
