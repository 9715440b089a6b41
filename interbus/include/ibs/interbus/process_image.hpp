// The master's process image: fixed-size word arrays, one slice per device, and the byte view of
// Phoenix's DDI (public-facts.md: words are big-endian in the image, high byte at the lower byte
// address). Nothing here allocates or throws; the image is sized for the INTERBUS maximum.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "ibs/base/words.hpp"

namespace ibs::interbus {

// 4096 input and 4096 output bits per system (public-facts.md, INTERBUS Club FAQ).
inline constexpr std::size_t kMaxProcessWords = 256;
// Up to 62 PCP devices (same source), each with a channel of at most 4 words (the widest PCP
// width the ID code can express, id_code.hpp).
inline constexpr std::size_t kMaxPcpDevices = 62;
inline constexpr std::size_t kMaxPcpChannelWords = 4;
inline constexpr std::size_t kMaxPcpWords = kMaxPcpDevices * kMaxPcpChannelWords;

// A device's place in one area of the image, in words.
struct Slice {
  std::size_t offset = 0;
  std::size_t length = 0;

  constexpr std::size_t end() const { return offset + length; }
  // DDI addresses are byte addresses (DDI_DTI_ReadData).
  constexpr std::size_t byte_offset() const { return offset * 2; }
  constexpr std::size_t byte_length() const { return length * 2; }
  friend constexpr bool operator==(const Slice&, const Slice&) = default;
};

// The four areas, named from the master's side: `in` is what the devices send (status words,
// actual values), `out` what the master sends (control words, references). The PCP areas carry
// the parameter-channel words of each cycle; the PCP layer owns their content.
enum class Area : std::uint8_t { in, out, pcp_in, pcp_out };

struct ProcessImage {
  std::array<Word, kMaxProcessWords> in{};
  std::array<Word, kMaxProcessWords> out{};
  std::array<Word, kMaxPcpWords> pcp_in{};
  std::array<Word, kMaxPcpWords> pcp_out{};

  std::span<Word> words(Area a) noexcept;
  std::span<const Word> words(Area a) const noexcept;

  // The words of `s` in area `a`; empty when `s` does not lie inside the area (a slice from a
  // checked BusConfig always does).
  std::span<Word> slice(Area a, Slice s) noexcept;
  std::span<const Word> slice(Area a, Slice s) const noexcept;

  // Byte view: byte 2k is the high byte of word k, byte 2k+1 its low byte. Any byte address and
  // length (DDI "BYTE" consistency); false, and nothing copied, when the range leaves the area
  // (the DDI's "area exceeded").
  bool read_bytes(Area a, std::size_t byte_address, std::span<std::uint8_t> dst) const noexcept;
  bool write_bytes(Area a, std::size_t byte_address, std::span<const std::uint8_t> src) noexcept;
  // One byte; 0 outside the area (check with size_bytes()).
  std::uint8_t byte(Area a, std::size_t byte_address) const noexcept;
  std::size_t size_bytes(Area a) const noexcept { return words(a).size() * 2; }

  void clear() noexcept;
};

}  // namespace ibs::interbus
