// An in-process CAN bus for tests and the simulator: several nodes, arbitration by identifier
// priority, frame times from the exact bit length (stuff bits included, bit_timing.hpp) at a
// baud rate of 25..500 kbit/s, delivery to every other node at the end of the frame, and bus
// load statistics. Time is passed in (it is a simulation component; no clock is read).
//
//   VirtualBus bus({.bitrate = 500'000});
//   auto a = bus.attach("master"), b = bus.attach("drive 1");
//   bus.send(a, frame, now);         // queued in a's transmit buffer from `now`
//   bus.advance(now);                // runs arbitration and transmissions up to `now`
//   while (auto d = bus.receive(b)) ... d->frame, d->time (end of the frame)
//   bus.next_event();                // the end of the frame on the bus / the next start
//
// Arbitration: when the bus is idle, every node whose oldest queued frame is ready contends; the
// lowest identifier wins (a data frame beats a remote frame of the same identifier: RTR is
// recessive); the others wait for the next idle bus. Each node transmits its queue in order (one
// transmit buffer, decision D19). send, advance and receive allocate nothing and throw nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/can/bit_timing.hpp"
#include "ibs/canlust/frame.hpp"
#include "ibs/base/time.hpp"

namespace ibs::can {

using canlust::CanFrame;
using NodeId = std::uint16_t;

struct VirtualBusConfig {
  std::uint32_t bitrate = 500'000;  // 25'000..500'000 (489-CLBDR)
  std::size_t tx_capacity = 64;     // per node
  std::size_t rx_capacity = 512;    // per node
};

struct Delivery {
  CanFrame frame{};
  Time time{};         // end of the frame (the EOF's last bit)
  Time start{};        // its SOF
  NodeId sender = 0;
};

struct BusStats {
  std::uint64_t frames = 0;
  std::uint64_t bits = 0;          // SOF..EOF, stuff bits included
  std::uint64_t stuff_bits = 0;
  std::uint64_t arbitration_losses = 0;  // a contender that had to wait for a lower identifier
  std::uint64_t tx_overflows = 0;  // send() into a full transmit buffer
  std::uint64_t rx_overflows = 0;  // deliveries to a full receive buffer (frame lost)
  Duration busy{};                 // frames plus their intermission
  Time since{};                    // start of the statistics
  Time until{};                    // the last advance()
  // Fraction of the time between `since` and `until` the bus was busy (0..1).
  [[nodiscard]] double load() const;
};

class VirtualBus {
 public:
  // Throws std::invalid_argument for a bit rate outside 25..500 kbit/s (configuration time).
  explicit VirtualBus(const VirtualBusConfig& config = {});

  NodeId attach(std::string_view name);  // configuration time: allocates the node's buffers
  // Queued for transmission, ready from `now`. False when the node's buffer is full or the frame
  // is invalid.
  bool send(NodeId node, const CanFrame& f, Time now);
  void advance(Time now);
  std::optional<Delivery> receive(NodeId node);
  // The end of the frame on the bus, or the start of the next one; Time::max() when idle.
  [[nodiscard]] Time next_event() const;
  [[nodiscard]] bool idle() const;

  [[nodiscard]] const BusStats& stats() const { return stats_; }
  void reset_stats(Time now);
  [[nodiscard]] Duration bit_time() const { return bit_; }
  [[nodiscard]] std::uint32_t bitrate() const { return config_.bitrate; }
  [[nodiscard]] std::string_view name(NodeId n) const { return nodes_[n].name; }
  [[nodiscard]] std::size_t nodes() const { return nodes_.size(); }

 private:
  struct Pending {
    CanFrame frame{};
    Time ready{};
  };
  struct Node {
    std::string name;
    std::vector<Pending> tx;  // ring
    std::size_t tx_head = 0;
    std::size_t tx_size = 0;
    std::vector<Delivery> rx;  // ring
    std::size_t rx_head = 0;
    std::size_t rx_size = 0;
  };
  struct OnBus {
    bool active = false;
    NodeId sender = 0;
    CanFrame frame{};
    Time start{};
    Time end{};
    FrameBits bits{};
  };
  [[nodiscard]] std::optional<Time> next_start() const;

  VirtualBusConfig config_;
  Duration bit_;
  std::vector<Node> nodes_;
  OnBus current_{};
  Time free_at_{};  // the bus is idle from here (after the intermission)
  BusStats stats_{};
};

}  // namespace ibs::can
