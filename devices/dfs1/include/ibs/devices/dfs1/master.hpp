// The DFS-1 master driver: a queue of requests sent one at a time through the host's
// transaction machine (ibs::dfs1::HostTransaction), each ending in one Completion: ACK, NAK,
// timeout, bad response, or "sent" for the global 83. Sans-I/O: the line side is pending() /
// consume() / receive() / poll() with time passed in; docs/dfs1.md, "Host".
//
// Fixed capacity; everything after construction allocates nothing and throws nothing.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "ibs/dfs1/frame.hpp"
#include "ibs/dfs1/host.hpp"
#include "ibs/base/time.hpp"

namespace ibs::devices::dfs1 {

using Ticket = std::uint32_t;

struct Completion {
  Ticket ticket = 0;
  ::ibs::dfs1::HostResult result;
};

class Master {
 public:
  // Requests queued, in flight and completed but not taken, together.
  static constexpr std::size_t kCapacity = 16;

  explicit Master(::ibs::dfs1::HostTimeouts timeouts = {}) : transaction_(timeouts) {}

  // nullopt when the queue is full or the request is refused by check_request().
  std::optional<Ticket> submit(const ::ibs::dfs1::Frame& request);

  // The bytes of the request in flight not yet put on the line; starts the next queued request
  // when none is in flight.
  std::span<const std::uint8_t> pending(Time now);
  // `n` bytes of pending() have left the line at `now` (the last one starts the response timer).
  void consume(std::size_t n, Time now);
  void receive(std::uint8_t byte, Time now);
  void receive(std::span<const std::uint8_t> bytes, Time now);
  void poll(Time now);
  std::optional<Time> next_deadline() const { return transaction_.next_deadline(); }

  std::optional<Completion> take_completion();
  // Nothing queued, nothing in flight (completions may wait to be taken).
  bool idle() const { return queued_ == 0 && !active_; }
  std::size_t completions() const { return done_count_; }
  const ::ibs::dfs1::HostTransaction& transaction() const { return transaction_; }

 private:
  void collect();

  ::ibs::dfs1::HostTransaction transaction_;
  std::array<std::pair<Ticket, ::ibs::dfs1::Frame>, kCapacity> queue_{};
  std::size_t queue_head_ = 0;
  std::size_t queued_ = 0;
  std::array<Completion, kCapacity> done_{};
  std::size_t done_head_ = 0;
  std::size_t done_count_ = 0;
  bool active_ = false;
  Ticket active_ticket_ = 0;
  std::size_t sent_ = 0;
  Ticket next_ticket_ = 1;
};

}  // namespace ibs::devices::dfs1
