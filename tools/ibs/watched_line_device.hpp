// The serial emulators' `emulate --json` (`ibs lustbus`, `ibs dfs1`): a wrapper around a served
// device (base::LineDevice) that passes every call through and prints what the call did as the
// events of emulate_events.hpp.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "emulate_events.hpp"
#include "ibs/base/line_device.hpp"
#include "ibs/base/time.hpp"
#include "ibs/serial/byte_log.hpp"

namespace ibs::cli {

// A served device whose answers are printed as `answer` events with their bytes; what it received
// is told by `on_receive` after each byte (the caller knows its device's protocol).
class WatchedLineDevice final : public base::LineDevice {
 public:
  using OnByte = std::function<void(std::uint8_t byte, Time now)>;
  WatchedLineDevice(base::LineDevice& inner, EmulateEvents& events, std::string device,
                    std::function<unsigned()> address, OnByte on_byte)
      : inner_(inner),
        events_(events),
        device_(std::move(device)),
        address_(std::move(address)),
        on_byte_(std::move(on_byte)) {}

  [[nodiscard]] std::optional<Time> next_due() const override { return inner_.next_due(); }
  void advance(Time now) override { inner_.advance(now); }
  // Byte by byte, so that each telegram is told when its last byte completes it.
  void receive(std::span<const std::uint8_t> bytes, Time now) override {
    if (bytes.empty()) inner_.receive(bytes, now);
    for (const std::uint8_t& b : bytes) {
      inner_.receive(std::span<const std::uint8_t>(&b, 1), now);
      on_byte_(b, now);
    }
  }
  std::span<const std::uint8_t> output(Time now) override {
    const auto out = inner_.output(now);
    if (!out.empty()) {
      nlohmann::ordered_json j = EmulateEvents::event(now, "answer", device_, address_());
      j["bytes"] = serial::format_bytes(out);
      events_.print(j);
    }
    return out;
  }
  void written(std::size_t n) override { inner_.written(n); }
  [[nodiscard]] std::uint32_t line_baud() const override { return inner_.line_baud(); }

  [[nodiscard]] const std::string& device() const { return device_; }
  [[nodiscard]] unsigned address() const { return address_(); }

 private:
  base::LineDevice& inner_;
  EmulateEvents& events_;
  std::string device_;
  std::function<unsigned()> address_;
  OnByte on_byte_;
};

}  // namespace ibs::cli
