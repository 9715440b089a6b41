// INTERBUS ID codes: the 16-bit word every device reports in the identification cycle.
// Structure (public-facts.md, "ID code"): low byte = device group (bits 1..0 direction, 3..2 type,
// 7..4 class), bits 8..12 = length code, bits 13..15 = dynamic error messages.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "ibs/base/words.hpp"

namespace ibs::interbus {

// Where a device sits in the ring: on the remote bus (its own couplers, up to 400 m apart) or on a
// local bus segment behind a bus terminal.
enum class BusKind : std::uint8_t { local, remote };

// Data direction, bits 1..0 of the device group (public-facts.md).
enum class Direction : std::uint8_t { none = 0, out = 1, in = 2, in_out = 3 };

// One row of the length-code table: bus words -> code in bits 8..12. Linear for 0..5 words, then
// the table of public-facts.md (Schneider 890USE19600). Code 0 is a device without data words
// (a bus terminal): the bus-coupler codes of public manuals report it with length 0.
struct LengthCodeRow {
  std::uint8_t words;
  std::uint8_t code;
};
inline constexpr std::array<LengthCodeRow, 16> kLengthCodes{{
    {0, 0x00},
    {1, 0x01},
    {2, 0x02},
    {3, 0x03},
    {4, 0x04},
    {5, 0x05},
    {6, 0x0E},
    {7, 0x0F},
    {8, 0x06},
    {9, 0x07},
    {10, 0x15},
    {12, 0x16},
    {14, 0x17},
    {16, 0x12},
    {24, 0x13},
    {26, 0x11},
}};

// Words -> length code and back, both from kLengthCodes; nullopt for a value the table lacks.
constexpr std::optional<int> words_from_length_code(unsigned code) {
  for (const LengthCodeRow& r : kLengthCodes) {
    if (r.code == code) return r.words;
  }
  return std::nullopt;
}
constexpr std::optional<unsigned> length_code_from_words(int words) {
  for (const LengthCodeRow& r : kLengthCodes) {
    if (r.words == words) return r.code;
  }
  return std::nullopt;
}

// PCP channel width in the two low bits of a PCP device's group byte (public-facts.md, Lenze
// EMF2113IB / KUKA; matches INTERBUS manual 3.2.2: 1D3H 1 word, 2D0H 2 words, 4D1H 4 words). 10b is not
// assigned.
struct PcpWidthRow {
  std::uint8_t bits;
  std::uint8_t words;
};
inline constexpr std::array<PcpWidthRow, 3> kPcpWidths{{{0b11, 1}, {0b00, 2}, {0b01, 4}}};

constexpr std::optional<int> pcp_words_from_bits(unsigned bits) {
  for (const PcpWidthRow& r : kPcpWidths) {
    if (r.bits == bits) return r.words;
  }
  return std::nullopt;
}
constexpr std::optional<unsigned> pcp_bits_from_words(int words) {
  for (const PcpWidthRow& r : kPcpWidths) {
    if (r.words == words) return r.bits;
  }
  return std::nullopt;
}

inline constexpr Word kLengthCodeMask = 0x1F00;  // bits 8..12
inline constexpr Word kErrorBitsMask = 0xE000;   // bits 13..15, dynamic error messages
inline constexpr unsigned kLengthCodeShift = 8;

// A device's ID code. Decoding ignores the error bits 13..15 except in error_bits().
//
// Two properties are not spelled out by any public source and are modelling choices derived from
// the codes we know (INTERBUS manual 3.1.2 and 3.2.2, KUKA 0/1/2/4-word PCP codes 03H/EBH/E8H/E9H, WAGO
// 750-344 remote-bus codes 01H..03H, 31H..33H, 3CH):
//  - PCP device: class bits 7 and 6 both set (classes CH..FH). INTERBUS manual: class DH has PCP, classes
//    9H, 7H, 3H (193H, 17BH, 33BH) have none; KUKA's PCP codes are class EH.
//  - Local bus device: class bit 7 set and type bit 3 clear. INTERBUS manual: MC6000 local 193H, 1D3H,
//    2D0H, 4D1H against remote 17BH, 1DBH, 2D8H, 4D9H and the VF1000's 33BH; the WAGO and KUKA
//    remote-bus codes (class below 8H or type bit 3 set) agree. A bus configuration may override
//    it per device.
struct IdCode {
  Word raw = 0;

