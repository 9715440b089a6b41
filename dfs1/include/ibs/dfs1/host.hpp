// The host's side of the DFS-1 protocol: request builders and one transaction at a time.
//
// start() encodes a request; the caller sends tx() and calls transmitted() when the last byte
// has left; then receive() takes the line's bytes and poll() the time. The transaction ends in
// exactly one HostResult: ACK (with its data), NAK (with its error code), a timeout, a bad
// response, or "sent" for the global 83 that no one answers (notes, "PowerTec DFS-1").
// Timeouts follow the serial practice of ../shared/notes/public-facts.md: a response timeout
// until the first byte of the response, then an inter-byte timeout between its bytes.
//
// Frames for other UIDs and frames that are no response (ACK/NAK) are ignored; corrupt frames are
// counted and named in the result if the transaction then times out. Allocates nothing, throws
// nothing; time is passed in.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "ibs/dfs1/frame.hpp"
#include "ibs/dfs1/protocol.hpp"
#include "ibs/base/time.hpp"

namespace ibs::dfs1 {

// Request builders: the command list's data fields (docs/dfs1.md, "Commands").
namespace request {
Frame status(std::uint8_t uid);
Frame set_speed(std::uint8_t uid, std::int32_t rpm);
Frame execute_speed(std::uint8_t uid);  // uid 0: every controller on the line, no answer
Frame set_and_execute_speed(std::uint8_t uid, std::int32_t rpm);
Frame read_parameter(std::uint8_t uid, std::uint8_t parameter);
Frame write_parameter(std::uint8_t uid, std::uint8_t parameter, std::uint32_t value);
Frame read_analog_input(std::uint8_t uid, std::uint8_t channel);
Frame read_analog_output(std::uint8_t uid, std::uint8_t channel);
Frame write_analog_output(std::uint8_t uid, std::uint8_t channel, std::uint32_t value);
Frame read_digital_input(std::uint8_t uid, std::uint8_t channel);
Frame read_digital_output(std::uint8_t uid, std::uint8_t channel);
Frame write_digital_output(std::uint8_t uid, std::uint8_t channel, std::uint32_t value);
// 00 00 SMH SML: a mask of the digital inputs; bit 0 (input 1, E-stop) must be 0 (notes).
Frame set_operational_mode(std::uint8_t uid, std::uint16_t mask);
Frame read_operational_mode(std::uint8_t uid);
Frame application_mode(std::uint8_t uid, std::uint8_t mode, std::uint32_t value);
}  // namespace request

// Whether a request may be sent at all: a known command with its data length, UID 0 only for 83.
enum class RequestCheck : std::uint8_t { ok, unknown_command, bad_size, global_not_83 };
RequestCheck check_request(const Frame& request);
std::string_view to_string(RequestCheck c);

struct HostTimeouts {
  Duration response = 100ms;   // transmitted() -> first byte of the response
  Duration inter_byte = 10ms;  // between two bytes of the response
  // transmitted() -> the end, however the line behaves: the response time and then the longest
  // frame with every gap at the inter-byte limit. A device that keeps sending (each byte
  // restarting the inter-byte timer) cannot hold the host beyond it (outcome line_busy).
  [[nodiscard]] Duration overall() const {
    return response + static_cast<Duration::rep>(kMaxEncodedSize) * inter_byte;
  }
};

enum class Outcome : std::uint8_t {
  ack,                 // HostResult::response holds the data
  nak,                 // HostResult::error holds the code (80..86 or another byte)
  timeout,             // no response began in time
  inter_byte_timeout,  // a response began and stopped
  bad_response,        // our UID answered with a data length that does not fit the request
  sent,                // a global 83: no response is expected
  line_busy,           // bytes kept coming and no response ended by HostTimeouts::overall()
};
std::string_view to_string(Outcome o);

struct HostResult {
  Outcome outcome = Outcome::timeout;
  Frame request{};
  Frame response{};                              // ack, nak, bad_response
  std::uint8_t error = 0;                        // nak
  Duration elapsed{};                            // transmitted() -> end
  std::optional<DecodeError> last_decode_error;  // the last corrupt frame seen while waiting
  // What the line carried while the host waited: bytes, frames that were not our response
  // (another UID, a request), corrupt frames.
  std::uint32_t bytes_heard = 0;
  std::uint32_t other_frames = 0;
  std::uint32_t corrupt_frames = 0;
  std::uint32_t value() const { return response.value_at(0); }
};

enum class StartStatus : std::uint8_t { accepted, busy, rejected };

class HostTransaction {
 public:
  enum class State : std::uint8_t { idle, sending, awaiting_response, done };

  explicit HostTransaction(HostTimeouts timeouts = {}) : timeouts_(timeouts) {}

  // rejected: check_request() said no; busy: a transaction is not yet taken.
  StartStatus start(const Frame& request, Time now);
  // The request's bytes, while State::sending.
  std::span<const std::uint8_t> tx() const { return tx_.span(); }
  void transmitted(Time now);
  void receive(std::uint8_t byte, Time now);
  void receive(std::span<const std::uint8_t> bytes, Time now);
  void poll(Time now);
  // When poll() must be called next; nullopt when no timer runs.
  std::optional<Time> next_deadline() const;

  State state() const { return state_; }
  bool done() const { return state_ == State::done; }
  // The result once done(); the transaction is idle again afterwards.
  std::optional<HostResult> take_result();

  const HostTimeouts& timeouts() const { return timeouts_; }
  void set_timeouts(HostTimeouts t) { timeouts_ = t; }
  // Frames seen for another UID, non-response frames, corrupt frames (over the object's life).
  std::uint64_t foreign_frames() const { return foreign_frames_; }
  std::uint64_t decode_errors() const { return decode_errors_; }

 private:
  void finish(Outcome o, Time now);

  HostTimeouts timeouts_;
  State state_ = State::idle;
  Frame request_{};
  EncodedFrame tx_{};
  FrameDecoder decoder_;
  HostResult result_{};
  Time sent_at_{};
  Time deadline_{};
  Time response_deadline_{};
  Time overall_deadline_{};
  std::uint32_t bytes_heard_ = 0;
  std::uint32_t other_frames_ = 0;
  std::uint32_t corrupt_frames_ = 0;
  std::optional<DecodeError> last_error_;
  std::uint64_t foreign_frames_ = 0;
  std::uint64_t decode_errors_ = 0;
};

}  // namespace ibs::dfs1
