#include "ibs/can/bit_timing.hpp"

#include <array>

namespace ibs::can {

std::uint16_t crc15_bits(const std::uint8_t* bits, unsigned count) {
  std::uint16_t crc = 0;
  for (unsigned i = 0; i < count; ++i) {
    const unsigned c = crc;
    const unsigned next = static_cast<unsigned>(bits[i]) ^ ((c >> 14U) & 1U);
    crc = static_cast<std::uint16_t>((c << 1U) & 0x7FFFU);
    if (next != 0) crc = static_cast<std::uint16_t>(crc ^ 0x4599U);
  }
  return crc;
}

FrameBits frame_bits(const canlust::CanFrame& f) {
  // SOF(1) ID(11) RTR(1) IDE(1) r0(1) DLC(4) DATA(0..64) CRC(15): at most 98 bits.
  std::array<std::uint8_t, 98> bits{};
  unsigned n = 0;
  const auto put = [&](unsigned value, unsigned width) {
    for (unsigned i = width; i-- > 0;) bits[n++] = static_cast<std::uint8_t>((value >> i) & 1U);
  };
  put(0, 1);                          // SOF, dominant
  put(f.id & 0x7FFU, 11);
  put(f.rtr ? 1U : 0U, 1);            // RTR: recessive for a remote frame
  put(0, 1);                          // IDE: dominant, standard frame
  put(0, 1);                          // r0
  const unsigned dlc = f.dlc & 0x0FU;
  put(dlc, 4);
  const unsigned data_bytes = f.rtr ? 0U : (dlc > 8 ? 8U : dlc);
  for (unsigned i = 0; i < data_bytes; ++i) put(f.data[i], 8);
  const std::uint16_t crc = crc15_bits(bits.data(), n);
  put(crc, 15);

  FrameBits r;
  r.stuffed_region = n;
  r.crc = crc;
  // Stuffing: after five equal bits, one of the opposite value, which starts the next run.
  unsigned run = 0;
  std::uint8_t last = 2;
  for (unsigned i = 0; i < n; ++i) {
    if (bits[i] == last) {
      ++run;
    } else {
      last = bits[i];
      run = 1;
    }
    if (run == 5) {
      ++r.stuff;
      last = static_cast<std::uint8_t>(1U - last);
      run = 1;
    }
  }
  return r;
}

}  // namespace ibs::can
