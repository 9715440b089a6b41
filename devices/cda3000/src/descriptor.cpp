#include "ibs/devices/cda3000/descriptor.hpp"

#include <cmath>
#include <cstdio>

#include "ibs/canlust/errors.hpp"
#include "ibs/canlust/parameter_channel.hpp"
#include "ibs/devices/cda3000/parameters.hpp"
#include "ibs/drivecom/control_word.hpp"

namespace ibs::devices::cda3000 {

namespace {

using namespace ibs::canlust;

std::string hex(unsigned v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%0*X", digits, v);
  return buf;
}

std::string hz_text(double hz) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g Hz", hz);
  return buf;
}

std::string who(const Classified& c) { return "CDA " + std::to_string(c.address); }

std::string parameter_name(std::uint16_t number) {
  if (const ParameterInfo* p = find_parameter(number)) return display_name(*p);
  return std::to_string(number) + " (not a CDA3000 parameter here)";
}

// Four characters of a string block (non-printable bytes as \xNN).
std::string block_text(std::uint32_t data) {
  std::string s = "'";
  for (unsigned i = 0; i < 4; ++i) {
    const auto c = static_cast<unsigned char>((data >> (8U * i)) & 0xFFU);
    if (c == 0) {
      s += "\\0";
    } else if (c >= 0x20 && c < 0x7F) {
      s += static_cast<char>(c);
    } else {
      s += "\\x" + hex(c, 2);
    }
  }
  return s + "'";
}

std::string data_text(std::uint16_t number, std::uint32_t data) {
  if (const ParameterInfo* p = find_parameter(number); p != nullptr && !p->is_string()) {
    return format_value(*p, data);
  }
  return std::to_string(data) + " (" + hex(data, 8) + "H)";
}

}  // namespace

std::optional<std::int32_t> wire_from_hz(ValueWidth w, double hz) {
  if (!std::isfinite(hz)) return std::nullopt;
  if (w == ValueWidth::int32q16) {
    const double raw = std::round(hz * 65536.0);
    if (raw < -2147483648.0 || raw > 2147483647.0) return std::nullopt;
    return static_cast<std::int32_t>(raw);
  }
  const double raw = std::round(hz);
  if (raw < -32768.0 || raw > 32767.0) return std::nullopt;
  return static_cast<std::int32_t>(raw);
}

std::string explain_status_word(ibs::Word status) {
  const auto st = drivecom::decode_state(status);
  std::string s = hex(status, 4) + " " + (st ? std::string(drivecom::to_string(*st)) : "no DRIVECOM state");
  if (!bit(status, drivecom::sw::kPowerBlocked)) s += ", block-power request";
  if (!bit(status, drivecom::sw::kEmergencyStop) && st != drivecom::State::emergency_stop_active) {
    s += ", e-stop request";
  }
  if (bit(status, status_bits::kWarning)) s += ", warning";
  if (bit(status, status_bits::kRemote)) s += ", remote";
  if (bit(status, status_bits::kReferenceReached)) s += ", reference reached";
  if (bit(status, status_bits::kLimit)) s += ", limit";
  const ibs::Word other = status & 0xF100U;
  if (other != 0) s += ", bits " + hex(other, 4) + " set (no function)";
  return s;
}

namespace {
std::string bit_names(ibs::Word w, std::initializer_list<std::pair<unsigned, std::string_view>> names) {
  std::string s;
  ibs::Word known = 0;
  for (const auto& [b, n] : names) {
    known = static_cast<ibs::Word>(known | (1U << b));
    if (bit(w, b)) s += std::string(s.empty() ? " " : ", ") + std::string(n);
  }
  const ibs::Word other = static_cast<ibs::Word>(w & ~known);
  if (other != 0) s += std::string(s.empty() ? " " : ", ") + "bits " + hex(other, 4) + " (no function)";
  return s.empty() ? " (none)" : s;
}
}  // namespace

std::string explain_easydrive_control(ibs::Word control) {
  namespace e = easydrive;
  return hex(control, 4) + bit_names(control, {{e::kStr, "STR"}, {e::kStl, "STL"}, {e::kFftb1, "FFTB1"},
                                               {e::kFftb2, "FFTB2"}, {e::kEres, "error reset"},
                                               {e::kCusel, "CUSEL"}, {e::kUm0, "UM0"}});
}

std::string explain_easydrive_status(ibs::Word status) {
  namespace e = easydrive::status;
  return hex(status, 4) + bit_names(status, {{e::kReady, "READY"}, {e::kError, "ERROR"}, {e::kActiv, "ACTIV"},
                                             {e::kRot0, "ROT_0"}, {e::kBrk, "BRK"}, {e::kWarning, "warning"},
                                             {e::kCanStart, "CAN Start"},
                                             {e::kReferenceReached, "reference reached"}});
}

