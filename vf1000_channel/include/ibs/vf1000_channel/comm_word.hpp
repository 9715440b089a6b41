// The VF1000 communication word: the third process-data word, which carries the byte-wise
// parameter channel (INTERBUS manual 4.1.2). One table of bit masks serves both sides: the client
// encodes master words and decodes inverter words with it, the server the other way round.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "ibs/base/words.hpp"

namespace ibs::vf1000_channel {

// Telegram types: the CODE field, bits 2-4 of the master's control byte (4.1.2.1, 4.1.3).
// CODE 0 is the master's "starting position" that ends every transaction; 4-7 are undefined.
enum class Code : std::uint8_t {
  reset = 0,
  value_inquiry = 1,     // 4.1.3.1
  value_transfer = 2,    // 4.1.3.2
  description_scan = 3,  // 4.1.3.3
};

// Parameter numbers run from 0 to 3FFH: the low byte of the number travels in the data byte,
// bits 8-9 in bits 0-1 of the master's control byte (4.1.2.1, 4.1.3).
inline constexpr std::uint16_t kMaxParameterNumber = 0x3FF;
// The description record of a description scan: 18 bytes (4.1.3.3).
inline constexpr std::size_t kDescriptionLength = 18;

// Bits of the communication word from the master (4.1.2.1; bit n of the high byte is word bit
// n + 8).
inline constexpr Word kMasterUnusedMask = 0xC000;  // high-byte bits 7, 6: "not used, always 0"
inline constexpr Word kMasterToggle = 0x2000;      // high-byte bit 5
inline constexpr Word kMasterCodeMask = 0x1C00;    // high-byte bits 2-4
inline constexpr unsigned kMasterCodeShift = 10;
inline constexpr Word kMasterNumberHighMask = 0x0300;  // high-byte bits 0-1: PNR bits 8-9
inline constexpr unsigned kMasterNumberHighShift = 8;

// Bits of the communication word from the inverter (4.1.2.2).
inline constexpr Word kInverterReady =
    0x8000;  // high-byte bit 7: RESET distinction, 1 in operation
inline constexpr Word kInverterUnusedMask = 0x4700;  // high-byte bits 6, 2, 1, 0: always 0
inline constexpr Word kInverterToggle = 0x2000;      // high-byte bit 5
inline constexpr Word kInverterNak = 0x1000;         // high-byte bit 4: last byte, error
inline constexpr Word kInverterAck = 0x0800;         // high-byte bit 3: last byte, no error
inline constexpr Word kDataMask = 0x00FF;            // low byte of both words: the data byte

// The inverter in wait mode: ready, toggle 0, neither ACK nor NAK, data 00 (4.1.3.1.1 row 0).
inline constexpr Word kInverterWaitWord = kInverterReady;
// The master in its starting position: CODE 0, toggle 0, data 00 (4.1.3.1.1 rows 0 and 5).
inline constexpr Word kMasterIdleWord = 0x0000;

// --- master word ---------------------------------------------------------------------------

constexpr Word master_word(bool toggle, Code code, std::uint8_t number_high, std::uint8_t data) {
  return static_cast<Word>(
      (toggle ? kMasterToggle : 0U) |
      ((static_cast<unsigned>(code) << kMasterCodeShift) & kMasterCodeMask) |
      ((static_cast<unsigned>(number_high) << kMasterNumberHighShift) & kMasterNumberHighMask) |
      data);
}
// The first word of a telegram: CODE with the parameter number split over both bytes.
constexpr Word master_start_word(bool toggle, Code code, std::uint16_t number) {
  return master_word(toggle, code, static_cast<std::uint8_t>((number >> 8U) & 0x3U),
                     static_cast<std::uint8_t>(number & 0xFFU));
}
constexpr bool master_toggle(Word w) {
  return (w & kMasterToggle) != 0;
}
// The raw CODE field 0-7 (4-7 are not telegram types).
constexpr std::uint8_t master_code(Word w) {
  return static_cast<std::uint8_t>((w & kMasterCodeMask) >> kMasterCodeShift);
}
constexpr std::uint8_t master_number_high(Word w) {
  return static_cast<std::uint8_t>((w & kMasterNumberHighMask) >> kMasterNumberHighShift);
}
// The parameter number a start word carries.
constexpr std::uint16_t master_number(Word w) {
  return static_cast<std::uint16_t>((static_cast<unsigned>(master_number_high(w)) << 8U) |
                                    low_byte(w));
}
constexpr bool master_unused_bits(Word w) {
  return (w & kMasterUnusedMask) != 0;
}
constexpr bool is_telegram_code(std::uint8_t code) {
  return code >= 1 && code <= 3;
}

// --- inverter word -------------------------------------------------------------------------

enum class Flag : std::uint8_t { none, ack, nak };

constexpr Word inverter_word(bool toggle, Flag flag, std::uint8_t data) {
  return static_cast<Word>(kInverterReady | (toggle ? kInverterToggle : 0U) |
                           (flag == Flag::ack ? kInverterAck : 0U) |
                           (flag == Flag::nak ? kInverterNak : 0U) | data);
}
constexpr bool inverter_ready(Word w) {
  return (w & kInverterReady) != 0;
}
constexpr bool inverter_toggle(Word w) {
  return (w & kInverterToggle) != 0;
}
constexpr bool inverter_ack(Word w) {
  return (w & kInverterAck) != 0;
}
constexpr bool inverter_nak(Word w) {
  return (w & kInverterNak) != 0;
}
// Ready, toggle 0, neither ACK nor NAK: what the inverter shows in wait mode (the data byte is not
// looked at).
constexpr bool inverter_idle(Word w) {
  return (w & (kInverterReady | kInverterToggle | kInverterAck | kInverterNak)) == kInverterReady;
}

// Human-readable readings for traces and reports (allocate; not for the cycle path), e.g.
// "toggle 1, CODE 1 value inquiry, byte 16H (as PNR: 22)" and "ready, toggle 1, data 03H".
std::string explain_master_word(Word w);
std::string explain_inverter_word(Word w);
std::string_view to_string(Code c);

}  // namespace ibs::vf1000_channel
