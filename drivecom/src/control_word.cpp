#include "ibs/drivecom/control_word.hpp"

#include <cstdio>

namespace ibs::drivecom {

std::string explain_control_word(Word control, Word previous) {
  char hex[8];
  std::snprintf(hex, sizeof hex, "%04X", static_cast<unsigned>(control));
  std::string s = std::string(hex) + " " + std::string(to_string(decode_command(control)));
  if (reset_fault_edge(previous, control)) {
    s += ", RESET FAULT edge";
  } else if (bit(control, cw::kResetFault)) {
    s += ", bit 7 high (no edge)";
  }
  if ((control & cw::kReservedMask) != 0) s += ", reserved bits 8-10 set (must be 0)";
  return s;
}

}  // namespace ibs::drivecom
