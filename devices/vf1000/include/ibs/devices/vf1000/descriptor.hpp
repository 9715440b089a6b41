// What a SMARTDRIVE VF1000 is on INTERBUS (INTERBUS manual 3.1, 4.1, 5.2, 7.1): its ID code and three
// process-data words, what the device-specific bits of its control and status words mean, its
// reference and actual words in engineering units, its processing period and the error its
// process-data watchdog reports. Everything here is static data or a pure function.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "ibs/devices/descriptor.hpp"
#include "ibs/drivecom/status_word.hpp"
#include "ibs/base/time.hpp"
#include "ibs/base/words.hpp"

namespace ibs::devices::vf1000 {

// The drive kind's name in scenario files, traces and on the command line.
inline constexpr std::string_view kName = "vf1000";
// Remote bus device, class 3H (profile device), 3 words, no PCP (3.1.2).
inline constexpr Word kIdCode = 0x033B;
// Control (status) word, reference (actual) word, communication word (3.1.2, 4.1.2).
inline constexpr std::size_t kWords = 3;
// Process data and the parameter channel are processed every 8.2 ms (7.1).
inline constexpr Duration kSamplePeriod = 8200us;
// 907-IBCOD = 1: the process-data watchdog shuts down with error E-IBS, number 12 (4.1.1).
inline constexpr int kWatchdogError = 12;

// The rotating-field frequency in the reference word: 0.05 Hz per bit, an absolute value (5.2.3).
inline constexpr double kHzPerBit = 0.05;
Word reference_word(double hz);
double reference_hz(Word w);
// The actual frequency in the second status-side word: 0.05 Hz per bit, signed (negative =
// counter-clockwise) -- a modelling choice, the manual does not define this word.
Word actual_word(double hz);
double actual_hz(Word w);

// Control-word bits 4-6 and 11-15 (5.2.1).
struct ControlBits {
  bool ramp_enable = false;  // bit 4: 0 = stop function of 36-RSTOP
  bool ramp_run = false;     // bit 5: 0 = ramp held at its current value
  bool ramp_follow = false;  // bit 6: 0 = ramp to 0 Hz
  bool s2ind = false;        // bit 12
  bool s1ind = false;        // bit 13
  bool stl = false;          // bit 14: start counter-clockwise
  bool str = false;          // bit 15: start clockwise
};
constexpr ControlBits decode_control_bits(Word w) {
  return {bit(w, 4), bit(w, 5), bit(w, 6), bit(w, 12), bit(w, 13), bit(w, 14), bit(w, 15)};
}
constexpr Word encode_control_bits(const ControlBits& b) {
  Word w = 0;
  w = with_bit(w, 4, b.ramp_enable);
  w = with_bit(w, 5, b.ramp_run);
  w = with_bit(w, 6, b.ramp_follow);
  w = with_bit(w, 12, b.s2ind);
  w = with_bit(w, 13, b.s1ind);
  w = with_bit(w, 14, b.stl);
  w = with_bit(w, 15, b.str);
  return w;
}
// Ramp generator running freely (bits 4, 5, 6 set): what a master sends to let the drive run.
inline constexpr Word kRampRun = 0x0070;

// The inverter's terminals a plant event names (EventFacts::inputs, in this order; docs/errata.md
// VF-E22): the inputs S1IND, S2IND (their parameter-set function, 5.2.1 bits 13 / 12), STR, STL
// (start clockwise / counter-clockwise, 5.2.1 bits 15 / 14) and the outputs S1OUT, S2OUT (5.2.2
// bits 15 / 14), whose level the event states because the seeds do not give their programmed
// function.
enum class Terminal : std::uint8_t { s1ind, s2ind, str, stl, s1out, s2out };
inline constexpr std::size_t kTerminalCount = 6;
inline constexpr std::string_view kTerminalNames[kTerminalCount] = {"S1IND", "S2IND", "STR",
                                                                    "STL",   "S1OUT", "S2OUT"};

// Status-word bits 8, 14, 15 (5.2.2): bit 8 is not implemented; S2OUT, S1OUT.
inline constexpr drivecom::StatusBitNames kStatusBits{"bit 8 (not implemented) set", "S2OUT", "S1OUT"};

// A control word in words: the DRIVECOM command and the VF1000's bits, e.g. "807F POWER-ON/ENABLE,
// STR"; `previous` tells the reset-fault edge.
std::string explain_control_word(Word control, Word previous);
std::string explain_status_word(Word status);

// The VF1000 as a drive kind (descriptor.hpp): what the registry lists.
const DriveDescriptor& descriptor();

}  // namespace ibs::devices::vf1000