  constexpr std::uint8_t group() const { return low_byte(raw); }
  constexpr unsigned direction_bits() const { return group() & 0x03U; }
  constexpr unsigned type_bits() const { return (group() >> 2U) & 0x03U; }
  constexpr unsigned device_class() const { return (group() >> 4U) & 0x0FU; }
  constexpr unsigned length_code() const {
    return static_cast<unsigned>(raw & kLengthCodeMask) >> kLengthCodeShift;
  }
  constexpr unsigned error_bits() const {
    return static_cast<unsigned>(raw & kErrorBitsMask) >> 13U;
  }
  // The code as configured, without the dynamic error messages.
  constexpr IdCode without_errors() const {
    return IdCode{static_cast<Word>(raw & static_cast<Word>(~kErrorBitsMask))};
  }

  constexpr bool has_pcp() const { return (device_class() & 0x0CU) == 0x0CU; }
  constexpr BusKind bus() const {
    const bool local = (device_class() & 0x08U) != 0 && (type_bits() & 0x02U) == 0;
    return local ? BusKind::local : BusKind::remote;
  }

  // Words the device occupies in the ring (process data plus PCP); nullopt for an unknown code.
  constexpr std::optional<int> ring_words() const { return words_from_length_code(length_code()); }
  // PCP channel width: 0 for a device without PCP, nullopt for the unassigned width bits 10b.
  constexpr std::optional<int> pcp_words() const {
    if (!has_pcp()) return 0;
    return pcp_words_from_bits(direction_bits());
  }
  // Process-data words = ring words - PCP words; nullopt when either is unknown or PCP is wider
  // than the device.
  constexpr std::optional<int> pd_words() const {
    const auto ring = ring_words();
    const auto pcp = pcp_words();
    if (!ring || !pcp || *pcp > *ring) return std::nullopt;
    return *ring - *pcp;
  }
  // Process-data direction. A PCP device uses bits 1..0 for the PCP width; PCP needs both
  // directions, so its process data is taken as in/out.
  constexpr Direction direction() const {
    if (has_pcp()) return Direction::in_out;
    return static_cast<Direction>(direction_bits());
  }
  // Every field decodes (known length code, assigned PCP width that fits the device).
  constexpr bool decodable() const { return pd_words().has_value(); }

  friend constexpr bool operator==(IdCode, IdCode) = default;
};

// Builds an ID code from a device group byte and the number of ring words; nullopt when the word
// count has no length code.
constexpr std::optional<IdCode> make_id_code(std::uint8_t group, int ring_words) {
  const auto code = length_code_from_words(ring_words);
  if (!code) return std::nullopt;
  return IdCode{static_cast<Word>((*code << kLengthCodeShift) | group)};
}

// Builds a PCP device's code: class and type as given, width bits from pcp_words, length code
// from pd_words + pcp_words. nullopt when the class is not a PCP class or a count is not
// encodable.
constexpr std::optional<IdCode> make_pcp_id_code(unsigned device_class, unsigned type_bits,
                                                 int pd_words, int pcp_words) {
  if ((device_class & 0x0CU) != 0x0CU || device_class > 0x0FU || type_bits > 0x03U) {
    return std::nullopt;
  }
  const auto width = pcp_bits_from_words(pcp_words);
  if (!width) return std::nullopt;
  const auto group = static_cast<std::uint8_t>((device_class << 4U) | (type_bits << 2U) | *width);
  return make_id_code(group, pd_words + pcp_words);
}

const char* to_string(BusKind b);
const char* to_string(Direction d);

// The code in words for a person, e.g. "33BH: remote bus device, class 3H, type 2, in/out,
// 3 words process data, no PCP". Unknown fields are named as such.
std::string describe(IdCode id);

// "33BH", "04DBH": the manual's hex notation (at least three digits).
std::string to_hex(IdCode id);

}  // namespace ibs::interbus
