#include "ibs/pcp/crc16.hpp"

#include <array>

namespace ibs::pcp {

namespace {

constexpr std::array<std::uint16_t, 256> make_table() {
  std::array<std::uint16_t, 256> t{};
  for (unsigned i = 0; i < 256; ++i) {
    unsigned c = i << 8U;
    for (int b = 0; b < 8; ++b) c = (c & 0x8000U) != 0 ? ((c << 1U) ^ 0x1021U) : (c << 1U);
    t[i] = static_cast<std::uint16_t>(c & 0xFFFFU);
  }
  return t;
}

constexpr std::array<std::uint16_t, 256> kTable = make_table();

}  // namespace

std::uint16_t crc16(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
  for (const std::uint8_t b : bytes) {
    const unsigned i = ((static_cast<unsigned>(crc) >> 8U) ^ b) & 0xFFU;
    crc = static_cast<std::uint16_t>(((static_cast<unsigned>(crc) << 8U) ^ kTable[i]) & 0xFFFFU);
  }
  return crc;
}

}  // namespace ibs::pcp
