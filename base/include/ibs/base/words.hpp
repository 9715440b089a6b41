// 16-bit bus words and the byte/word helpers every protocol layer uses.
#pragma once

#include <cstdint>

namespace ibs {

using Word = std::uint16_t;

constexpr std::uint8_t high_byte(Word w) { return static_cast<std::uint8_t>(w >> 8U); }
constexpr std::uint8_t low_byte(Word w) { return static_cast<std::uint8_t>(w & 0xFFU); }
constexpr Word make_word(std::uint8_t high, std::uint8_t low) {
  return static_cast<Word>((static_cast<unsigned>(high) << 8U) | low);
}
constexpr bool bit(Word w, unsigned n) { return ((static_cast<unsigned>(w) >> n) & 1U) != 0; }
constexpr Word with_bit(Word w, unsigned n, bool on) {
  return on ? static_cast<Word>(w | (1U << n)) : static_cast<Word>(w & ~(1U << n));
}

// A 32-bit value spread over two bus words, high word first (INTERBUS manual 5.3.3: Q16 references).
constexpr Word high_word(std::uint32_t v) { return static_cast<Word>(v >> 16U); }
constexpr Word low_word(std::uint32_t v) { return static_cast<Word>(v & 0xFFFFU); }
constexpr std::uint32_t make_dword(Word high, Word low) {
  return (static_cast<std::uint32_t>(high) << 16U) | low;
}

}  // namespace ibs
