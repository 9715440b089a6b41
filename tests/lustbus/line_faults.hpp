// What can happen to one character on an RS-485 line, for the interruption tests of the protocol
// core (tests/lustbus) and of the drive wings (tests/lustbus_devices): lost, replaced by EOT,
// garbage, a character with a parity/framing error or a NUL, or one bit flipped (at the BCC: a
// wrong BCC).
#pragma once

#include <cstdint>
#include <optional>

#include "ibs/lustbus/chars.hpp"

namespace ibs::lustbus::test {

enum class Fault { lose, eot, garbage, garbled, nul, flip };
inline constexpr Fault kFaults[] = {Fault::lose, Fault::eot, Fault::garbage, Fault::garbled, Fault::nul,
                                    Fault::flip};

// The character that arrives instead of `b`; nullopt: none.
inline std::optional<std::uint8_t> apply(Fault f, std::uint8_t b) {
  switch (f) {
    case Fault::lose:
      return std::nullopt;
    case Fault::eot:
      return kEot;
    case Fault::garbage:
      return 'X';
    case Fault::garbled:
      return kGarbled;
    case Fault::nul:
      return 0;
    case Fault::flip:
      return static_cast<std::uint8_t>(b ^ 0x01);
  }
  return b;
}

}  // namespace ibs::lustbus::test
