// The message check of the PCP channel segmentation (docs/pcp.md, "Message check"):
// CRC-16 with polynomial 1021H, initial value FFFFH, no reflection, no final XOR.
#pragma once

#include <cstdint>
#include <span>

namespace ibs::pcp {

std::uint16_t crc16(std::span<const std::uint8_t> bytes, std::uint16_t crc = 0xFFFF);

}  // namespace ibs::pcp