std::string explain_control_word(ibs::Word control, std::optional<ibs::Word> previous) {
  std::string s = hex(control, 4) + " " + std::string(drivecom::to_string(drivecom::decode_command(control)));
  if (bit(control, drivecom::cw::kResetFault)) {
    if (!previous) {
      s += ", reset fault bit";
    } else if (drivecom::reset_fault_edge(*previous, control)) {
      s += ", RESET FAULT edge";
    } else {
      s += ", reset fault bit high (no edge)";
    }
  }
  if ((control & drivecom::cw::kReservedMask) != 0) s += ", reserved bits 8-10 set (must be 0)";
  const ibs::Word other = control & 0xF870U;
  if (other != 0) s += ", bits " + hex(other, 4) + " set (no function in DRIVECOM mode)";
  return s;
}

FrameExplanation explain_frame(const CanFrame& f, const IdentifierMap& ids, const ProcessLayout& layout) {
  FrameExplanation e;
  e.id = ids.classify(f.id);
  if (!e.id) {
    e.text = "not a CANLust identifier";
    return e;
  }
  const Classified c = *e.id;
  const auto bad = [&](DecodeError err) {
    return std::string(to_string(c.kind)) + " " + (c.kind == TelegramKind::system ? "" : who(c) + " ") +
           "refused: " + std::string(to_string(err));
  };
  switch (c.kind) {
    case TelegramKind::system: {
      const auto d = decode_system(f);
      e.text = d ? std::string(to_string(d.value)) : bad(d.error);
      return e;
    }
    case TelegramKind::logon:
      e.text = f.rtr ? bad(DecodeError::remote) : "logon " + who(c);
      return e;
    case TelegramKind::control: {
      const auto d = decode_control(f, layout);
      if (!d) {
        e.text = bad(d.error);
        return e;
      }
      e.text = "control " + who(c) + ": " + (layout.mode == WordMode::drivecom
                                                   ? explain_control_word(d.value.word)
                                                   : "EasyDrive " + explain_easydrive_control(d.value.word)) +
               "; reference " + hz_text(hz_from_wire(layout.reference, d.value.reference));
      return e;
    }
    case TelegramKind::status: {
      const auto d = decode_status(f, layout);
      if (!d) {
        e.text = bad(d.error);
        return e;
      }
      e.text = "status " + who(c) + ": " + (layout.mode == WordMode::drivecom
                                                  ? explain_status_word(d.value.word)
                                                  : "EasyDrive " + explain_easydrive_status(d.value.word)) +
               "; actual " + hz_text(hz_from_wire(layout.actual, d.value.actual));
      return e;
    }
    case TelegramKind::error: {
      const auto d = decode_error(f);
      if (!d) {
        e.text = bad(d.error);
        return e;
      }
      const auto info = find_error(d.value.number);
      e.text = "error " + who(c) + ": " +
               (info ? std::string(info->name) + " (" + std::to_string(d.value.number) + ") " +
                           std::string(info->cause)
                     : "error " + std::to_string(d.value.number)) +
               ", location " + std::to_string(d.value.location) + ", reaction " +
               (d.value.reaction <= 3 ? std::string(to_string(static_cast<ErrorReaction>(d.value.reaction)))
                                      : std::to_string(d.value.reaction));
      return e;
    }
    case TelegramKind::parameter_request: {
      const auto d = decode_parameter(f);
      if (!d) {
        e.text = bad(d.error);
        return e;
      }
      const auto& t = d.value;
      std::string s = "parameter request " + who(c) + ": " + parameter_name(t.parameter) + " " +
                      std::string(mode_name(t.code));
      switch (t.code) {
        case kModeWrite: s += " " + data_text(t.parameter, t.data); break;
        case kModeStringWrite:
          s += t.block == 0 ? " (handshake)" : " block " + std::to_string(t.block) + " " + block_text(t.data);
          break;
        case kModeListEnd: s += " checksum " + hex(t.data, 8) + "H"; break;
        case kModeDescribe: s += " item " + std::to_string(t.block); break;
        case kModeStringRead: s += " block " + std::to_string(t.block); break;
        default: break;
      }
      if ((t.code == kModeRead || t.code == kModeWrite) && t.block != 0) s += ", index " + std::to_string(t.block);
      e.text = s;
      return e;
    }
    case TelegramKind::parameter_reply: {
      const auto d = decode_parameter(f);
      if (!d) {
        e.text = bad(d.error);
        return e;
      }
      const auto& t = d.value;
      std::string s = "parameter reply " + who(c) + ": " + parameter_name(t.parameter) + " status " +
                      hex(t.code, 2) + "H " + (t.code == 0 ? std::string("done") : describe_status(t.code));
      const ParameterInfo* p = find_parameter(t.parameter);
      if (t.code == kStatusOk) {
        if (p != nullptr && p->is_string()) {
          s += ", block " + std::to_string(t.block) + " " + block_text(t.data);
        } else {
          s += ", data " + data_text(t.parameter, t.data);
          if (t.block != 0) s += ", block " + std::to_string(t.block);
        }
      } else if (t.code == kStatusListEnd && p != nullptr && p->is_string()) {
        s += " / List_End, checksum " + hex(t.data, 8) + "H, block " + std::to_string(t.block);
      }
      e.text = s;
      return e;
    }
  }
  return e;
}

}  // namespace ibs::devices::cda3000
