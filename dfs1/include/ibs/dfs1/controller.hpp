// The controller's side of the DFS-1 protocol: it hears every byte on the line, takes the
// frames for its UID and the global 83 (UID 0), answers unknown commands and wrong data lengths
// with NAK 86 itself, hands every other request to a RequestHandler (the drive), and sends the
// reply after the communications turnaround delay (parameter 56; decision D2 for its unit).
//
// receive(), pending(), consume() allocate nothing and throw nothing; time is passed in.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "ibs/dfs1/frame.hpp"
#include "ibs/dfs1/protocol.hpp"
#include "ibs/base/time.hpp"

namespace ibs::dfs1 {

// What the drive answers to one request.
struct Reply {
  enum class Kind : std::uint8_t { ack, nak, none };
  Kind kind = Kind::none;
  ErrorCode error = ErrorCode::illegal_command;  // nak
  std::uint8_t size = 0;                         // ack data bytes
  std::array<std::uint8_t, kMaxData> data{};

  static Reply ack(std::span<const std::uint8_t> d = {});
  static Reply ack_value(std::uint32_t v);
  static Reply nak(ErrorCode e);
  static Reply none() { return {}; }
};

// The drive behind a receiver. `request` has a known command with its data length (protocol.hpp);
// `global` is true for the 83 to UID 0, whose reply is never sent.
class RequestHandler {
 public:
  virtual Reply handle(const Frame& request, bool global, Time now) = 0;

 protected:
  RequestHandler() = default;
  RequestHandler(const RequestHandler&) = default;
  RequestHandler& operator=(const RequestHandler&) = default;
  ~RequestHandler() = default;
};

// A frame begun and not finished (or a DLE that may begin one), followed by this much silence,
// is dropped before the next byte is taken (docs/dfs1.md D13): 20 characters of 10 bits at the
// line's rate, never less than 50 ms. The seed gives no time; without one, a host that dies
// mid-frame has its frame completed or the next host's request swallowed by the bytes after it.
inline constexpr Duration kFragmentTimeoutFloor = std::chrono::milliseconds(50);
constexpr Duration fragment_timeout(std::uint32_t baud) {
  const Duration twenty{(std::int64_t{200} * 1'000'000'000 + baud / 2) / baud};
  return twenty > kFragmentTimeoutFloor ? twenty : kFragmentTimeoutFloor;
}

class ControllerReceiver {
 public:
  ControllerReceiver(std::uint8_t uid, Duration turnaround) : uid_(uid), turnaround_(turnaround) {}

  void receive(std::uint8_t byte, Time now, RequestHandler& handler);
  void receive(std::span<const std::uint8_t> bytes, Time now, RequestHandler& handler);
  // The reply bytes not yet sent, once the turnaround has passed at `now`; empty otherwise.
  std::span<const std::uint8_t> pending(Time now) const;
  // `n` bytes of pending() have been put on the line.
  void consume(std::size_t n);
  // When a reply becomes due; nullopt when none waits.
  std::optional<Time> next_deadline() const;
  bool replying() const { return sent_ < reply_.size; }
  // The controller was switched off and on: a frame being received and a reply not yet sent are
  // lost (what a power cycle does to a UART and its buffers); UID, turnaround, fragment timeout
  // and the counters stay, they belong to whoever owns the receiver.
  void restart();

  std::uint8_t uid() const { return uid_; }
  void set_uid(std::uint8_t uid) { uid_ = uid; }
  Duration turnaround() const { return turnaround_; }
  void set_turnaround(Duration d) { turnaround_ = d; }
  // The silence after which a fragment is dropped (zero: never); fragment_timeout(9600) until set.
  Duration fragment_timeout() const { return gap_; }
  void set_fragment_timeout(Duration d) { gap_ = d; }

  struct Counters {
    std::uint64_t requests = 0;  // frames for us or global, handled or NAKed
    std::uint64_t globals = 0;   // 83 to UID 0
    std::uint64_t foreign = 0;   // frames for another UID, or UID 0 with another command
    std::uint64_t decode_errors = 0;
    std::uint64_t dropped_replies = 0;  // a new request came before the old reply was sent
    std::uint64_t fragments = 0;        // partial frames dropped after a silence (D13)
  };
  const Counters& counters() const { return counters_; }

 private:
  void on_frame(const Frame& f, Time now, RequestHandler& handler);

  std::uint8_t uid_;
  Duration turnaround_;
  FrameDecoder decoder_;
  EncodedFrame reply_{};
  std::size_t sent_ = 0;
  Time due_{};
  Counters counters_{};
  Duration gap_ = dfs1::fragment_timeout(9600);
  Time last_byte_at_{};
};

}  // namespace ibs::dfs1
