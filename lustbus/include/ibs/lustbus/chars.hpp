// The LUSTBUS characters (LUSTBUS manual 2.2), addresses (4.2) and the block check (2.2).
// 7 data bits, even parity, 1 stop bit (2.1) are the UART's job: every byte here is 7-bit ASCII,
// and a byte with bit 7 set stands for a character the UART received with a parity or framing
// error (the line simulation delivers kGarbled for characters that collided, 9.1).
#pragma once

#include <cstdint>
#include <optional>
#include <span>

namespace ibs::lustbus {

// 2.2. NAK is 15H = 21 decimal; the table's "15" decimal is an erratum (docs/errata.md, LB-E2).
inline constexpr std::uint8_t kStx = 0x02;
inline constexpr std::uint8_t kEtx = 0x03;
inline constexpr std::uint8_t kEot = 0x04;
inline constexpr std::uint8_t kEnq = 0x05;
inline constexpr std::uint8_t kAck = 0x06;
inline constexpr std::uint8_t kNak = 0x15;
inline constexpr std::uint8_t kEquals = 0x3D;  // '=' between CODE and VALUE

// A character received with a parity or framing error (any byte >= 80H counts as one).
inline constexpr std::uint8_t kGarbled = 0xFF;
constexpr bool is_garbled(std::uint8_t b) { return b >= 0x80; }

// 4.2: 0 '@' every device answers; 1..30 ('A'..'^') one device; 31 '_' (5FH) broadcast, SELECT
// only, never answered. ADR = 40H + address (2.2).
using Address = std::uint8_t;
inline constexpr Address kAddressAny = 0;
inline constexpr Address kFirstDeviceAddress = 1;
inline constexpr Address kLastDeviceAddress = 30;
inline constexpr Address kAddressBroadcast = 31;
inline constexpr std::uint8_t kAddressBase = 0x40;

constexpr bool is_valid_address(Address a) { return a <= kAddressBroadcast; }
constexpr bool is_device_address(Address a) {
  return a >= kFirstDeviceAddress && a <= kLastDeviceAddress;
}
constexpr std::uint8_t address_char(Address a) {
  return static_cast<std::uint8_t>(kAddressBase + (a & 0x1FU));
}
constexpr std::optional<Address> address_from_char(std::uint8_t c) {
  if (c < kAddressBase || c > kAddressBase + kAddressBroadcast) return std::nullopt;
  return static_cast<Address>(c - kAddressBase);
}

// 2.2: "All bytes between STX (exclusive) and ETX (inclusive) are EXOR'ed". The caller passes
// exactly those bytes. The result is 7-bit when they are; the byte after ETX is the BCC whatever
// its value, even a control character.
constexpr std::uint8_t bcc(std::span<const std::uint8_t> after_stx_through_etx) {
  std::uint8_t x = 0;
  for (const std::uint8_t b : after_stx_through_etx) x = static_cast<std::uint8_t>(x ^ b);
  return x;
}

// Characters a VALUE may hold: 7-bit, not one of the frame's control characters. NUL is allowed
// (the MC6000 description ends its name with '\0', 11.2.1).
// The six frame characters are all below 20H: one mask test (LustbusShortcuts checks every byte
// against the list).
inline constexpr std::uint32_t kFrameCharMask = (1U << kStx) | (1U << kEtx) | (1U << kEot) |
                                                (1U << kEnq) | (1U << kAck) | (1U << kNak);
constexpr bool is_value_char(std::uint8_t b) {
  return b < 0x80 && (b >= 0x20 || ((kFrameCharMask >> b) & 1U) == 0);
}

}  // namespace ibs::lustbus
