// What the CDA3000's CANLust words and values mean, for both sides and for reports: the reference
// and actual frequency in Hz as 492-CACNF lays them out, the DRIVECOM status bits the CDA3000 adds
// (seed 003, 5.4.2; the state bits are drivecom's, seed 001 5.1.3), and a frame explained in words
// (the monitor, `ibs decode`).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "ibs/canlust/frame.hpp"
#include "ibs/canlust/identifiers.hpp"
#include "ibs/canlust/telegrams.hpp"
#include "ibs/drivecom/status_word.hpp"

namespace ibs::devices::cda3000 {

// The frequency in a control or status telegram (5.5.5, 5.5.6): Q16 Hz (20.5 Hz = 00 80 14 00),
// or Int16Q0 - whole Hz (decision D25).
constexpr double hz_from_wire(canlust::ValueWidth w, std::int32_t raw) {
  return w == canlust::ValueWidth::int32q16 ? static_cast<double>(raw) / 65536.0 : static_cast<double>(raw);
}
// nullopt when `hz` does not fit the width (Q16: +-32767.99 Hz, Int16Q0: +-32767 Hz) or is NaN.
std::optional<std::int32_t> wire_from_hz(canlust::ValueWidth w, double hz);

// Status-word bits the CDA3000 sets beside the DRIVECOM state bits 0-6 (decision D27).
namespace status_bits {
inline constexpr unsigned kWarning = 7;            // a warning (error reaction WRN, 6.1)
inline constexpr unsigned kRemote = 9;             // 260-CLSEL = OPTN2: the bus controls the drive
inline constexpr unsigned kReferenceReached = 10;  // |actual - reference| within the window
inline constexpr unsigned kLimit = 11;             // the reference was limited to +-fmax
}  // namespace status_bits

// "0237 ENABLED, remote" / "0208 FAULT, remote, warning".
std::string explain_status_word(ibs::Word status);
// "000F POWER-ON/ENABLE" / "0086 SHUTDOWN, reset fault (edge)" when `previous` has bit 7 low.
std::string explain_control_word(ibs::Word control, std::optional<ibs::Word> previous = {});

// A frame in words: its kind, the drive, the words and values and what they mean; parameter
// numbers with the CDA3000's names. "not a CANLust identifier" for foreign frames.
struct FrameExplanation {
  std::optional<canlust::Classified> id;  // nullopt: not a CANLust identifier on this map
  std::string text;
};
FrameExplanation explain_frame(const canlust::CanFrame& f, const canlust::IdentifierMap& ids,
                               const canlust::ProcessLayout& layout);

}  // namespace ibs::devices::cda3000
