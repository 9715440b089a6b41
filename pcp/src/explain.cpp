#include "ibs/pcp/explain.hpp"

#include <cstdio>

namespace ibs::pcp {

std::string explain_frame(std::span<const Word> words, Direction expected) {
  if (words.empty()) return "no channel words";
  char buf[64];
  const std::uint8_t admin = high_byte(words[0]);
  const auto a = decode_admin(admin);
  if (!a) {
    std::snprintf(buf, sizeof buf, "invalid administrative byte %02XH (parity or code)", admin);
    return buf;
  }
  std::string out;
  if (a->dir != expected) {
    out = a->dir == Direction::to_server ? "wrong direction (master->servo) "
                                         : "wrong direction (servo->master) ";
  }
  if (a->type == FrameType::control) {
    switch (static_cast<ControlCode>(a->seq)) {
      case ControlCode::idle:
        std::snprintf(buf, sizeof buf, "IDLE a%u", a->ack);
        break;
      case ControlCode::abort:
        std::snprintf(buf, sizeof buf, "ABORT (resynchronise)");
        break;
      case ControlCode::abort_ack:
        std::snprintf(buf, sizeof buf, "ABORT-ACK");
        break;
    }
    return out + buf;
  }
  static constexpr const char* kTypeNames[] = {"", "FIRST", "NEXT", "LAST"};
  std::snprintf(buf, sizeof buf, "%s s%u a%u:", kTypeNames[static_cast<unsigned>(a->type)], a->seq,
                a->ack);
  out += buf;
  std::uint8_t data[2 * kMaxChannelWords] = {};
  std::size_t n = 0;
  for (std::size_t i = 0; i < words.size() && i < static_cast<std::size_t>(kMaxChannelWords); ++i) {
    if (i > 0) data[n++] = high_byte(words[i]);
    data[n++] = low_byte(words[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    std::snprintf(buf, sizeof buf, " %02X", data[i]);
    out += buf;
  }
  if (a->type == FrameType::first && n >= 2) {
    const Word code = make_word(data[0], data[1]);
    const bool conf =
        (code & kConfirmationBit) != 0 && code != static_cast<Word>(ServiceCode::abort);
    const auto base = static_cast<Word>(conf ? (code & ~kConfirmationBit) : code);
    if (is_known_service(base)) {
      const bool unconfirmed = base == static_cast<Word>(ServiceCode::abort) ||
                               base == static_cast<Word>(ServiceCode::information_report);
      out += " (" + std::string(to_string(static_cast<ServiceCode>(base))) +
             (conf ? ".conf" : (unconfirmed ? "" : ".req")) + ")";
    }
  }
  return out;
}

}  // namespace ibs::pcp
