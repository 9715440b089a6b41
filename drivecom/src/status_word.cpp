#include "ibs/drivecom/status_word.hpp"

#include <cstdio>

namespace ibs::drivecom {

std::string explain_status_word(Word status, const StatusBitNames& names) {
  char hex[8];
  std::snprintf(hex, sizeof hex, "%04X", static_cast<unsigned>(status));
  const auto st = decode_state(status);
  std::string s = std::string(hex) + " " + (st ? std::string(to_string(*st)) : "no DRIVECOM state");
  if (!bit(status, sw::kPowerBlocked)) s += ", block-power request";
  if (!bit(status, sw::kEmergencyStop) && st != State::emergency_stop_active) {
    s += ", e-stop request";
  }
  if (bit(status, sw::kAlarm)) s += ", alarm";
  if (bit(status, sw::kMessage)) s += ", " + std::string(names.bit8);
  if (bit(status, sw::kRemote)) s += ", remote";
  if (bit(status, sw::kReferenceReached)) s += ", reference reached";
  if (bit(status, sw::kLimitValue)) s += ", limit value";
  if (bit(status, 14)) s += ", " + std::string(names.bit14);
  if (bit(status, 15)) s += ", " + std::string(names.bit15);
  return s;
}

}  // namespace ibs::drivecom
