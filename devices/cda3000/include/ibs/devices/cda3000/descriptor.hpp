// What the CDA3000's CANLust words and values mean, for both sides and for reports: the reference
// and actual frequency in Hz as 492-CACNF lays them out, the DRIVECOM status bits the CDA3000 adds
// (CANLust manual 5.4.2; the state bits are drivecom's, INTERBUS manual 5.1.3), and a frame explained in words
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

// EasyDrive direct control (492-CACNF = 4, CANLust manual 5.4.1 and 7.1.1). The seed keeps fragments of
// the bit tables only: control bits 5 FFTB1, 6 FFTB2 (table reference select, 2^1, 2^2), 8 CUSEL
// (characteristic data set 1 / 2), 9 UM0 (user mode 2^0), the STR start of 5.4.1's text, and the
// end of an "... error" function at 7; status bits 4 ACTIV (power stage active), 5 ROT_0 (speed
// 0 Hz), 6 BRK (the drive brakes), 7 warning, 8 CAN status (0 System Stop, 1 System Start). The
// other positions are chosen (decision D26, docs/canlust.md): STR 0, STL 1, error reset 7 (edge);
// status READY 0, ERROR 3, reference reached 10.
namespace easydrive {
inline constexpr unsigned kStr = 0;    // start clockwise (5.4.1) - position chosen
inline constexpr unsigned kStl = 1;    // start counter-clockwise - chosen
inline constexpr unsigned kFftb1 = 5;  // table reference select 2^1 (seed)
inline constexpr unsigned kFftb2 = 6;  // table reference select 2^2 (seed)
inline constexpr unsigned kEres = 7;   // error reset, on its 0 -> 1 edge (seed: "... error" at 7)
inline constexpr unsigned kCusel = 8;  // characteristic data set 2 (seed)
inline constexpr unsigned kUm0 = 9;    // user mode 2^0 (seed)
namespace status {
inline constexpr unsigned kReady = 0;              // no fault, the power stage may be started - chosen
inline constexpr unsigned kError = 3;              // a fault - chosen
inline constexpr unsigned kActiv = 4;              // power stage active (seed)
inline constexpr unsigned kRot0 = 5;               // speed 0 Hz (seed)
inline constexpr unsigned kBrk = 6;                // the drive brakes (seed)
inline constexpr unsigned kWarning = 7;            // a warning (seed)
inline constexpr unsigned kCanStart = 8;           // 1 System Start, 0 System Stop (seed)
inline constexpr unsigned kReferenceReached = 10;  // as in DRIVECOM mode - chosen
}  // namespace status
}  // namespace easydrive
// "0001 STR" / "0139 READY, ACTIV, ROT_0, CAN Start".
std::string explain_easydrive_control(ibs::Word control);
std::string explain_easydrive_status(ibs::Word status);

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
