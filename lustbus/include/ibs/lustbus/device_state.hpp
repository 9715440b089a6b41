// What every LUSTBUS drive keeps the same way, whatever its parameters: the 85-SIOF/SERR latch of
// LUSTBUS manual 6 and 9.2, and the network watchdog of 5.2 (84-SIOT/SWDGT). Drive-neutral: the wings'
// Responders (devices/*/emulator/.../lustbus_device.hpp) hold one of each. Allocation-free.
#pragma once

#include <chrono>
#include <cstdint>

#include "ibs/base/time.hpp"
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

// 10: "the time to react to a telegram depends on the individual device and its load". The
// emulated drives draw each reaction from a seeded generator, uniformly between `min` and `max` in
// whole microseconds (LB-D18): the same seed gives the same times. min == max is a fixed time.
// Each drive's range (10's table, with and without a KEYPAD) is its wing's: lustbus_reaction() in
// devices/<drive>/emulator/.../lustbus_device.hpp.
struct ReactionModel {
  Duration min = std::chrono::milliseconds(2);
  Duration max = std::chrono::milliseconds(2);
  std::uint64_t seed = 0;

  static constexpr ReactionModel fixed(Duration d) { return {d, d, 0}; }
  static constexpr ReactionModel uniform(Duration lo, Duration hi, std::uint64_t seed) { return {lo, hi, seed}; }
};

class ReactionTimes {
 public:
  constexpr explicit ReactionTimes(ReactionModel m = {}) : model_(m), state_(m.seed) {}
  // The next reaction time (splitmix64; allocation-free).
  constexpr Duration next() {
    if (model_.max <= model_.min) return model_.min;
    state_ += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27U)) * 0x94D049BB133111EBULL;
    z ^= z >> 31U;
    const auto span_us = static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::microseconds>(model_.max - model_.min).count());
    return model_.min + std::chrono::microseconds(static_cast<std::int64_t>(z % (span_us + 1)));
  }
  [[nodiscard]] constexpr const ReactionModel& model() const { return model_; }

 private:
  ReactionModel model_;
  std::uint64_t state_;
};

}  // namespace ibs::lustbus
