#include "ibs/vf1000_channel/comm_word.hpp"

#include <string>

#include "ibs/base/number_text.hpp"

namespace ibs::vf1000_channel {

namespace {

std::string hex2(unsigned v) { return hex_text(v & 0xFFU, 2) + "H"; }

}  // namespace

std::string_view to_string(Code c) {
  switch (c) {
    case Code::reset:
      return "starting position";
    case Code::value_inquiry:
      return "value inquiry";
    case Code::value_transfer:
      return "value transfer";
    case Code::description_scan:
      return "description scan";
  }
  return "?";
}

std::string explain_master_word(Word w) {
  const std::uint8_t code = master_code(w);
  std::string s;
  if (code == 0) {
    s = "starting position (CODE 0)";
    if (master_toggle(w)) s += ", toggle 1";
    if (master_number_high(w) != 0 || low_byte(w) != 0) s += ", byte " + hex2(low_byte(w));
  } else {
    s = std::string("toggle ") + (master_toggle(w) ? "1" : "0") + ", CODE " + std::to_string(code) +
        " ";
    s += is_telegram_code(code) ? std::string(to_string(static_cast<Code>(code)))
                                : std::string("(undefined)");
    s += ", byte " + hex2(low_byte(w)) + " (as PNR: " + std::to_string(master_number(w)) + ")";
  }
  if (master_unused_bits(w)) s += ", unused bits 6/7 set";
  return s;
}

std::string explain_inverter_word(Word w) {
  if (!inverter_ready(w)) {
    std::string s = "initialising (RESET distinction 0)";
    if (w != 0) s += ", other bits " + hex2(high_byte(w)) + " " + hex2(low_byte(w));
    return s;
  }
  std::string s = std::string("ready, toggle ") + (inverter_toggle(w) ? "1" : "0");
  if (inverter_ack(w)) s += ", ACK";
  if (inverter_nak(w)) s += ", NAK";
  s += ", data " + hex2(low_byte(w));
  if (w == kInverterWaitWord) s += " (wait mode, or a data byte 00H)";
  if ((w & kInverterUnusedMask) != 0) s += ", unused bits set";
  return s;
}

}  // namespace ibs::vf1000_channel
