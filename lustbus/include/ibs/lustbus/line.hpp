// A multi-drop RS-485 line in simulated time, for tests and simulators (floor 2 keeps it beside
// the protocol because it has no I/O: bytes and time only). One host and any number of devices
// (Receivers, each serving its drive) share one half-duplex pair. A character takes 10 bits at
// the baud rate (LB-E10); every node hears every character but its own when it ends. Characters
// that overlap in time (two devices answering at address 0, 9.1) are delivered as kGarbled.
// Devices answer after the reaction time their Responder gives (10).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "ibs/base/time.hpp"
#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/receiver.hpp"

namespace ibs::lustbus {

inline constexpr int kHostNode = -1;

// A character as it went over the line.
struct LineChar {
  int node = kHostNode;  // kHostNode or the device's index
  std::uint8_t byte = 0;
  bool collided = false;
  Time start{};
  Time end{};
};

struct LineStats {
  std::uint64_t characters = 0;
  std::uint64_t collisions = 0;
};

class Line {
 public:
  explicit Line(std::uint32_t baud, Time start = Time{0});

  // Configuration (allocates). Nodes must outlive the Line.
  void attach(Host& host);
  int attach(Receiver& device);  // returns the device's index
  // A device set to another rate (4, 81-SIOC/SBAUD) hears only framing errors and is heard as
  // such (5.1: the host must find the rate). 0 = the line's rate.
  void set_device_baud(int device, std::uint32_t baud) {
    devices_.at(static_cast<std::size_t>(device)).baud = baud;
  }
  // Every character as it ends (tests: byte checks, timing).
  void set_tap(std::function<void(const LineChar&)> tap) { tap_ = std::move(tap); }
  // Fault injection: may replace a character (return another byte) or lose it (nullopt) before
  // the other nodes hear it; the sender still spends its time.
  void set_filter(std::function<std::optional<std::uint8_t>(const LineChar&)> f) {
    filter_ = std::move(f);
  }
  void set_baud(std::uint32_t baud) { baud_ = baud; }
  [[nodiscard]] std::uint32_t baud() const { return baud_; }

  // Advances simulated time to `t`, moving every character due until then.
  void run_until(Time t);
  // Runs until the host has finished every request and nothing is on the line, or `limit`.
  // true when idle.
  bool run_until_idle(Time limit);
  [[nodiscard]] Time now() const { return now_; }
  [[nodiscard]] const LineStats& stats() const { return stats_; }

 private:
  struct Node {
    Host* host = nullptr;
    Receiver* device = nullptr;
    int index = kHostNode;
    std::uint32_t baud = 0;  // 0: the line's
    std::vector<std::uint8_t> tx;  // reserved once; the bytes waiting to go out
    std::size_t tx_head = 0;
    bool in_flight = false;
    LineChar current{};
  };
  [[nodiscard]] Time next_event() const;
  void process(Time t);
  void deliver(const Node& from);
  void start_character(Node& n, Time t);
  void append(Node& n, std::span<const std::uint8_t> bytes);
  [[nodiscard]] bool quiet() const;
  [[nodiscard]] bool host_idle() const;

  std::uint32_t baud_;
  Time now_;
  Node host_{};
  std::vector<Node> devices_;
  LineStats stats_{};
  std::function<void(const LineChar&)> tap_;
  std::function<std::optional<std::uint8_t>(const LineChar&)> filter_;
};

}  // namespace ibs::lustbus
