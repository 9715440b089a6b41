// What every LUSTBUS drive keeps the same way, whatever its parameters: the 85-SIOF/SERR latch of
// seed 000, 6 and 9.2, and the network watchdog of 5.2 (84-SIOT/SWDGT). Drive-neutral: the wings'
// Responders (devices/*/emulator/.../lustbus_device.hpp) hold one of each. Allocation-free.
#pragma once

#include <chrono>
#include <cstdint>

#include "ibs/interbus/time.hpp"
#include "ibs/lustbus/siof.hpp"

namespace ibs::lustbus {

// 6, 9.2: "after every new start the power-on bit is set"; "as long as an error bit is set, no
// parameter can be changed"; a refused SELECT enters its cause; "the set error bits are erased
// after reading from SIOF". An ENQUIRY never enters a cause (6.1 note): there is no call for it.
class SiofLatch {
 public:
  // A new start (power on, reset): only the power-on bit.
  constexpr void power_on() { bits_ = siof_mask(SiofBit::power_on); }
  constexpr void set(SiofBit b) { bits_ = static_cast<std::uint8_t>(bits_ | siof_mask(b)); }
  // Is a SELECT refused before it is even looked at?
  [[nodiscard]] constexpr bool blocks_select() const { return bits_ != 0; }
  [[nodiscard]] constexpr std::uint8_t bits() const { return bits_; }
  // The ENQUIRY of 85: the bits, which the read clears.
  constexpr std::uint8_t read_and_clear() {
    const std::uint8_t b = bits_;
    bits_ = 0;
    return b;
  }

 private:
  std::uint8_t bits_ = siof_mask(SiofBit::power_on);
};

// 5.2: "Setting [SIOT/SWDGT] to 0 deactivates the watchdog. If activated, the device monitors for
// a valid telegram to arrive within the set time"; any valid ENQUIRY or SELECT resets it (a dummy
// telegram on 83-SIOW/SDMMY is the usual one). The time is in ms (LB-D17).
class SerialWatchdog {
 public:
  // A valid telegram at `now` with the current 84 value (ms, 0 = off). Returns true when the
  // watchdog had already run out before this telegram (the caller enters its error).
  constexpr bool telegram(Time now, std::uint16_t timeout_ms) {
    const bool expired = expired_at(now, timeout_ms);
    last_ = now;
    return expired;
  }
  // Restarts the time (power on, the watchdog's own setting changed).
  constexpr void restart(Time now) { last_ = now; }
  [[nodiscard]] constexpr bool expired_at(Time now, std::uint16_t timeout_ms) const {
    return timeout_ms != 0 && now - last_ > std::chrono::milliseconds(timeout_ms);
  }
  [[nodiscard]] constexpr Time last() const { return last_; }

 private:
  Time last_{};
};

}  // namespace ibs::lustbus
