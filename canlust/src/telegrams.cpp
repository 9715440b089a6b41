#include "ibs/canlust/telegrams.hpp"

namespace ibs::canlust {

std::string_view to_string(DecodeError e) {
  switch (e) {
    case DecodeError::none: return "none";
    case DecodeError::wrong_kind: return "wrong kind";
    case DecodeError::remote: return "remote frame";
    case DecodeError::too_short: return "too short";
    case DecodeError::bad_value: return "bad value";
  }
  return "?";
}

std::string_view to_string(SystemCommand c) {
  return c == SystemCommand::start ? "System Start" : "System Stop";
}

CanFrame encode_system(SystemCommand c) {
  return CanFrame::make(kIdSystem, {static_cast<std::uint8_t>(c)});
}

Decoded<SystemCommand> decode_system(const CanFrame& f) {
  if (f.id != kIdSystem) return {{}, DecodeError::wrong_kind};
  if (f.rtr) return {{}, DecodeError::remote};
  if (f.dlc < 1) return {{}, DecodeError::too_short};
  switch (f.data[0]) {
    case 0x00: return {SystemCommand::stop, DecodeError::none};
    case 0x01: return {SystemCommand::start, DecodeError::none};
    default: return {{}, DecodeError::bad_value};
  }
}

CanFrame encode_logon(const IdentifierMap& ids, Address a) {
  CanFrame f;
  f.id = ids.id(TelegramKind::logon, a).value_or(0);
  f.dlc = 0;
  return f;
}

std::optional<ProcessLayout> process_layout_for_cacnf(std::uint8_t cacnf) {
  switch (cacnf) {
    case 1: return ProcessLayout{WordMode::drivecom, ValueWidth::int16q0, ValueWidth::int16q0};
    case 2: return ProcessLayout{WordMode::drivecom, ValueWidth::int32q16, ValueWidth::int32q16};
    case 3: return ProcessLayout{WordMode::drivecom, ValueWidth::int32q16, ValueWidth::int16q0};
    case 4: return ProcessLayout{WordMode::easydrive, ValueWidth::int32q16, ValueWidth::int32q16};
    default: return std::nullopt;
  }
}

namespace {

std::optional<CanFrame> encode_word_value(std::optional<std::uint16_t> id, std::uint16_t word,
                                          ValueWidth w, std::int32_t value) {
  if (!id) return std::nullopt;
  CanFrame f;
  f.id = *id;
  f.dlc = nominal_length(w);
  put_le16(f.data, word);
  if (w == ValueWidth::int16q0) {
    put_le16(std::span(f.data).subspan(2), static_cast<std::uint16_t>(static_cast<std::uint32_t>(value) & 0xFFFFU));
  } else {
    put_le32(std::span(f.data).subspan(2), static_cast<std::uint32_t>(value));
  }
  return f;
}

DecodeError check(const CanFrame& f, std::uint8_t need) {
  if (f.rtr) return DecodeError::remote;
  if (f.dlc < need) return DecodeError::too_short;
  return DecodeError::none;
}

std::int32_t read_value(const CanFrame& f, ValueWidth w) {
  const std::span<const std::uint8_t> d(f.data);
  if (w == ValueWidth::int16q0) return static_cast<std::int16_t>(get_le16(d.subspan(2)));
  return static_cast<std::int32_t>(get_le32(d.subspan(2)));
}

}  // namespace

std::optional<CanFrame> encode_control(const IdentifierMap& ids, Address a,
                                       const ProcessLayout& layout, const ControlTelegram& t) {
  return encode_word_value(ids.id(TelegramKind::control, a), t.word, layout.reference, t.reference);
}

std::optional<CanFrame> encode_status(const IdentifierMap& ids, Address a,
                                      const ProcessLayout& layout, const StatusTelegram& t) {
  return encode_word_value(ids.id(TelegramKind::status, a), t.word, layout.actual, t.actual);
}

Decoded<ControlTelegram> decode_control(const CanFrame& f, const ProcessLayout& layout) {
  const auto e = check(f, nominal_length(layout.reference));
  if (e != DecodeError::none) return {{}, e};
  return {{get_le16(f.data), read_value(f, layout.reference)}, DecodeError::none};
}

Decoded<StatusTelegram> decode_status(const CanFrame& f, const ProcessLayout& layout) {
  const auto e = check(f, nominal_length(layout.actual));
  if (e != DecodeError::none) return {{}, e};
  return {{get_le16(f.data), read_value(f, layout.actual)}, DecodeError::none};
}

std::optional<CanFrame> encode_error(const IdentifierMap& ids, Address a, const ErrorTelegram& e) {
  const auto id = ids.id(TelegramKind::error, a);
  if (!id) return std::nullopt;
  return CanFrame::make(*id, {e.number, e.location, e.reaction});
}

Decoded<ErrorTelegram> decode_error(const CanFrame& f) {
  const auto e = check(f, 3);
  if (e != DecodeError::none) return {{}, e};
  return {{f.data[0], f.data[1], f.data[2]}, DecodeError::none};
}

}  // namespace ibs::canlust
