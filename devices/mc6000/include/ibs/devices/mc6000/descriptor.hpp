// What a MASTERDRIVE MC6000 is on INTERBUS (INTERBUS manual 3.2, 5.3, 7.2): what the device-specific
// bits of its control and status words mean, its processing period and the error its bus
// watchdog reports. Its ID code and words follow from 405-SUPI / 406-IBCNF (layout.hpp), its
// reference and actual words from the layout too.
#pragma once

#include <string>
#include <string_view>

#include "ibs/devices/descriptor.hpp"
#include "ibs/drivecom/status_word.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"

namespace ibs::devices::mc6000 {

// The drive kind's name in scenario files, traces and on the command line.
inline constexpr std::string_view kName = "mc6000";
// DRIVECOM, the speed loop and the PCP channel are processed every 1 ms (7.2).
inline constexpr Duration kSamplePeriod = 1ms;
// 409-BUTWD ran out: error 16 (E-OP1) at location 1 (3.2.4).
inline constexpr int kWatchdogError = 16;
inline constexpr int kWatchdogLocation = 1;

// Control-word bits 14 and 15 (5.3.1); bits 4-6 and 11-13 have no function.
struct ControlBits {
  bool os00 = false;  // bit 14: reference state of output OS00 (445-FOS00 = ROPT1)
  bool os01 = false;  // bit 15: reference state of output OS01 (446-FOS01 = ROPT1)
};
constexpr ControlBits decode_control_bits(Word w) { return {bit(w, 14), bit(w, 15)}; }
// Control-word bits without function (4-6, 11-13).
inline constexpr Word kControlBitsWithoutFunction = 0x3870;

// Status-word bits 8, 14, 15 (5.3.2): message; the inputs IS00, IS01.
inline constexpr drivecom::StatusBitNames kStatusBits{"message", "IS00", "IS01"};

// A control word in words: the DRIVECOM command and the MC6000's bits, e.g. "C00F
// POWER-ON/ENABLE, OS00, OS01"; `previous` tells the reset-fault edge.
std::string explain_control_word(Word control, Word previous);
std::string explain_status_word(Word status);

// The MC6000 as a drive kind (descriptor.hpp): what the registry lists.
const DriveDescriptor& descriptor();

}  // namespace ibs::devices::mc6000
