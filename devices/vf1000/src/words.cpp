// The reference and actual words in engineering units (descriptor.hpp): pure functions the
// master, the emulator and the drive core share.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "ibs/devices/vf1000/descriptor.hpp"

namespace ibs::devices::vf1000 {

Word reference_word(double hz) {
  const double bits = std::clamp(std::round(std::fabs(hz) / kHzPerBit), 0.0, 65535.0);
  return static_cast<Word>(bits);
}
double reference_hz(Word w) { return static_cast<double>(w) * kHzPerBit; }
Word actual_word(double hz) {
  const double bits = std::clamp(std::round(hz / kHzPerBit), -32768.0, 32767.0);
  return static_cast<Word>(static_cast<std::int16_t>(bits));
}
double actual_hz(Word w) { return static_cast<double>(static_cast<std::int16_t>(w)) * kHzPerBit; }

}  // namespace ibs::devices::vf1000
