// DFS-1 frames: DLE STX UID CMD [data] DLE ETX CSM (DFS-1 manual 6.0). A 10H inside the frame is
// sent twice; CSM is the 2's complement of the sum of the unstuffed bytes between STX and ETX
// (the seed's example: 01 82 00 00 10 00 -> 6DH). A CSM of 10H is sent twice as well (decision
// D1). Responses use the same frame with ACK or NAK in the CMD position.
//
// encode() and FrameDecoder::push() allocate nothing and throw nothing.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "ibs/dfs1/protocol.hpp"

namespace ibs::dfs1 {

// The longest data part of any frame: the status response (decision D3).
inline constexpr std::size_t kMaxData = 16;
// DLE STX, UID CMD data each possibly doubled, DLE ETX, CSM possibly doubled.
inline constexpr std::size_t kMaxEncodedSize = 2 + 2 * (2 + kMaxData) + 2 + 2;

struct Frame {
  std::uint8_t uid = 0;
  std::uint8_t code = 0;  // CMD in a request, ACK or NAK in a response
  std::uint8_t size = 0;  // data bytes used
  std::array<std::uint8_t, kMaxData> data{};

  std::span<const std::uint8_t> payload() const { return {data.data(), size}; }
  bool is_ack() const { return code == kAck; }
  bool is_nak() const { return code == kNak; }
  // The 4-byte value at data[offset] (most significant first); 0 when the frame is too short.
  std::uint32_t value_at(std::size_t offset) const;

  friend bool operator==(const Frame& a, const Frame& b);
};

// Builders. Data longer than kMaxData is cut (only a programming error can ask for it).
Frame make_frame(std::uint8_t uid, std::uint8_t code, std::span<const std::uint8_t> data = {});
Frame make_ack(std::uint8_t uid, std::span<const std::uint8_t> data = {});
Frame make_nak(std::uint8_t uid, ErrorCode error);

// The checksum of the unstuffed bytes between STX and ETX.
std::uint8_t checksum(const Frame& f);

struct EncodedFrame {
  std::array<std::uint8_t, kMaxEncodedSize> bytes{};
  std::size_t size = 0;
  std::span<const std::uint8_t> span() const { return {bytes.data(), size}; }
};
EncodedFrame encode(const Frame& f);

enum class DecodeError : std::uint8_t {
  bad_checksum,          // CSM does not match the bytes
  too_short,             // DLE ETX before UID and CMD
  too_long,              // more than kMaxData data bytes: the frame is dropped, the decoder hunts
  lone_dle,              // a DLE inside the frame followed by neither DLE, ETX nor STX
  checksum_not_doubled,  // a CSM of 10H not followed by its second 10H (decision D1)
  interrupted,           // DLE STX inside a frame: the partial frame is dropped, a new one begins
};
std::string_view to_string(DecodeError e);

enum class DecodeStatus : std::uint8_t { need_more, frame, error };

struct DecodeResult {
  DecodeStatus status = DecodeStatus::need_more;
  DecodeError error = DecodeError::bad_checksum;  // meaningful when status == error
};

// A streaming decoder: one byte in, "need more" / a frame / an error out. Outside a frame it
// hunts for DLE STX and discards everything else (counted in garbage()).
class FrameDecoder {
 public:
  DecodeResult push(std::uint8_t byte);
  // The frame of the last DecodeStatus::frame; valid until the next push().
  const Frame& frame() const { return frame_; }
  // Inside a frame (after DLE STX, before its end).
  bool in_frame() const { return state_ != State::hunt && state_ != State::hunt_dle; }
  // Hunting with nothing held: not inside a frame, and no DLE that may begin one.
  bool at_rest() const { return state_ == State::hunt; }
  void reset();
  std::uint64_t garbage() const { return garbage_; }

 private:
  enum class State : std::uint8_t { hunt, hunt_dle, body, body_dle, checksum, checksum_dle };
  DecodeResult finish(std::uint8_t csm);
  void start();

  State state_ = State::hunt;
  Frame frame_{};
  std::size_t body_size_ = 0;  // unstuffed bytes after STX: UID, CMD, data
  std::uint8_t sum_ = 0;
  std::uint64_t garbage_ = 0;
};

}  // namespace ibs::dfs1
