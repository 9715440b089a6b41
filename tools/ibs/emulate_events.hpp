// `emulate --json` of `ibs lustbus` and `ibs dfs1` (docs/lustbus.md and docs/dfs1.md, "Events as
// JSON"): one JSON object a line on standard output per event, in one shape for both buses, so
// that a program follows an emulator's line without reading its text. Every object has `time_s`
// (seconds since the emulator began to serve) and `event`; an event of one drive has its `device`
// (as given, `vf1000@1`) and `address` (the LUSTBUS address, the DFS-1 UID). Errors stay on
// standard error as text.
//
// A wrapper around a served device (base::LineDevice): it passes every call through and prints
// what the call did. The emulator's line loop is the tool's own (floor 4, steady clock, real
// ports); printing allocates there as the byte log of --log does.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "ibs/base/line_device.hpp"
#include "ibs/base/time.hpp"
#include "ibs/serial/byte_log.hpp"

namespace ibs::cli {

class EmulateEvents {
 public:
  explicit EmulateEvents(std::ostream& out) : out_(out) {}

  // An object with `time_s` and `event`; the caller adds the rest and print()s it.
  [[nodiscard]] static nlohmann::ordered_json event(Time at, std::string_view what) {
    nlohmann::ordered_json j;
    j["time_s"] = std::chrono::duration<double>(at).count();
    j["event"] = std::string(what);
    return j;
  }
  // The same for one drive.
  [[nodiscard]] static nlohmann::ordered_json event(Time at, std::string_view what, const std::string& device,
                                                    unsigned address) {
    nlohmann::ordered_json j = event(at, what);
    j["device"] = device;
    j["address"] = address;
    return j;
  }
  // Where the emulator serves, its first line: `pty: PATH` / `port: PATH` (and `pty link: PATH`),
  // or with --json the `serving` event that says the same.
  void serving(bool json, const std::string& key, const std::string& path, const std::string& link) {
    if (!json) {
      out_ << key << ": " << path << "\n";
      if (!link.empty()) out_ << "pty link: " << link << "\n";
      out_ << std::flush;
      return;
    }
    nlohmann::ordered_json j = event(Time{0}, "serving");
    j[key] = path;
    if (!link.empty()) j["pty_link"] = link;
    print(j);
  }
  void print(const nlohmann::ordered_json& j) { out_ << j.dump() << '\n' << std::flush; }

 private:
  std::ostream& out_;
};

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
