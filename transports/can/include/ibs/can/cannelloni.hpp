// cannelloni's UDP format, version 2 (public-facts "Serial and CAN practice"; cannelloni's
// doc/udp_format.md): a datagram is a header - version (2), op code (0 = DATA), sequence
// number, frame count (2 bytes) - and the frames, each the 4-byte Linux can_id with its flags
// (EFF 80000000H, RTR 40000000H, ERR 20000000H), a length byte (CAN FD: flag 80H, then a flags
// byte) and the data; RTR frames carry their DLC but no data. All big-endian. Sans-I/O, no
// allocation: encode into a caller's buffer, decode into a caller's span.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "ibs/canlust/frame.hpp"

namespace ibs::can::cannelloni {

using canlust::CanFrame;

inline constexpr std::uint8_t kVersion = 2;
inline constexpr std::uint8_t kOpData = 0;
inline constexpr std::size_t kHeaderSize = 5;
inline constexpr std::uint32_t kEffFlag = 0x80000000U;
inline constexpr std::uint32_t kRtrFlag = 0x40000000U;
inline constexpr std::uint32_t kErrFlag = 0x20000000U;
inline constexpr std::uint8_t kCanFdFrame = 0x80;  // in the length byte
// cannelloni's default datagram limit; a CANLust datagram of one frame is 5 + 13 bytes.
inline constexpr std::size_t kMaxDatagram = 1472;

[[nodiscard]] std::size_t encoded_size(std::span<const CanFrame> frames);
// The datagram's length, or nullopt when `out` is too small or a frame is invalid.
std::optional<std::size_t> encode(std::span<const CanFrame> frames, std::uint8_t sequence,
                                  std::span<std::uint8_t> out);

enum class DecodeStatus : std::uint8_t {
  ok,
  truncated,     // the datagram ends inside the header or a frame
  bad_version,
  bad_op_code,
  out_full,      // more 2.0A frames than `out` holds: the first ones are in `out`
  trailing,      // bytes after the frames the header counts
};
// Any status but `ok` means a broken datagram: the header and the content disagree (a count the
// bytes do not hold, a frame cut short, bytes left over) or the datagram is not cannelloni's.
// Frames already written to `out` must not be used -- a receiver drops the datagram whole.
std::string_view to_string(DecodeStatus s);

struct DecodeResult {
  DecodeStatus status = DecodeStatus::ok;
  std::uint8_t sequence = 0;
  std::uint16_t count = 0;     // frames the header declares
  std::size_t frames = 0;      // CAN 2.0A frames written to `out`
  std::size_t skipped = 0;     // extended, error and CAN FD frames (not CANLust's)
};
DecodeResult decode(std::span<const std::uint8_t> datagram, std::span<CanFrame> out);

}  // namespace ibs::can::cannelloni
