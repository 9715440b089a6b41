// A classical CAN 2.0A frame as CANLust uses it: an 11-bit identifier, 0..8 data bytes and the
// RTR flag (CANLust manual 5.5; public-facts "CANLust": every CANLust identifier is 11 bits). Plain
// value type: no allocation, no exceptions.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <initializer_list>
#include <span>

namespace ibs::canlust {

inline constexpr std::uint16_t kMaxStandardId = 0x7FF;
inline constexpr std::uint8_t kMaxDlc = 8;

// Aligned to 4 (issue 26): still 12 bytes, but an std::optional<CanFrame> - what the
// take_frame() of the client, the node and the drives return - is then 16 whole bytes, which the
// compiler moves as two words instead of piecing 14 bytes together through the stack.
struct alignas(4) CanFrame {
  std::uint16_t id = 0;   // 0..7FFH
  std::uint8_t dlc = 0;   // 0..8; an RTR frame has a DLC but carries no data
  bool rtr = false;
  std::array<std::uint8_t, kMaxDlc> data{};

  [[nodiscard]] constexpr std::span<const std::uint8_t> payload() const {
    return {data.data(), rtr ? 0U : std::min<std::size_t>(dlc, kMaxDlc)};
  }
  [[nodiscard]] constexpr bool valid() const { return id <= kMaxStandardId && dlc <= kMaxDlc; }

  // Two frames are the same on the bus when id, RTR, DLC and the bytes the DLC covers agree.
  friend constexpr bool operator==(const CanFrame& a, const CanFrame& b) {
    if (a.id != b.id || a.dlc != b.dlc || a.rtr != b.rtr) return false;
    if (a.rtr) return true;
    const auto n = std::min<std::size_t>(a.dlc, kMaxDlc);
    for (std::size_t i = 0; i < n; ++i) {
      if (a.data[i] != b.data[i]) return false;
    }
    return true;
  }

  static constexpr CanFrame make(std::uint16_t id, std::initializer_list<std::uint8_t> bytes) {
    CanFrame f;
    f.id = id;
    std::size_t i = 0;
    for (const auto b : bytes) {
      if (i == kMaxDlc) break;
      f.data[i++] = b;
    }
    f.dlc = static_cast<std::uint8_t>(i);
    return f;
  }
};

// Intel byte order (CANLust manual 4.1.1 table 4.1: "Low Word Low Byte" first).
constexpr void put_le16(std::span<std::uint8_t> out, std::uint16_t v) {
  out[0] = static_cast<std::uint8_t>(v & 0xFFU);
  out[1] = static_cast<std::uint8_t>(v >> 8U);
}
constexpr void put_le32(std::span<std::uint8_t> out, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) out[i] = static_cast<std::uint8_t>((v >> (8U * i)) & 0xFFU);
}
constexpr std::uint16_t get_le16(std::span<const std::uint8_t> in) {
  return static_cast<std::uint16_t>(in[0] | (in[1] << 8U));
}
constexpr std::uint32_t get_le32(std::span<const std::uint8_t> in) {
  return static_cast<std::uint32_t>(in[0]) | (static_cast<std::uint32_t>(in[1]) << 8U) |
         (static_cast<std::uint32_t>(in[2]) << 16U) | (static_cast<std::uint32_t>(in[3]) << 24U);
}

}  // namespace ibs::canlust
