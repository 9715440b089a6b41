// Classical CAN bit timing: the exact length of a 2.0A frame on the wire, stuff bits included
// (ISO 11898-1: SOF, 11-bit identifier, RTR, IDE, r0, DLC, data, CRC-15 are bit-stuffed - after
// five equal bits one complementary bit - then CRC delimiter, ACK slot, ACK delimiter and 7 EOF
// bits are not), and the bit time of a baud rate (489-CLBDR: 25..500 kbit/s, CANLust manual 4.3.1).
#pragma once

#include <cstdint>

#include "ibs/canlust/frame.hpp"
#include "ibs/base/time.hpp"

namespace ibs::can {

inline constexpr std::uint32_t kMinBitrate = 25'000;   // 489-CLBDR range
inline constexpr std::uint32_t kMaxBitrate = 500'000;
inline constexpr unsigned kIntermissionBits = 3;      // bus idle between two frames
inline constexpr unsigned kUnstuffedTailBits = 10;    // CRC delimiter, ACK slot + delimiter, EOF

struct FrameBits {
  unsigned stuffed_region = 0;  // SOF .. CRC, before stuffing: 34 + 8 x data bytes
  unsigned stuff = 0;           // stuff bits inserted
  unsigned tail = kUnstuffedTailBits;
  std::uint16_t crc = 0;        // the frame's CRC-15
  // SOF .. EOF as on the wire.
  [[nodiscard]] constexpr unsigned total() const { return stuffed_region + stuff + tail; }
  // What the frame takes of the bus, the intermission after it included.
  [[nodiscard]] constexpr unsigned on_bus() const { return total() + kIntermissionBits; }
};

// The bits of `f` computed from its actual identifier, RTR, DLC and data.
FrameBits frame_bits(const canlust::CanFrame& f);

// The CRC-15 of ISO 11898-1 (polynomial 4599H) over `bits` bits given MSB-first in `bytes`.
std::uint16_t crc15_bits(const std::uint8_t* bits, unsigned count);

constexpr bool valid_bitrate(std::uint32_t bps) { return bps >= kMinBitrate && bps <= kMaxBitrate; }
// Integer nanoseconds; exact for 25, 50, 100, 125, 250, 500 kbit/s.
constexpr Duration bit_time(std::uint32_t bps) { return Duration(1'000'000'000LL / bps); }

}  // namespace ibs::can
