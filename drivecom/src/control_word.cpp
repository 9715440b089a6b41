#include "ibs/drivecom/control_word.hpp"

#include <cstdio>

namespace ibs::drivecom {

std::string_view to_string(DeviceType d) { return d == DeviceType::vf1000 ? "vf1000" : "mc6000"; }

std::string explain_control_word(DeviceType d, Word control, Word previous) {
  char hex[8];
  std::snprintf(hex, sizeof hex, "%04X", static_cast<unsigned>(control));
  std::string s = std::string(hex) + " " + std::string(to_string(decode_command(control)));
  if (reset_fault_edge(previous, control)) {
    s += ", RESET FAULT edge";
  } else if (bit(control, cw::kResetFault)) {
    s += ", bit 7 high (no edge)";
  }
  if ((control & cw::kReservedMask) != 0) s += ", reserved bits 8-10 set (must be 0)";
  if (d == DeviceType::vf1000) {
    const auto b = decode_vf1000_bits(control);
    if (!b.ramp_enable) s += ", ramp disabled (stop function)";
    if (b.ramp_enable && !b.ramp_run) s += ", ramp held";
    if (b.ramp_enable && !b.ramp_follow) s += ", ramp to 0 Hz";
    if (b.s2ind) s += ", S2IND";
    if (b.s1ind) s += ", S1IND";
    if (b.stl) s += ", STL";
    if (b.str) s += ", STR";
    if (bit(control, 11)) s += ", bit 11 (unoccupied) set";
  } else {
    const auto b = decode_mc6000_bits(control);
    if (b.os00) s += ", OS00";
    if (b.os01) s += ", OS01";
    if ((control & 0x3870U) != 0) s += ", bits without function set";
  }
  return s;
}

}  // namespace ibs::drivecom
